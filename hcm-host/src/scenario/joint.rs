//! Joints between bodies (`[[joint]]`): a revolute joint (a hinge) holds a point of one
//! body on a point of the other and lets them turn relative to each other about one
//! axis only. The simulator keeps it by constraint forces (`simulate/joints.rs`); bodies
//! joined this way touch only where a `[[contact]]` says so, like any two bodies.
//!
//! The joint's angle θ (rad) is body 2's turn relative to body 1 about the axis, 0 where
//! the two bodies' frames are aligned (a URDF `continuous` or `revolute` joint whose
//! origin has no rotation), positive by the right-hand rule about the axis as body 1
//! carries it.

use super::ScenarioError;
use hcm_core::joint::JointLaw;
use nalgebra::{Unit, UnitQuaternion, Vector3};
use serde::Deserialize;

/// A joint as a scenario file gives it.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    /// Name, for messages (default: `joint #i`).
    #[serde(default)]
    pub(crate) name: String,
    /// What it lets the bodies do: `revolute` (the default), `prismatic` or `fixed`.
    #[serde(default)]
    pub(crate) kind: JointKind,
    /// The two bodies: body 1 (the parent) and body 2 (the child).
    pub(crate) bodies: [String; 2],
    /// The joint's point in each body's frame (m, from its centre of mass): the point of
    /// body 1 and the point of body 2 that the joint holds together.
    pub(crate) anchors: [[f64; 3]; 2],
    /// The hinge's axis (–, any length but 0) in body 1's frame; with θ = 0 at aligned
    /// frames it is the same in body 2's.
    pub(crate) axis: [f64; 3],
    /// The joint's own torque about its axis: `{ spring = { stiffness, rest_angle },
    /// viscous = { damping }, coulomb = { torque, smoothing_rate } }`, each optional
    /// (N·m/rad, rad, N·m·s/rad, N·m, rad/s; [`hcm_core::joint`]). None: a free hinge.
    #[serde(default)]
    pub(crate) law: JointLaw<f64>,
}

/// The kinds of joint: what the two bodies may still do relative to each other.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum JointKind {
    /// One rotation about the axis (a hinge): 5 rows.
    #[default]
    Revolute,
    /// One translation along the axis (a slide, a gripper's finger), no rotation: 5 rows.
    /// Its law acts along the axis: the same terms in N, m and m/s (the joint's
    /// coordinate s the child's anchor's displacement from the parent's along the axis).
    Prismatic,
    /// Nothing (a tool bolted to a link): 6 rows; its law has nothing to act on.
    Fixed,
}

impl JointKind {
    /// Its name in a scenario file: `revolute`, `prismatic`, `fixed`.
    pub fn name(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Prismatic => "prismatic",
            JointKind::Fixed => "fixed",
        }
    }
}

/// A joint resolved against the scenario's bodies.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// Its name.
    pub name: String,
    /// Body 1 (parent) and body 2 (child), indices into the model's bodies.
    pub bodies: [usize; 2],
    /// The joint's point in each body's frame (m, from its centre of mass).
    pub anchors: [Vector3<f64>; 2],
    /// The axis, unit, in body 1's frame (and body 2's).
    pub axis: Unit<Vector3<f64>>,
    /// Two unit vectors perpendicular to the axis and to each other, in the same frames:
    /// the axis rows' directions, and the angle's reference.
    pub normals: [Vector3<f64>; 2],
    /// Its own torque about the axis (spring, viscous and Coulomb friction); for a
    /// prismatic joint its force along the axis.
    pub law: JointLaw<f64>,
    /// What it lets the bodies do.
    pub kind: JointKind,
    /// The learned torque added to its law's (the joint's HCM), once attached
    /// (`Model::with_residual`; trained by `hcm train` on a mechanism's poses).
    pub residual: Option<crate::residual::JointResidual>,
}

/// Largest gap between the two anchors, and angle between the axes as the two bodies
/// carry them, that a scenario's initial state may leave (m, rad): the state must be
/// one the joint allows.
pub const ASSEMBLY_TOLERANCE: f64 = 1e-6;

impl Joint {
    /// The joint's angle θ (rad, in (−π, π]) with the bodies turned by `q1` and `q2`
    /// (body → world).
    pub fn angle(&self, q1: &UnitQuaternion<f64>, q2: &UnitQuaternion<f64>) -> f64 {
        let [u, _] = self.normals;
        let turned = (q1.inverse() * q2) * u;
        let a = self.axis.into_inner();
        u.cross(&turned).dot(&a).atan2(u.dot(&turned))
    }

    /// The gap between the anchors (m; a prismatic joint's off its axis) and the angle
    /// the joint does not allow (rad: between the axes of a hinge, the whole relative
    /// turn of a slide or a fixed joint) with the bodies at `(p1, q1)` and `(p2, q2)`.
    pub fn misfit(
        &self,
        (p1, q1): (&Vector3<f64>, &UnitQuaternion<f64>),
        (p2, q2): (&Vector3<f64>, &UnitQuaternion<f64>),
    ) -> (f64, f64) {
        let gap = (p1 + q1 * self.anchors[0]) - (p2 + q2 * self.anchors[1]);
        let axis = q1 * self.axis.into_inner();
        let (a1, a2) = (axis, q2 * self.axis.into_inner());
        match self.kind {
            JointKind::Revolute => (gap.norm(), a1.cross(&a2).norm().atan2(a1.dot(&a2))),
            JointKind::Prismatic => (
                (gap - axis * gap.dot(&axis)).norm(),
                (q1.inverse() * q2).angle(),
            ),
            JointKind::Fixed => (gap.norm(), (q1.inverse() * q2).angle()),
        }
    }
}

