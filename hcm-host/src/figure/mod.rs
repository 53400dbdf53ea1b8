//! Line plots — a few curves on linear axes with round ticks, a title, axis titles and a
//! legend, optionally a shaded band (e.g. the noise of a measured mean), the zero line and
//! an inset zooming on the peak — written as SVG ([`Figure::svg`]) and PNG ([`Figure::png`]).
//!
//! Everything a figure shows is placed once, in a `Layout` (`layout.rs`, with `plot.rs`
//! for the axes, `ticks.rs` for the tick values, `legend.rs`, and `inset.rs` for the
//! zoom): the ranges, every text and its position, the legend and the curves in pixels.
//! The two renderers (`svg.rs`, and `png.rs` on `canvas.rs`) only draw that layout, so the
//! two files show the same figure. Text is measured and, in the PNG, drawn anti-aliased
//! with the DejaVu Sans font compiled into the binary (`font.rs`), so Greek letters, µ, ±,
//! superscripts and δ̇ show as they are written.

mod aspect;
mod canvas;
mod events;
mod font;
mod inset;
mod layout;
mod legend;
mod panels;
mod plot;
mod png;
mod rigid_run;
mod side_view;
mod style;
mod svg;
mod ticks;
pub use events::{event_figure, EventSpan, Quantity};
pub use rigid_run::rigid_figures;

use layout::Layout;
pub use style::{Dash, Stroke};

/// A figure and the file stem it is written under (`STEM.svg`, `STEM.png`).
pub struct NamedFigure {
    /// File stem, e.g. `contact_force`.
    pub stem: &'static str,
    /// The figure.
    pub figure: Figure<'static>,
}

/// An sRGB colour, 8 bits per channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Colour {
    /// Red, 0–255.
    pub(crate) r: u8,
    /// Green, 0–255.
    pub(crate) g: u8,
    /// Blue, 0–255.
    pub(crate) b: u8,
}

impl Colour {
    /// Black.
    pub(crate) const BLACK: Colour = Colour::hex(0x000000);
    /// White.
    pub(crate) const WHITE: Colour = Colour::hex(0xffffff);
    /// The light grey of the grid lines.
    const GRID: Colour = Colour::hex(0xe4e4e4);
    /// The dark grey of the zero line and of the frames.
    const AXIS: Colour = Colour::hex(0x444444);
    /// The mid grey of the zoomed window's outline.
    const MARKER: Colour = Colour::hex(0x999999);

    /// The colour written `0xRRGGBB`, e.g. `Colour::hex(0x1f77b4)`.
    pub const fn hex(rgb: u32) -> Colour {
        Colour {
            r: (rgb >> 16) as u8,
            g: (rgb >> 8) as u8,
            b: rgb as u8,
        }
    }

    /// CSS notation, `#rrggbb`.
    pub(crate) fn css(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }
}

/// One curve: label, colour, points (x, y).
pub struct Series<'a> {
    /// Legend label; an empty one gives no legend entry (e.g. a curve of the same kind
    /// as one before it, which is named).
    pub(crate) label: &'a str,
    /// Stroke colour.
    pub(crate) colour: Colour,
    /// Points in data units; points with a non-finite coordinate are left out.
    pub(crate) points: Vec<(f64, f64)>,
}

impl<'a> Series<'a> {
    /// A curve labelled `label` (empty: no legend entry) in `colour` through `points`
    /// (x, y in data units).
    pub fn new(label: &'a str, colour: Colour, points: Vec<(f64, f64)>) -> Self {
        Series {
            label,
            colour,
            points,
        }
    }
}

/// A shaded band: at each x, the range from `low` to `high` — e.g. ±2 standard errors of
/// a measured mean, within which a model's deviation cannot be told from noise.
pub struct Band<'a> {
    /// Legend label.
    pub(crate) label: &'a str,
    /// Fill colour (a light one: the band is drawn under the grid and the curves).
    pub(crate) colour: Colour,
    /// (x, low, high) in data units; points with a non-finite value are left out.
    pub(crate) points: Vec<(f64, f64, f64)>,
}

impl Band<'_> {
    /// The points whose three values are finite.
    fn finite(&self) -> impl Iterator<Item = (f64, f64, f64)> + '_ {
        self.points
            .iter()
            .copied()
            .filter(|p| p.0.is_finite() && p.1.is_finite() && p.2.is_finite())
    }
}

/// One set of axes of a figure: its curves, its axis titles (naming the units), a
/// title of its own in a figure of several panels, and the line y = 0 if asked for.
pub struct Panel<'a> {
    /// Title over the axes; empty for the one panel of a plain figure.
    title: String,
    x_label: String,
    y_label: String,
    series: Vec<Series<'a>>,
    zero_line: bool,
}

