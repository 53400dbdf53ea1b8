//! An RGB image in memory with the few drawing operations a figure needs: crisp
//! axis-aligned lines and fills for the frame, grid and band, anti-aliased strokes for the
//! curves, coverage blending for the glyphs, and PNG encoding.
//!
//! Pixel `(i, j)` is centred on the point (i, j) px of the layout, so a 1 px line at
//! y = 100.0 fills row 100 exactly.

use super::plot::Rect;
use super::Colour;

/// Coordinates are clamped to this far outside the image before rounding (px), so that no
/// data, however large, can overflow the integer arithmetic.
const BEYOND: f64 = 1e5;

/// An RGB image, 8 bits per channel, rows top to bottom.
pub(super) struct Canvas {
    /// Width (px).
    width: u32,
    /// Height (px).
    height: u32,
    /// `3 × width × height` bytes: red, green, blue of each pixel, row by row.
    rgb: Vec<u8>,
}

impl Canvas {
    /// A `width` × `height` px canvas filled with `background`.
    pub(super) fn new(width: u32, height: u32, background: Colour) -> Canvas {
        let pixels = width as usize * height as usize;
        Canvas {
            width,
            height,
            rgb: [background.r, background.g, background.b].repeat(pixels),
        }
    }

    /// The index of pixel `(x, y)` in `rgb`'s pixels, or None outside the canvas.
    fn index(&self, (x, y): (i64, i64)) -> Option<usize> {
        let inside = (0..self.width as i64).contains(&x) && (0..self.height as i64).contains(&y);
        inside.then(|| y as usize * self.width as usize + x as usize)
    }

    /// Mixes `colour` into pixel `at` by `coverage` (0: unchanged, 1: `colour`); a pixel
    /// outside the canvas is ignored.
    pub(super) fn blend(&mut self, at: (i64, i64), colour: Colour, coverage: f32) {
        let Some(i) = self.index(at) else {
            return;
        };
        let c = coverage.clamp(0.0, 1.0);
        let pixel = &mut self.rgb[3 * i..3 * i + 3];
        for (old, new) in pixel.iter_mut().zip([colour.r, colour.g, colour.b]) {
            *old = (*old as f32 + c * (new as f32 - *old as f32)).round() as u8;
        }
    }

    /// Paints the pixels from column `x0` to `x1` and row `y0` to `y1` (px, rounded to
    /// the nearest pixel, ends included).
    pub(super) fn fill(&mut self, (x0, x1): (f64, f64), (y0, y1): (f64, f64), colour: Colour) {
        let (x0, x1) = (pixel(x0.min(x1)), pixel(x0.max(x1)));
        let (y0, y1) = (pixel(y0.min(y1)), pixel(y0.max(y1)));
        let (x0, x1) = (x0.max(0), x1.min(self.width as i64 - 1));
        let (y0, y1) = (y0.max(0), y1.min(self.height as i64 - 1));
        for y in y0..=y1 {
            for x in x0..=x1 {
                self.blend((x, y), colour, 1.0);
            }
        }
    }

    /// A horizontal line `thickness` px thick through y from `x0` to `x1` (px).
    pub(super) fn horizontal(
        &mut self,
        (x0, x1): (f64, f64),
        y: f64,
        thickness: f64,
        colour: Colour,
    ) {
        let half = 0.5 * (thickness - 1.0).max(0.0);
        self.fill((x0, x1), (y - half, y + half), colour);
    }

    /// A vertical line 1 px wide through x from `y0` to `y1` (px).
    pub(super) fn vertical(&mut self, x: f64, (y0, y1): (f64, f64), colour: Colour) {
        self.fill((x, x), (y0, y1), colour);
    }

    /// The 1 px outline of `r`, on its edges.
    pub(super) fn outline(&mut self, r: Rect, colour: Colour) {
        self.horizontal((r.left, r.right), r.top, 1.0, colour);
        self.horizontal((r.left, r.right), r.bottom, 1.0, colour);
        self.vertical(r.left, (r.top, r.bottom), colour);
        self.vertical(r.right, (r.top, r.bottom), colour);
    }

    /// Strokes the polyline through `points` (px) `width` px wide with round joins and
    /// ends, anti-aliased (see [`Canvas::stroke_pieces`]).
    #[cfg(test)]
    pub(super) fn stroke(&mut self, points: &[(f64, f64)], width: f64, colour: Colour) {
        self.stroke_pieces(&[points.to_vec()], width, colour);
    }

