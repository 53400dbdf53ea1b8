//! Line plots — a few polylines on linear axes with tick labels, a title, axis labels and a
//! legend — written as SVG ([`Figure::svg`]) and as PNG ([`Figure::png`]).
//!
//! Everything a figure shows is placed once, here, in a `Layout`: the axis ranges, the
//! ticks, every text and its position, the legend and the mapping from data to pixels. The
//! two renderers (`svg.rs`, `png.rs`) only draw that layout, so the two files show the same
//! figure. Neither needs a font file or a system font: the SVG leaves the text to the viewer,
//! the PNG uses the bitmap fonts built into `embedded-graphics`.

mod png;
mod svg;

/// Width of the image (px).
const WIDTH: f64 = 720.0;
/// Height of the image (px).
const HEIGHT: f64 = 440.0;
/// Margins around the plot area: left, right, top, bottom (px).
const MARGIN: (f64, f64, f64, f64) = (80.0, 20.0, 40.0, 60.0);
/// Intervals between ticks per axis (so one more tick label than this).
const TICK_INTERVALS: usize = 5;
/// Width assumed for one character of normal-size text, to size the legend box (px); the
/// PNG's font is exactly this wide, the SVG's sans-serif font about as wide on average.
const CHAR_WIDTH: f64 = 7.0;
/// Vertical distance between legend rows (px).
const LEGEND_ROW: f64 = 16.0;

/// An sRGB colour, 8 bits per channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Colour {
    /// Red, 0–255.
    pub r: u8,
    /// Green, 0–255.
    pub g: u8,
    /// Blue, 0–255.
    pub b: u8,
}

impl Colour {
    /// Black.
    pub const BLACK: Colour = Colour::hex(0x000000);
    /// White.
    pub const WHITE: Colour = Colour::hex(0xffffff);
    /// The light grey of the horizontal grid lines.
    const GRID: Colour = Colour::hex(0xdddddd);
    /// The grey of the legend box's border.
    const LEGEND_BORDER: Colour = Colour::hex(0xbbbbbb);

    /// The colour written `0xRRGGBB`, e.g. `Colour::hex(0x1f77b4)`.
    pub const fn hex(rgb: u32) -> Colour {
        Colour {
            r: (rgb >> 16) as u8,
            g: (rgb >> 8) as u8,
            b: rgb as u8,
        }
    }

    /// CSS notation, `#rrggbb`.
    pub fn css(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }
}

/// One curve: label, colour, points (x, y).
pub struct Series<'a> {
    /// Legend label.
    pub label: &'a str,
    /// Stroke colour.
    pub colour: Colour,
    /// Points in data units; points with a non-finite coordinate are left out.
    pub points: Vec<(f64, f64)>,
}

/// A line plot, laid out and ready to be written as SVG or PNG.
pub struct Figure<'a> {
    series: Vec<Series<'a>>,
    layout: Layout,
}

impl<'a> Figure<'a> {
    /// Lays out `series` as a line plot with a title and axis labels (all in data units as
    /// given; the labels should name the units).
    pub fn new(title: &str, x_label: &str, y_label: &str, series: Vec<Series<'a>>) -> Self {
        let layout = Layout::new(title, x_label, y_label, &series);
        Figure { series, layout }
    }

    /// The figure as an SVG document.
    pub fn svg(&self) -> String {
        svg::render(self)
    }

    /// The figure as a PNG file (8-bit RGB, [`Figure::size`] pixels).
    pub fn png(&self) -> Result<Vec<u8>, ::png::EncodingError> {
        png::render(self)
    }

    /// Width and height of the image (px).
    pub fn size(&self) -> (u32, u32) {
        (self.layout.width as u32, self.layout.height as u32)
    }

    /// The plot area, where the curves are drawn: left, top, right, bottom edges (px from
    /// the image's top-left corner).
    pub fn plot_area(&self) -> (f64, f64, f64, f64) {
        let p = &self.layout.plot;
        (p.left, p.top, p.right, p.bottom)
    }
}

/// An axis-aligned rectangle, edges in px from the image's top-left corner (y down).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rect {
    left: f64,
    top: f64,
    right: f64,
    bottom: f64,
}

/// Where a text's reference point is along the text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Anchor {
    Start,
    Middle,
    End,
}

/// A text's size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum TextSize {
    /// The title: 15 px in the SVG, a 9 × 15 px font in the PNG.
    Title,
    /// Everything else: 12 px in the SVG, a 7 × 13 px font in the PNG.
    Normal,
}

