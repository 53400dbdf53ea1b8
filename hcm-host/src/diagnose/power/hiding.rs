//! How strong a hidden effect is: a strength x is the share of the peak force the
//! effect changes the force by at most, to first order, along the data with nothing
//! hidden. The effect's parameter is then x·F̂ / max|g|, with F̂ the largest measured
//! normal force in contact and g the effect's linear column on a line of force
//! ([`Candidate::column`], the derivative of the force with respect to the parameter
//! at 0). One definition for every effect the 1D catalogue holds, from the data's own
//! scales, none from an example: viscous damping c = x·F̂/δ̇̂, an offset or adhesion
//! x·F̂, a delay τ ≈ x·t_c/π on a half-sine of duration t_c (its steepest slope is
//! π·F̂/t_c), …

use super::PowerError;
use crate::diagnose::catalogue::reference_depth;
use crate::diagnose::{Candidate, ContactSamples};
use crate::scenario::Model;
use hcm_core::effect::ExtendedLaw;
use nalgebra::Vector3;

/// The hysteresis exponent p a hidden hysteresis damping c·δ^p·δ̇ has (–): a point of
/// the selection's grid away from the elastic exponents of the catalogue's laws (1,
/// 1.25, 1.5), where a law's own damping term δ^n·δ̇ would take it up once the base is
/// re-fitted.
pub const HIDDEN_HYSTERESIS_EXPONENT: f64 = 0.5;

/// One effect of the catalogue, hidden at a strength: its parameter per unit of
/// strength and what else it needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hiding {
    /// The effect.
    pub candidate: Candidate,
    /// Its first parameter's value at strength 1 (the whole peak force), in the
    /// parameter's unit ([`Candidate::strength`]).
    pub per_strength: f64,
    /// The shape parameter (hysteresis p, –; NaN for effects without one).
    pub shape: f64,
    /// Reference depth δ_ref of a stiffness-exponent change (m): the median of the
    /// contact events' deepest indentations, as the diagnosis takes it.
    pub reference_depth: f64,
    /// Unit vector along which the recorded force vector reads the line's normal force
    /// (a force offset is added along it).
    pub direction: [f64; 3],
}

impl Hiding {
    /// `candidate`'s strength scale on `samples` (the contact's data with nothing
    /// hidden, read with `law`, the scenario's own), its force read along
    /// `direction`.
    pub fn of(
        candidate: Candidate,
        samples: &ContactSamples,
        law: &ExtendedLaw<f64>,
        direction: [f64; 3],
    ) -> Result<Hiding, PowerError> {
        let contact = |i: &usize| samples.in_contact[*i] && samples.depth[*i] > 0.0;
        let peak = (0..samples.len())
            .filter(contact)
            .map(|i| samples.measured[i])
            .fold(0.0_f64, f64::max);
        let shape = match candidate {
            Candidate::HysteresisDamping => HIDDEN_HYSTERESIS_EXPONENT,
            _ => f64::NAN,
        };
        let reference_depth = reference_depth(samples);
        let base_force = samples.model_force(law);
        let column = candidate.column(samples, law, &base_force, shape, reference_depth);
        let largest = column.iter().map(|g| g.abs()).fold(0.0_f64, f64::max);
        let per_strength = peak / largest;
        if !(per_strength.is_finite() && per_strength > 0.0) {
            return Err(PowerError::Setup(format!(
                "`{}` cannot be hidden at a share of the peak force in these data: its \
                 force change along them is {largest:e} per unit and the peak force \
                 {peak:e} N (leave it out of --effects)",
                candidate.name()
            )));
        }
        Ok(Hiding {
            candidate,
            per_strength,
            shape,
            reference_depth,
            direction,
        })
    }

    /// The first parameter's value at strength `level` (a share of the peak force, –).
    pub fn value(&self, level: f64) -> f64 {
        level * self.per_strength
    }

    /// Contact `c` of `model` (a condition's) with the effect at strength `level`:
    /// a law term added to the contact's normal law, or the sensor changed.
    pub fn hide(&self, model: &mut Model, c: usize, level: f64) -> Result<(), PowerError> {
        let value = self.value(level);
        let experiment = &mut model.scenario.experiment;
        match self.candidate {
            Candidate::ForceOffset => {
                let offset = Vector3::from(self.direction) * value;
                for (b, v) in experiment.force_offset.iter_mut().zip(offset.iter()) {
                    *b += v;
                }
            }
            Candidate::SensorDelay => experiment.sensor_delay += value,
            Candidate::SensorFilter => experiment.sensor_filter += value,
            physical => {
                let term = physical.effect(value, self.shape, self.reference_depth);
                let effects = &mut model.contacts[c].model.normal.effects;
                if term.is_none_or(|term| effects.push(term).is_err()) {
                    return Err(PowerError::Setup(format!(
                        "contact {c}'s law has no room for one more effect term to hide \
                         `{}` in (remove one of its `effects`)",
                        physical.name()
                    )));
                }
            }
        }
        Ok(())
    }
}
