//! One set of axes: a rectangle of the image, the data ranges it shows (whole ticks), and
//! everything inside it mapped to pixels — grid lines, the zero line, the curves and the
//! shaded band. The main plot and the inset are both a `Plot`.

use super::style::Stroke;
use super::ticks::Ticks;
use super::{Band, Colour, Series};

/// An axis-aligned rectangle, edges in px from the image's top-left corner (y down).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Rect {
    pub(crate) left: f64,
    pub(crate) top: f64,
    pub(crate) right: f64,
    pub(crate) bottom: f64,
}

impl Rect {
    /// True if the two rectangles share some area (touching edges do not count).
    pub(super) fn overlaps(&self, other: &Rect) -> bool {
        self.left < other.right
            && other.left < self.right
            && self.top < other.bottom
            && other.top < self.bottom
    }

    #[cfg(test)]
    /// True if `other` lies wholly inside this rectangle (edges included).
    pub(super) fn contains(&self, other: &Rect) -> bool {
        other.left >= self.left
            && other.right <= self.right
            && other.top >= self.top
            && other.bottom <= self.bottom
    }

    /// True if the point (px) lies inside (edges included).
    pub(super) fn holds(&self, (x, y): (f64, f64)) -> bool {
        (self.left..=self.right).contains(&x) && (self.top..=self.bottom).contains(&y)
    }

    pub(super) fn width(&self) -> f64 {
        self.right - self.left
    }

    pub(super) fn height(&self) -> f64 {
        self.bottom - self.top
    }
}

/// A curve in px: its colour, its stroke and its polylines (one unless it was clipped
/// to a window).
pub(super) struct Curve {
    pub(crate) colour: Colour,
    pub(crate) stroke: Stroke,
    pub(crate) pieces: Vec<Vec<(f64, f64)>>,
}

/// A band in px: its colour and, along x, its upper and lower edge.
pub(super) struct Shade {
    pub(crate) colour: Colour,
    /// (x, upper edge, lower edge) (px), in the order of the band's points.
    pub(crate) columns: Vec<(f64, f64, f64)>,
}

/// One set of axes and what is drawn in it.
pub(super) struct Plot {
    /// The frame around the curves.
    pub(crate) area: Rect,
    pub(crate) x: Ticks,
    pub(crate) y: Ticks,
    /// Heights of the horizontal grid lines, one per y tick (px).
    pub(crate) grid_y: Vec<f64>,
    /// Positions of the vertical grid lines, one per x tick (px).
    pub(crate) grid_x: Vec<f64>,
    /// Height of the line y = 0, if it is drawn (px).
    pub(crate) zero: Option<f64>,
    pub(crate) curves: Vec<Curve>,
    pub(crate) band: Option<Shade>,
}

impl Plot {
    /// Axes over `area` showing the ticks' ranges, without curves yet.
    pub(super) fn new(area: Rect, x: Ticks, y: Ticks) -> Plot {
        let mut plot = Plot {
            area,
            x,
            y,
            grid_y: Vec::new(),
            grid_x: Vec::new(),
            zero: None,
            curves: Vec::new(),
            band: None,
        };
        plot.grid_y = y.values().map(|v| plot.py(v)).collect();
        plot.grid_x = x.values().map(|v| plot.px(v)).collect();
        plot
    }

    /// The pixel column of `x` (data units → px).
    pub(super) fn px(&self, x: f64) -> f64 {
        let (x0, x1) = self.x.range();
        self.area.left + (x - x0) / (x1 - x0) * self.area.width()
    }

    /// The pixel row of `y` (data units → px).
    pub(super) fn py(&self, y: f64) -> f64 {
        let (y0, y1) = self.y.range();
        self.area.bottom - (y - y0) / (y1 - y0) * self.area.height()
    }

    /// Adds each series as one polyline through its finite points (all inside the
    /// ranges), stroked as the stroke of the same index.
    pub(super) fn draw_series(&mut self, series: &[Series], strokes: &[Stroke]) {
        for (s, &stroke) in series.iter().zip(strokes) {
            let path = finite(&s.points).map(|p| self.at(p)).collect();
            self.curves.push(Curve {
                colour: s.colour,
                stroke,
                pieces: vec![path],
            });
        }
    }

    /// Adds each series cut to the plot's x range (inset windows on a longer curve).
    pub(super) fn draw_series_clipped(&mut self, series: &[Series], strokes: &[Stroke]) {
        let window = self.x.range();
        for (s, &stroke) in series.iter().zip(strokes) {
            let pieces = clip(&s.points, window)
                .into_iter()
                .map(|piece| piece.into_iter().map(|p| self.at(p)).collect())
                .collect();
            self.curves.push(Curve {
                colour: s.colour,
                stroke,
                pieces,
            });
        }
    }