/// Joint `i` of `specs` resolved against the body names `names`; `error(field,
/// message)` makes the scenario's error.
pub(crate) fn resolve_joint(
    spec: &JointSpec,
    i: usize,
    names: &[&str],
    error: impl Fn(String, String) -> ScenarioError,
) -> Result<Joint, ScenarioError> {
    let name = match spec.name.is_empty() {
        true => format!("joint #{i}"),
        false => spec.name.clone(),
    };
    let field = |key: &str| format!("joint `{name}` (#{i}) {key}");
    let index = |body: &str| {
        (names.iter().position(|n| *n == body)).ok_or_else(|| {
            error(
                field("bodies"),
                format!("no body `{body}` (bodies: {})", names.join(", ")),
            )
        })
    };
    let bodies = [index(&spec.bodies[0])?, index(&spec.bodies[1])?];
    if bodies[0] == bodies[1] {
        return Err(error(
            field("bodies"),
            "joins a body to itself: give two different bodies".into(),
        ));
    }
    let finite = |v: &[f64; 3]| v.iter().all(|x| x.is_finite());
    if !spec.anchors.iter().all(finite) {
        return Err(error(
            field("anchors"),
            "must be finite [x, y, z] in metres".into(),
        ));
    }
    let axis = Vector3::from(spec.axis);
    let axis = (finite(&spec.axis) && axis.norm() > 0.0)
        .then(|| Unit::new_normalize(axis))
        .ok_or_else(|| {
            error(
                field("axis"),
                format!("must be a finite nonzero direction, found {:?}", spec.axis),
            )
        })?;
    spec.law
        .validate()
        .map_err(|e| error(field("law"), e.to_string()))?;
    Ok(Joint {
        name,
        bodies,
        anchors: spec.anchors.map(Vector3::from),
        axis,
        normals: normals(&axis),
        law: spec.law,
        kind: spec.kind,
        residual: None,
    })
}

/// Two unit vectors perpendicular to `axis` and to each other.
fn normals(axis: &Unit<Vector3<f64>>) -> [Vector3<f64>; 2] {
    let a = axis.into_inner();
    let seed = if a.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let first = a.cross(&seed).normalize();
    [first, a.cross(&first)]
}

impl Joint {
    /// The larger of the anchors' relative velocity (m/s) and the bodies' relative
    /// angular velocity off the axis (rad/s), bodies as the scenario starts them: both
    /// 0 where the joint holds.
    pub(crate) fn relative_velocity(&self, b1: &super::Body, b2: &super::Body) -> f64 {
        let velocity = |b: &super::Body, anchor: &Vector3<f64>| {
            b.velocity + b.angular_velocity.cross(&(b.orientation * anchor))
        };
        let slip = velocity(b1, &self.anchors[0]) - velocity(b2, &self.anchors[1]);
        let axis = b1.orientation * self.axis.into_inner();
        let turn = b2.angular_velocity - b1.angular_velocity;
        let off_axis = turn - axis * turn.dot(&axis);
        match self.kind {
            JointKind::Revolute => slip.norm().max(off_axis.norm()),
            // A slide's anchors move apart along the axis as fast as they like: the rate
            // of their gap off the axis, normals carried by body 1.
            JointKind::Prismatic => {
                let gap = (b1.position + b1.orientation * self.anchors[0])
                    - (b2.position + b2.orientation * self.anchors[1]);
                let off = |n: &Vector3<f64>| {
                    let m = b1.orientation * n;
                    (b1.angular_velocity.cross(&m).dot(&gap) + m.dot(&slip)).abs()
                };
                off(&self.normals[0])
                    .max(off(&self.normals[1]))
                    .max(turn.norm())
            }
            JointKind::Fixed => slip.norm().max(turn.norm()),
        }
    }
}

/// What a joint's own torque acts against, from its child body: the sizes the boxes
/// of a fit or a diagnosis of its law are scaled by (no number from one example).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointScales {
    /// The child's moment of inertia about the joint's axis through the anchor (kg·m²):
    /// a·I·a + m·r⊥², r⊥ the anchor's distance from the child's centre of mass off
    /// the axis.
    pub inertia: f64,
    /// The child's weight on its lever about the joint, m·|g|·r (N·m), r the larger of
    /// r⊥ and the child's radius of gyration about the axis (a joint through the
    /// centre of mass still turns a body of that size).
    pub torque: f64,
    /// The child swinging about the joint as a pendulum, √(torque / inertia) (rad/s).
    pub rate: f64,
}

impl Joint {
    /// The joint's scales with its bodies as in `model` (NaN where the child has no
    /// mass or inertia about the axis).
    pub fn scales(&self, model: &super::Model) -> JointScales {
        let child = &model.bodies[self.bodies[1]];
        let a = self.axis.into_inner();
        let r = self.anchors[1];
        let off_axis = (r - a * r.dot(&a)).norm();
        let own = a.dot(&(child.inertia * a));
        let inertia = own + child.mass * off_axis * off_axis;
        let gyration = (own / child.mass).sqrt();
        let torque = child.mass * model.gravity.norm() * off_axis.max(gyration);
        JointScales {
            inertia,
            torque,
            rate: (torque / inertia).sqrt(),
        }
    }
}
