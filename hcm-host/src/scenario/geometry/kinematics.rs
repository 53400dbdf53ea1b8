//! Where a contact pair touches: indentation, its rate, normal and contact point,
//! from the two bodies' positions and velocities, for a pair touching on its line of
//! centres. Used to read indentation back from measured data and by the scenario's
//! checks.

use crate::scenario::{Contact, Model, Shape};
use hcm_core::geometry::{sphere_plane, sphere_sphere};
use nalgebra::Vector3;

/// Contact kinematics of one pair at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairKinematics {
    /// Indentation δ (m), > 0 in contact.
    pub(crate) depth: f64,
    /// Indentation rate δ̇ = −(v1 − v2)·n (m/s), > 0 approaching.
    pub(crate) rate: f64,
    /// Unit normal from body 2 to body 1.
    pub(crate) normal: Vector3<f64>,
    /// Contact point (m).
    pub(crate) point: Vector3<f64>,
}

impl PairKinematics {
    /// NaN everywhere: a pair whose contact is not one point along a line of centres.
    fn undefined() -> Self {
        PairKinematics {
            depth: f64::NAN,
            rate: f64::NAN,
            normal: Vector3::repeat(f64::NAN),
            point: Vector3::repeat(f64::NAN),
        }
    }
}

/// Kinematics of `contact` with body 1 at (p1, v1) and body 2 at (p2, v2) (m, m/s):
/// a sphere against a plane or a sphere, which never turn in the 1D examples. Pairs
/// with a box touch at a manifold of points ([`super::pair_contacts`]); here they are NaN.
// Always inlined: a call returning the 64-byte result through memory doubled the
// cost of reading indentation back from a data set (measured by criterion).
#[inline(always)]
pub fn pair_kinematics(
    model: &Model,
    contact: &Contact,
    (p1, v1): (Vector3<f64>, Vector3<f64>),
    (p2, v2): (Vector3<f64>, Vector3<f64>),
) -> PairKinematics {
    let Shape::Sphere { radius } = model.bodies[contact.body_1].shape else {
        return PairKinematics::undefined();
    };
    let geometry = match model.bodies[contact.body_2].shape {
        Shape::Plane { normal, offset } => {
            sphere_plane::contact(&p1, radius, &(p2 + normal * offset), &normal)
        }
        Shape::Sphere { radius: radius_2 } => sphere_sphere::contact(&p1, radius, &p2, radius_2),
        // Pairs with corners turn with the bodies: their manifold, not one point.
        Shape::Box { .. } | Shape::Compound { .. } => return PairKinematics::undefined(),
    };
    PairKinematics {
        depth: geometry.depth,
        rate: -(v1 - v2).dot(&geometry.normal),
        normal: geometry.normal,
        point: geometry.point,
    }
}
