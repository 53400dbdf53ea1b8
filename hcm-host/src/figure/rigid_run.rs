//! The figures of a 3D run (`hcm simulate --figures`): a side view of the moving bodies'
//! motion among the fixed ones (`trajectory`), and the contact force and torque on the
//! moving bodies over time with each contact event's touch-down marked (`contact_force`,
//! `contact_torque`), and both over each of the first events on its own time scale
//! (`contact_events`: a contact of a millisecond is a spike on the run's time axis).

use super::events::{event_figure, EventSpan, Quantity};
use super::side_view::{plane_trace, shape_outlines, Outline};
use super::style::{Dash, Stroke};
use super::NamedFigure;
use super::{Colour, Figure, Series};
use crate::dataset::{BodyTrack, Sample};
use crate::scenario::{Model, Shape};
use crate::simulate::Simulation;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// Events given a panel of their own in `contact_events`: the first ones (a body coming
/// to rest may touch down many times).
pub(crate) const MAX_EVENT_PANELS: usize = 6;
/// Touch-downs per body at which its outline is drawn: the first ones (a body coming to
/// rest may touch down many times; more outlines would hide each other).
pub(crate) const MAX_TOUCH_DOWN_OUTLINES: usize = 6;
/// Millimetres per metre: the side view is drawn in mm.
const MM: f64 = 1e3;
/// Margin around the drawn bodies over which a plane's trace runs, as a fraction of
/// the larger side of their bounding box.
const PLANE_MARGIN: f64 = 0.15;

const PATH: Colour = Colour::hex(0x1f77b4);
const FIXED: Colour = Colour::hex(0x555555);
const START: Colour = Colour::hex(0x2ca02c);
const TOUCH_DOWN: Colour = Colour::hex(0xff7f0e);
const END: Colour = Colour::hex(0xd62728);
const MARK: Colour = Colour::hex(0x999999);

/// The four figures of a 3D run of `model`: `trajectory`, `contact_force`,
/// `contact_torque`, `contact_events`.
pub fn rigid_figures(model: &Model, simulation: &Simulation) -> Vec<NamedFigure> {
    let name = &model.scenario.name;
    let force = |s: &Sample| s.force;
    let torque = |s: &Sample| s.torque;
    vec![
        NamedFigure {
            stem: "trajectory",
            figure: trajectory(model, simulation),
        },
        NamedFigure {
            stem: "contact_force",
            figure: wrench(
                &format!("{name}: contact force on the moving body"),
                "contact force ‖F‖ (N)",
                "‖F‖ on the moving body",
                simulation,
                &force,
            ),
        },
        NamedFigure {
            stem: "contact_torque",
            figure: wrench(
                &format!("{name}: contact torque about the centre of mass"),
                "contact torque ‖T‖ (N·m)",
                "‖T‖ on the moving body",
                simulation,
                &torque,
            ),
        },
        NamedFigure {
            stem: "contact_events",
            figure: per_event(model, simulation),
        },
    ]
}

/// ‖F‖ (N) and ‖T‖ (N·m) on every recorded body over each of the first
/// `MAX_EVENT_PANELS` (6) contact events, one column per event on its own time scale (ms).
pub fn per_event(model: &Model, simulation: &Simulation) -> Figure<'static> {
    let ms = |s: &Sample| 1e3 * s.time;
    let norms = |y_label: &'static str, component: fn(&Sample) -> [f64; 3]| {
        let series = (simulation.run.bodies.iter())
            .map(|track| {
                let points = track.samples.iter();
                let points = points.map(|s| (ms(s), Vector3::from(component(s)).norm()));
                curve("moving body", PATH, points.collect())
            })
            .collect();
        (y_label, series)
    };
    let quantities = [
        norms("‖F‖ (N)", |s| s.force),
        norms("‖T‖ about the centre of mass (N·m)", |s| s.torque),
    ]
    .map(|(y_label, series)| Quantity {
        x_label: "time (ms)".to_owned(),
        y_label: y_label.to_owned(),
        series,
        zero_line: false,
    });
    let events: Vec<(String, EventSpan)> = (simulation.events.iter())
        .take(MAX_EVENT_PANELS)
        .enumerate()
        .map(|(k, e)| {
            let c = &model.contacts[e.contact];
            let pair = format!(
                "{}–{}",
                model.bodies[c.body_1].name, model.bodies[c.body_2].name
            );
            let lift_off = e.lift_off.unwrap_or(simulation.end_time);
            let span = EventSpan {
                touch_down: 1e3 * e.touch_down,
                lift_off: 1e3 * lift_off,
            };
            let name = format!(
                "event {}, {pair}: {:.2} ms long",
                k + 1,
                span.lift_off - span.touch_down
            );
            (name, span)
        })
        .collect();
    let shown = if simulation.events.len() > MAX_EVENT_PANELS {
        format!(
            " (the first {MAX_EVENT_PANELS} of {})",
            simulation.events.len()
        )
    } else {
        String::new()
    };
    let title = format!(
        "{}: contact force and torque on the moving body, each event on its own time scale{shown}",
        model.scenario.name
    );
    event_figure(&title, &events, &quantities)
}

