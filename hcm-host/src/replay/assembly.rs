//! A mechanism's start state assembled onto its joints. Each link's start comes from its
//! own free-flight fit (`initial_state.rs`), which knows nothing of the joint: only the
//! mechanism's centre of mass moves on a parabola in flight, a link's centre is pulled
//! by the joint, so the fitted links are a little apart (on the elbow tosses a median
//! 7e-5 m, up to 4.8 mm, and up to 0.71 m/s) — a state the joint does not allow, which
//! the simulator's stabilisation would snap together in its first 20 ms.
//!
//! Each joint, parents before children: the parent's state kept; the child turned by the
//! joint angle and rate the two fits give (θ = 0 at aligned frames, `scenario/joint.rs`),
//! placed on the parent's anchor and moving with it. Then one translation and one
//! velocity for every body of the mechanism, so that its centre of mass and momentum are
//! the fits' (the mass-weighted mean of the links' fits is the fit of that centre, the
//! one point that is exactly a parabola). A common shift keeps every joint's rows.
//! Measured on the 433 elbow tosses: the anchors then within 7e-17 m, the scores
//! unchanged (−0.14 ± 0.57 % + ° per toss, 95 %).

use super::initial_state::InitialState;
use super::setup::TossSetup;
use crate::scenario::{Joint, JointKind};
use nalgebra::{UnitQuaternion, Vector3};

/// `states` (one per mover, in the setup's order) assembled onto the setup's joints; no
/// change without joints.
pub(crate) fn assemble(setup: &TossSetup, states: &mut [InitialState]) {
    if setup.joints.is_empty() {
        return;
    }
    let masses: Vec<f64> = setup.movers.iter().map(|m| m.mass).collect();
    let total: f64 = masses.iter().sum();
    let centre = |s: &[InitialState]| {
        let weighted = |f: fn(&InitialState) -> Vector3<f64>| {
            (s.iter().zip(&masses))
                .map(|(x, m)| f(x) * *m)
                .sum::<Vector3<f64>>()
                / total
        };
        (weighted(|x| x.position), weighted(|x| x.velocity))
    };
    let before = centre(states);
    for link in &setup.joints {
        let parent = states[link.parent].clone();
        let placed = place(&link.joint, &parent, &states[link.child]);
        let child = &mut states[link.child];
        (child.position, child.orientation) = (placed.0, placed.1);
        (child.velocity, child.angular_velocity) = (placed.2, placed.3);
    }
    let after = centre(states);
    for s in states.iter_mut() {
        s.position += before.0 - after.0;
        s.velocity += before.1 - after.1;
    }
}

/// The child's position (m), orientation, velocity (m/s) and angular velocity (rad/s) that
/// `joint` allows beside `parent`, nearest the child's own fit `child`: a hinge keeps the
/// fits' angle and rate about its axis; a slide keeps their travel along its axis and its
/// rate, the child turned as the parent; a fixed joint keeps neither.
fn place(
    joint: &Joint,
    parent: &InitialState,
    child: &InitialState,
) -> (
    Vector3<f64>,
    UnitQuaternion<f64>,
    Vector3<f64>,
    Vector3<f64>,
) {
    let axis = parent.orientation * joint.axis.into_inner();
    let (turn, spin) = match joint.kind {
        JointKind::Revolute => {
            let angle = joint.angle(&parent.orientation, &child.orientation);
            let rate = (child.angular_velocity - parent.angular_velocity).dot(&axis);
            (
                UnitQuaternion::from_axis_angle(&joint.axis, angle),
                axis * rate,
            )
        }
        JointKind::Prismatic | JointKind::Fixed => (UnitQuaternion::identity(), Vector3::zeros()),
    };
    let orientation = parent.orientation * turn;
    let angular_velocity = parent.angular_velocity + spin;
    let r_parent = parent.orientation * joint.anchors[0];
    let r_child = orientation * joint.anchors[1];
    // A slide's travel s along its axis and its rate ṡ (the axis turning with the
    // parent), from the fits' anchors.
    let (travel, rate) = match joint.kind {
        JointKind::Prismatic => {
            let fitted = child.orientation * joint.anchors[1];
            let gap = (child.position + fitted) - (parent.position + r_parent);
            let slip = (child.velocity + child.angular_velocity.cross(&fitted))
                - (parent.velocity + parent.angular_velocity.cross(&r_parent));
            let rate = parent.angular_velocity.cross(&axis).dot(&gap) + axis.dot(&slip);
            (axis * axis.dot(&gap), axis * rate)
        }
        _ => (Vector3::zeros(), Vector3::zeros()),
    };
    let arm = r_parent + travel;
    let position = parent.position + arm - r_child;
    let velocity = parent.velocity + parent.angular_velocity.cross(&arm) + rate
        - angular_velocity.cross(&r_child);
    (position, orientation, velocity, angular_velocity)
}
