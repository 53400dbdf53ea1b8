//! The face a box lies on: of its six faces, the one whose outward normal points most
//! nearly down. At the end of a toss it is what a die shows, and the outcome a replay
//! gets right or wrong as a whole (a replay ending on another face than the real cube
//! carries a rotation error of 90° or 180° to its last frame).

use nalgebra::{UnitQuaternion, Vector3};

/// Faces of a box (–).
pub const FACES: usize = 6;

/// One of a box's faces by its outward normal in the body frame: 0 +x, 1 −x, 2 +y,
/// 3 −y, 4 +z, 5 −z.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Face(pub usize);

impl Face {
    /// The face's name, its outward normal's body axis: `+x`, `-x`, `+y`, `-y`, `+z`,
    /// `-z`.
    pub fn name(self) -> &'static str {
        ["+x", "-x", "+y", "-y", "+z", "-z"]
            .get(self.0)
            .copied()
            .unwrap_or("?")
    }

    /// The face of a box at `orientation` (body → world) whose outward normal points
    /// most nearly along `down` (world frame, any length > 0: the gravity); None for a
    /// zero or non-finite `down` or a NaN orientation.
    pub fn facing(orientation: &UnitQuaternion<f64>, down: &Vector3<f64>) -> Option<Face> {
        let local = orientation.inverse_transform_vector(down);
        if !(local.norm() > 0.0 && local.iter().all(|x| x.is_finite())) {
            return None;
        }
        let axis = local.iamax();
        Some(Face(2 * axis + usize::from(local[axis] < 0.0)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn an_upright_box_lies_on_its_minus_z_face_and_a_turned_one_on_another() {
        let down = Vector3::new(0.0, 0.0, -9.81);
        assert_eq!(
            Face::facing(&UnitQuaternion::identity(), &down),
            Some(Face(5))
        );
        // A quarter turn about x carries the body's +y axis onto world −z.
        let turned = UnitQuaternion::from_euler_angles(-FRAC_PI_2, 0.0, 0.0);
        assert_eq!(Face::facing(&turned, &down).map(Face::name), Some("+y"));
        // Tipped 40° (not yet over its edge): still on −z.
        let tipped = UnitQuaternion::from_euler_angles(0.7, 0.0, 0.0);
        assert_eq!(Face::facing(&tipped, &down), Some(Face(5)));
        assert_eq!(Face::facing(&tipped, &Vector3::zeros()), None);
    }
}
