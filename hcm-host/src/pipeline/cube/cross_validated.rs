//! The named chance cross-validated over both folds (issue 48). The first fold's
//! diagnosis fits the chance on the even tosses and forecasts the odd ones; here the
//! second fold does the reverse: its physics (fitted on the odd tosses) goes through
//! the diagnosis' own chance phase with the named chance alone in the catalogue — σ
//! fitted on the odd tosses, judged by the same rule on the even ones — and the even
//! tosses are forecast by its extended model. Every toss is then forecast by a model
//! and a spread fitted on the other half, and the 456 are scored together.

use super::forecast::{fold_forecast, results_of, FoldForecast, ForecastResults};
use super::CubeError;
use crate::dataset::Dataset;
use crate::dataset::Evidence;
use crate::diagnose::{diagnose_motion_split, Catalogue, MotionDiagnosis};
use crate::progress::Progress;
use crate::scenario::Model;
use serde::Serialize;
use std::fmt::Write;

/// The second fold's chance and both folds' forecasts together.
#[derive(Clone, Debug, Serialize)]
pub struct CrossValidated {
    /// The second fold's chance phase: the named chance fitted on the odd tosses and
    /// judged on the even ones.
    pub(crate) diagnosis: MotionDiagnosis,
    /// The even tosses forecast by its extended model (`null` where its rule named
    /// nothing: the second fold's model is then its replay).
    pub(crate) second: Option<ForecastResults>,
    /// Every toss forecast by the fold that did not fit it (`null` as above).
    pub(crate) pooled: Option<ForecastResults>,
}

/// The chance `first` (the first fold's diagnosis) named, cross-validated with
/// `second_fit` (the physics fitted on `odd`) and the first fold's forecast of `odd`;
/// None where `first` named no chance.
pub(crate) fn cross_validate(
    second_fit: &Model,
    first: &MotionDiagnosis,
    first_fold: &FoldForecast,
    (odd, even): (&Dataset, &Dataset),
    progress: &dyn Progress,
) -> Result<Option<CrossValidated>, CubeError> {
    let named: Vec<&str> = first.named.iter().map(|(n, _)| n.as_str()).collect();
    let catalogue = Catalogue::default()
        .with_chance()
        .retain(|e| e.stochastic() && named.contains(&e.name()));
    if catalogue.for_evidence(Evidence::Poses).next().is_none() {
        return Ok(None);
    }
    let diagnosis =
        diagnose_motion_split(second_fit, odd.clone(), even.clone(), &catalogue, progress)?;
    let (second, pooled) = match diagnosis.extended.varies() {
        true => {
            let fold = fold_forecast(second_fit, &diagnosis.extended, even, progress)?;
            let sets = super::extended_physics_sets(&diagnosis.extended);
            let pooled = results_of(&[first_fold, &fold], Vec::new());
            (Some(results_of(&[&fold], sets)), Some(pooled))
        }
        false => (None, None),
    };
    Ok(Some(CrossValidated {
        diagnosis,
        second,
        pooled,
    }))
}

impl CrossValidated {
    /// The report's section: each fold's forecast and both together.
    pub(crate) fn write_markdown(
        &self,
        first: Option<&ForecastResults>,
        out: &mut String,
    ) -> std::fmt::Result {
        writeln!(
            out,
            "## The named chance cross-validated\n\nThe second fold (the physics fitted on the \
             odd tosses) through the diagnosis' chance phase with the named chance alone: \
             {}\n",
            self.diagnosis.answer
        )?;
        let (Some(second), Some(pooled), Some(first)) = (&self.second, &self.pooled, first) else {
            return writeln!(out, "No second-fold forecast: its rule named nothing.\n");
        };
        writeln!(
            out,
            "| forecast tosses | physics and spread fitted on | energy score: position (%) | rotation (°) | replay: position (%) | rotation (°) | gain, 95 % | inside 50 % band | inside 90 % band | face Brier (replay) |\n|---|---|---|---|---|---|---|---|---|---|"
        )?;
        let rows = [
            ("odd", "even", first),
            ("even", "odd", second),
            ("all", "the other half", pooled),
        ];
        for (tosses, fitted, f) in rows {
            let brier = f.faces.as_ref().map_or("n/a".to_owned(), |s| {
                format!("{:.4} ({:.4})", s.brier.1, s.brier.0)
            });
            writeln!(
                out,
                "| {tosses} ({}) | {fitted} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} ({:.2} to {:.2}) | {:.3} | {:.3} | {brier} |",
                f.gain.units,
                f.ensemble.position,
                f.ensemble.rotation,
                f.replay.position,
                f.replay.rotation,
                f.gain.mean,
                f.gain.interval[0],
                f.gain.interval[1],
                f.ensemble.coverage[0],
                f.ensemble.coverage[1],
            )?;
        }
        writeln!(
            out,
            "\nThe second fold's extended model: {}.\n",
            second.variation.join(", ")
        )
    }
}
