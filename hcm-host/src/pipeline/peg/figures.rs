//! The peg-in-hole's figures: the contact force and torque of S2's mean and of each
//! model's replay, one panel per wall contact on its own time scale (the contacts last
//! about a millisecond, tens of milliseconds apart), the models' errors alike, and the
//! peg's path through the hole. The measured mean is drawn last, thick and dotted, so
//! that no model's curve hides it; PM2 is solid and the HCM dashed, so the three read
//! in greyscale too.

use super::curves::WrenchCurve;
use crate::figure::{event_figure, EventSpan, Quantity};
use crate::figure::{Colour, Figure, Series, Stroke};
use crate::identify::EventTarget;
use crate::pipeline::NamedFigure;

/// Colours: S2 mean, then the models.
const COLOURS: [u32; 4] = [0x000000, 0xd62728, 0x1f77b4, 0x2ca02c];

/// The S2 mean's label and stroke: thick dots, drawn over the models' lines.
const MEAN: (&str, Stroke) = ("S2 mean", Stroke::MEASURED);

/// The x axis of every figure over time.
const T_LABEL: &str = "time since the first wall contact (ms)";

/// Each measured event's touch-down and lift-off (ms after the first touch-down): its
/// mean delay and mean duration over S2's runs.
pub(super) fn event_spans(events: &[EventTarget]) -> Vec<EventSpan> {
    events
        .iter()
        .map(|e| EventSpan {
            touch_down: 1e3 * e.delay,
            lift_off: 1e3 * (e.delay + e.statistics.duration.mean),
        })
        .collect()
}

/// The times of a curve's samples (ms).
fn milliseconds(c: &WrenchCurve) -> Vec<f64> {
    c.time.iter().map(|t| 1e3 * t).collect::<Vec<_>>()
}

/// A curve's `values` against time (ms).
fn over_time(values: fn(&WrenchCurve) -> &Vec<f64>) -> impl Fn(&WrenchCurve) -> Vec<(f64, f64)> {
    move |c: &WrenchCurve| {
        milliseconds(c)
            .into_iter()
            .zip(values(c).iter().copied())
            .collect()
    }
}

/// `mean − curve` of a curve's `values` against time (ms).
fn error_against(
    mean: &WrenchCurve,
    values: fn(&WrenchCurve) -> &Vec<f64>,
) -> impl Fn(&WrenchCurve) -> Vec<(f64, f64)> + '_ {
    move |c: &WrenchCurve| -> Vec<(f64, f64)> {
        milliseconds(c)
            .into_iter()
            .zip(values(mean).iter().zip(values(c)).map(|(m, v)| m - v))
            .collect()
    }
}

/// The curves the figures draw, and S2's mean the errors are taken against.
struct Panels<'c> {
    /// S2's mean and the models drawn (the int8 HCM overlaps the f32 one at these
    /// scales: drawn in the table only).
    shown: Vec<&'c (&'static str, WrenchCurve)>,
    /// S2's mean curve.
    mean: &'c WrenchCurve,
}

impl Panels<'_> {
    /// One series per curve shown, of the points `pick` takes from it: the models
    /// first, S2's mean last (drawn over them).
    fn series(&self, pick: &dyn Fn(&WrenchCurve) -> Vec<(f64, f64)>) -> Vec<Series<'static>> {
        let mut all = self.errors(pick);
        if let Some((label, curve)) = self.shown.first() {
            all.push(Series {
                label,
                colour: Colour::hex(COLOURS[0]),
                points: pick(curve),
            });
        }
        all
    }

    /// The models' series of `pick` (S2's mean left out).
    fn errors(&self, pick: &dyn Fn(&WrenchCurve) -> Vec<(f64, f64)>) -> Vec<Series<'static>> {
        (self.shown.iter().zip(COLOURS))
            .skip(1)
            .map(|((label, curve), colour)| Series {
                label,
                colour: Colour::hex(colour),
                points: pick(curve),
            })
            .collect()
    }
}

/// Each event's panel title: its number, touch-down and duration (ms).
fn names(events: &[EventSpan]) -> Vec<(String, EventSpan)> {
    (events.iter().enumerate())
        .map(|(k, e)| {
            let name = format!(
                "wall contact {}: from {:.2} ms, {:.2} ms long (S2 mean)",
                k + 1,
                e.touch_down,
                e.lift_off - e.touch_down
            );
            (name, *e)
        })
        .collect()
}

/// ‖F‖ (N) and ‖T‖ (N·m) over each wall contact, S2 mean and models.
fn wrench_figure(panels: &Panels<'_>, events: &[EventSpan]) -> NamedFigure {
    let quantity = |y_label: &str, values| Quantity {
        x_label: T_LABEL.to_owned(),
        y_label: y_label.to_owned(),
        series: panels.series(&over_time(values)),
        zero_line: false,
    };
    let title = "Contact force and torque on the peg, each wall contact on its own time scale";
    let quantities = [
        quantity("‖F‖ (N)", force_norms),
        quantity("‖T‖ about the centre of mass (N·m)", torque_norms),
    ];
    NamedFigure {
        stem: "contact_force",
        figure: event_figure(title, &names(events), &quantities).with_stroke(MEAN.0, MEAN.1),
    }
}