    /// Strokes the polylines through each of `pieces` (px) `width` px wide with round
    /// joins and ends, anti-aliased: each pixel is covered by how far its centre lies
    /// inside the stroke (a 1 px ramp at the edge), once for all the pieces so that joins
    /// and touching dashes do not darken. A piece of one point is a round dot.
    pub(super) fn stroke_pieces(&mut self, pieces: &[Vec<(f64, f64)>], width: f64, colour: Colour) {
        let mut coverage = vec![0f32; self.width as usize * self.height as usize];
        let mut touched = Vec::new();
        let segments = pieces.iter().flat_map(|points| {
            let single = (points.len() == 1).then(|| (points[0], points[0]));
            points.windows(2).map(|w| (w[0], w[1])).chain(single)
        });
        let half = 0.5 * width;
        for (a, b) in segments {
            let (a, b) = (clamped(a), clamped(b));
            let reach = half + 1.0;
            let (x0, x1) = (pixel(a.0.min(b.0) - reach), pixel(a.0.max(b.0) + reach));
            let (y0, y1) = (pixel(a.1.min(b.1) - reach), pixel(a.1.max(b.1) + reach));
            for y in y0.max(0)..=y1.min(self.height as i64 - 1) {
                for x in x0.max(0)..=x1.min(self.width as i64 - 1) {
                    let d = distance((x as f64, y as f64), a, b);
                    let c = (half + 0.5 - d).clamp(0.0, 1.0) as f32;
                    let Some(i) = self.index((x, y)) else {
                        continue;
                    };
                    if c > coverage[i] {
                        if coverage[i] == 0.0 {
                            touched.push((x, y));
                        }
                        coverage[i] = c;
                    }
                }
            }
        }
        for at in touched {
            if let Some(i) = self.index(at) {
                self.blend(at, colour, coverage[i]);
            }
        }
    }

    /// The canvas as a PNG file.
    pub(super) fn encode(&self) -> Result<Vec<u8>, png::EncodingError> {
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

/// The pixel whose centre is nearest to coordinate `v` (px).
fn pixel(v: f64) -> i64 {
    v.clamp(-BEYOND, BEYOND).round() as i64
}

/// `p` with both coordinates clamped to ±[`BEYOND`] (px).
fn clamped(p: (f64, f64)) -> (f64, f64) {
    (p.0.clamp(-BEYOND, BEYOND), p.1.clamp(-BEYOND, BEYOND))
}

/// The distance from `p` to the segment `a`–`b` (px).
fn distance(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let length2 = dx * dx + dy * dy;
    let t = if length2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    const RED: Colour = Colour::hex(0xff0000);

    fn at(canvas: &Canvas, x: usize, y: usize) -> [u8; 3] {
        let i = 3 * (y * canvas.width as usize + x);
        [canvas.rgb[i], canvas.rgb[i + 1], canvas.rgb[i + 2]]
    }

    #[test]
    fn a_stroke_is_solid_in_its_core_and_fades_at_its_edges() {
        let mut canvas = Canvas::new(40, 40, Colour::WHITE);
        canvas.stroke(&[(5.0, 20.5), (35.0, 20.5)], 3.0, RED);
        // Core rows 20 and 21 (centres within 1 px of the line) are red; rows 19 and 22
        // (1.5 px away) half covered; farther rows untouched.
        for y in [20, 21] {
            assert_eq!(at(&canvas, 20, y), [255, 0, 0], "row {y}");
        }
        for y in [19, 22] {
            assert_eq!(at(&canvas, 20, y), [255, 128, 128], "row {y}");
        }
        assert_eq!(at(&canvas, 20, 18), [255, 255, 255]);
        assert_eq!(at(&canvas, 20, 23), [255, 255, 255]);
        // Where two segments meet, the join is not drawn darker than the line.
        let mut joined = Canvas::new(40, 40, Colour::WHITE);
        joined.stroke(
            &[(5.0, 20.2), (20.0, 20.2), (35.0, 20.2)],
            3.0,
            Colour::BLACK,
        );
        assert_eq!(at(&joined, 20, 19), at(&joined, 10, 19));
        assert_ne!(at(&joined, 20, 19), [255, 255, 255]);
    }

    #[test]
    fn fills_and_strokes_outside_the_canvas_are_cut_off() {
        let mut canvas = Canvas::new(10, 10, Colour::WHITE);
        canvas.fill((-5.0, 50.0), (-1e300, 1e300), RED);
        assert!(canvas.rgb.chunks_exact(3).all(|p| p == [255, 0, 0]));
        let mut canvas = Canvas::new(10, 10, Colour::WHITE);
        canvas.stroke(&[(-1e9, -1e9), (1e9, 1e9)], 2.0, RED);
        assert_eq!(at(&canvas, 5, 5), [255, 0, 0]);
        // A single point is a round dot.
        let mut canvas = Canvas::new(10, 10, Colour::WHITE);
        canvas.stroke(&[(5.0, 5.0)], 3.0, RED);
        assert_eq!(at(&canvas, 5, 5), [255, 0, 0]);
        assert_eq!(at(&canvas, 9, 9), [255, 255, 255]);
    }

    #[test]
    fn blending_mixes_by_coverage() {
        let mut canvas = Canvas::new(2, 1, Colour::WHITE);
        canvas.blend((0, 0), Colour::BLACK, 0.25);
        canvas.blend((1, 0), Colour::BLACK, 2.0);
        canvas.blend((5, 0), Colour::BLACK, 1.0);
        assert_eq!(at(&canvas, 0, 0), [191, 191, 191]);
        assert_eq!(at(&canvas, 1, 0), [0, 0, 0]);
    }
}
