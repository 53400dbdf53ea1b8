//! The SVG renderer: writes a [`Figure`]'s layout as SVG elements by hand — a few lines,
//! polylines and texts need no drawing library, and the viewer supplies the font.

use super::{Anchor, Figure, Label, Rect, TextSize};
use std::fmt::Write;

/// The figure as an SVG document (sizes in px).
pub(super) fn render(figure: &Figure) -> String {
    let layout = &figure.layout;
    let (width, height) = (layout.width, layout.height);
    let plot = layout.plot;
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    for y in &layout.grid {
        let _ = writeln!(
            svg,
            r#"<line x1="{}" x2="{}" y1="{y:.1}" y2="{y:.1}" stroke="{}"/>"#,
            plot.left,
            plot.right,
            super::Colour::GRID.css()
        );
    }
    rect(&mut svg, plot, "none", "black");
    for s in &figure.series {
        let path: Vec<String> = layout
            .path(s)
            .iter()
            .map(|(x, y)| format!("{x:.2},{y:.2}"))
            .collect();
        let _ = writeln!(
            svg,
            r#"<polyline fill="none" stroke="{}" stroke-width="1.6" points="{}"/>"#,
            s.colour.css(),
            path.join(" ")
        );
    }
    if let Some(frame) = layout.legend_box {
        rect(
            &mut svg,
            frame,
            "white",
            &super::Colour::LEGEND_BORDER.css(),
        );
    }
    for (s, row) in figure.series.iter().zip(&layout.legend) {
        let _ = writeln!(
            svg,
            r#"<line x1="{}" x2="{}" y1="{}" y2="{}" stroke="{}" stroke-width="2"/>"#,
            row.x0,
            row.x1,
            row.y,
            row.y,
            s.colour.css()
        );
    }
    for label in &layout.labels {
        text(&mut svg, label);
    }
    svg.push_str("</svg>\n");
    svg
}

/// Appends a rectangle filled with `fill` and outlined in `stroke` (CSS colours).
fn rect(svg: &mut String, r: Rect, fill: &str, stroke: &str) {
    let _ = writeln!(
        svg,
        r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{fill}" stroke="{stroke}"/>"#,
        r.left,
        r.top,
        r.right - r.left,
        r.bottom - r.top
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
        TextSize::Title => r#" font-size="15""#,
        TextSize::Normal => "",
    };
    let (x, y) = (label.x, label.y);
    let turn = if label.vertical {
        format!(r#" transform="rotate(-90 {x} {y})""#)
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
    use super::super::{Colour, Series};
    use super::*;

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
}
