//! Side views of 3D shapes: each shape projected orthographically onto the world x–z
//! plane (the viewer looks along +y, x to the right, z up), as the closed outline of its
//! silhouette. A box's silhouette is the convex hull of its eight projected vertices; a
//! compound's is one outline per box, so that the inner edges (a hole's walls) show as
//! in a wire-frame drawing; a plane, unbounded, is drawn as its trace in a section.

use crate::scenario::{Part, Shape};
use nalgebra::{UnitQuaternion, Vector3};

/// Segments of a sphere's outline.
const CIRCLE_SEGMENTS: usize = 48;

/// A closed polyline in the x–z plane, (x, z) (m): the first point is repeated last.
pub type Outline = Vec<(f64, f64)>;

/// The silhouette of the box of `half_extents` (m) centred at `centre` (m, world) and
/// turned by `orientation` (box → world): the convex hull of its projected vertices,
/// anticlockwise from the leftmost (then lowest) vertex, closed.
pub(crate) fn box_silhouette(
    centre: &Vector3<f64>,
    orientation: &UnitQuaternion<f64>,
    half_extents: &Vector3<f64>,
) -> Outline {
    let vertices = (0..8).map(|corner| {
        let sign = |bit: u32| if corner >> bit & 1 == 1 { 1.0 } else { -1.0 };
        let local = Vector3::new(
            sign(0) * half_extents.x,
            sign(1) * half_extents.y,
            sign(2) * half_extents.z,
        );
        let world = centre + orientation * local;
        (world.x, world.z)
    });
    convex_hull(vertices.collect())
}

/// The outline of a sphere of `radius` (m) centred at `centre` (m, world): a circle.
pub(crate) fn sphere_silhouette(centre: &Vector3<f64>, radius: f64) -> Outline {
    (0..=CIRCLE_SEGMENTS)
        .map(|i| {
            let angle =
                std::f64::consts::TAU * (i % CIRCLE_SEGMENTS) as f64 / CIRCLE_SEGMENTS as f64;
            (
                centre.x + radius * angle.cos(),
                centre.z + radius * angle.sin(),
            )
        })
        .collect()
}

/// The outlines of `shape` on a body at `position` (m) turned by `orientation` (body →
/// world): one for a box or a sphere, one per part for a compound, none for a plane
/// (see [`plane_trace`]).
pub(crate) fn shape_outlines(
    shape: &Shape,
    position: &Vector3<f64>,
    orientation: &UnitQuaternion<f64>,
) -> Vec<Outline> {
    match shape {
        Shape::Sphere { radius } => vec![sphere_silhouette(position, *radius)],
        Shape::Box { half_extents, .. } => {
            vec![box_silhouette(position, orientation, half_extents)]
        }
        Shape::Compound { parts } => parts
            .iter()
            .map(|part| part_silhouette(part, position, orientation))
            .collect(),
        Shape::Plane { .. } => Vec::new(),
    }
}

/// The silhouette of one box of a compound body at `position` (m), `orientation`.
fn part_silhouette(
    part: &Part,
    position: &Vector3<f64>,
    orientation: &UnitQuaternion<f64>,
) -> Outline {
    let centre = position + orientation * part.position;
    box_silhouette(
        &centre,
        &(orientation * part.orientation),
        &part.half_extents,
    )
}

/// Where the plane of unit outward `normal` (body frame) at `offset` (m) from a body at
/// `position` (m), `orientation`, cuts the section y = `y` (m): the segment of that line
/// across `window` ((x low, x high), (z low, z high)) (m) — along x for a plane closer to
/// horizontal, along z otherwise. `None` for a plane parallel to the section.
pub(crate) fn plane_trace(
    normal: &Vector3<f64>,
    offset: f64,
    position: &Vector3<f64>,
    orientation: &UnitQuaternion<f64>,
    y: f64,
    window: ((f64, f64), (f64, f64)),
) -> Option<[(f64, f64); 2]> {
    let n = orientation * normal;
    // Points of the plane: n·p = n·position + offset; in the section, n_x x + n_z z = c.
    let c = n.dot(position) + offset - n.y * y;
    let ((x0, x1), (z0, z1)) = window;
    if n.x.hypot(n.z) < 1e-9 {
        None
    } else if n.z.abs() >= n.x.abs() {
        let z = |x: f64| (c - n.x * x) / n.z;
        Some([(x0, z(x0)), (x1, z(x1))])
    } else {
        let x = |z: f64| (c - n.z * z) / n.x;
        Some([(x(z0), z0), (x(z1), z1)])
    }
}

