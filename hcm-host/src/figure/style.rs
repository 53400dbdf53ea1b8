//! How a curve is stroked — its width and dash pattern — so that the curves of a figure
//! can be told apart in greyscale as well as by colour. Each kind of curve (each
//! distinct legend label, in order of first appearance; an unnamed curve continues the
//! kind before it) gets the next pattern of [`Dash::CYCLE`] unless the figure sets its
//! stroke by label ([`super::Figure::with_stroke`]).

/// A dash pattern.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dash {
    /// A continuous line.
    Solid,
    /// Short dashes.
    Dashed,
    /// Round dots.
    Dotted,
    /// Dash, dot, dash, dot.
    DashDot,
    /// Long dashes.
    LongDash,
}

impl Dash {
    /// The patterns given to the kinds of curve in turn.
    pub(super) const CYCLE: [Dash; 5] = [
        Dash::Solid,
        Dash::Dashed,
        Dash::Dotted,
        Dash::DashDot,
        Dash::LongDash,
    ];

    /// Alternating lengths on, off, on, … along the curve (px) for a line 2 px wide;
    /// empty for a solid line. An "on" of 0 is a round dot.
    fn pattern(self) -> &'static [f64] {
        match self {
            Dash::Solid => &[],
            Dash::Dashed => &[7.0, 4.0],
            Dash::Dotted => &[0.0, 5.5],
            Dash::DashDot => &[9.0, 4.0, 0.0, 4.0],
            Dash::LongDash => &[16.0, 5.0],
        }
    }

    /// The name used in SVG output and tests.
    pub(super) fn name(self) -> &'static str {
        match self {
            Dash::Solid => "solid",
            Dash::Dashed => "dashed",
            Dash::Dotted => "dotted",
            Dash::DashDot => "dash-dot",
            Dash::LongDash => "long-dash",
        }
    }
}

/// A curve's stroke: width (px) and dash pattern.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stroke {
    /// Width of the line (px).
    pub width: f64,
    /// Its dash pattern.
    pub dash: Dash,
}

impl Stroke {
    /// Width of the curves by default (px).
    pub(super) const WIDTH: f64 = 2.0;

    /// A measured mean's stroke: thick dots (3 px), drawn last over the models' lines,
    /// so that no model hides it and it reads apart from them in greyscale.
    pub const MEASURED: Stroke = Stroke {
        width: 3.0,
        dash: Dash::Dotted,
    };

    /// A line `Stroke::WIDTH` (2 px) wide with the dashes `dash`.
    pub const fn dashed(dash: Dash) -> Stroke {
        Stroke {
            width: Stroke::WIDTH,
            dash,
        }
    }

    /// The dash pattern scaled to the width (px): lengths on, off, on, …; a wider line
    /// gets proportionally longer dashes and gaps, so its dots do not run together.
    pub(super) fn pattern(&self) -> Vec<f64> {
        let scale = (self.width / Stroke::WIDTH).max(1.0);
        self.dash.pattern().iter().map(|l| l * scale).collect()
    }
}

/// The stroke of each curve, in order, of curves labelled `labels` (the figure's series
/// in drawing order, over all its panels): a curve labelled in `chosen` gets that
/// stroke; otherwise each new label takes the next pattern of [`Dash::CYCLE`], a label
/// seen before the same stroke again, and an empty label the stroke of the curve before.
pub(super) fn strokes<'l>(
    labels: impl Iterator<Item = &'l str>,
    chosen: &[(String, Stroke)],
) -> Vec<Stroke> {
    let mut kinds: Vec<(&str, Stroke)> = Vec::new();
    let mut out: Vec<Stroke> = Vec::new();
    for label in labels {
        let stroke = if label.is_empty() {
            out.last().copied()
        } else {
            kinds.iter().find(|k| k.0 == label).map(|k| k.1)
        };
        let stroke = stroke.unwrap_or_else(|| {
            let stroke = match chosen.iter().find(|c| c.0 == label) {
                Some(c) => c.1,
                None => {
                    let free = kinds
                        .iter()
                        .filter(|k| !chosen.iter().any(|c| c.0 == k.0))
                        .count();
                    Stroke::dashed(Dash::CYCLE[free % Dash::CYCLE.len()])
                }
            };
            kinds.push((label, stroke));
            stroke
        });
        out.push(stroke);
    }
    out
}

/// The polyline through `points` (px) cut into the dashes of `pattern` (lengths on,
/// off, … along it, px; empty for a solid line): the pieces to stroke. A dash of
/// length 0 is a single point (a round dot).
pub(super) fn dashes(points: &[(f64, f64)], pattern: &[f64]) -> Vec<Vec<(f64, f64)>> {
    if pattern.is_empty() || pattern.iter().sum::<f64>() <= 0.0 || points.len() < 2 {
        return vec![points.to_vec()];
    }
    let mut pieces: Vec<Vec<(f64, f64)>> = vec![vec![points[0]]];
    // Where in the pattern the walk is: the part, and the length left of it (px).
    let (mut part, mut left) = (0, pattern[0]);
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let length = (b.0 - a.0).hypot(b.1 - a.1);
        let mut done = 0.0;
        while length - done >= left {
            done += left;
            let t = if length > 0.0 { done / length } else { 1.0 };
            let at = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
            if part % 2 == 0 {
                pieces.last_mut().expect("a piece").push(at);
            } else {
                pieces.push(vec![at]);
            }
            part = (part + 1) % pattern.len();
            left = pattern[part];
        }
        left -= length - done;
        if part % 2 == 0 {
            pieces.last_mut().expect("a piece").push(b);
        }
    }
    pieces.retain(|p| !p.is_empty());
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_take_the_patterns_in_turn_and_keep_them() {
        let labels = ["a", "b", "", "a", "c"];
        let got = strokes(labels.into_iter(), &[]);
        let dashes: Vec<Dash> = got.iter().map(|s| s.dash).collect();
        assert_eq!(
            dashes,
            [
                Dash::Solid,
                Dash::Dashed,
                Dash::Dashed,
                Dash::Solid,
                Dash::Dotted
            ]
        );
        // A chosen stroke takes no place in the cycle.
        let thick = Stroke {
            width: 3.0,
            dash: Dash::Dotted,
        };
        let got = strokes(["m", "a", "b"].into_iter(), &[("m".into(), thick)]);
        assert_eq!(
            got,
            [
                thick,
                Stroke::dashed(Dash::Solid),
                Stroke::dashed(Dash::Dashed)
            ]
        );
    }

    #[test]
    fn dashes_follow_the_pattern_along_the_line_and_across_corners() {
        let line = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0)];
        let pieces = dashes(&line, &[4.0, 2.0]);
        // On 0–4, off 4–6, on 6–10, off 10–12: the third dash starts 12 px along the
        // line, round the corner at (10, 2).
        assert_eq!(pieces[0], [(0.0, 0.0), (4.0, 0.0)]);
        assert_eq!(pieces[1], [(6.0, 0.0), (10.0, 0.0)]);
        assert_eq!(pieces[2], [(10.0, 2.0), (10.0, 6.0)]);
        assert_eq!(pieces[3], [(10.0, 8.0), (10.0, 10.0)]);
        // Dots are single points, one per period.
        let dots = dashes(&[(0.0, 0.0), (20.0, 0.0)], &[0.0, 5.0]);
        assert_eq!(dots.len(), 5);
        assert!(dots
            .iter()
            .all(|d| d.len() <= 2 && d[0] == *d.last().unwrap()));
        // Solid: the line itself.
        assert_eq!(dashes(&line, &[]), [line.to_vec()]);
    }
}
