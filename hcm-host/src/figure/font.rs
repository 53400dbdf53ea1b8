//! The figures' typeface: DejaVu Sans, shipped in `hcm-host/assets/fonts/` with its
//! licence and compiled into the binary, so a PNG looks the same on every machine and
//! needs no system font. The layout measures text with it; the PNG renderer draws its
//! anti-aliased glyphs (rasterised by `ab_glyph`); the SVG names it first in its
//! font-family list, so a viewer that has it shows the same text widths.
//!
//! Text is set glyph by glyph with kerning and no other shaping, which is all the labels
//! here need (Latin, Greek, µ, ±, superscripts) — except combining marks such as the dot
//! of δ̇ (δ + U+0307), which are centred over the glyph before them and raised clear of
//! it. A character the font lacks shows as its empty-box glyph.

use ab_glyph::{point, Font, FontRef, Glyph, PxScale, ScaleFont};
use std::sync::LazyLock;

/// DejaVu Sans 2.37 (Debian `fonts-dejavu-core`), Bitstream Vera licence:
/// `hcm-host/assets/fonts/LICENSE-DejaVu.txt`.
const DEJAVU_SANS: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// The SVG font-family list: the PNG's typeface first, then the fonts of the same width
/// that most systems have.
pub(super) const FAMILY: &str = "'DejaVu Sans', 'Bitstream Vera Sans', Verdana, sans-serif";

/// Vertical gap kept between a combining mark and the glyph it sits on (px).
const MARK_GAP: f32 = 1.0;

/// The parsed font; parsing the embedded file cannot fail unless the asset is replaced by
/// something else (the tests parse it).
static FACE: LazyLock<FontRef<'static>> = LazyLock::new(|| {
    FontRef::try_from_slice(DEJAVU_SANS).expect("assets/fonts/DejaVuSans.ttf is a TrueType font")
});

/// A line of text set on a baseline through (0, 0): its glyphs and its advance width.
pub(super) struct Line {
    /// Each glyph with its position (px, y down) and scale.
    pub(crate) glyphs: Vec<Glyph>,
    /// Distance from the start of the line to the end of its last glyph's advance (px).
    pub(crate) width: f64,
}

/// `text` set in DejaVu Sans at `size` px per em (as CSS `font-size`).
pub(super) fn set(text: &str, size: f64) -> Line {
    let face = &*FACE;
    let scale = px_scale(size);
    let scaled = face.as_scaled(scale);
    let mut glyphs: Vec<Glyph> = Vec::new();
    // The last glyph that is not a mark: marks are placed on it.
    let mut base: Option<Glyph> = None;
    let mut pen = 0.0f32;
    for c in text.chars() {
        let id = face.glyph_id(c);
        let mut glyph = id.with_scale_and_position(scale, point(pen, 0.0));
        if is_combining(c) {
            if let Some(base) = &base {
                glyph.position = on_top_of(base, &glyph);
            }
        } else {
            if let Some(previous) = &base {
                pen += scaled.kern(previous.id, id);
                glyph.position.x = pen;
            }
            base = Some(glyph.clone());
        }
        pen += scaled.h_advance(id);
        glyphs.push(glyph);
    }
    Line {
        glyphs,
        width: pen as f64,
    }
}

/// The advance width of `text` at `size` px per em (px).
pub(super) fn width(text: &str, size: f64) -> f64 {
    set(text, size).width
}

/// How far the font's tallest glyphs reach above the baseline at `size` px per em (px).
pub(super) fn ascent(size: f64) -> f64 {
    FACE.as_scaled(px_scale(size)).ascent() as f64
}

/// How far the font's glyphs reach below the baseline at `size` px per em (px, positive).
pub(super) fn descent(size: f64) -> f64 {
    -FACE.as_scaled(px_scale(size)).descent() as f64
}

#[cfg(test)]
/// True if the font has a glyph of its own for `c` (not the empty box).
pub(super) fn covers(c: char) -> bool {
    FACE.glyph_id(c).0 != 0
}

/// Draws `line` with its baseline starting at `origin` (px): calls `pixel(x, y, coverage)`
/// for every pixel a glyph touches, coverage 0–1.
pub(super) fn draw(line: &Line, origin: (f64, f64), mut pixel: impl FnMut(i64, i64, f32)) {
    for glyph in &line.glyphs {
        let mut glyph = glyph.clone();
        glyph.position.x += origin.0 as f32;
        glyph.position.y += origin.1 as f32;
        let Some(outline) = FACE.outline_glyph(glyph) else {
            continue; // a space
        };
        let corner = outline.px_bounds().min;
        outline.draw(|x, y, coverage| {
            let (x, y) = (corner.x as i64 + x as i64, corner.y as i64 + y as i64);
            pixel(x, y, coverage.min(1.0));
        });
    }
}

/// The `ab_glyph` scale for `size` px per em: `ab_glyph` scales to the font's whole
/// height (ascent − descent), CSS and SVG to the em.
fn px_scale(size: f64) -> PxScale {
    let face = &*FACE;
    let em = face.units_per_em().unwrap_or(2048.0);
    PxScale::from(size as f32 * face.height_unscaled() / em)
}