/// The convex hull of `points` (Andrew's monotone chain), anticlockwise from the
/// leftmost-lowest point, closed. Points that rounding puts a hair off a corner or an edge
/// (turns within 1e-12 of the squared size) are left out, as are non-finite ones.
fn convex_hull(mut points: Vec<(f64, f64)>) -> Outline {
    points.retain(|p| p.0.is_finite() && p.1.is_finite());
    points.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let size = points
        .iter()
        .map(|p| (p.0 - points[0].0).abs().max((p.1 - points[0].1).abs()))
        .fold(0.0, f64::max);
    let tolerance = 1e-12 * size * size;
    // (a − o) × (b − o): positive for an anticlockwise turn at a.
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let chain = |ordered: &mut dyn Iterator<Item = (f64, f64)>| {
        let mut chain: Vec<(f64, f64)> = Vec::new();
        for p in ordered {
            while chain.len() >= 2
                && cross(chain[chain.len() - 2], chain[chain.len() - 1], p) <= tolerance
            {
                chain.pop();
            }
            chain.push(p);
        }
        chain
    };
    // The lower chain left to right, then the upper one back; each ends where the
    // other starts.
    let mut hull = chain(&mut points.iter().copied());
    hull.pop();
    hull.extend(chain(&mut points.iter().rev().copied()));
    hull
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_4, SQRT_2};

    /// Whether the closed outlines `a` and `b` have the same vertices (within 1e-12 m) in
    /// the same order, from whichever vertex each starts (rounding decides which is
    /// leftmost among equals).
    fn close(a: &[(f64, f64)], b: &[(f64, f64)]) -> bool {
        let near =
            |p: &(f64, f64), q: &(f64, f64)| (p.0 - q.0).abs() < 1e-12 && (p.1 - q.1).abs() < 1e-12;
        let n = a.len().saturating_sub(1);
        a.len() == b.len()
            && near(&a[0], &a[n])
            && near(&b[0], &b[n])
            && (0..n).any(|shift| (0..n).all(|i| near(&a[(i + shift) % n], &b[i])))
    }

    #[test]
    fn an_unturned_box_projects_to_its_x_z_rectangle() {
        let outline = box_silhouette(
            &Vector3::new(1.0, 5.0, 2.0),
            &UnitQuaternion::identity(),
            &Vector3::new(0.5, 3.0, 0.25),
        );
        let expected = [
            (0.5, 1.75),
            (1.5, 1.75),
            (1.5, 2.25),
            (0.5, 2.25),
            (0.5, 1.75),
        ];
        assert!(close(&outline, &expected), "{outline:?}");
    }

    #[test]
    fn a_unit_cube_turned_45_degrees_about_y_projects_to_a_diamond() {
        let turn = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), FRAC_PI_4);
        let outline = box_silhouette(&Vector3::zeros(), &turn, &Vector3::repeat(0.5));
        let r = 0.5 * SQRT_2;
        let expected = [(-r, 0.0), (0.0, -r), (r, 0.0), (0.0, r), (-r, 0.0)];
        assert!(close(&outline, &expected), "{outline:?}");
        // Turned about z instead, the side view is a rectangle √2 wide, 1 high.
        let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), FRAC_PI_4);
        let outline = box_silhouette(&Vector3::zeros(), &turn, &Vector3::repeat(0.5));
        let expected = [(-r, -0.5), (r, -0.5), (r, 0.5), (-r, 0.5), (-r, -0.5)];
        assert!(close(&outline, &expected), "{outline:?}");
    }

    #[test]
    fn each_part_of_a_compound_gives_its_rectangle_placed_by_the_body() {
        let part = |x: f64, z: f64, hx: f64, hz: f64| Part {
            half_extents: Vector3::new(hx, 0.03, hz),
            position: Vector3::new(x, 0.0, z),
            orientation: UnitQuaternion::identity(),
        };
        // A block with a slot: two walls and a bottom, its top at z = 0.04 m.
        let shape = Shape::Compound {
            parts: vec![
                part(-0.02, 0.0, 0.01, 0.02),
                part(0.02, 0.0, 0.01, 0.02),
                part(0.0, -0.025, 0.03, 0.005),
            ],
        };
        let outlines = shape_outlines(
            &shape,
            &Vector3::new(0.0, 0.0, 0.02),
            &UnitQuaternion::identity(),
        );
        let rectangle =
            |x0: f64, z0: f64, x1: f64, z1: f64| [(x0, z0), (x1, z0), (x1, z1), (x0, z1), (x0, z0)];
        let expected = [
            rectangle(-0.03, 0.0, -0.01, 0.04),
            rectangle(0.01, 0.0, 0.03, 0.04),
            rectangle(-0.03, -0.01, 0.03, 0.0),
        ];
        assert_eq!(outlines.len(), 3);
        for (outline, expected) in outlines.iter().zip(&expected) {
            assert!(close(outline, expected), "{outline:?}");
        }
        // The body turned a quarter turn about y takes its parts with it: the bottom
        // (60 mm along x, 10 mm along z) stands upright, its centre 25 mm along −x.
        let quarter = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 2.0 * FRAC_PI_4);
        let turned = shape_outlines(&shape, &Vector3::zeros(), &quarter);
        let expected = rectangle(-0.03, -0.03, -0.02, 0.03);
        assert!(close(&turned[2], &expected), "{:?}", turned[2]);
    }

    #[test]
    fn a_sphere_is_a_closed_circle_and_a_plane_has_no_outline() {
        let circle = sphere_silhouette(&Vector3::new(1.0, 9.0, -1.0), 0.5);
        assert_eq!(circle.first(), circle.last());
        assert!(circle
            .iter()
            .all(|p| ((p.0 - 1.0).hypot(p.1 + 1.0) - 0.5).abs() < 1e-12));
        let plane = Shape::Plane {
            normal: Vector3::z(),
            offset: 0.0,
        };
        assert!(shape_outlines(&plane, &Vector3::zeros(), &UnitQuaternion::identity()).is_empty());
    }

    #[test]
    fn a_plane_traces_its_line_across_the_window() {
        let window = ((-1.0, 1.0), (-2.0, 2.0));
        let id = UnitQuaternion::identity();
        // The ground z = 0.1 m (offset 0.1 from a body at the origin).
        let ground = plane_trace(&Vector3::z(), 0.1, &Vector3::zeros(), &id, 0.0, window);
        assert_eq!(ground, Some([(-1.0, 0.1), (1.0, 0.1)]));
        // A wall x = 0.5 m, drawn along z.
        let wall = plane_trace(
            &Vector3::x(),
            0.0,
            &Vector3::new(0.5, 3.0, 0.0),
            &id,
            0.0,
            window,
        );
        assert_eq!(wall, Some([(0.5, -2.0), (0.5, 2.0)]));
        // A slope z = x tilted 45°; a plane facing the viewer has no trace.
        let n = Vector3::new(-1.0, 0.0, 1.0).normalize();
        let [a, b] = plane_trace(&n, 0.0, &Vector3::zeros(), &id, 0.0, window).unwrap();
        assert!((a.0 - a.1).abs() < 1e-12 && (b.0 - b.1).abs() < 1e-12 && a.0 == -1.0);
        assert_eq!(
            plane_trace(&Vector3::y(), 0.0, &Vector3::zeros(), &id, 0.0, window),
            None
        );
    }
}
