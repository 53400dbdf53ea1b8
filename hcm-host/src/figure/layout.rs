//! Where everything of a figure goes, in px of the image (origin at the top-left corner,
//! y down): the title, the legend in rows under it, the plot area with its round ticks, the
//! axis titles, and the inset if asked for. Margins are measured from the text they hold
//! (in the figures' font), so no label leaves the image or runs into another.

use super::aspect;
use super::font;
use super::inset::{self, Inset};
use super::legend::{self, LegendEntry};
use super::plot::{finite, Plot, Rect};
use super::ticks::Ticks;
use super::Figure;

/// Width of the image (px).
pub(super) const WIDTH: f64 = 720.0;
/// Height of the image (px).
pub(super) const HEIGHT: f64 = 440.0;
/// Space kept free between the image's edge and any text (px).
pub(super) const PAD: f64 = 8.0;
/// Gap between a tick label and its axis, or between two blocks of text (px).
pub(super) const GAP: f64 = 6.0;
/// Intervals aimed at between the ticks along x and along y.
const INTERVALS: (usize, usize) = (6, 5);
/// Least free space between neighbouring tick labels along x (px).
pub(super) const LABEL_SPACING: f64 = 12.0;
/// Least free space between neighbouring tick labels along y (px).
pub(super) const LINE_SPACING: f64 = 2.0;

/// Where a text's reference point is along the text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Anchor {
    Start,
    Middle,
    End,
}

/// A text's size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum TextSize {
    /// The title.
    Title,
    /// Tick labels, axis titles, the legend.
    Normal,
    /// The inset's tick labels.
    Small,
}

impl TextSize {
    /// The font size (px per em, as SVG `font-size`).
    pub(super) fn px(self) -> f64 {
        match self {
            TextSize::Title => 15.0,
            TextSize::Normal => 12.0,
            TextSize::Small => 10.0,
        }
    }

    /// Height of a line of text: ascent plus descent (px).
    pub(super) fn line(self) -> f64 {
        font::ascent(self.px()) + font::descent(self.px())
    }

    /// How far below a point to put the baseline so that digits are centred on it (px).
    pub(super) fn centring(self) -> f64 {
        0.36 * self.px()
    }

    /// Gap between an axis and the top of its x tick labels (px): enough that the first
    /// of them clears the lowest y tick label, which is centred on the same corner.
    pub(super) fn x_tick_gap(self) -> f64 {
        self.centring() + font::descent(self.px()) + 1.0
    }
}

/// One text of the figure.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Label {
    pub(crate) text: String,
    /// Reference point: horizontal position given by `anchor` (px).
    pub(crate) x: f64,
    /// Reference point: the baseline (px).
    pub(crate) y: f64,
    pub(crate) anchor: Anchor,
    pub(crate) size: TextSize,
    /// Turned a quarter turn anticlockwise about the reference point, to read bottom to top.
    pub(crate) vertical: bool,
}

impl Label {
    /// A horizontal label.
    pub(super) fn new(text: &str, (x, y): (f64, f64), anchor: Anchor, size: TextSize) -> Label {
        Label {
            text: text.to_owned(),
            x,
            y,
            anchor,
            size,
            vertical: false,
        }
    }

    #[cfg(test)]
    /// The box the text takes: its advance width by the font's ascent plus descent (px).
    pub(super) fn bounds(&self) -> Rect {
        let size = self.size.px();
        let width = font::width(&self.text, size);
        let start = match self.anchor {
            Anchor::Start => 0.0,
            Anchor::Middle => -0.5 * width,
            Anchor::End => -width,
        };
        let (ascent, descent) = (font::ascent(size), font::descent(size));
        let (x, y) = (self.x, self.y);
        if self.vertical {
            // Along the text is up the image; the glyphs' tops point left.
            Rect {
                left: x - ascent,
                top: y - start - width,
                right: x + descent,
                bottom: y - start,
            }
        } else {
            Rect {
                left: x + start,
                top: y - ascent,
                right: x + start + width,
                bottom: y + descent,
            }
        }
    }
}

/// Everything of a figure placed in a `width` × `height` px image.
pub(super) struct Layout {
    pub(crate) width: f64,
    pub(crate) height: f64,
    pub(crate) main: Plot,
    pub(crate) inset: Option<Inset>,
    /// Title, tick labels, axis titles, legend texts.
    pub(crate) labels: Vec<Label>,
    pub(crate) legend: Vec<LegendEntry>,
}

impl Layout {
    /// Lays `figure` out.
    pub(super) fn new(figure: &Figure) -> Layout {
        let mut labels = Vec::new();
        let title = TextSize::Title;
        let title_y = PAD + font::ascent(title.px());
        labels.push(Label::new(
            &figure.title,
            (0.5 * WIDTH, title_y),
            Anchor::Middle,
            title,
        ));
        let entries = legend::entries(figure);
        let rows = legend::rows(&entries, WIDTH - 2.0 * PAD);
        let legend_top = title_y + font::descent(title.px()) + GAP;
        let row = TextSize::Normal.line() + 4.0;
        let top = legend_top + row * rows.len() as f64 + GAP;
        let normal = TextSize::Normal.line();
        let x_ticks = TextSize::Normal.x_tick_gap() + normal;
        let bottom = HEIGHT - PAD - normal - GAP - x_ticks;
        let axes = |x, y| axes(x, y, top, bottom);
        let (area, x, y) = if figure.equal_scales {
            aspect::equal_scales(axes, x_extent(figure), y_extent(figure))
        } else {
            axes(x_extent(figure), y_extent(figure))
        };
        let mut main = Plot::new(area, x, y);
        if let Some(band) = &figure.band {
            main.draw_band(band);
        }
        if figure.zero_line {
            main.draw_zero_line();
        }
        main.draw_series(&figure.series);
        tick_labels(&main, TextSize::Normal, &mut labels);
        axis_titles(figure, &main.area, &mut labels);
        let legend = legend::place(&entries, &rows, &main.area, legend_top, &mut labels);
        let inset = if figure.peak_inset {
            inset::inset(&main, &figure.series, &mut labels)
        } else {
            None
        };
        Layout {
            width: WIDTH,
            height: HEIGHT,
            main,
            inset,
            labels,
            legend,
        }
    }
}

