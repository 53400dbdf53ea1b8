//! Equal scales on both axes (one data unit is as many px along x as along y), for
//! pictures of space such as a side view, where a distorted scale would bend the shapes.
//! The data ranges are widened to the plot area's proportions before the ticks are
//! rounded, then the area is narrowed to what the rounded ranges need, centred where it
//! was: the picture is undistorted at the cost of a little empty margin.

use super::plot::Rect;
use super::ticks::Ticks;

/// The axes laid out by `axes` (from the x and y data extents: the plot area and the x
/// and y ticks) with equal scales, for the data extents `x` and `y`.
pub(super) fn equal_scales(
    axes: impl Fn((f64, f64), (f64, f64)) -> (Rect, Ticks, Ticks),
    x: (f64, f64),
    y: (f64, f64),
) -> (Rect, Ticks, Ticks) {
    let (area, _, _) = axes(x, y);
    let (x, y) = widened(area.width() / area.height(), x, y);
    let (area, x_ticks, y_ticks) = axes(x, y);
    (
        narrowed(area, x_ticks.range(), y_ticks.range()),
        x_ticks,
        y_ticks,
    )
}

/// The extents `x`, `y` with the narrower one widened about its middle so that their
/// spans are in the proportion `ratio` = x span / y span; unchanged if either span is
/// zero or not finite.
fn widened(ratio: f64, x: (f64, f64), y: (f64, f64)) -> ((f64, f64), (f64, f64)) {
    let (width, height) = (x.1 - x.0, y.1 - y.0);
    let usable = |s: f64| s.is_finite() && s > 0.0;
    if !(usable(width) && usable(height) && usable(ratio)) {
        return (x, y);
    }
    let about = |(low, high): (f64, f64), span: f64| {
        let middle = 0.5 * (low + high);
        (middle - 0.5 * span, middle + 0.5 * span)
    };
    if width < ratio * height {
        (about(x, ratio * height), y)
    } else {
        (x, about(y, width / ratio))
    }
}

/// `area` narrowed along one axis, about its middle, so that the ranges `x` and `y`
/// (data units) take as many px per unit on both axes.
fn narrowed(area: Rect, x: (f64, f64), y: (f64, f64)) -> Rect {
    let (sx, sy) = (area.width() / (x.1 - x.0), area.height() / (y.1 - y.0));
    if !(sx.is_finite() && sy.is_finite() && sx > 0.0 && sy > 0.0) {
        return area;
    }
    let scale = sx.min(sy);
    let (width, height) = (scale * (x.1 - x.0), scale * (y.1 - y.0));
    let (cx, cy) = (
        0.5 * (area.left + area.right),
        0.5 * (area.top + area.bottom),
    );
    Rect {
        left: cx - 0.5 * width,
        top: cy - 0.5 * height,
        right: cx + 0.5 * width,
        bottom: cy + 0.5 * height,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_narrow_extent_is_widened_about_its_middle() {
        let (x, y) = widened(2.0, (0.0, 1.0), (10.0, 14.0));
        assert_eq!((x, y), ((-3.5, 4.5), (10.0, 14.0)));
        let (x, y) = widened(2.0, (0.0, 40.0), (-1.0, 1.0));
        assert_eq!((x, y), ((0.0, 40.0), (-10.0, 10.0)));
        // Nothing to scale: a single point, no points.
        assert_eq!(
            widened(2.0, (1.0, 1.0), (0.0, 3.0)),
            ((1.0, 1.0), (0.0, 3.0))
        );
        let none = (f64::INFINITY, f64::NEG_INFINITY);
        assert_eq!(widened(2.0, none, none), (none, none));
    }

    #[test]
    fn the_area_is_narrowed_to_equal_scales() {
        let area = Rect {
            left: 100.0,
            top: 50.0,
            right: 700.0,
            bottom: 350.0,
        };
        // 10 units by 10 units in 600 px by 300 px: 30 px per unit, 300 px wide.
        let r = narrowed(area, (0.0, 10.0), (0.0, 10.0));
        assert_eq!(
            r,
            Rect {
                left: 250.0,
                top: 50.0,
                right: 550.0,
                bottom: 350.0
            }
        );
    }
}
