//! The indicators of a 3D contact event (the peg-in-hole's, paper Section 5.3): over
//! an interval in which any point of a body pair touches, the maximum contact force,
//! the maximum contact torque about the moving body's centre of mass, the linear
//! impulse ∫**F** dt and angular impulse ∫**T** dt, and the duration.

use serde::Serialize;

/// The indicators of one 3D contact event of a body pair, on its moving body.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct WrenchIndicators {
    /// Maximum of ‖**F**‖ over the event (N).
    pub max_force: f64,
    /// Maximum of ‖**T**‖ about the moving body's centre of mass (N·m).
    pub max_torque: f64,
    /// ‖∫**F** dt‖ (N·s).
    pub linear_impulse: f64,
    /// ‖∫**T** dt‖ (N·m·s).
    pub angular_impulse: f64,
    /// Touch-down to lift-off (s).
    pub duration: f64,
    /// ∫**F** dt, world frame (N·s).
    pub(crate) linear_impulse_vector: [f64; 3],
    /// ∫**T** dt, world frame (N·m·s).
    pub(crate) angular_impulse_vector: [f64; 3],
}

impl WrenchIndicators {
    /// Names and units of the scalar indicators, in [`WrenchIndicators::values`] order.
    pub const NAMES: [(&'static str, &'static str); 5] = [
        ("max_force", "N"),
        ("max_torque", "N·m"),
        ("linear_impulse", "N·s"),
        ("angular_impulse", "N·m·s"),
        ("duration", "s"),
    ];

    /// The scalar indicators in a fixed order.
    pub fn values(&self) -> [f64; 5] {
        [
            self.max_force,
            self.max_torque,
            self.linear_impulse,
            self.angular_impulse,
            self.duration,
        ]
    }

    /// The indicators from the impulse vectors (N·s, N·m·s), the maxima (N, N·m) and
    /// the duration (s).
    pub fn new(
        max_force: f64,
        max_torque: f64,
        linear_impulse: [f64; 3],
        angular_impulse: [f64; 3],
        duration: f64,
    ) -> Self {
        let norm = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        WrenchIndicators {
            max_force,
            max_torque,
            linear_impulse: norm(linear_impulse),
            angular_impulse: norm(angular_impulse),
            duration,
            linear_impulse_vector: linear_impulse,
            angular_impulse_vector: angular_impulse,
        }
    }
}