/// The plot area between `top` and `bottom` (px) and the ticks of the data extents `x`
/// and `y`: the y tick labels set the left margin, the last x tick label the right one.
fn axes(x: (f64, f64), (y0, y1): (f64, f64), top: f64, bottom: f64) -> (Rect, Ticks, Ticks) {
    let normal = TextSize::Normal.line();
    let y = fit(Ticks::new(y0, y1, INTERVALS.1), |t| {
        spacing(t, bottom - top) >= normal + LINE_SPACING
    });
    let left = PAD + normal + GAP + widest(&y.labels(), TextSize::Normal) + GAP;
    let (area, x) = x_area(x, left, top, bottom);
    (area, x, y)
}

/// The plot area from `left`, `top` and `bottom` and the x ticks of the extent `x`, whose
/// last label sets the right margin: the area and the ticks.
fn x_area((x0, x1): (f64, f64), left: f64, top: f64, bottom: f64) -> (Rect, Ticks) {
    let fits = |right: f64| {
        move |t: &Ticks| {
            spacing(t, right - left) >= widest(&t.labels(), TextSize::Normal) + LABEL_SPACING
        }
    };
    let provisional = WIDTH - PAD - 16.0;
    let x = fit(Ticks::new(x0, x1, INTERVALS.0), fits(provisional));
    let last = x.labels().pop().unwrap_or_default();
    let half = 0.5 * font::width(&last, TextSize::Normal.px());
    let right = WIDTH - PAD - half.max(12.0);
    let x = fit(x, fits(right));
    let area = Rect {
        left,
        top,
        right,
        bottom,
    };
    (area, x)
}

/// `ticks` made coarser until `fits` holds (at most a few times: three steps are a
/// factor of ten).
pub(super) fn fit(mut ticks: Ticks, fits: impl Fn(&Ticks) -> bool) -> Ticks {
    for _ in 0..9 {
        if fits(&ticks) {
            break;
        }
        ticks = ticks.coarser();
    }
    ticks
}

/// The distance between neighbouring ticks on an axis `length` px long (px).
pub(super) fn spacing(ticks: &Ticks, length: f64) -> f64 {
    length / (ticks.values().count() - 1).max(1) as f64
}

/// The widest of `texts` at `size` (px).
pub(super) fn widest(texts: &[String], size: TextSize) -> f64 {
    texts
        .iter()
        .map(|t| font::width(t, size.px()))
        .fold(0.0, f64::max)
}

/// The smallest and largest x of every finite point and band column.
fn x_extent(figure: &Figure) -> (f64, f64) {
    let points = figure.series.iter().flat_map(|s| finite(&s.points));
    let band = figure.band.iter().flat_map(|b| b.finite());
    extent(points.map(|p| p.0).chain(band.map(|b| b.0)))
}

/// The smallest and largest y of every finite point and band edge, and 0 with a zero line.
fn y_extent(figure: &Figure) -> (f64, f64) {
    let points = figure.series.iter().flat_map(|s| finite(&s.points));
    let band = figure.band.iter().flat_map(|b| b.finite());
    let zero = figure.zero_line.then_some(0.0);
    extent(
        points
            .map(|p| p.1)
            .chain(band.flat_map(|b| [b.1, b.2]))
            .chain(zero),
    )
}

/// The smallest and largest of `values`; (∞, −∞) if there are none.
pub(super) fn extent(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), v| {
        (low.min(v), high.max(v))
    })
}

/// Adds the tick labels of `plot` in `size`: x below the area, y left of it.
pub(super) fn tick_labels(plot: &Plot, size: TextSize, labels: &mut Vec<Label>) {
    let area = plot.area;
    let below = area.bottom + size.x_tick_gap() + font::ascent(size.px());
    for (v, text) in plot.x.values().zip(plot.x.labels()) {
        labels.push(Label::new(&text, (plot.px(v), below), Anchor::Middle, size));
    }
    for (v, text) in plot.y.values().zip(plot.y.labels()) {
        let at = (area.left - GAP, plot.py(v) + size.centring());
        labels.push(Label::new(&text, at, Anchor::End, size));
    }
}

/// Adds the axis titles: x centred under the tick labels, y turned, left of them.
fn axis_titles(figure: &Figure, area: &Rect, labels: &mut Vec<Label>) {
    let size = TextSize::Normal;
    let x_y = HEIGHT - PAD - font::descent(size.px());
    let centre = 0.5 * (area.left + area.right);
    labels.push(Label::new(
        &figure.x_label,
        (centre, x_y),
        Anchor::Middle,
        size,
    ));
    labels.push(Label {
        vertical: true,
        ..Label::new(
            &figure.y_label,
            (
                PAD + font::ascent(size.px()),
                0.5 * (area.top + area.bottom),
            ),
            Anchor::Middle,
            size,
        )
    })
}
