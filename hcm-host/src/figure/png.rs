//! The raster renderer: draws a [`Figure`]'s layout into an RGB pixel buffer with
//! `embedded-graphics` and encodes it with the `png` crate.
//!
//! Text uses the bitmap fonts compiled into `embedded-graphics`, so no font file or system
//! font is needed. Those fonts cover ASCII only: other characters are drawn as an ASCII
//! look-alike ("δ" → "d", "µs" → "us", "–" → "-"; see [`ascii`]).

use super::{Anchor, Colour, Figure, Label, Rect, TextSize};
use embedded_graphics::mono_font::ascii::{FONT_7X13, FONT_9X15};
use embedded_graphics::mono_font::MonoTextStyle;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{
    Line, Polyline, PrimitiveStyle, PrimitiveStyleBuilder, Rectangle, StrokeAlignment,
};
use embedded_graphics::text::{Alignment, Baseline, Text, TextStyleBuilder};
use std::convert::Infallible;

/// Stroke width of the curves (px).
const CURVE_WIDTH: u32 = 2;
/// Stroke width of the legend's colour lines (px).
const SWATCH_WIDTH: u32 = 2;

/// The figure as a PNG file: 8-bit RGB, [`Figure::size`] pixels.
pub(super) fn render(figure: &Figure) -> Result<Vec<u8>, png::EncodingError> {
    let layout = &figure.layout;
    let (width, height) = figure.size();
    let mut canvas = Canvas::new(width, height, Colour::WHITE);
    for &y in &layout.grid {
        line(
            &mut canvas,
            (layout.plot.left, y),
            (layout.plot.right, y),
            Colour::GRID,
            1,
        );
    }
    rectangle(&mut canvas, layout.plot, None, Colour::BLACK);
    for s in &figure.series {
        let vertices: Vec<Point> = layout.path(s).into_iter().map(point).collect();
        let style = PrimitiveStyle::with_stroke(rgb(s.colour), CURVE_WIDTH);
        let Ok(()) = Polyline::new(&vertices)
            .into_styled(style)
            .draw(&mut canvas);
    }
    if let Some(frame) = layout.legend_box {
        rectangle(
            &mut canvas,
            frame,
            Some(Colour::WHITE),
            Colour::LEGEND_BORDER,
        );
    }
    for (s, row) in figure.series.iter().zip(&layout.legend) {
        line(
            &mut canvas,
            (row.x0, row.y),
            (row.x1, row.y),
            s.colour,
            SWATCH_WIDTH,
        );
    }
    for label in &layout.labels {
        text(&mut canvas, label);
    }
    canvas.encode()
}

/// An RGB image in memory, 8 bits per channel, rows top to bottom.
struct Canvas {
    /// Width (px).
    width: u32,
    /// Height (px).
    height: u32,
    /// `3 × width × height` bytes: red, green, blue of each pixel, row by row.
    rgb: Vec<u8>,
}

impl Canvas {
    /// A `width` × `height` px canvas filled with `background`.
    fn new(width: u32, height: u32, background: Colour) -> Canvas {
        let pixels = width as usize * height as usize;
        Canvas {
            width,
            height,
            rgb: [background.r, background.g, background.b].repeat(pixels),
        }
    }

    /// The canvas as a PNG file.
    fn encode(&self) -> Result<Vec<u8>, png::EncodingError> {
        let mut bytes = Vec::new();
        let mut encoder = png::Encoder::new(&mut bytes, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(&self.rgb)?;
        writer.finish()?;
        Ok(bytes)
    }
}

impl OriginDimensions for Canvas {
    fn size(&self) -> Size {
        Size::new(self.width, self.height)
    }
}

impl DrawTarget for Canvas {
    type Color = Rgb888;
    type Error = Infallible;

    /// Sets each pixel; those outside the canvas are dropped.
    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<Rgb888>>,
    {
        for Pixel(at, colour) in pixels {
            let (Ok(x), Ok(y)) = (u32::try_from(at.x), u32::try_from(at.y)) else {
                continue;
            };
            if x < self.width && y < self.height {
                let i = 3 * (y as usize * self.width as usize + x as usize);
                self.rgb[i..i + 3].copy_from_slice(&[colour.r(), colour.g(), colour.b()]);
            }
        }
        Ok(())
    }
}

/// Draws onto a canvas turned a quarter turn anticlockwise about `pivot`: what is drawn
/// left to right there reads bottom to top on the canvas (for the y axis label).
struct Turned<'c> {
    canvas: &'c mut Canvas,
    /// The fixed point (px).
    pivot: Point,
}

