//! The SVG renderer: writes a figure's [`Layout`] as SVG elements by hand — lines,
//! polylines, a polygon and texts need no drawing library. The text stays Unicode; the
//! font-family list names the PNG's font first, so the two look alike where it is installed.

use super::font::FAMILY;
use super::layout::{Anchor, Label, Layout, TextSize};
use super::legend::Swatch;
use super::plot::{Plot, Rect};
use super::style::Stroke;
use super::Colour;
use std::fmt::Write;

/// The layout as an SVG document (sizes in px).
pub(super) fn render(layout: &Layout) -> String {
    let (width, height) = (layout.width, layout.height);
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="{FAMILY}" font-size="{}">"#,
        TextSize::Normal.px()
    );
    let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    for p in &layout.plots {
        plot(&mut svg, p);
    }
    if let Some(inset) = &layout.inset {
        rect(&mut svg, inset.marker, "none", Colour::MARKER);
        rect(&mut svg, inset.background, "white", Colour::WHITE);
        plot(&mut svg, &inset.plot);
    }
    for entry in &layout.legend {
        let a = entry.area;
        match entry.swatch {
            Swatch::Line(stroke) => {
                let y = 0.5 * (a.top + a.bottom);
                let _ = writeln!(
                    svg,
                    r#"<line x1="{:.1}" x2="{:.1}" y1="{y:.1}" y2="{y:.1}" stroke="{}"{}/>"#,
                    a.left,
                    a.right,
                    entry.colour.css(),
                    stroke_attributes(stroke)
                );
            }
            Swatch::Block => rect(&mut svg, a, &entry.colour.css(), entry.colour),
        }
    }
    for label in &layout.labels {
        text(&mut svg, label);
    }
    svg.push_str("</svg>\n");
    svg
}

/// Appends one set of axes as a group that names its data ranges (`data-x`, `data-y`:
/// low and high, data units): band, grid, zero line, frame, curves.
fn plot(svg: &mut String, plot: &Plot) {
    let area = plot.area;
    let ((x0, x1), (y0, y1)) = (plot.x.range(), plot.y.range());
    let _ = writeln!(
        svg,
        r#"<g class="panel" data-x="{x0} {x1}" data-y="{y0} {y1}">"#
    );
    if let Some(band) = &plot.band {
        let upper = band.columns.iter().map(|c| (c.0, c.1));
        let lower = band.columns.iter().rev().map(|c| (c.0, c.2));
        let _ = writeln!(
            svg,
            r#"<polygon fill="{}" stroke="none" points="{}"/>"#,
            band.colour.css(),
            points(upper.chain(lower))
        );
    }
    for &y in &plot.grid_y {
        line(svg, (area.left, y), (area.right, y), Colour::GRID, 1.0);
    }
    for &x in &plot.grid_x {
        line(svg, (x, area.top), (x, area.bottom), Colour::GRID, 1.0);
    }
    if let Some(y) = plot.zero {
        line(svg, (area.left, y), (area.right, y), Colour::AXIS, 1.2);
    }
    rect(svg, area, "none", Colour::AXIS);
    for curve in &plot.curves {
        for piece in &curve.pieces {
            let _ = writeln!(
                svg,
                r#"<polyline fill="none" stroke="{}"{} stroke-linejoin="round" points="{}"/>"#,
                curve.colour.css(),
                stroke_attributes(curve.stroke),
                points(piece.iter().copied())
            );
        }
    }
    svg.push_str("</g>\n");
}

