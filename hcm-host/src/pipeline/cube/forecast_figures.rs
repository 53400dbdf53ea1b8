//! The forecast's figures: one held-out toss's recorded centre over its ensemble's
//! central 50 % and 90 % bands, and the calibration curve — each band level's share of
//! the held-out tosses' recorded coordinates inside it, against the level.

use super::forecast::{ForecastResults, ShownToss};
use crate::figure::{Colour, Dash, Figure, Panel, Series, Stroke};
use crate::numerics::scores::calibrated_coverage;
use crate::pipeline::NamedFigure;

/// The forecast stage's figures: the calibration curve, and the bands of the toss of
/// median score where its members all ran.
pub(crate) fn forecast_figures(f: &ForecastResults) -> Vec<NamedFigure> {
    let mut figures = vec![calibration(f)];
    if let Some(shown) = &f.shown {
        figures.push(bands(shown, f.members));
    }
    figures
}

/// Observed against nominal coverage (%), beside what a calibrated ensemble of as many
/// members holds (the level itself, but for a band wider than the members reach).
fn calibration(f: &ForecastResults) -> NamedFigure {
    let points = |share: &dyn Fn(f64, f64) -> f64| -> Vec<(f64, f64)> {
        (f.ensemble.calibration.iter())
            .map(|&(level, observed)| (100.0 * level, 100.0 * share(level, observed)))
            .collect()
    };
    let series = vec![
        Series::new(
            "calibrated",
            Colour::hex(0x7f7f7f),
            points(&|level, _| calibrated_coverage(f.members, level)),
        ),
        Series::new(
            "extended model",
            Colour::hex(0x1f77b4),
            points(&|_, observed| observed),
        ),
    ];
    let figure = Figure::new(
        &format!(
            "Calibration on {} held-out tosses ({} members): recorded x, y, z inside the central band",
            f.gain.units, f.members
        ),
        "nominal band level (%)",
        "recorded coordinates inside (%)",
        series,
    )
    .with_stroke("calibrated", Stroke::dashed(Dash::Dashed))
    .with_stroke("extended model", Stroke::dashed(Dash::Solid));
    NamedFigure {
        stem: "forecast_calibration",
        figure,
    }
}

/// The toss's recorded x, y and z (mm) over time, each over the members' 50 % and 90 %
/// bands, one panel per coordinate.
fn bands(shown: &ShownToss, members: usize) -> NamedFigure {
    const LINES: [(&str, u32, Dash); 3] = [
        ("90 % band", 0xfdae6b, Dash::Dotted),
        ("50 % band", 0xe6550d, Dash::Dashed),
        ("recorded", 0x08306b, Dash::Solid),
    ];
    let panels = (0..3)
        .map(|axis| {
            let curve = |value: &dyn Fn(usize) -> f64| -> Vec<(f64, f64)> {
                (shown.time.iter().enumerate())
                    .map(|(i, &t)| (t, 1e3 * value(i)))
                    .collect()
            };
            let mut series = Vec::new();
            // The 90 % band (BAND_LEVELS' second) under the 50 % band (its first).
            for (band, (label, colour, _)) in [(1, LINES[0]), (0, LINES[1])] {
                let colour = Colour::hex(colour);
                series.push(Series::new(
                    label,
                    colour,
                    curve(&|i| shown.bands[i][axis][band].0),
                ));
                series.push(Series::new(
                    "",
                    colour,
                    curve(&|i| shown.bands[i][axis][band].1),
                ));
            }
            let (label, colour, _) = LINES[2];
            series.push(Series::new(
                label,
                Colour::hex(colour),
                curve(&|i| shown.recorded[i][axis]),
            ));
            let name = ["x", "y", "z"][axis];
            Panel::new(
                name,
                "time since the window start (s)",
                &format!("{name} (mm)"),
                series,
            )
        })
        .collect();
    let figure = LINES.iter().fold(
        Figure::grid(
            &format!(
                "Held-out toss {}: the recorded centre over the forecast's bands ({members} members)",
                shown.run
            ),
            3,
            panels,
        ),
        |figure, (label, _, dash)| figure.with_stroke(label, Stroke::dashed(*dash)),
    );
    NamedFigure {
        stem: "forecast_bands",
        figure,
    }
}
