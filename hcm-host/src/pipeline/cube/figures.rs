//! The report's figures: three held-out tosses (the fitted model's best, median and
//! worst by score, position % + rotation °) predicted beside their recorded paths —
//! seen from above and as height over time — and the held-out error over time of the
//! fitted model and of the scenario's parameters.

use super::errors::{recorded, TimePoint};
use super::stages::{Predictions, Timeline};
use super::CubeError;
use crate::dataset::{Dataset, Sample};
use crate::figure::{Colour, Dash, Figure, Series, Stroke};
use crate::pipeline::NamedFigure;
use crate::replay::{TossEvaluation, TossSetup};

/// The three tosses shown, with their legend labels and colours (recorded dark,
/// predicted light).
const SHOWN: [(&str, &str, u32, u32); 3] = [
    ("best, recorded", "best, predicted", 0x1f77b4, 0x9ecae1),
    ("median, recorded", "median, predicted", 0x2ca02c, 0xa1d99b),
    ("worst, recorded", "worst, predicted", 0xd62728, 0xfc9272),
];

/// The fitted model's best, median and worst held-out tosses (indices).
fn chosen(evaluations: &[TossEvaluation]) -> [usize; 3] {
    let score = |e: &TossEvaluation| e.score.position_error + e.score.rotation_error;
    let mut order: Vec<usize> = (0..evaluations.len()).collect();
    order.sort_by(|&a, &b| score(&evaluations[a]).total_cmp(&score(&evaluations[b])));
    let last = order.len().saturating_sub(1);
    [order[0], order[order.len() / 2], order[last]]
}

/// Every figure of the report.
pub fn toss_figures(
    setup: &TossSetup,
    held_out: &Dataset,
    predicted: &Predictions,
    timeline: &Timeline,
) -> Result<Vec<NamedFigure>, CubeError> {
    let fitted = &predicted.held_out_fitted;
    if fitted.is_empty() {
        return Ok(Vec::new());
    }
    let mut paths = Vec::new();
    for index in chosen(fitted) {
        let e = &fitted[index];
        paths.push((e, recorded(setup, held_out, e)?));
    }
    let runs: Vec<&str> = paths
        .iter()
        .map(|(e, _)| e.prediction.run.as_str())
        .collect();
    let tosses = runs.join(", ");
    let mm = |s: &Sample, axis: usize| 1e3 * s.position[axis];
    let path_series = |x: &dyn Fn(&Sample, f64) -> f64, y: &dyn Fn(&Sample) -> f64| {
        let mut series = Vec::new();
        for ((e, real), (real_label, model_label, dark, light)) in paths.iter().zip(SHOWN) {
            let t0 = real.first().map_or(0.0, |s| s.time);
            let line = |samples: &[Sample]| samples.iter().map(|s| (x(s, t0), y(s))).collect();
            series.push(Series {
                label: real_label,
                colour: Colour::hex(dark),
                points: line(real),
            });
            series.push(Series {
                label: model_label,
                colour: Colour::hex(light),
                points: line(&e.prediction.samples),
            });
        }
        series
    };
    let top = recorded_solid(
        Figure::new(
            &format!("Held-out tosses {tosses} from above (fitted model)"),
            "x (mm)",
            "y (mm)",
            path_series(&|s, _| mm(s, 0), &|s| mm(s, 1)),
        )
        .with_equal_scales(),
    );
    let height = recorded_solid(Figure::new(
        &format!("Held-out tosses {tosses}: height of the centre (fitted model)"),
        "time since the window start (s)",
        "z (mm)",
        path_series(&|s, t0| s.time - t0, &|s| mm(s, 2)),
    ));
    Ok(vec![
        NamedFigure {
            stem: "paths_top",
            figure: top,
        },
        NamedFigure {
            stem: "paths_height",
            figure: height,
        },
        error_figure(timeline, fitted.len(), true),
        error_figure(timeline, fitted.len(), false),
    ])
}

/// `figure` with every recorded path solid and every predicted one dashed, so that a
/// toss's two curves are told apart in greyscale as well as by their shades.
fn recorded_solid(figure: Figure<'static>) -> Figure<'static> {
    SHOWN.iter().fold(figure, |f, (recorded, predicted, _, _)| {
        f.with_stroke(recorded, Stroke::dashed(Dash::Solid))
            .with_stroke(predicted, Stroke::dashed(Dash::Dashed))
    })
}

/// The held-out mean position (or rotation) error over time, both models, where at
/// least a quarter of the tosses last.
fn error_figure(timeline: &Timeline, tosses: usize, position: bool) -> NamedFigure {
    let least = tosses.div_ceil(4).max(1);
    let curve = |points: &[TimePoint]| -> Vec<(f64, f64)> {
        (points.iter())
            .filter(|p| p.tosses >= least)
            .map(|p| (p.time, if position { p.position } else { p.rotation }))
            .collect()
    };
    let series = vec![
        Series {
            label: "fitted",
            colour: Colour::hex(0x1f77b4),
            points: curve(&timeline.fitted.over_time),
        },
        Series {
            label: "scenario's parameters",
            colour: Colour::hex(0xff7f0e),
            points: curve(&timeline.scenario.over_time),
        },
    ];
    let (stem, what, unit) = if position {
        (
            "error_position",
            "position error",
            "position error (% of the width)",
        )
    } else {
        ("error_rotation", "rotation error", "rotation error (°)")
    };
    let title = format!(
        "Held-out {what} over time, mean over the {tosses} tosses (shown while ≥ {least} last)"
    );
    NamedFigure {
        stem,
        figure: Figure::new(&title, "time since the window start (s)", unit, series)
            .with_zero_line(),
    }
}
