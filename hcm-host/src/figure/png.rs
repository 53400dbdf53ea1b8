//! The raster renderer: draws a figure's [`Layout`] onto a [`Canvas`] and encodes it as
//! PNG. Curves are anti-aliased strokes; text is drawn anti-aliased in the DejaVu Sans
//! font that `font.rs` compiles in, so every label shows as written (δ̇, µ, σ, ±,
//! superscripts).

use super::canvas::Canvas;
use super::font;
use super::layout::{Anchor, Label, Layout};
use super::legend::Swatch;
use super::plot::{Plot, Shade};
use super::style::{dashes, Stroke};
use super::Colour;

/// The layout as a PNG file: 8-bit RGB, `width` × `height` pixels.
pub(super) fn render(layout: &Layout) -> Result<Vec<u8>, png::EncodingError> {
    let mut canvas = Canvas::new(layout.width as u32, layout.height as u32, Colour::WHITE);
    for p in &layout.plots {
        plot(&mut canvas, p);
    }
    if let Some(inset) = &layout.inset {
        canvas.outline(inset.marker, Colour::MARKER);
        let b = inset.background;
        canvas.fill((b.left, b.right), (b.top, b.bottom), Colour::WHITE);
        plot(&mut canvas, &inset.plot);
    }
    for entry in &layout.legend {
        let a = entry.area;
        match entry.swatch {
            Swatch::Line(stroke) => {
                let y = 0.5 * (a.top + a.bottom);
                let line = [(a.left, y), (a.right, y)];
                dashed(&mut canvas, &[line.to_vec()], stroke, entry.colour);
            }
            Swatch::Block => canvas.fill((a.left, a.right), (a.top, a.bottom), entry.colour),
        }
    }
    for label in &layout.labels {
        text(&mut canvas, label);
    }
    canvas.encode()
}

/// Draws one set of axes: band, grid, zero line, frame, curves.
fn plot(canvas: &mut Canvas, plot: &Plot) {
    let area = plot.area;
    if let Some(band) = &plot.band {
        shade(canvas, band);
    }
    for &y in &plot.grid_y {
        canvas.horizontal((area.left, area.right), y, 1.0, Colour::GRID);
    }
    for &x in &plot.grid_x {
        canvas.vertical(x, (area.top, area.bottom), Colour::GRID);
    }
    if let Some(y) = plot.zero {
        canvas.horizontal((area.left, area.right), y, 1.0, Colour::AXIS);
    }
    canvas.outline(area, Colour::AXIS);
    for curve in &plot.curves {
        dashed(canvas, &curve.pieces, curve.stroke, curve.colour);
    }
}

/// Strokes the polylines `pieces` (px) with `stroke`'s width and dashes in `colour`.
fn dashed(canvas: &mut Canvas, pieces: &[Vec<(f64, f64)>], stroke: Stroke, colour: Colour) {
    let pattern = stroke.pattern();
    let cut: Vec<Vec<(f64, f64)>> = pieces.iter().flat_map(|p| dashes(p, &pattern)).collect();
    canvas.stroke_pieces(&cut, stroke.width, colour);
}

/// Fills the band: every pixel column between two of its points, from the upper to the
/// lower edge, both interpolated linearly.
fn shade(canvas: &mut Canvas, band: &Shade) {
    for pair in band.columns.windows(2) {
        let ((x0, top0, bottom0), (x1, top1, bottom1)) = (pair[0], pair[1]);
        let mut column = x0.min(x1).round();
        while column <= x0.max(x1).round() {
            let t = if x1 == x0 {
                0.0
            } else {
                (column - x0) / (x1 - x0)
            };
            let t = t.clamp(0.0, 1.0);
            let (top, bottom) = (top0 + t * (top1 - top0), bottom0 + t * (bottom1 - bottom0));
            canvas.fill((column, column), (top, bottom), band.colour);
            column += 1.0;
        }
    }
}

/// Draws a label in black, anti-aliased; a vertical one turned a quarter turn
/// anticlockwise about its reference point.
fn text(canvas: &mut Canvas, label: &Label) {
    let size = label.size.px();
    let line = font::set(&label.text, size);
    let start = match label.anchor {
        Anchor::Start => 0.0,
        Anchor::Middle => -0.5 * line.width,
        Anchor::End => -line.width,
    };
    let pivot = (label.x.round() as i64, label.y.round() as i64);
    let origin = (pivot.0 as f64 + start, pivot.1 as f64);
    font::draw(&line, origin, |x, y, coverage| {
        let at = if label.vertical {
            turned(pivot, (x, y))
        } else {
            (x, y)
        };
        canvas.blend(at, Colour::BLACK, coverage);
    });
}