/// The models' errors over each wall contact, S2 mean − model: of ‖F‖ (N) and of ‖T‖
/// (N·m).
fn error_figure(panels: &Panels<'_>, events: &[EventSpan]) -> NamedFigure {
    let quantity = |y_label: &str, values| Quantity {
        x_label: T_LABEL.to_owned(),
        y_label: y_label.to_owned(),
        series: panels.errors(&error_against(panels.mean, values)),
        zero_line: true,
    };
    let quantities = [
        quantity("‖F‖ error (N)", force_norms),
        quantity("‖T‖ error (N·m)", torque_norms),
    ];
    NamedFigure {
        stem: "force_error",
        figure: event_figure(
            "Force and torque error, S2 mean − model, over each wall contact",
            &names(events),
            &quantities,
        ),
    }
}

/// The peg's centre of mass in the x–z plane (mm), S2 mean and models.
fn path_figure(panels: &Panels<'_>) -> NamedFigure {
    NamedFigure {
        stem: "peg_path",
        figure: Figure::new(
            "The peg's centre of mass through the hole (side view, x stretched)",
            "x (mm)",
            "z (mm)",
            panels.series(&|c: &WrenchCurve| {
                c.x.iter()
                    .zip(&c.z)
                    .map(|(x, z)| (1e3 * x, 1e3 * z))
                    .collect()
            }),
        )
        .with_stroke(MEAN.0, MEAN.1),
    }
}

/// A curve's force norms (N).
fn force_norms(c: &WrenchCurve) -> &Vec<f64> {
    &c.force
}

/// A curve's torque norms (N·m).
fn torque_norms(c: &WrenchCurve) -> &Vec<f64> {
    &c.torque
}

/// ‖F‖ and ‖T‖ over each of `events` (S2 mean and models), their errors (S2 mean −
/// model), and the peg's path in the x–z plane. `curves` holds S2's mean first.
pub(super) fn figures(
    curves: &[(&'static str, WrenchCurve)],
    events: &[EventSpan],
) -> Vec<NamedFigure> {
    let panels = Panels {
        shown: curves.iter().take(3).collect(),
        mean: &curves[0].1,
    };
    vec![
        wrench_figure(&panels, events),
        error_figure(&panels, events),
        path_figure(&panels),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A curve of 20 µs samples from −2 ms to 35 ms with pulses of 1 ms at 0 and of
    /// 3 ms at 27 ms, scaled by `scale`.
    fn curve(scale: f64) -> WrenchCurve {
        let time: Vec<f64> = (0..1850).map(|j| -2e-3 + 20e-6 * j as f64).collect();
        let pulse = |t: f64, at: f64, long: f64| {
            if (at..=at + long).contains(&t) {
                (std::f64::consts::PI * (t - at) / long).sin()
            } else {
                0.0
            }
        };
        let force: Vec<f64> = (time.iter())
            .map(|&t| scale * (pulse(t, 0.0, 1e-3) + pulse(t, 27e-3, 3e-3)))
            .collect();
        WrenchCurve {
            torque: force.iter().map(|f| 0.03 * f).collect(),
            x: vec![0.0; time.len()],
            z: vec![0.0; time.len()],
            force,
            time,
        }
    }

    #[test]
    fn the_wrench_figure_has_a_panel_per_event_with_the_mean_drawn_last_in_dots() {
        let curves = [
            ("S2 mean", curve(1.0)),
            ("PM2", curve(0.9)),
            ("HCM", curve(1.01)),
        ];
        let events = [
            EventSpan {
                touch_down: 0.0,
                lift_off: 0.96,
            },
            EventSpan {
                touch_down: 27.25,
                lift_off: 30.5,
            },
        ];
        let figures = figures(&curves, &events);
        let stems: Vec<&str> = figures.iter().map(|f| f.stem).collect();
        assert_eq!(stems, ["contact_force", "force_error", "peg_path"]);
        let svg = figures[0].figure.svg();
        let groups: Vec<&str> = svg.split("<g class=\"panel\"").skip(1).collect();
        // Force and torque rows, one column per event.
        assert_eq!(groups.len(), 4);
        for (i, group) in groups.iter().enumerate() {
            let x = group
                .split("data-x=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap();
            let x: Vec<f64> = x.split(' ').map(|v| v.parse().unwrap()).collect();
            let e = events[i % 2];
            assert!(x[0] <= e.touch_down && e.lift_off <= x[1], "{i}: {x:?}");
            assert!(
                x[1] - x[0] <= 4.0 * (e.lift_off - e.touch_down),
                "{i}: {x:?}"
            );
            let lines: Vec<&str> = group
                .lines()
                .filter(|l| l.starts_with("<polyline"))
                .collect();
            assert_eq!(lines.len(), 3);
            assert!(lines[0].contains("data-dash=\"solid\"") && lines[0].contains("#d62728"));
            assert!(lines[1].contains("data-dash=\"dashed\"") && lines[1].contains("#1f77b4"));
            assert!(lines[2].contains("data-dash=\"dotted\"") && lines[2].contains("#000000"));
        }
        // The error figure: the models only, around the same events, with y = 0.
        let errors = figures[1].figure.svg();
        assert_eq!(errors.matches("<g class=\"panel\"").count(), 4);
        assert!(!errors.contains(">S2 mean</text>"));
    }
}