impl<'a> Panel<'a> {
    /// `series` on axes titled `x_label` and `y_label` (units named there), with `title`
    /// over them. The axes span every finite point, widened to round ticks.
    pub fn new(title: &str, x_label: &str, y_label: &str, series: Vec<Series<'a>>) -> Self {
        Panel {
            title: title.to_owned(),
            x_label: x_label.to_owned(),
            y_label: y_label.to_owned(),
            series,
            zero_line: false,
        }
    }

    /// True for a panel of nothing (no curves, no titles): a gap left in a grid.
    fn is_blank(&self) -> bool {
        self.series.is_empty()
            && self.title.is_empty()
            && self.x_label.is_empty()
            && self.y_label.is_empty()
    }

    /// The panel with a dark line at y = 0 (the y axis includes 0).
    pub fn with_zero_line(self) -> Self {
        Panel {
            zero_line: true,
            ..self
        }
    }
}

/// A line plot — one set of axes, or several panels in a grid — ready to be written as
/// SVG or PNG.
pub struct Figure<'a> {
    title: String,
    /// The panels, row by row; one for a plain figure.
    panels: Vec<Panel<'a>>,
    /// Panels per row.
    columns: usize,
    band: Option<Band<'a>>,
    peak_inset: bool,
    equal_scales: bool,
    /// Strokes chosen by legend label (the other kinds of curve take the dash patterns
    /// in turn).
    strokes: Vec<(String, Stroke)>,
}

impl<'a> Figure<'a> {
    /// `series` as a line plot with a title and axis titles (all in data units as given;
    /// the axis titles should name the units). The axes span every finite point, widened
    /// to round ticks.
    pub fn new(title: &str, x_label: &str, y_label: &str, series: Vec<Series<'a>>) -> Self {
        Figure::grid(title, 1, vec![Panel::new("", x_label, y_label, series)])
    }

    /// `panels` in rows of `columns` (at least 1) under one title and one legend, which
    /// names each label of every panel's curves once; a label is drawn alike in every
    /// panel. The image grows with the grid.
    pub fn grid(title: &str, columns: usize, panels: Vec<Panel<'a>>) -> Self {
        Figure {
            title: title.to_owned(),
            panels,
            columns: columns.max(1),
            band: None,
            peak_inset: false,
            equal_scales: false,
            strokes: Vec::new(),
        }
    }

    /// The figure with the curves labelled `label` drawn with `stroke` (e.g. a measured
    /// mean thick and dotted, over the models' lines).
    pub fn with_stroke(mut self, label: &str, stroke: Stroke) -> Self {
        self.strokes.push((label.to_owned(), stroke));
        self
    }

    /// Every series of every panel, in drawing order.
    fn all_series(&self) -> impl Iterator<Item = &Series<'a>> {
        self.panels.iter().flat_map(|p| &p.series)
    }

    /// The figure with `band` shaded under the curves (the y axis spans it too) and
    /// named in the legend after them.
    pub(crate) fn with_band(self, band: Band<'a>) -> Self {
        Figure {
            band: Some(band),
            ..self
        }
    }

    /// The figure with a dark line at y = 0 (the y axis includes 0): for differences,
    /// where the sign matters.
    pub(crate) fn with_zero_line(mut self) -> Self {
        for panel in &mut self.panels {
            panel.zero_line = true;
        }
        self
    }

    /// The figure with an inset that zooms on the highest point of the first series,
    /// showing every series there, for curves too close together to be told apart at
    /// full scale; the zoomed window is outlined on the plot.
    pub(crate) fn with_peak_inset(self) -> Self {
        Figure {
            peak_inset: true,
            ..self
        }
    }

    /// The figure with as many px per data unit along x as along y, for pictures of
    /// space (a side view): the axis ranges are widened to the plot's proportions and
    /// the plot area narrowed to fit the round ticks.
    pub(crate) fn with_equal_scales(self) -> Self {
        Figure {
            equal_scales: true,
            ..self
        }
    }

    /// The figure as an SVG document.
    pub fn svg(&self) -> String {
        svg::render(&Layout::new(self))
    }

    /// The figure as a PNG file (8-bit RGB, [`Figure::size`] pixels).
    pub fn png(&self) -> Result<Vec<u8>, ::png::EncodingError> {
        png::render(&Layout::new(self))
    }

    /// Width and height of the image (px).
    pub fn size(&self) -> (u32, u32) {
        let layout = Layout::new(self);
        (layout.width as u32, layout.height as u32)
    }

    /// The plot area, where the curves are drawn: left, top, right, bottom edges (px from
    /// the image's top-left corner).
    #[cfg(test)]
    pub(crate) fn plot_area(&self) -> (f64, f64, f64, f64) {
        let p = Layout::new(self).plots[0].area;
        (p.left, p.top, p.right, p.bottom)
    }
}