    /// Shades `band` between its lower and upper values at its finite points.
    pub(super) fn draw_band(&mut self, band: &Band) {
        let columns = band
            .points
            .iter()
            .filter(|(x, low, high)| x.is_finite() && low.is_finite() && high.is_finite())
            .map(|&(x, low, high)| (self.px(x), self.py(high.max(low)), self.py(low.min(high))))
            .collect();
        self.band = Some(Shade {
            colour: band.colour,
            columns,
        });
    }

    /// Draws the line y = 0 (which the y range must include).
    pub(super) fn draw_zero_line(&mut self) {
        self.zero = Some(self.py(0.0));
    }

    /// A data point in px.
    fn at(&self, (x, y): (f64, f64)) -> (f64, f64) {
        (self.px(x), self.py(y))
    }
}

/// The points of `points` with both coordinates finite.
pub(super) fn finite(points: &[(f64, f64)]) -> impl Iterator<Item = (f64, f64)> + '_ {
    points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
}

/// The parts of the polyline through the finite `points` with x in `low`–`high` (data
/// units): each part starts and ends where the line enters and leaves the window.
pub(super) fn clip(points: &[(f64, f64)], (low, high): (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let points: Vec<_> = finite(points).collect();
    let mut pieces: Vec<Vec<(f64, f64)>> = Vec::new();
    if let [p] = points[..] {
        if (low..=high).contains(&p.0) {
            pieces.push(vec![p]);
        }
    }
    // True while the last segment reached its end point inside the window.
    let mut open = false;
    for pair in points.windows(2) {
        let (q, p) = (pair[0], pair[1]);
        let Some((t0, t1)) = span_inside(q.0, p.0, (low, high)) else {
            open = false;
            continue;
        };
        let at = |t: f64| (q.0 + t * (p.0 - q.0), q.1 + t * (p.1 - q.1));
        if !(open && t0 == 0.0) {
            pieces.push(vec![at(t0)]);
        }
        if let Some(piece) = pieces.last_mut() {
            piece.push(if t1 == 1.0 { p } else { at(t1) });
        }
        open = t1 == 1.0;
    }
    pieces
}

/// The part of the segment from x = `a` to x = `b` inside `low`–`high`, as fractions
/// (t0, t1) of the segment; None if it misses the window.
fn span_inside(a: f64, b: f64, (low, high): (f64, f64)) -> Option<(f64, f64)> {
    if a == b {
        return (low..=high).contains(&a).then_some((0.0, 1.0));
    }
    let (ta, tb) = ((low - a) / (b - a), (high - a) / (b - a));
    let (t0, t1) = (ta.min(tb).max(0.0), ta.max(tb).min(1.0));
    (t0 <= t1).then_some((t0, t1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_keeps_the_window_and_cuts_at_its_edges() {
        let pieces = clip(&[(0.0, 0.0), (2.0, 2.0), (4.0, 0.0)], (1.0, 3.0));
        assert_eq!(pieces, [vec![(1.0, 1.0), (2.0, 2.0), (3.0, 1.0)]]);
        // Leaving and coming back makes two pieces; points outside are dropped.
        let zigzag = [(0.0, 0.0), (2.0, 0.0), (0.0, 1.0), (2.0, 1.0)];
        let pieces = clip(&zigzag, (1.0, 5.0));
        assert_eq!(
            pieces,
            [
                vec![(1.0, 0.0), (2.0, 0.0), (1.0, 0.5)],
                vec![(1.0, 1.0), (2.0, 1.0)]
            ]
        );
        assert!(clip(&[(0.0, 0.0), (0.5, 1.0)], (1.0, 2.0)).is_empty());
        assert_eq!(clip(&[(1.5, 7.0)], (1.0, 2.0)), [vec![(1.5, 7.0)]]);
        // Non-finite points are left out, as on the main plot.
        let gappy = [(1.0, 0.0), (f64::NAN, 3.0), (2.0, 1.0)];
        assert_eq!(clip(&gappy, (0.0, 3.0)), [vec![(1.0, 0.0), (2.0, 1.0)]]);
    }

    #[test]
    fn rectangles_overlap_only_with_common_area() {
        let r = |left, top, right, bottom| Rect {
            left,
            top,
            right,
            bottom,
        };
        let a = r(0.0, 0.0, 10.0, 10.0);
        assert!(a.overlaps(&r(9.0, 9.0, 20.0, 20.0)));
        assert!(!a.overlaps(&r(10.0, 0.0, 20.0, 10.0)));
        assert!(a.contains(&r(0.0, 2.0, 10.0, 3.0)) && !a.contains(&r(-1.0, 2.0, 5.0, 3.0)));
        assert!(a.holds((10.0, 0.0)) && !a.holds((10.1, 0.0)));
    }
}