/// The side view (x–z, mm, equal scales): each recorded body's centre-of-mass path and
/// its outline at the start, at its first touch-downs and at the end; every fixed body's
/// outline (a plane's trace in the section y = the first recorded body's start y).
pub fn trajectory(model: &Model, simulation: &Simulation) -> Figure<'static> {
    let tracks: Vec<&BodyTrack> = simulation
        .run
        .bodies
        .iter()
        .filter(|t| !t.samples.is_empty())
        .collect();
    let mut series = Vec::new();
    for track in &tracks {
        let path = track.samples.iter().map(|s| (s.position[0], s.position[2]));
        series.push(curve("centre of mass", PATH, path.collect()));
    }
    let mut moving = Vec::new();
    for track in &tracks {
        moving.extend(instants(model, simulation, track));
    }
    let mut fixed: Vec<Outline> = model
        .bodies
        .iter()
        .filter(|b| b.fixed)
        .flat_map(|b| shape_outlines(&b.shape, &b.position, &b.orientation))
        .collect();
    let window = padded_window(
        series
            .iter()
            .map(|s| &s.points)
            .chain(&fixed)
            .chain(moving.iter().map(|m| &m.1)),
    );
    let section = tracks.first().map_or(0.0, |t| t.samples[0].position[1]);
    for body in model.bodies.iter().filter(|b| b.fixed) {
        if let Shape::Plane { normal, offset } = &body.shape {
            let trace = plane_trace(
                normal,
                *offset,
                &body.position,
                &body.orientation,
                section,
                window,
            );
            fixed.extend(trace.map(|t| t.to_vec()));
        }
    }
    series.extend(fixed.into_iter().map(|o| curve("fixed bodies", FIXED, o)));
    series.extend(
        moving
            .into_iter()
            .map(|(label, o, colour)| curve(label, colour, o)),
    );
    for s in &mut series {
        s.points.iter_mut().for_each(|p| *p = (p.0 * MM, p.1 * MM));
    }
    let title = format!("{}: side view, looking along +y", model.scenario.name);
    Figure::new(&title, "x (mm)", "z (mm)", series)
        .with_equal_scales()
        .with_stroke("fixed bodies", Stroke::dashed(Dash::Solid))
}

/// The outlines of the body of `track` at the start, at its first touch-downs and at
/// the end: (legend label, outline (m), colour).
fn instants(
    model: &Model,
    simulation: &Simulation,
    track: &BodyTrack,
) -> Vec<(&'static str, Outline, Colour)> {
    let Some(index) = model.body_index(&track.body) else {
        return Vec::new();
    };
    let shape = &model.bodies[index].shape;
    let touch_downs = simulation
        .events
        .iter()
        .filter(|e| {
            let c = &model.contacts[e.contact];
            c.body_1 == index || c.body_2 == index
        })
        .map(|e| e.touch_down)
        .take(MAX_TOUCH_DOWN_OUTLINES);
    let (first, last) = (&track.samples[0], &track.samples[track.samples.len() - 1]);
    let mut at = vec![("at start", first.time, START)];
    at.extend(touch_downs.map(|t| ("at touch-down", t, TOUCH_DOWN)));
    at.push(("at end", last.time, END));
    at.into_iter()
        .flat_map(|(label, time, colour)| {
            let (position, orientation) = pose_at(&track.samples, time);
            shape_outlines(shape, &position, &orientation)
                .into_iter()
                .map(move |o| (label, o, colour))
        })
        .collect()
}

