//! The legend: one entry per curve (but those of an empty label), then the band, each a colour swatch and its label,
//! set in rows between the title and the plot area, so that it never hides a curve.

use super::font;
use super::layout::{Anchor, Label, TextSize, PAD, WIDTH};
use super::plot::Rect;
use super::{Colour, Figure};

/// Length of a swatch, gap from swatch to text, gap between entries (px).
const SWATCH: (f64, f64, f64) = (24.0, 6.0, 20.0);

/// How a legend entry shows its colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Swatch {
    /// A short line through the middle of the area, for a curve.
    Line,
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

/// The legend's entries: the band (if any) after the curves, each with its label's width.
pub(super) fn entries<'f>(figure: &'f Figure) -> Vec<(&'f str, Colour, Swatch, f64)> {
    let curves = figure
        .series
        .iter()
        .filter(|s| !s.label.is_empty())
        .map(|s| (s.label, s.colour, Swatch::Line));
    let band = figure
        .band
        .iter()
        .map(|b| (b.label, b.colour, Swatch::Block));
    curves
        .chain(band)
        .map(|(label, colour, swatch)| {
            let width = SWATCH.0 + SWATCH.1 + font::width(label, TextSize::Normal.px());
            (label, colour, swatch, width)
        })
        .collect()
}

/// The entries split into rows no wider than `room` (px), in order; an entry wider than
/// the room gets a row of its own.
pub(super) fn rows(entries: &[(&str, Colour, Swatch, f64)], room: f64) -> Vec<Vec<usize>> {
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

/// Places the legend rows from `top` down, each centred over the plot area (kept inside
/// the image): the swatches, and their texts into `labels`.
pub(super) fn place(
    entries: &[(&str, Colour, Swatch, f64)],
    rows: &[Vec<usize>],
    area: &Rect,
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
        let mut x = (centre - 0.5 * total).clamp(PAD, (WIDTH - PAD - total).max(PAD));
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
