//! One panel laid out in its room of the image: its title on top, the plot area with
//! its round ticks, the x axis title under the tick labels and the y axis title turned
//! at the left. Margins are measured from the text they hold, so no label leaves the
//! room or runs into another; a plain figure is one panel filling the image under the
//! legend, a grid one panel per cell.

use super::aspect;
use super::font;
use super::layout::{
    extent, fit, spacing, tick_labels, widest, Anchor, Label, TextSize, GAP, INTERVALS,
    LABEL_SPACING, LINE_SPACING, PAD,
};
use super::plot::{finite, Plot, Rect};
use super::style::Stroke;
use super::ticks::Ticks;
use super::{Band, Panel};

/// What the figure adds to a panel's own curves.
pub(super) struct Look<'f, 'a> {
    /// The shaded band (the first panel's only).
    pub(super) band: Option<&'f Band<'a>>,
    /// Equal px per data unit along x and y.
    pub(super) equal_scales: bool,
    /// The stroke of each of the panel's curves, in order.
    pub(super) strokes: &'f [Stroke],
}

/// Lays `panel` out in `room` (px): its axes, with the curves drawn, and its texts
/// added to `labels`.
pub(super) fn lay_out(panel: &Panel, look: &Look, room: Rect, labels: &mut Vec<Label>) -> Plot {
    let normal = TextSize::Normal;
    let mut top = room.top;
    if !panel.title.is_empty() {
        let centre = 0.5 * (room.left + room.right);
        let baseline = top + font::ascent(normal.px());
        labels.push(Label::new(
            &panel.title,
            (centre, baseline),
            Anchor::Middle,
            normal,
        ));
        top = baseline + font::descent(normal.px()) + GAP;
    }
    let x_ticks = normal.x_tick_gap() + normal.line();
    let bottom = room.bottom - PAD - normal.line() - GAP - x_ticks;
    let axes = |x, y| axes(x, y, (top, bottom), (room.left, room.right));
    let (x, y) = (x_extent(panel, look.band), y_extent(panel, look.band));
    let (area, x, y) = if look.equal_scales {
        aspect::equal_scales(axes, x, y)
    } else {
        axes(x, y)
    };
    let mut plot = Plot::new(area, x, y);
    if let Some(band) = look.band {
        plot.draw_band(band);
    }
    if panel.zero_line {
        plot.draw_zero_line();
    }
    plot.draw_series(&panel.series, look.strokes);
    tick_labels(&plot, normal, labels);
    axis_titles(panel, &plot.area, room, labels);
    plot
}

/// The plot area between `top` and `bottom` and inside `left`–`right` (px), and the
/// ticks of the data extents `x` and `y`: the y tick labels set the left margin, the
/// last x tick label the right one.
fn axes(
    x: (f64, f64),
    (y0, y1): (f64, f64),
    (top, bottom): (f64, f64),
    (left, right): (f64, f64),
) -> (Rect, Ticks, Ticks) {
    let normal = TextSize::Normal.line();
    let y = fit(Ticks::new(y0, y1, INTERVALS.1), |t| {
        spacing(t, bottom - top) >= normal + LINE_SPACING
    });
    let inner = left + PAD + normal + GAP + widest(&y.labels(), TextSize::Normal) + GAP;
    let (area, x) = x_area(x, (inner, right), top, bottom);
    (area, x, y)
}

/// The plot area from `left`, `top` and `bottom` and the x ticks of the extent `x`, whose
/// last label sets the right margin inside `limit` (px): the area and the ticks.
fn x_area((x0, x1): (f64, f64), (left, limit): (f64, f64), top: f64, bottom: f64) -> (Rect, Ticks) {
    let fits = |right: f64| {
        move |t: &Ticks| {
            spacing(t, right - left) >= widest(&t.labels(), TextSize::Normal) + LABEL_SPACING
        }
    };
    let provisional = limit - PAD - 16.0;
    let x = fit(Ticks::new(x0, x1, INTERVALS.0), fits(provisional));
    let last = x.labels().pop().unwrap_or_default();
    let half = 0.5 * font::width(&last, TextSize::Normal.px());
    let right = limit - PAD - half.max(12.0);
    let x = fit(x, fits(right));
    let area = Rect {
        left,
        top,
        right,
        bottom,
    };
    (area, x)
}

/// The smallest and largest x of every finite point and band column.
fn x_extent(panel: &Panel, band: Option<&Band>) -> (f64, f64) {
    let points = panel.series.iter().flat_map(|s| finite(&s.points));
    let band = band.iter().flat_map(|b| b.finite());
    extent(points.map(|p| p.0).chain(band.map(|b| b.0)))
}

/// The smallest and largest y of every finite point and band edge, and 0 with a zero line.
fn y_extent(panel: &Panel, band: Option<&Band>) -> (f64, f64) {
    let points = panel.series.iter().flat_map(|s| finite(&s.points));
    let band = band.iter().flat_map(|b| b.finite());
    let zero = panel.zero_line.then_some(0.0);
    extent(
        points
            .map(|p| p.1)
            .chain(band.flat_map(|b| [b.1, b.2]))
            .chain(zero),
    )
}

/// Adds the axis titles: x centred under the tick labels at the bottom of `room`, y
/// turned, at its left.
fn axis_titles(panel: &Panel, area: &Rect, room: Rect, labels: &mut Vec<Label>) {
    let size = TextSize::Normal;
    let x_y = room.bottom - PAD - font::descent(size.px());
    let centre = 0.5 * (area.left + area.right);
    labels.push(Label::new(
        &panel.x_label,
        (centre, x_y),
        Anchor::Middle,
        size,
    ));
    labels.push(Label {
        vertical: true,
        ..Label::new(
            &panel.y_label,
            (
                room.left + PAD + font::ascent(size.px()),
                0.5 * (area.top + area.bottom),
            ),
            Anchor::Middle,
            size,
        )
    })
}
