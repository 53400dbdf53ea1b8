//! The physics file of a fit from motion: the fitted law and friction of the thrown
//! body's contact, with the fit's fitness in its notes and the table offset and the
//! body's inertia as its `sets` (applied with the file) — what `hcm identify-motion`
//! and `hcm reproduce cube-toss` write.

use super::MotionFit;
use crate::identify::{FitRecord, Physics};
use crate::scenario::Assignment;
use std::fmt::Display;

/// `fit`'s physics file for its `contacts` (the fitted one first, then those fitted
/// as one with it): made by `method` on `runs` training tosses of `data`, the table
/// offset, the inertia and the joints' terms applied by `sets` ([`super::beside_physics`]).
pub fn fitted_physics(
    fit: &MotionFit,
    contacts: &[usize],
    sets: &[Assignment],
    method: &str,
    data: &str,
    runs: usize,
) -> Physics {
    let record = FitRecord {
        method: method.to_owned(),
        data: data.to_owned(),
        runs,
        seconds: fit.seconds,
        force_rms: f64::NAN,
        curve_rms: f64::NAN,
        notes: vec![
            format!(
                "fitness {:.4}: mean position error (% of the width) + mean rotation error \
                 (degrees) over the training tosses (even toss numbers)",
                fit.fitness
            ),
            format!(
                "the body and table values (in `sets`): {}",
                set_options(sets)
            ),
        ],
        ..FitRecord::default()
    };
    let of =
        |c: usize| Physics::for_contact(&fit.model, c, fit.model.contacts[c].law(), record.clone());
    let mut physics = of(contacts.first().copied().unwrap_or(0));
    for &c in contacts.iter().skip(1) {
        physics.contacts.extend(of(c).contacts);
    }
    physics.sets = sets.to_vec();
    physics
}

/// `sets` as command-line options: `--set a --set b`.
pub fn set_options(sets: &[impl Display]) -> String {
    let options: Vec<String> = sets.iter().map(|s| format!("--set {s}")).collect();
    options.join(" ")
}
