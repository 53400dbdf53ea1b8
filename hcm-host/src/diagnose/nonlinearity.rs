//! A force sensor whose gain grows with the force, told from a stiffness-exponent change
//! by the momentum balance — or not told, and then not named.
//!
//! A sensor reading f + κ·f² has, once its mean gain is taken off, the shape of a
//! stiffness-exponent change: both tilt the force curve about a middle force level
//! (κ·f·(f − w) against f_el·Δ·ln(δ/δ_ref)). The force alone cannot tell them. The
//! momentum balance ([`super::momentum`]) can, where the motion is recorded: a
//! nonlinearity reads every impulse 1 + κ·w too high, w = Σf²/Σf over the contact
//! samples (N), while a stiffer or softer law delivers the impulse the motion shows.
//! So the κ̂ that would mimic the named stiffness term — the least-squares fit of κ·f·(f −
//! w) to that term, in contact — predicts a gain 1 + κ̂·w. Where the balance measured
//! the gain at 1 and that prediction lies beyond [`GAIN_SIGMAS`] of its standard error
//! from it, no such sensor made the data and the stiffness change stands. Where the
//! balance named a gain (the sensor is off; a force-dependent gain would show as both)
//! or could not measure one (motion from a camera), the data cannot tell the two: the
//! answer is "ambiguous" between `stiffness_exponent` and `sensor_nonlinearity` (not a
//! catalogue effect: hcm has no correction for it), the term kept in the extended model
//! as a provisional one.

use super::momentum::{SensorGain, GAIN_SIGMAS};
use super::ContactSamples;
use hcm_core::effect::ExtendedLaw;

/// The name the answer gives a force-dependent sensor gain.
pub const SENSOR_NONLINEARITY: &str = "sensor_nonlinearity";

/// The gain shift κ̂·w (–) a sensor reading f + κ·f² would show in the momentum balance
/// if it, not a stiffness-exponent change, made `law`'s `stiffness_exponent` term on
/// `samples`; None where `law` has no such term or the contact gives no force.
pub fn mimicking_gain_shift(samples: &ContactSamples, law: &ExtendedLaw<f64>) -> Option<f64> {
    let mut without = law.clone();
    without.effects.retain(|e| e.name() != "stiffness_exponent");
    if without.effects.len() == law.effects.len() {
        return None;
    }
    let (with, base) = (samples.model_force(law), samples.model_force(&without));
    let contact: Vec<usize> = (0..samples.len())
        .filter(|&i| samples.in_contact[i] && base[i] > 0.0)
        .collect();
    let sum = |g: &dyn Fn(usize) -> f64| contact.iter().map(|&i| g(i)).sum::<f64>();
    let w = sum(&|i| base[i] * base[i]) / sum(&|i| base[i]);
    let column = |i: usize| base[i] * (base[i] - w);
    let norm = sum(&|i| column(i) * column(i));
    if !(w.is_finite() && norm > 0.0) {
        return None;
    }
    let kappa = sum(&|i| column(i) * (with[i] - base[i])) / norm;
    Some(kappa * w)
}

/// Whether the momentum balance's `gain` rules out a sensor nonlinearity whose gain
/// shift would be `shift` (–): measured, not named, and the shift beyond
/// [`GAIN_SIGMAS`] standard errors of the measured gain's own departure from 1.
pub fn ruled_out(shift: f64, gain: Option<SensorGain>) -> bool {
    gain.is_some_and(|g| {
        !g.named && (shift - (g.value - 1.0)).abs() > GAIN_SIGMAS * g.standard_error
    })
}
