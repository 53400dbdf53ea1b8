//! The legend: one entry per label of the curves (each named once, however many curves
//! and panels carry it; none for an empty label), then the band, each a swatch — a
//! short line in the curve's colour, width and dashes, or a block of the band's colour —
//! and its label, set in rows between the title and the plot area, so that it never
//! hides a curve.

use super::font;
use super::layout::{Anchor, Label, TextSize, PAD};
use super::plot::Rect;
use super::style::Stroke;
use super::{Colour, Figure};

/// Length of a swatch, gap from swatch to text, gap between entries (px).
const SWATCH: (f64, f64, f64) = (32.0, 6.0, 20.0);

/// How a legend entry shows its colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Swatch {
    /// A short line through the middle of the area, stroked as the curve, for a curve.
    Line(Stroke),
    /// The area filled, for a band.
    Block,
}

/// One legend entry's swatch (its text is among [`Layout::labels`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct LegendEntry {
    pub(crate) colour: Colour,
    pub(crate) swatch: Swatch,
    /// Where the swatch goes (px).
    pub(crate) area: Rect,
}

/// One entry before it is placed: its label, colour, swatch and width with its swatch
/// (px).
pub(super) type Entry<'f> = (&'f str, Colour, Swatch, f64);

/// The legend's entries: each label of the curves of every panel once, in order of
/// first appearance, stroked as `strokes` (one per curve, in order) says; then the
/// band (if any); each with its width.
pub(super) fn entries<'f>(figure: &'f Figure, strokes: &[Stroke]) -> Vec<Entry<'f>> {
    let mut curves: Vec<(&str, Colour, Swatch)> = Vec::new();
    for (s, &stroke) in figure.all_series().zip(strokes) {
        if !s.label.is_empty() && !curves.iter().any(|c| c.0 == s.label) {
            curves.push((s.label, s.colour, Swatch::Line(stroke)));
        }
    }
    let band = figure
        .band
        .iter()
        .map(|b| (b.label, b.colour, Swatch::Block));
    curves
        .into_iter()
        .chain(band)
        .map(|(label, colour, swatch)| {
            let width = SWATCH.0 + SWATCH.1 + font::width(label, TextSize::Normal.px());
            (label, colour, swatch, width)
        })
        .collect()
}

/// The entries split into rows no wider than `room` (px), in order; an entry wider than
/// the room gets a row of its own.
pub(super) fn rows(entries: &[Entry], room: f64) -> Vec<Vec<usize>> {
    let mut rows: Vec<Vec<usize>> = Vec::new();
    let mut used = f64::INFINITY;
    for (i, entry) in entries.iter().enumerate() {
        let width = entry.3;
        match rows.last_mut() {
            Some(row) if used + SWATCH.2 + width <= room => {
                row.push(i);
                used += SWATCH.2 + width;
            }
            _ => {
                rows.push(vec![i]);
                used = width;
            }
        }
    }
    rows
}

/// Places the legend rows from `top` down, each centred over `area` (kept inside the
/// image, `width` px wide): the swatches, and their texts into `labels`.
pub(super) fn place(
    entries: &[Entry],
    rows: &[Vec<usize>],
    (area, width): (&Rect, f64),
    top: f64,
    labels: &mut Vec<Label>,
) -> Vec<LegendEntry> {
    let size = TextSize::Normal;
    let row_height = size.line() + 4.0;
    let mut placed = Vec::new();
    for (r, row) in rows.iter().enumerate() {
        let total: f64 =
            row.iter().map(|&i| entries[i].3).sum::<f64>() + SWATCH.2 * (row.len() - 1) as f64;
        let centre = 0.5 * (area.left + area.right);
        let mut x = (centre - 0.5 * total).clamp(PAD, (width - PAD - total).max(PAD));
        let middle = top + row_height * (r as f64 + 0.5);
        for &i in row {
            let (text, colour, swatch, width) = entries[i];
            let swatch_area = Rect {
                left: x,
                top: middle - 4.0,
                right: x + SWATCH.0,
                bottom: middle + 4.0,
            };
            placed.push(LegendEntry {
                colour,
                swatch,
                area: swatch_area,
            });
            let at = (x + SWATCH.0 + SWATCH.1, middle + size.centring());
            labels.push(Label::new(text, at, Anchor::Start, size));
            x += width + SWATCH.2;
        }
    }
    placed
}
