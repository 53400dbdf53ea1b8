//! A cuboid (box): half extents, centre and orientation, and its eight vertices.

use crate::Real;
use nalgebra::{UnitQuaternion, Vector3};

/// A rectangular box, every vector in the caller's common (world) frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cuboid<T: Real> {
    /// Half extents along the box's own x, y and z axes (m), each > 0.
    pub half_extents: Vector3<T>,
    /// Centre (m).
    pub center: Vector3<T>,
    /// Orientation: rotates the box's own axes into the common frame (–).
    pub orientation: UnitQuaternion<T>,
}

impl<T: Real> Cuboid<T> {
    /// Vertex `index` (0..8) in the common frame (m). Bit 0 of the index picks the sign
    /// of x (set: +), bit 1 of y, bit 2 of z, so the order is fixed and repeatable.
    pub fn vertex(&self, index: usize) -> Vector3<T> {
        let h = &self.half_extents;
        let signed = |bit: usize, half: T| if index & bit != 0 { half } else { -half };
        let local = Vector3::new(signed(1, h.x), signed(2, h.y), signed(4, h.z));
        self.center + self.orientation * local
    }

    /// Half extents (m) of the box's axis-aligned bounding box in the common frame:
    /// |R|·h, with |R| the rotation matrix's entries made positive.
    pub fn world_half_extents(&self) -> Vector3<T> {
        self.orientation.to_rotation_matrix().matrix().abs() * self.half_extents
    }

    /// `point` (m, common frame) in the box's own frame, relative to its centre (m).
    pub fn to_local(&self, point: &Vector3<T>) -> Vector3<T> {
        self.orientation
            .inverse_transform_vector(&(point - self.center))
    }

    /// `local` (m, box frame relative to the centre) in the common frame (m).
    pub fn to_world(&self, local: &Vector3<T>) -> Vector3<T> {
        self.center + self.orientation * local
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertices_are_the_eight_signed_corners() {
        let cuboid = Cuboid {
            half_extents: Vector3::new(1.0_f64, 2.0, 3.0),
            center: Vector3::new(10.0, 0.0, 0.0),
            orientation: UnitQuaternion::identity(),
        };
        assert_eq!(cuboid.vertex(0), Vector3::new(9.0, -2.0, -3.0));
        assert_eq!(cuboid.vertex(7), Vector3::new(11.0, 2.0, 3.0));
        assert_eq!(cuboid.vertex(5), Vector3::new(11.0, -2.0, 3.0));
    }

    #[test]
    fn local_and_world_frames_round_trip() {
        let cuboid = Cuboid {
            half_extents: Vector3::new(1.0_f64, 2.0, 3.0),
            center: Vector3::new(0.3, -0.2, 0.1),
            orientation: UnitQuaternion::from_euler_angles(0.3, -0.7, 1.1),
        };
        let p = Vector3::new(0.5, 0.25, -2.0);
        assert!((cuboid.to_world(&cuboid.to_local(&p)) - p).norm() < 1e-15);
    }
}
