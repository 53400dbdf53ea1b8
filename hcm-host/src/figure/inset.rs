//! The inset: a zoom on the peak of the first curve, for curves that lie too close
//! together to be told apart at full scale (measured and modelled contact forces differ by
//! about 1 % of the peak). The zoomed window is outlined on the main plot; the inset goes
//! where it hides the least of the curves.

use super::layout::{fit, spacing, tick_labels, widest, Label, TextSize, GAP, LABEL_SPACING};
use super::plot::{clip, finite, Plot, Rect};
use super::style::Stroke;
use super::ticks::Ticks;
use super::{font, Series};

/// Half the width of the zoomed window, as a fraction of the curves' x range (–): at
/// the top of a half-sine pulse the force falls by 1 − cos(π·0.05) ≈ 1.2 % within it,
/// about the size of the differences between the models.
const HALF_WINDOW: f64 = 0.05;
/// The inset's frame as fractions of the plot area's width and height (–).
const SIZE: (f64, f64) = (0.34, 0.36);
/// Space kept between the inset (with its labels) and the plot area's frame (px).
const MARGIN: f64 = 8.0;
/// Intervals aimed at between the inset's ticks.
const INTERVALS: usize = 3;
/// Where the inset may go, as fractions of the free room across and down the plot area,
/// in order of preference: under a pulse's middle first, then the corners.
const PLACES: [(f64, f64); 9] = [
    (0.5, 1.0),
    (0.0, 0.0),
    (1.0, 0.0),
    (0.0, 1.0),
    (1.0, 1.0),
    (0.5, 0.5),
    (0.0, 0.5),
    (1.0, 0.5),
    (0.5, 0.0),
];

/// A zoom drawn inside the main plot.
pub(super) struct Inset {
    /// The zoomed axes and the curves cut to its window.
    pub(crate) plot: Plot,
    /// The white box behind the inset's frame and tick labels (px).
    pub(crate) background: Rect,
    /// The zoomed window outlined on the main plot (px).
    pub(crate) marker: Rect,
}

/// The inset zooming on the highest point of the first series with a finite point, placed
/// in `main`'s area, each curve stroked as in `strokes`; its tick labels go into
/// `labels`. None without finite points, or if the x range has no width.
pub(super) fn inset(
    main: &Plot,
    series: &[Series],
    strokes: &[Stroke],
    labels: &mut Vec<Label>,
) -> Option<Inset> {
    let reference = series.iter().find(|s| finite(&s.points).next().is_some())?;
    let peak = finite(&reference.points).max_by(|a, b| a.1.total_cmp(&b.1))?;
    let (x_low, x_high) =
        super::layout::extent(series.iter().flat_map(|s| finite(&s.points)).map(|p| p.0));
    let half = HALF_WINDOW * (x_high - x_low);
    if half.is_nan() || half <= 0.0 {
        return None;
    }
    let (frame_width, frame_height) = (SIZE.0 * main.area.width(), SIZE.1 * main.area.height());
    let small = TextSize::Small;
    let x = fit(Ticks::new(peak.0 - half, peak.0 + half, INTERVALS), |t| {
        spacing(t, frame_width) >= widest(&t.labels(), small) + LABEL_SPACING
    });
    let window: Vec<_> = series
        .iter()
        .flat_map(|s| clip(&s.points, x.range()))
        .collect();
    let (y_low, y_high) = super::layout::extent(window.iter().flatten().map(|p| p.1));
    let y = fit(Ticks::new(y_low, y_high, INTERVALS), |t| {
        spacing(t, frame_height) >= small.line()
    });
    let marker = marker(main, &x, &y);
    // Room around the frame for the tick labels: y labels left, x labels below, and the
    // halves of the end labels that stick out past the frame's corners.
    let x_labels = x.labels();
    let half = |text: Option<&String>| 0.5 * text.map_or(0.0, |t| font::width(t, small.px()));
    let room = Rect {
        left: (widest(&y.labels(), small) + GAP).max(half(x_labels.first())) + 2.0,
        top: small.line() * 0.5 + 2.0,
        right: half(x_labels.last()).max(2.0) + 2.0,
        bottom: small.x_tick_gap() + small.line() + 2.0,
    };
    let size = (
        room.left + frame_width + room.right,
        room.top + frame_height + room.bottom,
    );
    let background = place(main, size, &marker)?;
    let frame = Rect {
        left: background.left + room.left,
        top: background.top + room.top,
        right: background.right - room.right,
        bottom: background.bottom - room.bottom,
    };
    let mut plot = Plot::new(frame, x, y);
    plot.draw_series_clipped(series, strokes);
    tick_labels(&plot, small, labels);
    Some(Inset {
        plot,
        background,
        marker,
    })
}

/// The zoomed window in the main plot's px, cut to its area.
fn marker(main: &Plot, x: &Ticks, y: &Ticks) -> Rect {
    let area = main.area;
    let ((x0, x1), (y0, y1)) = (x.range(), y.range());
    Rect {
        left: main.px(x0).max(area.left),
        top: main.py(y1).max(area.top),
        right: main.px(x1).min(area.right),
        bottom: main.py(y0).min(area.bottom),
    }
}

/// A box of `size` (px) inside `main`'s area, away from its frame by [`MARGIN`], at the
/// first of [`PLACES`] that covers the fewest points of the curves and keeps clear of
/// `marker`; None if the area is too small.
fn place(main: &Plot, (width, height): (f64, f64), marker: &Rect) -> Option<Rect> {
    let area = main.area;
    let free = (
        area.width() - 2.0 * MARGIN - width,
        area.height() - 2.0 * MARGIN - height,
    );
    if free.0 < 0.0 || free.1 < 0.0 {
        return None;
    }
    let samples = samples(main);
    let mut best: Option<(usize, Rect)> = None;
    for (across, down) in PLACES {
        let left = area.left + MARGIN + across * free.0;
        let top = area.top + MARGIN + down * free.1;
        let candidate = Rect {
            left,
            top,
            right: left + width,
            bottom: top + height,
        };
        let hidden = samples.iter().filter(|p| candidate.holds(**p)).count();
        let cost = hidden
            + if candidate.overlaps(marker) {
                samples.len() + 1
            } else {
                0
            };
        if best.is_none_or(|(lowest, _)| cost < lowest) {
            best = Some((cost, candidate));
        }
    }
    best.map(|(_, r)| r)
}

/// Points along every curve of `main` no more than 2 px apart (px).
fn samples(main: &Plot) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for piece in main.curves.iter().flat_map(|c| &c.pieces) {
        out.extend(piece.first().copied());
        for pair in piece.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let length = (b.0 - a.0).hypot(b.1 - a.1);
            let n = (length / 2.0).ceil().clamp(1.0, 1e4) as usize;
            out.extend((1..=n).map(|k| {
                let t = k as f64 / n as f64;
                (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
            }));
        }
    }
    out
}