impl Turned<'_> {
    /// The canvas pixel that `at` (in the turned frame) lands on.
    fn to_canvas(&self, at: Point) -> Point {
        let (c, d) = (self.pivot, at - self.pivot);
        Point::new(c.x + d.y, c.y - d.x)
    }
}

impl Dimensions for Turned<'_> {
    /// The canvas, seen from the turned frame.
    fn bounding_box(&self) -> Rectangle {
        let (c, size) = (self.pivot, self.canvas.size());
        let top_left = Point::new(c.x + c.y - size.height as i32 + 1, c.y - c.x);
        Rectangle::new(top_left, Size::new(size.height, size.width))
    }
}

impl DrawTarget for Turned<'_> {
    type Color = Rgb888;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<Rgb888>>,
    {
        let turned: Vec<_> = pixels
            .into_iter()
            .map(|Pixel(at, colour)| Pixel(self.to_canvas(at), colour))
            .collect();
        self.canvas.draw_iter(turned)
    }
}

/// The nearest pixel to `(x, y)` (px), kept well clear of `i32`'s limits so that the drawing
/// arithmetic cannot overflow whatever the data.
fn point((x, y): (f64, f64)) -> Point {
    let clamp = |v: f64| v.round().clamp(-1e5, 1e5) as i32;
    Point::new(clamp(x), clamp(y))
}

fn rgb(colour: Colour) -> Rgb888 {
    Rgb888::new(colour.r, colour.g, colour.b)
}

/// Draws a straight line `width` px wide from `from` to `to` (px).
fn line(canvas: &mut Canvas, from: (f64, f64), to: (f64, f64), colour: Colour, width: u32) {
    let style = PrimitiveStyle::with_stroke(rgb(colour), width);
    let Ok(()) = Line::new(point(from), point(to))
        .into_styled(style)
        .draw(canvas);
}

/// Draws `r` with a 1 px outline in `stroke` (on its edges), filled with `fill` if any.
fn rectangle(canvas: &mut Canvas, r: Rect, fill: Option<Colour>, stroke: Colour) {
    let (top_left, bottom_right) = (point((r.left, r.top)), point((r.right, r.bottom)));
    let size = Size::new(
        (bottom_right.x - top_left.x + 1).max(0) as u32,
        (bottom_right.y - top_left.y + 1).max(0) as u32,
    );
    let mut style = PrimitiveStyleBuilder::new()
        .stroke_color(rgb(stroke))
        .stroke_width(1)
        .stroke_alignment(StrokeAlignment::Inside);
    if let Some(fill) = fill {
        style = style.fill_color(rgb(fill));
    }
    let Ok(()) = Rectangle::new(top_left, size)
        .into_styled(style.build())
        .draw(canvas);
}

/// Draws a label in black.
fn text(canvas: &mut Canvas, label: &Label) {
    let font = match label.size {
        TextSize::Title => &FONT_9X15,
        TextSize::Normal => &FONT_7X13,
    };
    let alignment = match label.anchor {
        Anchor::Start => Alignment::Left,
        Anchor::Middle => Alignment::Center,
        Anchor::End => Alignment::Right,
    };
    let shown = ascii(&label.text);
    let at = point((label.x, label.y));
    let text = Text::with_text_style(
        &shown,
        at,
        MonoTextStyle::new(font, Rgb888::BLACK),
        TextStyleBuilder::new()
            .alignment(alignment)
            .baseline(Baseline::Alphabetic)
            .build(),
    );
    let Ok(_) = if label.vertical {
        text.draw(&mut Turned { canvas, pivot: at })
    } else {
        text.draw(canvas)
    };
}

