//! The physics file of a fit from motion: the fitted law and friction of the tossed
//! body's contact, with the fit's fitness and the table offset's `--set` (which a
//! physics file has no place for) in its notes — what `hcm identify-motion` and `hcm
//! reproduce cube-toss` write.

use super::MotionFit;
use crate::identify::{FitRecord, Physics};

/// `fit`'s physics file for its `contact`: made by `method` on `runs` training tosses
/// of `data`, the table offset applied by `table_set`.
pub fn fitted_physics(
    fit: &MotionFit,
    contact: usize,
    table_set: &str,
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
            format!("table offset: apply with --set {table_set}"),
        ],
        ..FitRecord::default()
    };
    let law = fit.model.contacts[contact].law();
    Physics::for_contact(&fit.model, contact, law, record)
}
