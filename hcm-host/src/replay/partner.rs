//! The fixed bodies a replayed body can touch, as the motion fit and its diagnosis see
//! them: how far a centre is from each one's surface (where a toss's window starts),
//! and the two changes a tracker's calibration error makes to where it is — a shift
//! along the up direction (the table's height) and a tilt about the horizontal axes.
//!
//! A plane keeps the tosses' convention: its clearance is measured from its reference
//! point along its normal (not from the surface its `offset` moves), so that fitting
//! the offset leaves every window as it was. Every other shape's clearance is the
//! distance to its surface at its scenario pose.

use crate::scenario::{Model, Shape};
use nalgebra::{UnitQuaternion, Vector3};

/// One fixed body in contact with the replayed body.
#[derive(Clone, Debug, PartialEq)]
pub struct Partner {
    /// Index of the fixed body in the model.
    pub(crate) body: usize,
    /// Its shape (body frame).
    shape: Shape,
    /// Its reference point (m, world frame).
    position: Vector3<f64>,
    /// Its orientation (body → world).
    orientation: UnitQuaternion<f64>,
}

impl Partner {
    /// Fixed body `body` of `model` as it stands in the scenario.
    pub fn of(model: &Model, body: usize) -> Partner {
        let fixed = &model.bodies[body];
        Partner {
            body,
            shape: fixed.shape.clone(),
            position: fixed.position,
            orientation: fixed.orientation,
        }
    }

    /// A body of `shape` at `position` (m) and `orientation`: a moving body where a
    /// frame records it.
    pub(crate) fn at(
        body: usize,
        shape: Shape,
        position: Vector3<f64>,
        orientation: UnitQuaternion<f64>,
    ) -> Partner {
        Partner {
            body,
            shape,
            position,
            orientation,
        }
    }

    /// Clearance of a point `p` (m, world frame) from this body (m): for a plane its
    /// height above the reference point along the normal, otherwise the distance to
    /// the surface (negative inside).
    pub fn clearance(&self, p: &Vector3<f64>) -> f64 {
        let local = self.orientation.inverse() * (p - self.position);
        match &self.shape {
            Shape::Plane { normal, .. } => normal.dot(&local),
            Shape::Sphere { radius } => local.norm() - radius,
            Shape::Box { half_extents, .. } => box_clearance(&local, half_extents),
            Shape::Compound { parts } => (parts.iter())
                .map(|part| {
                    let inside = part.orientation.inverse() * (local - part.position);
                    box_clearance(&inside, &part.half_extents)
                })
                .fold(f64::INFINITY, f64::min),
        }
    }
}

/// Signed distance (m) of `local` (box frame, m) to a box of half extents `half`.
fn box_clearance(local: &Vector3<f64>, half: &Vector3<f64>) -> f64 {
    let q = local.abs() - half;
    let outside = q.map(|x| x.max(0.0)).norm();
    outside + q.max().min(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_clearance_is_the_distance_outside_and_minus_the_depth_inside() {
        let half = Vector3::new(1.0, 2.0, 3.0);
        assert_eq!(box_clearance(&Vector3::new(0.0, 0.0, 5.0), &half), 2.0);
        let corner = box_clearance(&Vector3::new(4.0, 6.0, 3.0), &half);
        assert!((corner - 5.0).abs() < 1e-12, "{corner}");
        assert_eq!(box_clearance(&Vector3::new(0.5, 0.0, 0.0), &half), -0.5);
    }
}
