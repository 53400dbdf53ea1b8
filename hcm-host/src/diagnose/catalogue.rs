//! How an effect of the one catalogue ([`super::CATALOGUE`]) is judged on a line of
//! force (1D): as the column it adds to a linear model of the residual (measured −
//! model force) at small strength, the fast pre-ranking the 1D selection runs before
//! its joint re-fit. An effect that has one names it ([`super::Effect::column`]).
//!
//! Physical effects are core law terms (`hcm_core::effect`), so an extended model runs
//! in a controller; measurement effects (a sensor offset or lag) correct the data and
//! are reported, not added to the physics. Each candidate's column is the derivative
//! of the predicted force with respect to its strength at strength 0 — the residual it
//! would leave if the model lacked it:
//!
//! | effect | strength | column g (per sample) |
//! |---|---|---|
//! | `viscous_damping` | c (N·s/m) | δ̇ in contact |
//! | `hysteresis_damping` | c (N·s/m^(1+p)) | δ^p·δ̇ in contact, p on a grid |
//! | `stiffness_exponent` | Δ (–) | f_el(δ)·ln(δ/δ_ref) in contact |
//! | `adhesion` | a (N) | −1 in contact |
//! | `plasticity` | ρ (–) | −(δ_max − δ)·∂f/∂δ while unloading |
//! | `force_offset` | b (N) | 1 on every sample, in flight too |
//! | `sensor_delay` | τ (s) | −df/dt of the model force along the run |
//! | `sensor_filter` | T (s) | −df/dt too: a first-order low-pass lags by T at first order |
//!
//! Air drag lives in the flight motion, not in the force, and is read from the
//! recorded velocities (not part of this force library).

use super::{ContactSamples, Family};
use hcm_core::effect::{
    Adhesion, ContactEffect, ExtendedLaw, HysteresisDamping, Plasticity, StiffnessExponent,
    ViscousDamping,
};
use hcm_core::model::ContactModel;

/// The linear column of an effect judged on a line of force.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Candidate {
    /// f += c·δ̇.
    ViscousDamping,
    /// f += c·δ^p·δ̇.
    HysteresisDamping,
    /// Elastic exponent n → n + Δ about δ_ref.
    StiffnessExponent,
    /// f −= a in contact.
    Adhesion,
    /// Unloading on a curve shifted by ρ·δ_max.
    Plasticity,
    /// The sensor reads f + b.
    ForceOffset,
    /// The sensor reads f(t − τ).
    SensorDelay,
    /// The sensor reads y, T·ẏ + y = f: a first-order low-pass filter.
    SensorFilter,
}

/// The columns of the effects of the one catalogue ([`super::CATALOGUE`]) judged on a
/// line of force, in its order.
pub fn line_candidates() -> impl Iterator<Item = Candidate> {
    (super::CATALOGUE.iter())
        .filter(|e| e.evidence(crate::dataset::Evidence::LineForce))
        .filter_map(|e| e.column())
}

/// Grid of the hysteresis exponent p searched by the selection (the joint re-fit then
/// refines it); p = 0 is viscous damping, a candidate of its own.
pub const HYSTERESIS_EXPONENTS: [f64; 12] = [
    0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0, 2.25, 2.5, 2.75, 3.0,
];