#[cfg(test)]
mod tests {
    use super::layout::{Label, Layout};
    use super::plot::Rect;
    use super::*;

    fn series(label: &str, colour: Colour, points: Vec<(f64, f64)>) -> Series<'_> {
        Series {
            label,
            colour,
            points,
        }
    }

    /// A half-sine force pulse like the ball's (N over µs), shifted by `offset` (N).
    fn pulse(offset: f64) -> Vec<(f64, f64)> {
        (0..=118)
            .map(|t| {
                let t = t as f64;
                (
                    t,
                    3000.0 * (std::f64::consts::PI * t / 118.0).sin() + offset,
                )
            })
            .collect()
    }

    /// The force figure of `reproduce`: three nearly equal pulses, with the peak inset.
    fn force_figure() -> Figure<'static> {
        Figure::new(
            "Contact force over the contact (S2)",
            "time since touch-down (µs)",
            "normal force (N)",
            vec![
                series("S2 mean", Colour::hex(0x333333), pulse(0.0)),
                series("PM2", Colour::hex(0xd62728), pulse(25.0)),
                series("HCM", Colour::hex(0x1f77b4), pulse(8.0)),
            ],
        )
        .with_peak_inset()
    }

    /// The error figure of `reproduce`: two differences, the noise band, the zero line.
    fn error_figure() -> Figure<'static> {
        let wave = |a: f64| (0..=118).map(move |t| (t as f64, a * (t as f64 / 20.0).sin()));
        Figure::new(
            "Force error: S2 mean − model",
            "time since touch-down (µs)",
            "force error (N)",
            vec![
                series("PM2", Colour::hex(0xd62728), wave(-37.0).collect()),
                series("HCM", Colour::hex(0x1f77b4), wave(12.0).collect()),
            ],
        )
        .with_band(Band {
            label: "±2 standard errors of the S2 mean",
            colour: Colour::hex(0xd9d9d9),
            points: (0..=118).map(|t| (t as f64, -6.5, 6.5)).collect(),
        })
        .with_zero_line()
    }

    /// Figures that stress the layout: the two of `reproduce`, long labels, tiny and huge
    /// values, a single point, nothing at all.
    fn figures() -> Vec<Figure<'static>> {
        let long = "a rather long legend label for one of several series";
        vec![
            force_figure(),
            error_figure(),
            Figure::new(
                "Mean residual against the indentation rate δ̇/δ̇₀",
                "indentation rate / approach speed (–)",
                "mean residual, measured − model (N)",
                vec![
                    series(long, Colour::BLACK, vec![(-1.2, 1.1e-4), (0.93, 1.9e-4)]),
                    series(long, Colour::BLACK, vec![(0.0, 1.5e-4)]),
                    series("third", Colour::BLACK, vec![(0.5, 1.2e-4)]),
                ],
            )
            .with_zero_line(),
            Figure::new(
                "huge",
                "x",
                "y",
                vec![series("a", Colour::BLACK, vec![(-3e7, 2e6), (9e7, -4e6)])],
            ),
            Figure::new(
                "one",
                "x",
                "y",
                vec![series("a", Colour::BLACK, vec![(1e300, -1e300)])],
            ),
            Figure::new("none", "x", "y", Vec::new()).with_peak_inset(),
            side_view(),
            grid(),
        ]
    }

    /// Three panels in rows of two, with titles, the last row short, a label shared.
    fn grid() -> Figure<'static> {
        let panel = |title: &'static str, y: &'static str| {
            Panel::new(
                title,
                "time since the first wall contact (ms)",
                y,
                vec![
                    series("PM2", Colour::hex(0xd62728), pulse(3.0)),
                    series("S2 mean", Colour::BLACK, pulse(0.0)),
                ],
            )
        };
        Figure::grid(
            "Contact force and torque on the peg, each wall contact on its own time scale",
            2,
            vec![
                panel("wall contact 1: from 0.00 ms, 0.96 ms long", "‖F‖ (N)"),
                panel("wall contact 2", "‖F‖ (N)"),
                panel("", "‖T‖ about the centre of mass (N·m)").with_zero_line(),
            ],
        )
        .with_stroke(
            "S2 mean",
            Stroke {
                width: 3.0,
                dash: Dash::Dotted,
            },
        )
    }

    #[test]
    fn a_grid_lays_its_panels_side_by_side_with_one_legend_entry_per_label() {
        let layout = Layout::new(&grid());
        assert_eq!(layout.plots.len(), 3);
        assert_eq!(
            (layout.width, layout.plots.len()),
            (2.0 * layout::CELL.0, 3)
        );
        let (a, b, c) = (
            layout.plots[0].area,
            layout.plots[1].area,
            layout.plots[2].area,
        );
        assert!(a.right < b.left && (a.top - b.top).abs() < 1e-9);
        assert!(a.bottom < c.top && (a.left - c.left).abs() < 1e-9);
        assert_eq!(layout.legend.len(), 2);
        let dotted = Stroke {
            width: 3.0,
            dash: Dash::Dotted,
        };
        assert_eq!(layout.legend[1].swatch, legend::Swatch::Line(dotted));
        for plot in &layout.plots {
            let strokes: Vec<Stroke> = plot.curves.iter().map(|c| c.stroke).collect();
            assert_eq!(strokes, [Stroke::dashed(Dash::Solid), dotted]);
        }
        assert!(layout.plots[2].zero.is_some() && layout.plots[0].zero.is_none());
    }

    /// A side view with equal scales: a tall narrow path over a wide floor, and a curve
    /// left out of the legend.
    fn side_view() -> Figure<'static> {
        Figure::new(
            "side view",
            "x (mm)",
            "z (mm)",
            vec![
                series("path", Colour::BLACK, vec![(0.0, 150.0), (10.0, 50.0)]),
                series("floor", Colour::BLACK, vec![(-120.0, 0.0), (60.0, 0.0)]),
                series("", Colour::BLACK, vec![(-20.0, 10.0), (20.0, 10.0)]),
            ],
        )
        .with_equal_scales()
    }

    #[test]
    fn equal_scales_take_as_many_px_per_unit_on_both_axes_and_show_every_point() {
        let layout = Layout::new(&side_view());
        let plot = &layout.plots[0];
        let (x0, x1) = plot.x.range();
        let (y0, y1) = plot.y.range();
        let (sx, sy) = (
            plot.area.width() / (x1 - x0),
            plot.area.height() / (y1 - y0),
        );
        assert!((sx / sy - 1.0).abs() < 1e-12, "{sx} vs {sy} px per mm");
        assert!(x0 <= -120.0 && x1 >= 60.0 && y0 <= 0.0 && y1 >= 150.0);
        // Not much of the image is given away: the plot fills one side of the room.
        let full = Layout::new(&Figure::new("side view", "x (mm)", "z (mm)", Vec::new()));
        let filled = (plot.area.width() / full.plots[0].area.width())
            .max(plot.area.height() / full.plots[0].area.height());
        assert!(filled > 0.99, "{filled}");
        // Two legend entries: the unnamed curve has none.
        assert_eq!(layout.legend.len(), 2);
    }

    #[test]
    fn the_axes_span_every_finite_point_on_whole_ticks_and_pixels_follow_them() {
        let figure = Figure::new(
            "t",
            "x",
            "y",
            vec![series(
                "a",
                Colour::BLACK,
                vec![(1.0, -2.0), (3.0, 8.0), (f64::NAN, 100.0)],
            )],
        );
        let plot = Layout::new(&figure).plots.remove(0);
        assert_eq!(plot.x.range(), (1.0, 3.0));
        assert_eq!(plot.y.range(), (-2.0, 8.0));
        assert_eq!(plot.px(1.0), plot.area.left);
        assert_eq!(plot.px(3.0), plot.area.right);
        assert_eq!(plot.py(-2.0), plot.area.bottom);
        assert_eq!(plot.py(8.0), plot.area.top);
        assert_eq!(plot.grid_y.len(), plot.y.values().count());
        assert_eq!(plot.grid_x.len(), plot.x.values().count());
    }

    #[test]
    fn the_force_figure_has_round_ticks() {
        let plot = Layout::new(&force_figure()).plots.remove(0);
        assert_eq!(plot.x.labels(), ["0", "20", "40", "60", "80", "100", "120"]);
        assert_eq!(
            plot.y.labels(),
            ["0", "500", "1000", "1500", "2000", "2500", "3000", "3500"]
        );
    }

    #[test]
    fn every_label_lies_inside_the_image_and_no_two_overlap() {
        for figure in figures() {
            let layout = Layout::new(&figure);
            let image = Rect {
                left: 0.0,
                top: 0.0,
                right: layout.width,
                bottom: layout.height,
            };
            let boxes: Vec<(&Label, Rect)> =
                layout.labels.iter().map(|l| (l, l.bounds())).collect();
            for (i, (a, ra)) in boxes.iter().enumerate() {
                assert!(image.contains(ra), "{:?} leaves the image: {ra:?}", a.text);
                for (b, rb) in &boxes[i + 1..] {
                    assert!(
                        !ra.overlaps(rb),
                        "{:?} {ra:?} overlaps {:?} {rb:?}",
                        a.text,
                        b.text
                    );
                }
                // Nor does a label run into a plot area: only the inset's labels lie in
                // the main one, on the inset's background.
                let inset = layout.inset.as_ref();
                for other in &layout.plots[1..] {
                    assert!(!ra.overlaps(&other.area), "{:?} in a panel", a.text);
                }
                if ra.overlaps(&layout.plots[0].area) {
                    let inset = inset.unwrap_or_else(|| panic!("{:?} in the plot", a.text));
                    assert!(inset.background.contains(ra), "{:?} off the inset", a.text);
                    assert!(!ra.overlaps(&inset.plot.area), "{:?} in the inset", a.text);
                }
                for entry in &layout.legend {
                    assert!(!ra.overlaps(&entry.area), "{:?} on a swatch", a.text);
                }
            }
        }
    }

    #[test]
    fn the_error_figure_has_its_zero_line_and_noise_band() {
        let layout = Layout::new(&error_figure());
        let plot = &layout.plots[0];
        assert_eq!(plot.zero, Some(plot.py(0.0)));
        assert!(plot.y.values().any(|v| v == 0.0));
        let band = plot.band.as_ref().expect("a band");
        assert_eq!(band.columns.len(), 119);
        for &(_, upper, lower) in &band.columns {
            assert!((upper - plot.py(6.5)).abs() < 1e-9 && (lower - plot.py(-6.5)).abs() < 1e-9);
        }
        // The band is named in the legend, after the curves.
        assert_eq!(layout.legend.len(), 3);
        assert_eq!(layout.legend[2].swatch, legend::Swatch::Block);
        // Without the zero line there is none, and 0 need not be in the range.
        let away = Figure::new(
            "t",
            "x",
            "y",
            vec![series("a", Colour::BLACK, vec![(0.0, 5.0), (1.0, 6.0)])],
        );
        let plot = Layout::new(&away).plots.remove(0);
        assert_eq!(plot.zero, None);
        assert!(plot.y.range().0 > 0.0);
    }

    #[test]
    fn the_peak_inset_zooms_where_the_curves_differ_and_hides_none_of_the_peak() {
        let layout = Layout::new(&force_figure());
        let inset = layout.inset.as_ref().expect("an inset");
        let (main, zoom) = (&layout.plots[0], &inset.plot);
        // Inside the plot area, clear of the window it zooms on.
        assert!(main.area.contains(&inset.background));
        assert!(!inset.background.overlaps(&inset.marker));
        // The window is around the peak (59 µs), and much taller in px than on the main plot.
        let (x0, x1) = zoom.x.range();
        assert!(x0 < 59.0 && x1 > 59.0 && x1 - x0 < 30.0, "{x0}–{x1}");
        let (y0, y1) = zoom.y.range();
        let gain = zoom.area.height() / (y1 - y0) / (main.area.height() / 3500.0);
        assert!(gain > 5.0, "zoom ×{gain}");
        // The 25 N between two curves is several px apart in the inset.
        assert!(zoom.py(3000.0) - zoom.py(3025.0) > 8.0);
        // Every curve shows there, inside the inset's frame.
        assert_eq!(zoom.curves.len(), 3);
        for curve in &zoom.curves {
            assert!(!curve.pieces.is_empty());
            let inside = |p: &(f64, f64)| {
                zoom.area.left - 1e-9 <= p.0
                    && p.0 <= zoom.area.right + 1e-9
                    && zoom.area.top - 1e-9 <= p.1
                    && p.1 <= zoom.area.bottom + 1e-9
            };
            assert!(curve.pieces.iter().flatten().all(inside));
        }
        // No inset is asked of the error figure, and a figure without points gets none.
        assert!(Layout::new(&error_figure()).inset.is_none());
        assert!(Layout::new(&figures()[5]).inset.is_none());
    }

    #[test]
    fn colours_read_and_write_hex() {
        let c = Colour::hex(0x1f77b4);
        assert_eq!((c.r, c.g, c.b), (0x1f, 0x77, 0xb4));
        assert_eq!(c.css(), "#1f77b4");
    }
}