/// The body's pose at `time` (s): position (m) and orientation interpolated between the
/// samples around it (linearly, and by slerp); the first or last sample outside them.
fn pose_at(samples: &[Sample], time: f64) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let pose = |s: &Sample| {
        let [w, i, j, k] = s.orientation;
        (
            Vector3::from(s.position),
            UnitQuaternion::new_normalize(Quaternion::new(w, i, j, k)),
        )
    };
    let after = samples.partition_point(|s| s.time <= time);
    if after == 0 || after == samples.len() {
        return pose(&samples[after.min(samples.len() - 1)]);
    }
    let (a, b) = (&samples[after - 1], &samples[after]);
    let f = (time - a.time) / (b.time - a.time);
    let ((pa, qa), (pb, qb)) = (pose(a), pose(b));
    (pa.lerp(&pb, f), qa.try_slerp(&qb, f, 1e-12).unwrap_or(qa))
}

/// `‖component(sample)‖` of every recorded body over time (legend `label`), with a vertical line from 0
/// to the largest value at each contact event's touch-down.
fn wrench(
    title: &str,
    y_label: &str,
    label: &'static str,
    simulation: &Simulation,
    component: &dyn Fn(&Sample) -> [f64; 3],
) -> Figure<'static> {
    let norms: Vec<Series<'static>> = simulation
        .run
        .bodies
        .iter()
        .map(|track| {
            let points = track
                .samples
                .iter()
                .map(|s| (s.time, Vector3::from(component(s)).norm()));
            curve(label, PATH, points.collect())
        })
        .collect();
    let top = norms
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    // The marks first, so that the curves are drawn over them.
    let mut series: Vec<Series<'static>> = simulation
        .events
        .iter()
        .map(|e| {
            curve(
                "touch-down",
                MARK,
                vec![(e.touch_down, 0.0), (e.touch_down, top)],
            )
        })
        .collect();
    series.extend(norms);
    let mark = Stroke {
        width: 1.2,
        dash: Dash::Dashed,
    };
    Figure::new(title, "time (s)", y_label, series)
        .with_stroke("touch-down", mark)
        .with_stroke(label, Stroke::dashed(Dash::Solid))
}

fn curve(label: &'static str, colour: Colour, points: Vec<(f64, f64)>) -> Series<'static> {
    Series {
        label,
        colour,
        points,
    }
}

/// The bounding box of every finite point of `curves` (m), padded on every side by
/// [`PLANE_MARGIN`] of its larger side (0.05 m if it is a point, ±0.05 m without points):
/// ((x low, x high),
/// (z low, z high)).
fn padded_window<'a>(
    curves: impl Iterator<Item = &'a Vec<(f64, f64)>>,
) -> ((f64, f64), (f64, f64)) {
    let mut x = (f64::INFINITY, f64::NEG_INFINITY);
    let mut z = x;
    for &(px, pz) in curves
        .flatten()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
    {
        x = (x.0.min(px), x.1.max(px));
        z = (z.0.min(pz), z.1.max(pz));
    }
    if x.0 > x.1 {
        return ((-0.05, 0.05), (-0.05, 0.05));
    }
    let side = (x.1 - x.0).max(z.1 - z.0);
    let margin = if side > 0.0 {
        PLANE_MARGIN * side
    } else {
        0.05
    };
    ((x.0 - margin, x.1 + margin), (z.0 - margin, z.1 + margin))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(time: f64, x: f64, angle: f64) -> Sample {
        let q = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), angle);
        Sample {
            position: [x, 0.0, 2.0 * x],
            orientation: [q.w, q.i, q.j, q.k],
            ..Sample::at_rest(time)
        }
    }

    #[test]
    fn a_pose_between_samples_is_interpolated_and_held_outside_them() {
        let samples = [
            sample(0.0, 0.0, 0.0),
            sample(1.0, 1.0, 0.4),
            sample(2.0, 1.0, 0.4),
        ];
        let (p, q) = pose_at(&samples, 0.25);
        assert!((p - Vector3::new(0.25, 0.0, 0.5)).norm() < 1e-12);
        assert!((q.angle() - 0.1).abs() < 1e-12, "{}", q.angle());
        let (p, _) = pose_at(&samples, -1.0);
        assert_eq!(p, Vector3::zeros());
        let (p, q) = pose_at(&samples, 9.0);
        assert_eq!(p, Vector3::new(1.0, 0.0, 2.0));
        assert!((q.angle() - 0.4).abs() < 1e-12);
    }

    #[test]
    fn the_plane_window_pads_the_drawing() {
        let curves = [vec![(0.0, 0.0), (0.2, 0.1)], vec![(f64::NAN, 5.0)]];
        let ((x0, x1), (z0, z1)) = padded_window(curves.iter());
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(close(x0, -0.03) && close(x1, 0.23) && close(z0, -0.03) && close(z1, 0.13));
        assert_eq!(padded_window([].iter()), ((-0.05, 0.05), (-0.05, 0.05)));
    }
}