/// The attributes of a line stroked with `stroke`: its width, and its dashes (with
/// round ends, as the PNG draws them) named in `data-dash`.
fn stroke_attributes(stroke: Stroke) -> String {
    let width = stroke.width;
    let pattern = stroke.pattern();
    if pattern.is_empty() {
        return format!(r#" stroke-width="{width}" data-dash="solid""#);
    }
    let lengths: Vec<String> = pattern.iter().map(|l| format!("{l}")).collect();
    format!(
        r#" stroke-width="{width}" stroke-dasharray="{}" stroke-linecap="round" data-dash="{}""#,
        lengths.join(" "),
        stroke.dash.name()
    )
}

/// `x,y x,y …` with two decimals (px).
fn points(points: impl Iterator<Item = (f64, f64)>) -> String {
    let pairs: Vec<String> = points.map(|(x, y)| format!("{x:.2},{y:.2}")).collect();
    pairs.join(" ")
}

/// Appends a straight line `width` px wide.
fn line(svg: &mut String, from: (f64, f64), to: (f64, f64), colour: Colour, width: f64) {
    let _ = writeln!(
        svg,
        r#"<line x1="{:.1}" x2="{:.1}" y1="{:.1}" y2="{:.1}" stroke="{}" stroke-width="{width}"/>"#,
        from.0,
        to.0,
        from.1,
        to.1,
        colour.css()
    );
}

/// Appends a rectangle filled with `fill` (a CSS colour or "none") and outlined in `stroke`.
fn rect(svg: &mut String, r: Rect, fill: &str, stroke: Colour) {
    let _ = writeln!(
        svg,
        r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="{fill}" stroke="{}"/>"#,
        r.left,
        r.top,
        r.width(),
        r.height(),
        stroke.css()
    );
}

/// Appends a `<text>` element.
fn text(svg: &mut String, label: &Label) {
    let anchor = match label.anchor {
        Anchor::Start => "start",
        Anchor::Middle => "middle",
        Anchor::End => "end",
    };
    let size = match label.size {
        TextSize::Normal => String::new(),
        other => format!(r#" font-size="{}""#, other.px()),
    };
    let (x, y) = (label.x, label.y);
    let turn = if label.vertical {
        format!(r#" transform="rotate(-90 {x:.1} {y:.1})""#)
    } else {
        String::new()
    };
    let _ = writeln!(
        svg,
        r#"<text x="{x:.1}" y="{y:.1}" text-anchor="{anchor}"{size}{turn}>{}</text>"#,
        escape(&label.text)
    );
}

/// `text` with the characters that XML reserves written as entities.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::{Band, Colour, Figure, Series};

    #[test]
    fn a_plot_holds_every_series_and_its_label() {
        let svg = Figure::new(
            "t",
            "x",
            "y",
            vec![
                Series {
                    label: "a",
                    colour: Colour::hex(0xff0000),
                    points: vec![(0.0, 0.0), (1.0, 1.0)],
                },
                Series {
                    label: "b",
                    colour: Colour::hex(0x0000ff),
                    points: vec![(0.0, 1.0), (1.0, f64::NAN)],
                },
            ],
        )
        .svg();
        assert_eq!(svg.matches("<polyline").count(), 2);
        assert!(svg.contains(">a</text>") && svg.contains(">b</text>") && !svg.contains("NaN"));
        assert!(svg.contains(r##"stroke="#ff0000""##) && svg.contains(r##"stroke="#0000ff""##));
    }

    #[test]
    fn reserved_characters_in_labels_are_escaped() {
        let svg = Figure::new("a < b & c", "x", "y", Vec::new()).svg();
        assert!(svg.contains(">a &lt; b &amp; c</text>"));
    }

    #[test]
    fn text_is_unicode_in_the_pngs_font_first() {
        let svg = Figure::new("δ̇ (µm/s) ± σ", "x", "y", Vec::new()).svg();
        assert!(svg.contains(">δ̇ (µm/s) ± σ</text>"));
        assert!(svg.contains(r#"font-family="'DejaVu Sans', "#));
    }

    #[test]
    fn a_band_is_one_polygon_in_its_colour_with_a_legend_block() {
        let band = Band {
            label: "noise",
            colour: Colour::hex(0xcccccc),
            points: vec![(0.0, -1.0, 1.0), (1.0, -2.0, 2.0), (2.0, f64::NAN, 1.0)],
        };
        let svg = Figure::new("t", "x", "y", Vec::new()).with_band(band).svg();
        assert_eq!(svg.matches("<polygon").count(), 1);
        // Upper edge forward, lower edge back: 2 finite points, 4 corners.
        let polygon = svg.lines().find(|l| l.starts_with("<polygon")).unwrap();
        let corners = polygon.split("points=\"").nth(1).unwrap();
        assert_eq!(corners.split(' ').count(), 4, "{polygon}");
        assert!(svg.contains(r##"<rect"##) && svg.contains(">noise</text>"));
        assert!(svg.contains(r##"fill="#cccccc""##));
    }
}
