//! A search box scaled from the rig's own data (from the scenario and the
//! measured peak force, not fixed numbers that fit the examples).
//!
//! The defaults ([`crate::identify::bounds`]) put a stiffness between 1e8 and 1e11
//! N/m^n: the paper's steel balls and peg. `scenarios/cube_drop.toml`'s 1e7 lies
//! outside, and a fit held there reproduces nothing. From the recorded contact the
//! scales follow without a law-specific fit:
//! - stiffness k₀ = Σ Fₙ·S / Σ S² over the rows, S = Σ_points δᵉ (m^e) and Fₙ the
//!   measured force along the points' mean normal (N), e the law's exponent: the
//!   elastic part's least-squares level; the box is k₀/100 … 100·k₀ (k₀/10⁴ … 10⁴·k₀ with the exponent free);
//! - a damping in N·s/m (IMPACT's `max_damping`): 0 … 10·Fₙ,max / δ̇max, the damping
//!   that alone would make ten times the largest force at the fastest approach;
//! - a depth (IMPACT's `full_damping_depth`): δmax/10⁴ … 10·δmax.
//!
//! A box the scenario gives (`[identify.bounds.<law>]`) is kept as given.

use super::recorded::RecordedContact;
use super::RigidParameters;
use crate::scenario::Model;

/// Factor on each side of the least-squares stiffness k₀ (–), squared when the
/// exponent is fitted too.
const STIFFNESS_SPAN: f64 = 100.0;

/// What a recorded contact says about its law's scales.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactScales {
    /// Least-squares elastic level k₀ at the law's exponent (N/m^e); NaN without rows.
    pub stiffness: f64,
    /// Largest measured normal force (N).
    pub peak_force: f64,
    /// Fastest approach of a point, |δ̇| (m/s).
    pub peak_rate: f64,
    /// Deepest point (m).
    pub peak_depth: f64,
}

impl ContactScales {
    /// The scales of `recorded` with exponent `exponent` (–).
    pub fn of(recorded: &RecordedContact, exponent: f64) -> ContactScales {
        let (mut fs, mut ss) = (0.0, 0.0);
        let mut scales = ContactScales {
            stiffness: f64::NAN,
            peak_force: 0.0,
            peak_rate: 0.0,
            peak_depth: 0.0,
        };
        for sample in &recorded.samples {
            let mut normal = nalgebra::Vector3::zeros();
            let mut elastic = 0.0;
            for p in sample.points.iter() {
                let depth = p.indentation.depth.max(0.0);
                elastic += depth.powf(exponent);
                normal += p.normal;
                scales.peak_rate = scales.peak_rate.max(p.indentation.rate.abs());
                scales.peak_depth = scales.peak_depth.max(depth);
            }
            let force =
                nalgebra::Vector3::new(sample.measured[0], sample.measured[1], sample.measured[2]);
            let along = force.dot(&normal.normalize()).abs();
            if along.is_finite() && elastic.is_finite() {
                fs += along * elastic;
                ss += elastic * elastic;
                scales.peak_force = scales.peak_force.max(along);
            }
        }
        if ss > 0.0 {
            scales.stiffness = fs / ss;
        }
        scales
    }

    /// Scales `parameters`' box for contact `c` of `model` (see the module docs); the
    /// names of the parameters whose box changed.
    pub fn apply(&self, model: &Model, c: usize, parameters: &mut RigidParameters) -> Vec<String> {
        let mut changed = Vec::new();
        let law = model.contacts[c].law();
        let k = self.stiffness;
        // A free exponent moves the stiffness's unit: δ^Δe at δ ~ 10 µm is 10^(5Δe).
        let span = if parameters.fits_exponent() {
            STIFFNESS_SPAN * STIFFNESS_SPAN
        } else {
            STIFFNESS_SPAN
        };
        if law.get("stiffness").is_ok()
            && k > 0.0
            && parameters.scale("stiffness", k / span, k * span)
        {
            changed.push("stiffness".to_owned());
        }
        if self.peak_rate > 0.0
            && parameters.scale("max_damping", 0.0, 10.0 * self.peak_force / self.peak_rate)
        {
            changed.push("max_damping".to_owned());
        }
        if self.peak_depth > 0.0
            && parameters.scale(
                "full_damping_depth",
                self.peak_depth * 1e-4,
                self.peak_depth * 10.0,
            )
        {
            changed.push("full_damping_depth".to_owned());
        }
        changed
    }
}