/// One text of the figure.
#[derive(Clone, Debug, PartialEq)]
struct Label {
    text: String,
    /// Reference point: horizontal position given by `anchor` (px).
    x: f64,
    /// Reference point: the baseline (px).
    y: f64,
    anchor: Anchor,
    size: TextSize,
    /// Turned a quarter turn anticlockwise about the reference point, to read bottom to top.
    vertical: bool,
}

/// One legend row: a short line in the series' colour, then its label (whose position is
/// among [`Layout::labels`]).
#[derive(Clone, Copy, Debug, PartialEq)]
struct LegendRow {
    /// The line's ends (px).
    x0: f64,
    x1: f64,
    /// The line's height (px).
    y: f64,
}

/// Where everything of a figure goes, in px of a `width` × `height` image (origin at the
/// top-left corner, y down).
struct Layout {
    width: f64,
    height: f64,
    /// The plot area: the frame around the curves.
    plot: Rect,
    /// Data range shown along x: left and right edge of the plot area (data units).
    x_range: (f64, f64),
    /// Data range shown along y: bottom and top edge of the plot area (data units).
    y_range: (f64, f64),
    /// Heights of the horizontal grid lines, one per y tick (px).
    grid: Vec<f64>,
    /// Title, tick labels, axis labels and legend labels.
    labels: Vec<Label>,
    /// The box behind the legend, if there is any series.
    legend_box: Option<Rect>,
    /// One legend row per series, in order.
    legend: Vec<LegendRow>,
}

impl Layout {
    fn new(title: &str, x_label: &str, y_label: &str, series: &[Series]) -> Layout {
        let (width, height) = (WIDTH, HEIGHT);
        let (left, right, top, bottom) = MARGIN;
        let plot = Rect {
            left,
            top,
            right: width - right,
            bottom: height - bottom,
        };
        let finite = || {
            series
                .iter()
                .flat_map(|s| s.points.iter())
                .filter(|(x, y)| x.is_finite() && y.is_finite())
        };
        let x_range = range(finite().map(|p| p.0));
        let (y0, y1) = range(finite().map(|p| p.1));
        let pad = 0.05 * (y1 - y0);
        let mut layout = Layout {
            width,
            height,
            plot,
            x_range,
            y_range: (y0 - pad, y1 + pad),
            grid: Vec::new(),
            labels: Vec::new(),
            legend_box: None,
            legend: Vec::new(),
        };
        let label = |text: &str, x: f64, y: f64, anchor: Anchor| Label {
            text: text.to_owned(),
            x,
            y,
            anchor,
            size: TextSize::Normal,
            vertical: false,
        };
        let mut labels = vec![Label {
            size: TextSize::Title,
            ..label(title, width / 2.0, 22.0, Anchor::Middle)
        }];
        let (x0, x1) = layout.x_range;
        let (y0, y1) = layout.y_range;
        let n = TICK_INTERVALS as f64;
        let steps = ((x1 - x0) / n, (y1 - y0) / n);
        for i in 0..=TICK_INTERVALS {
            let (x, y) = (x0 + steps.0 * i as f64, y0 + steps.1 * i as f64);
            let (px, py) = (layout.px(x), layout.py(y));
            labels.push(label(
                &tick(x, steps.0),
                px,
                plot.bottom + 16.0,
                Anchor::Middle,
            ));
            labels.push(label(
                &tick(y, steps.1),
                plot.left - 6.0,
                py + 4.0,
                Anchor::End,
            ));
            layout.grid.push(py);
        }
        labels.push(label(
            x_label,
            (plot.left + plot.right) / 2.0,
            height - 18.0,
            Anchor::Middle,
        ));
        labels.push(Label {
            vertical: true,
            ..label(y_label, 18.0, height / 2.0, Anchor::Middle)
        });
        // The legend sits in the plot area's top-right corner, on a box sized to its labels.
        let longest = series
            .iter()
            .map(|s| s.label.chars().count())
            .max()
            .unwrap_or(0);
        let text_x = plot.right - 14.0 - CHAR_WIDTH * longest as f64;
        for (i, s) in series.iter().enumerate() {
            let y = plot.top + 18.0 + LEGEND_ROW * i as f64;
            layout.legend.push(LegendRow {
                x0: text_x - 30.0,
                x1: text_x - 5.0,
                y,
            });
            labels.push(label(s.label, text_x, y + 4.0, Anchor::Start));
        }
        if let (Some(first), Some(last)) = (layout.legend.first(), layout.legend.last()) {
            layout.legend_box = Some(Rect {
                left: first.x0 - 8.0,
                top: first.y - 11.0,
                right: plot.right - 6.0,
                bottom: last.y + 10.0,
            });
        }
        layout.labels = labels;
        layout
    }