/// `text` in printable ASCII, which the built-in fonts cover: each other character becomes
/// a look-alike ("δ" → "d", "µ" → "u", "–" → "-", "²" → "^2"), or "?" if it has none.
fn ascii(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c == ' ' || c.is_ascii_graphic() {
            out.push(c);
            continue;
        }
        out.push_str(match c {
            'α' => "a",
            'β' => "b",
            'γ' => "g",
            'δ' => "d",
            'Δ' => "D",
            'ε' => "e",
            'η' => "eta",
            'θ' => "th",
            'κ' => "k",
            'λ' => "l",
            'µ' | 'μ' => "u",
            'ν' => "nu",
            'π' => "pi",
            'ρ' => "rho",
            'σ' => "s",
            'τ' => "tau",
            'φ' => "phi",
            'ω' => "w",
            'Ω' => "Ohm",
            '–' | '—' | '−' | '‐' | '‑' => "-",
            '‘' | '’' | '′' => "'",
            '“' | '”' | '″' => "\"",
            '·' | '⋅' => "*",
            '×' => "x",
            '÷' => "/",
            '±' => "+/-",
            '≈' | '∼' => "~",
            '≤' => "<=",
            '≥' => ">=",
            '≠' => "!=",
            '→' => "->",
            '←' => "<-",
            '°' => "deg",
            '²' => "^2",
            '³' => "^3",
            '¹' => "^1",
            '√' => "sqrt",
            '…' => "...",
            '\u{a0}' | '\u{2009}' | '\u{202f}' | '\t' | '\n' => " ",
            _ => "?",
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::Series;
    use super::*;

    /// Decodes a PNG: width, height (px) and 8-bit RGB bytes, row by row.
    fn decode(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
        let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
            .read_info()
            .expect("a PNG header");
        let mut buffer = vec![0; reader.output_buffer_size().expect("a buffer size")];
        let info = reader.next_frame(&mut buffer).expect("a PNG frame");
        assert_eq!(
            (info.color_type, info.bit_depth),
            (png::ColorType::Rgb, png::BitDepth::Eight)
        );
        buffer.truncate(info.buffer_size());
        (info.width, info.height, buffer)
    }

    /// The pixels of colour `c` strictly inside `area` (left, top, right, bottom; px).
    fn count(
        (width, _, rgb): &(u32, u32, Vec<u8>),
        area: (f64, f64, f64, f64),
        c: Colour,
    ) -> usize {
        let (left, top, right, bottom) = area;
        rgb.chunks_exact(3)
            .enumerate()
            .filter(|(i, p)| {
                let (x, y) = ((i % *width as usize) as f64, (i / *width as usize) as f64);
                x > left && x < right && y > top && y < bottom && *p == [c.r, c.g, c.b]
            })
            .count()
    }

    const RED: Colour = Colour::hex(0xd62728);
    const BLUE: Colour = Colour::hex(0x1f77b4);

    fn series(label: &str, colour: Colour, points: Vec<(f64, f64)>) -> Series<'_> {
        Series {
            label,
            colour,
            points,
        }
    }

    #[test]
    fn the_png_decodes_to_the_declared_size() {
        let figure = Figure::new(
            "Contact force",
            "time (µs)",
            "force (N)",
            vec![series("a", RED, vec![(0.0, 0.0), (1.0, 2.0)])],
        );
        let (width, height, rgb) = decode(&figure.png().unwrap());
        assert_eq!((width, height), figure.size());
        assert_eq!((width, height), (720, 440));
        assert_eq!(rgb.len(), 3 * 720 * 440);
    }

    #[test]
    fn each_series_is_drawn_in_its_colour_inside_the_plot_area() {
        let figure = Figure::new(
            "t",
            "x",
            "y",
            vec![
                series(
                    "rising",
                    RED,
                    (0..50).map(|i| (i as f64, i as f64)).collect(),
                ),
                series("flat", BLUE, vec![(0.0, 10.0), (49.0, 10.0)]),
            ],
        );
        let image = decode(&figure.png().unwrap());
        let area = figure.plot_area();
        let (left, _, right, _) = area;
        // The diagonal and the flat line each cross the whole plot area, 2 px wide: far more
        // pixels than their legend lines (25 px × 2) alone.
        for colour in [RED, BLUE] {
            let n = count(&image, area, colour);
            assert!(n as f64 > 1.5 * (right - left), "{colour:?}: {n} px");
        }
        // Nothing is drawn in a colour that is not asked for.
        assert_eq!(count(&image, area, Colour::hex(0x00ff00)), 0);
    }

    #[test]
    fn a_flat_line_lies_at_its_value() {
        let figure = Figure::new(
            "t",
            "x",
            "y",
            vec![
                series("low", RED, vec![(0.0, 0.0), (1.0, 0.0)]),
                series("high", BLUE, vec![(0.0, 1.0), (1.0, 1.0)]),
            ],
        );
        let (width, _, rgb) = decode(&figure.png().unwrap());
        let (left, top, right, bottom) = figure.plot_area();
        // y runs from −0.05 to 1.05 (5 % padding): 0 is 1/22 of the height above the bottom.
        let expected = bottom - (bottom - top) / 22.0;
        let column = ((left + right) / 2.0) as usize;
        let rows: Vec<usize> = (0..rgb.len() / 3 / width as usize)
            .filter(|y| {
                let i = 3 * (y * width as usize + column);
                rgb[i..i + 3] == [RED.r, RED.g, RED.b]
            })
            .collect();
        assert!(!rows.is_empty());
        for y in rows {
            assert!((y as f64 - expected).abs() <= 1.5, "{y} vs {expected}");
        }
    }

    #[test]
    fn nan_points_a_single_point_and_empty_series_draw_without_panicking() {
        let cases = [
            vec![series("nan", RED, vec![(f64::NAN, 1.0), (0.0, f64::NAN)])],
            vec![series(
                "some nan",
                RED,
                vec![
                    (0.0, 0.0),
                    (f64::NAN, 5.0),
                    (2.0, f64::INFINITY),
                    (3.0, 1.0),
                ],
            )],
            vec![series("single", RED, vec![(1e300, -1e300)])],
            vec![
                series("empty", RED, Vec::new()),
                series("also", BLUE, vec![]),
            ],
            vec![],
        ];
        for (i, case) in cases.into_iter().enumerate() {
            let n = case.len();
            let figure = Figure::new("t", "x", "y", case);
            let image = decode(&figure.png().unwrap());
            assert_eq!((image.0, image.1), figure.size(), "case {i}");
            // The legend still shows every series' colour.
            let (_, top, right, _) = figure.plot_area();
            let legend = (right - 200.0, top, right, top + 20.0 + 16.0 * n as f64);
            if n > 0 {
                assert!(count(&image, legend, RED) > 0, "case {i}");
            }
        }
    }

    #[test]
    fn labels_are_drawn_and_non_ascii_falls_back_to_ascii() {
        assert_eq!(ascii("time (µs)"), "time (us)");
        assert_eq!(ascii("δ – S2 − model"), "d - S2 - model");
        assert_eq!(ascii("漢"), "?");
        // A label of non-ASCII characters still puts black pixels where the title goes.
        let figure = Figure::new("δδδ µµµ", "x", "y", Vec::new());
        let image = decode(&figure.png().unwrap());
        let (width, _) = figure.size();
        let title = (
            width as f64 / 2.0 - 40.0,
            5.0,
            width as f64 / 2.0 + 40.0,
            30.0,
        );
        assert!(count(&image, title, Colour::BLACK) > 20);
    }

    #[test]
    fn the_y_label_reads_bottom_to_top() {
        let mut canvas = Canvas::new(40, 40, Colour::WHITE);
        let pivot = Point::new(20, 20);
        let turned = Turned {
            canvas: &mut canvas,
            pivot,
        };
        // Right of the pivot in the turned frame is above it on the canvas; above is left.
        assert_eq!(turned.to_canvas(Point::new(25, 20)), Point::new(20, 15));
        assert_eq!(turned.to_canvas(Point::new(20, 15)), Point::new(15, 20));
        // The bounding box is exactly the canvas, seen from the turned frame.
        let on_canvas = |p: Point| (0..40).contains(&p.x) && (0..40).contains(&p.y);
        let frame = turned.bounding_box();
        assert_eq!(frame.points().count(), 40 * 40);
        assert!(frame.points().all(|p| on_canvas(turned.to_canvas(p))));
    }
}