/// Combining diacritical marks (U+0300–U+036F) and those for symbols (U+20D0–U+20FF):
/// drawn on the character before them, with no advance of their own.
fn is_combining(c: char) -> bool {
    matches!(c, '\u{0300}'..='\u{036F}' | '\u{20D0}'..='\u{20FF}')
}

/// Where `mark` goes on `base`: centred over the base's ink and, if the font's default
/// placement (made for lowercase letters) would touch a tall base such as δ, raised
/// clear of it. A mark placed below the baseline (e.g. U+0323) is only centred.
fn on_top_of(base: &Glyph, mark: &Glyph) -> ab_glyph::Point {
    let face = &*FACE;
    let (Some(b), Some(m)) = (
        face.outline_glyph(base.clone()),
        face.outline_glyph(mark.clone()),
    ) else {
        return mark.position;
    };
    let (b, m) = (b.px_bounds(), m.px_bounds());
    let dx = 0.5 * (b.min.x + b.max.x) - 0.5 * (m.min.x + m.max.x);
    let above = m.max.y <= base.position.y;
    let dy = if above {
        (b.min.y - MARK_GAP - m.max.y).min(0.0)
    } else {
        0.0
    };
    point(mark.position.x + dx, mark.position.y + dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ink of `text` drawn at `size` px: the covered pixels (coverage > 0.5).
    fn ink(text: &str, size: f64) -> Vec<(i64, i64)> {
        let mut pixels = Vec::new();
        draw(&set(text, size), (0.0, 0.0), |x, y, c| {
            if c > 0.5 {
                pixels.push((x, y));
            }
        });
        pixels
    }

    #[test]
    fn the_labels_characters_have_glyphs_of_their_own() {
        for c in "δ̇µμσ±–−×⁰¹²³⁴⁵⁶⁷⁸⁹⁻₀ΔεθλπτωΩ°·√≈≤≥→".chars()
        {
            assert!(covers(c), "no glyph for {c:?} (U+{:04X})", c as u32);
        }
        assert!(!covers('\u{E000}'));
    }

    #[test]
    fn the_font_is_proportional_and_kerned() {
        assert!(width("iiii", 12.0) < 0.6 * width("MMMM", 12.0));
        assert!(width("AV", 12.0) < width("A", 12.0) + width("V", 12.0));
        // Width grows with the size, in proportion.
        let (small, large) = (width("force (N)", 12.0), width("force (N)", 24.0));
        assert!((large / small - 2.0).abs() < 0.05, "{small} {large}");
        assert!(ascent(12.0) > 8.0 && ascent(12.0) < 13.0 && descent(12.0) > 1.0);
    }

    #[test]
    fn glyphs_are_anti_aliased() {
        let mut levels = Vec::new();
        draw(&set("µs", 12.0), (0.0, 0.0), |_, _, c| levels.push(c));
        let partial = levels.iter().filter(|c| **c > 0.05 && **c < 0.95).count();
        assert!(partial > 5, "{partial} partly covered pixels");
        assert!(levels.iter().any(|c| *c >= 0.95));
    }

    #[test]
    fn a_combining_dot_sits_above_its_letter_and_adds_no_width() {
        let (plain, dotted) = (ink("δ", 16.0), ink("δ̇", 16.0));
        assert_eq!(width("δ", 16.0), width("δ̇", 16.0));
        let top = |pixels: &[(i64, i64)]| pixels.iter().map(|p| p.1).min().unwrap();
        let columns = |pixels: &[(i64, i64)]| {
            let xs = pixels.iter().map(|p| p.0);
            (xs.clone().min().unwrap(), xs.max().unwrap())
        };
        // The dot is the ink above the letter's top, separated from it by a gap, and
        // lies within the letter's columns.
        let dot: Vec<_> = dotted
            .iter()
            .filter(|p| p.1 < top(&plain) - 1)
            .copied()
            .collect();
        assert!(dot.len() >= 2, "{dotted:?}");
        let (left, right) = columns(&plain);
        let (dot_left, dot_right) = columns(&dot);
        assert!(dot_left >= left && dot_right <= right);
        assert_eq!(dotted.len() - dot.len(), plain.len());
    }

    #[test]
    fn text_draws_where_it_is_placed() {
        let pixels = ink("Ag", 20.0);
        let (x0, x1) = (
            pixels.iter().map(|p| p.0).min(),
            pixels.iter().map(|p| p.0).max(),
        );
        let (y0, y1) = (
            pixels.iter().map(|p| p.1).min(),
            pixels.iter().map(|p| p.1).max(),
        );
        // From the origin rightwards within the advance width; above the baseline by
        // the cap height and below it by the descender of "g".
        assert!(x0.unwrap() >= 0 && (x1.unwrap() as f64) < width("Ag", 20.0));
        assert!(y0.unwrap() >= -(ascent(20.0) as i64) && y0.unwrap() < -12);
        assert!(y1.unwrap() > 2 && (y1.unwrap() as f64) <= descent(20.0));
    }
}