    /// The pixel column of `x` (data units → px).
    fn px(&self, x: f64) -> f64 {
        let (x0, x1) = self.x_range;
        self.plot.left + (x - x0) / (x1 - x0) * (self.plot.right - self.plot.left)
    }

    /// The pixel row of `y` (data units → px).
    fn py(&self, y: f64) -> f64 {
        let (y0, y1) = self.y_range;
        self.plot.bottom - (y - y0) / (y1 - y0) * (self.plot.bottom - self.plot.top)
    }

    /// The series' finite points, in px, in order.
    fn path(&self, series: &Series) -> Vec<(f64, f64)> {
        series
            .points
            .iter()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .map(|&(x, y)| (self.px(x), self.py(y)))
            .collect()
    }
}

/// The smallest and largest of `values` (all finite), widened to a range of non-zero length
/// if they are equal, or (0, 1) if there are none.
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), v| {
        (low.min(v), high.max(v))
    });
    if low > high {
        (0.0, 1.0)
    } else if low == high {
        let half = low.abs().max(1.0) * 0.5;
        (low - half, high + half)
    } else {
        (low, high)
    }
}

/// A short tick label for `value`, one of ticks `step` apart (data units): decimals down to
/// one place below the step's leading digit, so a label is off by at most 5 % of the step;
/// scientific notation for very large or small values.
fn tick(value: f64, step: f64) -> String {
    // A tick that is zero up to rounding (e.g. −1e−17) is shown as 0, not "-0".
    let value = if value.abs() < 1e-9 * step.abs() {
        0.0
    } else {
        value
    };
    let magnitude = value.abs().max(step.abs());
    if !(1e-3..1e5).contains(&magnitude) {
        format!("{value:.2e}")
    } else {
        let decimals = (1 - step.abs().log10().floor() as i32).clamp(0, 6) as usize;
        format!("{value:.decimals$}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_axes_span_every_finite_point_and_pixels_follow_them() {
        let layout = Layout::new(
            "t",
            "x",
            "y",
            &[Series {
                label: "a",
                colour: Colour::BLACK,
                points: vec![(1.0, -2.0), (3.0, 8.0), (f64::NAN, 100.0)],
            }],
        );
        assert_eq!(layout.x_range, (1.0, 3.0));
        assert_eq!(layout.y_range, (-2.5, 8.5));
        assert_eq!(layout.px(1.0), layout.plot.left);
        assert_eq!(layout.px(3.0), layout.plot.right);
        assert_eq!(layout.py(-2.5), layout.plot.bottom);
        assert_eq!(layout.py(8.5), layout.plot.top);
        assert_eq!(layout.grid.len(), TICK_INTERVALS + 1);
    }

    #[test]
    fn a_plot_without_finite_points_or_with_one_still_has_a_range() {
        assert_eq!(
            range([f64::NAN].into_iter().filter(|v| v.is_finite())),
            (0.0, 1.0)
        );
        assert_eq!(range([4.0].into_iter()), (2.0, 6.0));
        assert_eq!(range([0.0].into_iter()), (-0.5, 0.5));
    }

    #[test]
    fn tick_labels_have_the_decimals_their_spacing_needs() {
        assert_eq!(tick(3074.051, 644.087), "3074");
        assert_eq!(tick(-146.383, 644.087), "-146");
        assert_eq!(tick(23.6, 23.6), "24");
        assert_eq!(tick(-2.033, 4.513), "-2.0");
        assert_eq!(tick(0.25, 0.05), "0.250");
        assert_eq!(tick(-1e-17, 0.2), "0.00");
        assert_eq!(tick(2.5e-4, 1e-4), "2.50e-4");
        assert_eq!(tick(2e6, 5e5), "2.00e6");
    }

    #[test]
    fn colours_read_and_write_hex() {
        let c = Colour::hex(0x1f77b4);
        assert_eq!((c.r, c.g, c.b), (0x1f, 0x77, 0xb4));
        assert_eq!(c.css(), "#1f77b4");
    }
}