/// The canvas pixel that pixel `at` of a frame turned a quarter turn anticlockwise about
/// `pivot` lands on: right of the pivot there is above it on the canvas, below is right.
fn turned(pivot: (i64, i64), at: (i64, i64)) -> (i64, i64) {
    let (dx, dy) = (at.0 - pivot.0, at.1 - pivot.1);
    (pivot.0 + dy, pivot.1 - dx)
}

#[cfg(test)]
mod tests {
    use super::super::{Figure, Series};
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

    /// The pixels strictly inside `area` at least half covered by `c` over white: each
    /// channel at most half-way from `c` back to white.
    fn count_covered(
        (width, _, rgb): &(u32, u32, Vec<u8>),
        area: (f64, f64, f64, f64),
        c: Colour,
    ) -> usize {
        let (left, top, right, bottom) = area;
        let near = |p: u8, c: u8| (p as f64 - c as f64).abs() <= 0.5 * (255.0 - c as f64) + 0.5;
        rgb.chunks_exact(3)
            .enumerate()
            .filter(|(i, p)| {
                let (x, y) = ((i % *width as usize) as f64, (i / *width as usize) as f64);
                let inside = x > left && x < right && y > top && y < bottom;
                inside && near(p[0], c.r) && near(p[1], c.g) && near(p[2], c.b)
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
        // pixels than their legend lines (32 px × 2) alone. Anti-aliased, a 2 px line is
        // its colour exactly along its 1 px core and at least half so across its width.
        // The second curve is dashed (7 px on, 4 px off, round ends): over 6/10 of it.
        for (colour, share) in [(RED, 1.0), (BLUE, 0.6)] {
            let n = count_covered(&image, area, colour);
            assert!(
                n as f64 > 1.5 * share * (right - left),
                "{colour:?}: {n} px"
            );
            let core = count(&image, area, colour);
            assert!(
                core as f64 > 0.9 * share * (right - left),
                "{colour:?}: {core} px"
            );
            assert!(
                BLUE != colour || (core as f64) < 0.95 * (right - left),
                "dashed"
            );
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
                series("low", RED, vec![(0.0, 0.25), (1.0, 0.25)]),
                series("high", BLUE, vec![(0.0, 1.0), (1.0, 1.0)]),
            ],
        );
        let (width, _, rgb) = decode(&figure.png().unwrap());
        let (left, top, right, bottom) = figure.plot_area();
        // y runs from 0.2 to 1.0 (ticks every 0.1): 0.25 is 1/16 of the height above the bottom.
        let expected = bottom - (bottom - top) / 16.0;
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
            // The legend, between the title and the plot area, still shows every series' colour.
            let (_, top, _, _) = figure.plot_area();
            let legend = (0.0, 20.0, image.0 as f64, top);
            if n > 0 {
                assert!(count(&image, legend, RED) > 0, "case {i}");
            }
        }
    }

    #[test]
    fn labels_are_drawn_in_their_own_characters() {
        // A label of non-ASCII characters puts black pixels where the title goes.
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
        // δ and d are different glyphs now (the bitmap fonts drew δ as d), and so are
        // µ and u: the two titles differ in their pixels.
        let pixels =
            |title: &str| decode(&Figure::new(title, "x", "y", Vec::new()).png().unwrap()).2;
        assert_ne!(pixels("δ µs"), pixels("d us"));
        // Anti-aliased: the title's edges have grey levels between white and black.
        let greys = image
            .2
            .chunks_exact(3)
            .filter(|p| p[0] == p[1] && p[1] == p[2] && p[0] > 30 && p[0] < 220)
            .count();
        assert!(greys > 50, "{greys} grey pixels");
    }

    #[test]
    fn the_y_label_reads_bottom_to_top() {
        // Right of the pivot in the turned frame is above it on the canvas; above is left.
        assert_eq!(turned((20, 20), (25, 20)), (20, 15));
        assert_eq!(turned((20, 20), (20, 15)), (15, 20));
        // A vertical label's ink lies in a column left of the plot area, taller than wide.
        let figure = Figure::new("t", "x", "a long axis title", Vec::new());
        let image = decode(&figure.png().unwrap());
        let (left, top, _, bottom) = figure.plot_area();
        let ink: Vec<(usize, usize)> = image
            .2
            .chunks_exact(3)
            .enumerate()
            .filter(|(i, p)| {
                let (x, y) = (i % image.0 as usize, i / image.0 as usize);
                (x as f64) < left - 30.0 && (y as f64) > top && (y as f64) < bottom && p[0] < 128
            })
            .map(|(i, _)| (i % image.0 as usize, i / image.0 as usize))
            .collect();
        let (xs, ys) = (
            super::super::layout::extent(ink.iter().map(|p| p.0 as f64)),
            super::super::layout::extent(ink.iter().map(|p| p.1 as f64)),
        );
        assert!(ys.1 - ys.0 > 4.0 * (xs.1 - xs.0), "{xs:?} {ys:?}");
    }
}
