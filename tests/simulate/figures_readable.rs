//! Figures people read: contacts of a millisecond tens of milliseconds apart
//! each get a panel on their own time scale, windowed from the detected events; every
//! curve of a figure is told apart by its dashes as well as its colour (greyscale); a
//! curve given its own stroke is drawn as asked. Read from the SVG text: each panel is a
//! `<g class="panel" data-x="low high" …>` group, each curve a polyline naming its
//! dashes in `data-dash`.

use hcm_host::figure::rigid_figures;
use hcm_host::figure::{event_figure, EventSpan, Quantity};
use hcm_host::figure::{Colour, Figure, Series, Stroke};
use hcm_host::simulate::simulate;

/// A panel read from the SVG: its x range (data units) and its polylines' (stroke
/// colour, data-dash) in drawing order.
type PanelRead = ((f64, f64), Vec<(String, String)>);

/// Each panel group of `svg`.
fn panels(svg: &str) -> Vec<PanelRead> {
    let attribute = |line: &str, name: &str| -> String {
        let key = format!("{name}=\"");
        let rest = line.split(&key).nth(1).unwrap_or("");
        rest.split('"').next().unwrap_or("").to_owned()
    };
    let mut out: Vec<PanelRead> = Vec::new();
    for line in svg.lines() {
        if line.starts_with("<g class=\"panel\"") {
            let x: Vec<f64> = attribute(line, "data-x")
                .split(' ')
                .map(|v| v.parse().expect("a number"))
                .collect();
            out.push(((x[0], x[1]), Vec::new()));
        } else if line.starts_with("<polyline") {
            let curve = (attribute(line, "stroke"), attribute(line, "data-dash"));
            out.last_mut()
                .expect("a polyline inside a panel")
                .1
                .push(curve);
        }
    }
    out
}

#[test]
fn the_peg_in_hole_run_gets_one_panel_per_detected_event_around_it() {
    let model = hcm_tests::peg_in_hole().model().expect("the peg resolves");
    let simulation = simulate(&model).expect("the peg runs");
    let events = &simulation.events;
    // The shipped peg makes two wall contacts and the landing: three events, each a
    // millisecond or a few long, tens of milliseconds apart.
    assert_eq!(events.len(), 3, "{events:?}");
    let figures = rigid_figures(&model, &simulation);
    let figure = figures
        .iter()
        .find(|f| f.stem == "contact_events")
        .expect("a figure over the events");
    let svg = figure.figure.svg();
    let found = panels(&svg);
    // Force and torque rows, one column per event.
    assert_eq!(found.len(), 2 * events.len());
    for (k, event) in events.iter().enumerate() {
        let touch_down = 1e3 * event.touch_down;
        let lift_off = 1e3 * event.lift_off.expect("every event ends");
        let duration = lift_off - touch_down;
        for row in 0..2 {
            let ((low, high), curves) = &found[row * events.len() + k];
            assert!(
                *low <= touch_down && lift_off <= *high,
                "event {k}: {low}–{high} ms misses {touch_down}–{lift_off} ms"
            );
            // Its own time scale: a few durations, not the run's 70 ms.
            assert!(
                high - low <= 4.0 * duration,
                "event {k}: {low}–{high} ms for {duration} ms"
            );
            assert!(!curves.is_empty());
        }
    }
    // The image grows with the panels: wider and taller than a plain figure.
    let (width, height) = figure.figure.size();
    assert!(width > 720 && height > 440, "{width} × {height}");
}

#[test]
fn every_curve_of_a_figure_has_its_own_dashes_and_a_chosen_stroke_is_kept() {
    let wave = |a: f64| (0..100).map(move |i| (i as f64, a * (i as f64 / 9.0).sin()));
    let series = |label, colour, a| Series::new(label, Colour::hex(colour), wave(a).collect());
    let figure = Figure::new(
        "t",
        "x (s)",
        "y (N)",
        vec![
            series("a", 0xd62728, 1.0),
            series("b", 0x1f77b4, 2.0),
            series("c", 0x2ca02c, 3.0),
            series("d", 0xff7f0e, 4.0),
        ],
    );
    let found = panels(&figure.svg());
    let dashes: Vec<&str> = found[0].1.iter().map(|c| c.1.as_str()).collect();
    assert_eq!(dashes, ["solid", "dashed", "dotted", "dash-dot"]);
    // A measured mean given thick dots, last, keeps them; the others stay distinct.
    let mean = Stroke::MEASURED;
    let figure = Figure::new(
        "t",
        "x (s)",
        "y (N)",
        vec![
            series("PM2", 0xd62728, 1.0),
            series("HCM", 0x1f77b4, 1.1),
            series("S2 mean", 0x000000, 1.05),
        ],
    )
    .with_stroke("S2 mean", mean);
    let svg = figure.svg();
    let found = panels(&svg);
    let curves = &found[0].1;
    assert_eq!(curves.last().unwrap(), &("#000000".into(), "dotted".into()));
    assert_eq!(curves[0].1, "solid");
    assert_eq!(curves[1].1, "dashed");
    assert!(svg.contains(r##"stroke="#000000" stroke-width="3""##));
}

#[test]
fn an_event_figure_windows_each_panel_on_its_event_and_names_each_curve_once() {
    // Two contacts of 1 ms and 3 ms, 27 ms apart, on curves sampled every 20 µs.
    let pulse = |at: f64, long: f64, t: f64| {
        if (at..=at + long).contains(&t) {
            (std::f64::consts::PI * (t - at) / long).sin()
        } else {
            0.0
        }
    };
    let curve = |scale: f64| -> Vec<(f64, f64)> {
        (0..2000)
            .map(|i| {
                let t = -2.0 + 0.02 * i as f64;
                (t, scale * (pulse(0.0, 1.0, t) + pulse(27.0, 3.0, t)))
            })
            .collect()
    };
    let events = [
        EventSpan {
            touch_down: 0.0,
            lift_off: 1.0,
        },
        EventSpan {
            touch_down: 27.0,
            lift_off: 30.0,
        },
    ];
    let named: Vec<(String, EventSpan)> = (events.iter())
        .enumerate()
        .map(|(k, e)| (format!("contact {}", k + 1), *e))
        .collect();
    let quantity = |y: &str| Quantity {
        x_label: "time (ms)".into(),
        y_label: y.into(),
        series: vec![
            Series::new("model", Colour::hex(0xd62728), curve(1.0)),
            Series::new("mean", Colour::hex(0x000000), curve(1.01)),
        ],
        zero_line: false,
    };
    let figure = event_figure("t", &named, &[quantity("F (N)"), quantity("T (N·m)")]);
    let svg = figure.svg();
    let found = panels(&svg);
    assert_eq!(found.len(), 4);
    for (i, ((low, high), curves)) in found.iter().enumerate() {
        let event = events[i % 2];
        let duration = event.lift_off - event.touch_down;
        assert!(*low <= event.touch_down && event.lift_off <= *high, "{i}");
        assert!(high - low <= 4.0 * duration, "{i}: {low}–{high}");
        assert_eq!(curves.len(), 2);
        assert_ne!(curves[0].1, curves[1].1);
    }
    // One legend entry per label for the four panels: each label's text once.
    assert_eq!(svg.matches(">model</text>").count(), 1);
    assert_eq!(svg.matches(">mean</text>").count(), 1);
}