impl Candidate {
    /// The catalogue name.
    pub fn name(self) -> &'static str {
        match self {
            Candidate::ViscousDamping => "viscous_damping",
            Candidate::HysteresisDamping => "hysteresis_damping",
            Candidate::StiffnessExponent => "stiffness_exponent",
            Candidate::Adhesion => "adhesion",
            Candidate::Plasticity => "plasticity",
            Candidate::ForceOffset => "force_offset",
            Candidate::SensorDelay => "sensor_delay",
            Candidate::SensorFilter => "sensor_filter",
        }
    }

    /// Its family: the normal law's, or the sensor's (a measurement).
    pub fn family(self) -> Family {
        match self {
            Candidate::ForceOffset | Candidate::SensorDelay | Candidate::SensorFilter => {
                Family::Measurement
            }
            _ => Family::Normal,
        }
    }

    /// Values of the candidate's shape parameter to search (p for hysteresis damping);
    /// one NaN for candidates without one.
    pub fn shapes(self) -> &'static [f64] {
        match self {
            Candidate::HysteresisDamping => &HYSTERESIS_EXPONENTS,
            _ => &[f64::NAN],
        }
    }

    /// Name of the strength parameter and its unit.
    pub fn strength(self) -> (&'static str, &'static str) {
        match self {
            Candidate::ViscousDamping => ("coefficient", "N·s/m"),
            Candidate::HysteresisDamping => ("coefficient", "N·s/m^(1+p)"),
            Candidate::StiffnessExponent => ("exponent_change", "–"),
            Candidate::Adhesion => ("pull_off_force", "N"),
            Candidate::Plasticity => ("permanent_ratio", "–"),
            Candidate::ForceOffset => ("offset", "N"),
            Candidate::SensorDelay => ("delay", "s"),
            Candidate::SensorFilter => ("time_constant", "s"),
        }
    }

    /// The column g of this candidate over `samples` for shape parameter `shape`, given
    /// the base law, its force along the samples and the reference depth δ_ref (m).
    pub fn column(
        self,
        samples: &ContactSamples,
        base: &ExtendedLaw<f64>,
        base_force: &[f64],
        shape: f64,
        reference_depth: f64,
    ) -> Vec<f64> {
        let n = samples.len();
        let contact = |i: usize| samples.in_contact[i] && samples.depth[i] > 0.0;
        match self {
            Candidate::ViscousDamping => (0..n)
                .map(|i| if contact(i) { samples.rate[i] } else { 0.0 })
                .collect(),
            Candidate::HysteresisDamping => (0..n)
                .map(|i| {
                    if contact(i) {
                        samples.depth[i].powf(shape) * samples.rate[i]
                    } else {
                        0.0
                    }
                })
                .collect(),
            Candidate::StiffnessExponent => (0..n)
                .map(|i| {
                    if contact(i) {
                        base.base.elastic_force(samples.depth[i])
                            * (samples.depth[i] / reference_depth).ln()
                    } else {
                        0.0
                    }
                })
                .collect(),
            Candidate::Adhesion => (0..n)
                .map(|i| if contact(i) { -1.0 } else { 0.0 })
                .collect(),
            Candidate::Plasticity => {
                let physics = ContactModel::physics(base.clone());
                (0..n)
                    .map(|i| {
                        if !(contact(i) && samples.rate[i] < 0.0) {
                            return 0.0;
                        }
                        let (mut state, memory) = samples.state(i);
                        let h = 1e-4 * memory.max_depth.max(samples.depth[i]);
                        let depth = state.depth;
                        state.depth = depth + h;
                        let up = physics.physics_normal_force(&state, &memory);
                        state.depth = (depth - h).max(0.0);
                        let down = physics.physics_normal_force(&state, &memory);
                        let slope = (up - down) / (depth + h - state.depth);
                        -(memory.max_depth - depth) * slope
                    })
                    .collect()
            }
            Candidate::ForceOffset => vec![1.0; n],
            Candidate::SensorDelay | Candidate::SensorFilter => (0..n)
                .map(|i| {
                    let same = |j: usize| samples.run[j] == samples.run[i];
                    let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
                    let (a, b) = (if same(a) { a } else { i }, if same(b) { b } else { i });
                    if a == b {
                        return 0.0;
                    }
                    -(base_force[b] - base_force[a]) / (samples.time[b] - samples.time[a])
                })
                .collect(),
        }
    }

    /// The core term of a physical candidate with strength `strength` and shape
    /// `shape`; None for measurement effects.
    pub fn effect(
        self,
        strength: f64,
        shape: f64,
        reference_depth: f64,
    ) -> Option<ContactEffect<f64>> {
        Some(match self {
            Candidate::ViscousDamping => ViscousDamping {
                coefficient: strength,
            }
            .into(),
            Candidate::HysteresisDamping => HysteresisDamping {
                coefficient: strength,
                exponent: shape,
            }
            .into(),
            Candidate::StiffnessExponent => StiffnessExponent {
                exponent_change: strength,
                reference_depth,
            }
            .into(),
            Candidate::Adhesion => Adhesion {
                pull_off_force: strength,
            }
            .into(),
            Candidate::Plasticity => Plasticity {
                permanent_ratio: strength,
            }
            .into(),
            Candidate::ForceOffset | Candidate::SensorDelay | Candidate::SensorFilter => {
                return None
            }
        })
    }
}

/// The reference depth δ_ref of the stiffness-exponent term: the median over contact
/// events of their deepest indentation (m), so that Δ tilts the elastic curve about a
/// depth the data cover and is not confounded with the stiffness.
pub fn reference_depth(samples: &ContactSamples) -> f64 {
    let mut deepest: Vec<f64> = Vec::new();
    for i in 0..samples.len() {
        let last_of_run = i + 1 == samples.len() || samples.run[i + 1] != samples.run[i];
        if samples.in_contact[i] && (last_of_run || !samples.in_contact[i + 1]) {
            deepest.push(samples.max_depth[i]);
        }
    }
    deepest.sort_by(f64::total_cmp);
    deepest.get(deepest.len() / 2).copied().unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names a diagnosis reports for a cause's parameters are the core effect's
    /// own parameter names, and its catalogue name the effect's name.
    #[test]
    fn reported_names_are_the_core_effects_names() {
        for candidate in line_candidates() {
            let shape = candidate.shapes()[0];
            let Some(effect) = candidate.effect(0.5, shape, 1e-5) else {
                assert_eq!(candidate.family(), Family::Measurement);
                continue;
            };
            assert_eq!(effect.name(), candidate.name());
            let (strength, _) = candidate.strength();
            assert_eq!(effect.get(strength), Ok(0.5), "{}", candidate.name());
            if !shape.is_nan() {
                assert_eq!(effect.get("exponent"), Ok(shape));
            }
            if candidate == Candidate::StiffnessExponent {
                assert_eq!(effect.get("reference_depth"), Ok(1e-5));
            }
        }
    }

    /// Each column is the linearisation of the catalogue's effect of the same name and
    /// family, and the line's catalogue keeps its order.
    #[test]
    fn every_column_is_its_effects() {
        let line: Vec<Candidate> = line_candidates().collect();
        assert_eq!(line.len(), 8);
        assert_eq!(line[0], Candidate::ViscousDamping);
        assert_eq!(line[7], Candidate::SensorFilter);
        for effect in super::super::CATALOGUE.iter() {
            if let Some(column) = effect.column() {
                assert_eq!(column.name(), effect.name());
                assert_eq!(column.family(), effect.family());
            }
        }
    }
}
