//! Contact geometry: the materials and shapes that set a contact's stiffness, and
//! where two shapes touch (indentation, common normal, contact point).
//!
//! One file per pair of shapes; each gives the Hertz stiffness of Eq 3 for that pair
//! and the contact kinematics a simulator feeds to the laws in [`crate::law`].

pub mod box_box;
pub mod box_plane;
pub mod compound;
mod cuboid;
mod material;
pub mod sphere_box;
pub mod sphere_plane;
pub mod sphere_sphere;

pub use cuboid::Cuboid;
pub use material::{effective_modulus, Material};

use crate::Real;
use nalgebra::Vector3;

/// Where and how deep two shapes overlap, in the caller's common frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactGeometry<T: Real> {
    /// Indentation δ (m): > 0 when the undeformed shapes overlap.
    pub depth: T,
    /// Common normal **n** (unit, dimensionless), pointing from body 2 to body 1.
    pub normal: Vector3<T>,
    /// Contact point (m): the middle of the overlap along the normal.
    pub point: Vector3<T>,
    /// Which pair of geometric features made this point (–): the same value while the
    /// same features stay in contact, so a simulator can carry the point's history
    /// (approach speed δ̇0, δ_max) from step to step. Each generator documents its
    /// encoding; a shape pair with a single contact uses 0.
    pub feature: u32,
}

/// The contacts of one shape pair with several points (a box on a plane: up to 8),
/// fixed-size (no allocator), as many as a [`crate::model::Manifold`] holds.
pub type Contacts<T> = heapless::Vec<ContactGeometry<T>, { crate::model::MAX_POINTS }>;

/// Hertz contact stiffness k = 4/3 · E* · √R (N/m^1.5), Eq 3.
///
/// `effective_modulus` E* (Pa) as given by [`effective_modulus`] (without the 4/3),
/// `effective_radius` R (m). A negative or NaN radius gives NaN; the result saturates.
pub fn hertz_stiffness<T: Real>(effective_modulus: T, effective_radius: T) -> T {
    (T::of(4.0 / 3.0) * effective_modulus * effective_radius.square_root()).saturate()
}
