//! Where everything of a figure goes, in px of the image (origin at the top-left corner,
//! y down): the title, the legend in rows under it, the plot area with its round ticks, the
//! axis titles, and the inset if asked for. Margins are measured from the text they hold
//! (in the figures' font), so no label leaves the image or runs into another.

use super::font;
use super::inset::{self, Inset};
use super::legend::{self, LegendEntry};
use super::panels::{self, Look};
use super::plot::{Plot, Rect};
use super::style::{self, Stroke};
use super::ticks::Ticks;
use super::{Figure, Panel};

/// Width of the image (px).
pub(super) const WIDTH: f64 = 720.0;
/// Height of the image (px).
pub(super) const HEIGHT: f64 = 440.0;
/// Width and height of each cell of a grid of panels, with its title, tick labels and
/// axis titles (px).
pub(super) const CELL: (f64, f64) = (470.0, 300.0);
/// Space kept free between the image's edge and any text (px).
pub(super) const PAD: f64 = 8.0;
/// Gap between a tick label and its axis, or between two blocks of text (px).
pub(super) const GAP: f64 = 6.0;
/// Intervals aimed at between the ticks along x and along y.
pub(super) const INTERVALS: (usize, usize) = (6, 5);
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
    /// The panels' axes, row by row (at least one).
    pub(crate) plots: Vec<Plot>,
    pub(crate) inset: Option<Inset>,
    /// Title, tick labels, axis titles, legend texts.
    pub(crate) labels: Vec<Label>,
    pub(crate) legend: Vec<LegendEntry>,
}

impl Layout {
    /// Lays `figure` out: the title, the legend under it, then the panels in a grid.
    pub(super) fn new(figure: &Figure) -> Layout {
        let single = figure.panels.len() <= 1;
        let columns = figure.columns.min(figure.panels.len()).max(1);
        let rows = figure.panels.len().div_ceil(columns).max(1);
        let width = if single {
            WIDTH
        } else {
            CELL.0 * columns as f64
        };
        let mut labels = Vec::new();
        let title = TextSize::Title;
        let title_y = PAD + font::ascent(title.px());
        labels.push(Label::new(
            &figure.title,
            (0.5 * width, title_y),
            Anchor::Middle,
            title,
        ));
        let strokes = style::strokes(figure.all_series().map(|s| s.label), &figure.strokes);
        let entries = legend::entries(figure, &strokes);
        let legend_rows = legend::rows(&entries, width - 2.0 * PAD);
        let legend_top = title_y + font::descent(title.px()) + GAP;
        let row = TextSize::Normal.line() + 4.0;
        let top = legend_top + row * legend_rows.len() as f64 + GAP;
        let height = if single {
            HEIGHT
        } else {
            top + CELL.1 * rows as f64
        };
        let plots = lay_out_panels(figure, &strokes, (width, top, height), &mut labels);
        let span = if single {
            plots[0].area
        } else {
            Rect {
                left: 0.0,
                top,
                right: width,
                bottom: height,
            }
        };
        let legend = legend::place(
            &entries,
            &legend_rows,
            (&span, width),
            legend_top,
            &mut labels,
        );
        let inset = match (figure.peak_inset, figure.panels.first()) {
            (true, Some(panel)) => inset::inset(
                &plots[0],
                &panel.series,
                &strokes[..panel.series.len()],
                &mut labels,
            ),
            _ => None,
        };
        Layout {
            width,
            height,
            plots,
            inset,
            labels,
            legend,
        }
    }
}

/// The panels of `figure` in cells of the image (`width`, from `top` to `height`, px):
/// one cell for a plain figure, [`CELL`]s in rows of the figure's columns for a grid.
fn lay_out_panels(
    figure: &Figure,
    strokes: &[Stroke],
    (width, top, height): (f64, f64, f64),
    labels: &mut Vec<Label>,
) -> Vec<Plot> {
    let empty = Panel::new("", "", "", Vec::new());
    let panels: Vec<&Panel> = if figure.panels.is_empty() {
        vec![&empty]
    } else {
        figure.panels.iter().collect()
    };
    let single = panels.len() == 1;
    let mut plots = Vec::new();
    let mut first = 0;
    for (i, panel) in panels.into_iter().enumerate() {
        let (column, row) = ((i % figure.columns) as f64, (i / figure.columns) as f64);
        let room = if single {
            Rect {
                left: 0.0,
                top,
                right: width,
                bottom: height,
            }
        } else {
            Rect {
                left: CELL.0 * column,
                top: top + CELL.1 * row,
                right: CELL.0 * (column + 1.0),
                bottom: top + CELL.1 * (row + 1.0),
            }
        };
        let curves = &strokes[first..first + panel.series.len()];
        first += panel.series.len();
        if panel.is_blank() && !single {
            continue;
        }
        let look = Look {
            band: figure.band.as_ref().filter(|_| i == 0),
            equal_scales: figure.equal_scales,
            strokes: curves,
        };
        plots.push(panels::lay_out(panel, &look, room, labels));
    }
    plots
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
