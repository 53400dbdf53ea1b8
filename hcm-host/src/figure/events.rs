//! Curves over contact events, one panel per event on its own time scale: contacts of a
//! millisecond some tens of milliseconds apart would be spikes on one time axis. Each
//! event's window runs from its touch-down to its lift-off, widened on both sides by a
//! share of its duration; each quantity (force, torque, …) is a row of panels.

use super::{Figure, Panel, Series};

/// Margin of an event's window on each side, as a share of its duration (–).
pub const MARGIN: f64 = 0.4;
/// Events per row of panels: with more, the rows of quantities repeat under each other.
const COLUMNS: usize = 3;

/// A contact event: touch-down and lift-off, in the x unit of the curves (e.g. ms).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventSpan {
    /// Touch-down.
    pub touch_down: f64,
    /// Lift-off (after the touch-down).
    pub lift_off: f64,
}

impl EventSpan {
    /// The event's window: touch-down − [`MARGIN`] × duration to lift-off + [`MARGIN`] ×
    /// duration (x units); a duration of 0 widens by 1 % of |touch-down| (or 1e-3).
    pub fn window(&self) -> (f64, f64) {
        let duration = self.lift_off - self.touch_down;
        let margin = if duration > 0.0 {
            MARGIN * duration
        } else {
            1e-2 * self.touch_down.abs().max(0.1)
        };
        (self.touch_down - margin, self.lift_off + margin)
    }
}

/// One quantity drawn over every event: its curves over the whole run, its axis titles
/// (with units) and whether its panels show y = 0.
pub struct Quantity<'a> {
    /// Title of the x axis, e.g. `time since the first wall contact (ms)`.
    pub x_label: String,
    /// Title of the y axis, e.g. `‖F‖ (N)`.
    pub y_label: String,
    /// The curves over the whole run (x in the events' unit).
    pub series: Vec<Series<'a>>,
    /// Draw the line y = 0 (for differences).
    pub zero_line: bool,
}

/// The figure titled `title` with one column per event (named by `names`, one per
/// event) and one row per quantity: each panel shows the quantity's curves cut to the
/// event's window ([`EventSpan::window`]). Events beyond three per row wrap onto
/// further rows of the quantities.
pub fn event_figure<'a>(
    title: &str,
    events: &[(String, EventSpan)],
    quantities: &[Quantity<'a>],
) -> Figure<'a> {
    let columns = events.len().clamp(1, COLUMNS);
    let mut panels = Vec::new();
    for group in events.chunks(columns) {
        for (row, quantity) in quantities.iter().enumerate() {
            for (name, event) in group {
                let series = quantity
                    .series
                    .iter()
                    .map(|s| within(s, event.window()))
                    .collect();
                let title = if row == 0 { name.as_str() } else { "" };
                let panel = Panel::new(title, &quantity.x_label, &quantity.y_label, series);
                panels.push(if quantity.zero_line {
                    panel.with_zero_line()
                } else {
                    panel
                });
            }
            // A short last group leaves the rest of its rows empty.
            for _ in group.len()..columns {
                panels.push(Panel::new("", "", "", Vec::new()));
            }
        }
    }
    Figure::grid(title, columns, panels)
}

/// `series` with only its points of x within `window` (ends included).
fn within<'a>(series: &Series<'a>, (low, high): (f64, f64)) -> Series<'a> {
    Series {
        label: series.label,
        colour: series.colour,
        points: (series.points.iter())
            .copied()
            .filter(|p| (low..=high).contains(&p.0))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::Colour;

    #[test]
    fn an_event_window_holds_the_event_with_a_margin_of_its_duration() {
        let event = EventSpan {
            touch_down: 27.0,
            lift_off: 30.0,
        };
        let (low, high) = event.window();
        assert!((low - 25.8).abs() < 1e-12 && (high - 31.2).abs() < 1e-12);
        let instant = EventSpan {
            touch_down: 5.0,
            lift_off: 5.0,
        };
        let (low, high) = instant.window();
        assert!(low < 5.0 && high > 5.0);
    }

    #[test]
    fn each_event_gets_a_column_and_each_quantity_a_row() {
        let curve = |label| Series {
            label,
            colour: Colour::BLACK,
            points: (0..400).map(|i| (0.1 * i as f64, 1.0)).collect(),
        };
        let span = |t: f64| EventSpan {
            touch_down: t,
            lift_off: t + 1.0,
        };
        let events: Vec<(String, EventSpan)> = [1.0, 20.0, 30.0, 35.0]
            .iter()
            .map(|&t| (format!("at {t}"), span(t)))
            .collect();
        let quantity = |y: &str| Quantity {
            x_label: "t (ms)".into(),
            y_label: y.into(),
            series: vec![curve("a"), curve("b")],
            zero_line: false,
        };
        let figure = event_figure("t", &events, &[quantity("F (N)"), quantity("T (N·m)")]);
        // Four events: three columns, two groups of two rows.
        assert_eq!(figure.columns, 3);
        assert_eq!(figure.panels.len(), 12);
        let panel = &figure.panels[4];
        assert_eq!(panel.y_label, "T (N·m)");
        assert!(panel.title.is_empty() && figure.panels[1].title == "at 20");
        let xs: Vec<f64> = panel.series[0].points.iter().map(|p| p.0).collect();
        assert!(xs.iter().all(|&x| (19.59..=21.41).contains(&x)), "{xs:?}");
        assert!(figure.panels[7].series.is_empty() && figure.panels[6].title == "at 35");
    }
}
