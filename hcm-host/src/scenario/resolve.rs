//! From a scenario as written to a model ready to simulate: names resolved to
//! indices, laws built and validated, derived parameters filled in.

use super::rigid::{self, Part};
use super::{Scenario, ScenarioError, ShapeSpec};
use crate::law_catalogue;
use crate::residual::HostContactModel;
use hcm_core::effect::{AirDrag, ExtendedLaw, MAX_EFFECTS};
use hcm_core::geometry::{effective_modulus, sphere_sphere, Material};
use hcm_core::law::AnyNormalLaw;
use hcm_core::model::ContactModel;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use std::path::Path;

/// Contact geometry of a body, in the body's frame (which starts at the body's
/// initial orientation; the 1D examples never rotate it).
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A sphere of radius r (m) centred on the body's reference point.
    Sphere {
        /// Radius r (m).
        radius: f64,
    },
    /// A plane with unit outward `normal`, `offset` (m) from the reference point.
    Plane {
        /// Unit outward normal.
        normal: Vector3<f64>,
        /// Distance of the surface from the reference point along the normal (m).
        offset: f64,
    },
    /// A box centred on the reference point, edges along the body axes.
    Box {
        /// Half extents (m), of the outer box.
        half_extents: Vector3<f64>,
        /// Radius of the rounded edges and corners (m, 0 for a sharp box).
        rounding: f64,
    },
    /// Boxes fixed together (fixed bodies only).
    Compound {
        /// The boxes, placed in the body's frame.
        parts: Vec<Part>,
    },
}

impl Shape {
    /// Whether this shape makes a scenario 3D (it has corners or faces that turn with
    /// the body).
    pub fn is_polyhedral(&self) -> bool {
        matches!(self, Shape::Box { .. } | Shape::Compound { .. })
    }
}

/// A body of the model.
#[derive(Clone, Debug)]
pub struct Body {
    /// Name, as in data files.
    pub name: String,
    /// Mass (kg); +∞ for a fixed body.
    pub mass: f64,
    /// Whether the body is fixed in the world.
    pub(crate) fixed: bool,
    /// Contact geometry.
    pub(crate) shape: Shape,
    /// Material, if the scenario names one.
    pub(crate) material: Option<Material<f64>>,
    /// Initial position (m).
    pub position: Vector3<f64>,
    /// Initial velocity (m/s).
    pub velocity: Vector3<f64>,
    /// Initial orientation (body → world).
    pub orientation: UnitQuaternion<f64>,
    /// Initial angular velocity ω (rad/s, world frame).
    pub angular_velocity: Vector3<f64>,
    /// Inertia tensor about the centre of mass, body frame (kg·m²); the identity for
    /// fixed bodies (never used); NaN for a moving plane without one, which only a 1D
    /// scenario accepts (the simulator holds such a body from turning).
    pub inertia: Matrix3<f64>,
    /// Quadratic air drag in flight and in contact, if any.
    pub(crate) air_drag: Option<AirDrag<f64>>,
}

/// A contact pair of the model: body 1 a sphere or a box, body 2 a sphere, plane, box
/// or compound (see [`Model::is_rigid`] for which pairs make a scenario 3D).
#[derive(Clone, Debug)]
pub struct Contact {
    /// Index of body 1 in [`Model::bodies`].
    pub body_1: usize,
    /// Index of body 2.
    pub body_2: usize,
    /// The contact model — normal law with every parameter resolved, its effects,
    /// and the residual network (the HCM) once attached: the core type a controller
    /// ships, evaluated by every host stage.
    pub model: HostContactModel,
    /// Effective mass m_e = m1·m2/(m1 + m2) (kg) of the pair.
    pub effective_mass: f64,
    /// Parameter noise b per law or friction parameter (Eq 18), for generated
    /// experiments, sorted by name (the order of the draws).
    pub noise: Vec<(String, f64)>,
}

impl Contact {
    /// The base normal law (without effects).
    pub fn law(&self) -> &AnyNormalLaw<f64> {
        self.model.law()
    }
}

/// A scenario resolved and checked: what the simulator runs.
#[derive(Clone, Debug)]
pub struct Model {
    /// The scenario it came from (settings are read from here).
    pub scenario: Scenario,
    /// Gravity (m/s²).
    pub(crate) gravity: Vector3<f64>,
    /// Bodies, in file order.
    pub bodies: Vec<Body>,
    /// Contacts, in file order.
    pub contacts: Vec<Contact>,
    /// Joints, in file order.
    pub joints: Vec<super::Joint>,
}

impl Model {
    /// Whether the scenario is 3D: a box or compound body, friction or a tangential
    /// effect, or a body that starts turned or spinning. Otherwise it is 1D: spheres
    /// and planes that touch on their lines of centres and never turn (the paper's
    /// Eq 17 and Eq 21), judged by the four normal indicators. One simulator runs both.
    pub fn is_rigid(&self) -> bool {
        self.bodies.iter().any(|b| {
            b.shape.is_polyhedral()
                || (!b.fixed
                    && (b.angular_velocity != Vector3::zeros()
                        || b.orientation != UnitQuaternion::identity()))
        }) || self
            .contacts
            .iter()
            .any(|c| c.model.friction.is_some() || !c.model.tangential.is_empty())
    }

    /// Whether a run of the model varies by chance: a contact's parameter scatter
    /// (`noise`) or a `[variation]` — what a forecast's members draw. Otherwise one
    /// member is the whole forecast.
    pub fn varies(&self) -> bool {
        let v = &self.scenario.variation;
        self.contacts.iter().any(|c| !c.noise.is_empty())
            || v.start_state > 0.0
            || v.fixed_height > 0.0
            || v.fixed_tilt > 0.0
            || v.tracker > 0.0
    }

    /// The model without its variation: no contact's parameter scatter, `[variation]`
    /// all 0 — the deterministic model whose one member is the single replay.
    pub fn without_variation(&self) -> Model {
        let mut model = self.clone();
        model.contacts.iter_mut().for_each(|c| c.noise.clear());
        model.scenario.variation = Default::default();
        model
    }

    /// Index of the body named `name`.
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// `contact` if it numbers one of the contacts; else the message every command's
    /// `--contact` (and the Python API's `contact=`) gives.
    pub fn check_contact(&self, contact: usize) -> Result<usize, String> {
        match contact < self.contacts.len() {
            true => Ok(contact),
            false => Err(format!(
                "--contact {contact}: the scenario has {} contact(s), numbered from 0",
                self.contacts.len()
            )),
        }
    }
}

impl Scenario {
    /// [`Scenario::resolve`] naming the scenario by the file it was loaded from.
    pub fn model(&self) -> Result<Model, ScenarioError> {
        self.resolve(&self.source.path)
    }

    /// Resolves names, builds the laws and checks everything a simulation relies on.
    /// `path` names the scenario in errors.
    pub fn resolve(&self, path: &Path) -> Result<Model, ScenarioError> {
        super::validate::materials(self, path)?;
        let invalid = Invalid(path);
        let bodies = (0..self.bodies.len())
            .map(|i| self.resolve_body(i, &invalid))
            .collect::<Result<Vec<_>, _>>()?;
        if bodies.iter().all(|b| b.fixed) {
            return Err(invalid.error(
                "body".into(),
                "at least one body must move (fixed = false)".into(),
            ));
        }
        let contacts = (0..self.contacts.len())
            .map(|i| self.resolve_contact(i, &bodies, &invalid))
            .collect::<Result<Vec<_>, _>>()?;
        self.check_settings()
            .map_err(|(f, m)| invalid.error(f, m))?;
        for name in &self.record.bodies {
            if !bodies.iter().any(|b| &b.name == name) {
                return Err(invalid.error("record.bodies".into(), format!("no body `{name}`")));
            }
        }
        let joints = self.resolve_joints(&bodies, &invalid)?;
        let model = Model {
            scenario: self.clone(),
            gravity: Vector3::from(self.gravity),
            bodies,
            contacts,
            joints,
        };
        if model.is_rigid() {
            if let Some((i, b)) = model
                .bodies
                .iter()
                .enumerate()
                .find(|(_, b)| !b.fixed && b.inertia[(0, 0)].is_nan())
            {
                return Err(invalid.error(
                    format!("body `{}` (#{i}) inertia", b.name),
                    "is required for a moving plane in a 3D scenario (boxes, friction or \
                     rotation): give [Ixx, Iyy, Izz] in kg·m²"
                        .into(),
                ));
            }
        }
        super::validate::starts_apart(model, path)
    }

    /// The joints, each between two moving or fixed bodies (not both fixed), every one
    /// assembled in the initial state: its anchors within [`super::ASSEMBLY_TOLERANCE`]
    /// (m) of each other, its axes within that (rad), and moving together there.
    fn resolve_joints(
        &self,
        bodies: &[Body],
        invalid: &Invalid<'_>,
    ) -> Result<Vec<super::Joint>, ScenarioError> {
        let names: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
        let mut joints = Vec::new();
        for (i, spec) in self.joints.iter().enumerate() {
            let joint = super::joint::resolve_joint(spec, i, &names, |f, m| invalid.error(f, m))?;
            let [b1, b2] = joint.bodies.map(|b| &bodies[b]);
            let field = format!("joint `{}` (#{i})", joint.name);
            if b1.fixed && b2.fixed {
                return Err(invalid.error(field, "joins two fixed bodies: one must move".into()));
            }
            let tolerance = super::ASSEMBLY_TOLERANCE;
            let (gap, turn) = joint.misfit(
                (&b1.position, &b1.orientation),
                (&b2.position, &b2.orientation),
            );
            let slip = joint.relative_velocity(b1, b2);
            if gap > tolerance || turn > tolerance || slip > tolerance {
                return Err(invalid.error(
                    field,
                    format!(
                        "is not assembled in the initial state: its anchors {gap:.3e} m apart, \
                         its axes {turn:.3e} rad apart, the anchors' relative velocity and the \
                         turn off its axis {slip:.3e} m/s and rad/s (at most {tolerance:e}): \
                         place and move body `{}` so the joint holds",
                        b2.name
                    ),
                ));
            }
            joints.push(joint);
        }
        Ok(joints)
    }

    /// Body `i`: a unique name, its mass, shape, material, initial state and drag.
    fn resolve_body(&self, i: usize, invalid: &Invalid<'_>) -> Result<Body, ScenarioError> {
        let spec = &self.bodies[i];
        let field = |key: &str| format!("body `{}` (#{i}) {key}", spec.name);
        // Names are quoted in every message about the body, and match the data's
        // `body` column, whose cells are at most 200 characters.
        if spec.name.is_empty() || spec.name.chars().count() > 200 {
            return Err(invalid.error(
                format!("body #{i} name"),
                format!(
                    "must be 1 to 200 characters, found {}",
                    spec.name.chars().count()
                ),
            ));
        }
        if self.bodies[..i].iter().any(|b| b.name == spec.name) {
            return Err(invalid.error(
                field("name"),
                "appears twice; body names must be unique".into(),
            ));
        }
        let mass = body_mass(spec).map_err(|m| invalid.error(field("mass"), m))?;
        let shape = body_shape(&spec.shape).map_err(|(key, m)| invalid.error(field(&key), m))?;
        let material = self.body_material(spec, &field, invalid)?;
        let state = initial_state(spec, &field, invalid)?;
        if !spec.fixed && matches!(shape, Shape::Compound { .. }) {
            return Err(invalid.error(
                field("shape"),
                "a compound body must be fixed (set fixed = true); moving bodies are a sphere or a box".into(),
            ));
        }
        let inertia =
            body_inertia(spec, &shape, mass).map_err(|m| invalid.error(field("inertia"), m))?;
        Ok(Body {
            name: spec.name.clone(),
            mass,
            fixed: spec.fixed,
            shape,
            material,
            position: state.position,
            velocity: state.velocity,
            orientation: state.orientation,
            angular_velocity: state.angular_velocity,
            inertia,
            air_drag: spec.air_drag,
        })
    }

    /// The material `spec` names, if any (an error naming the known ones if unknown).
    fn body_material(
        &self,
        spec: &super::BodySpec,
        field: &impl Fn(&str) -> String,
        invalid: &Invalid<'_>,
    ) -> Result<Option<Material<f64>>, ScenarioError> {
        Ok(match &spec.material {
            None => None,
            Some(name) => Some(*self.materials.get(name).ok_or_else(|| {
                let known: Vec<_> = self.materials.keys().cloned().collect();
                invalid.error(
                    field("material"),
                    format!(
                        "names `{name}`, but the materials are: {}",
                        known.join(", ")
                    ),
                )
            })?),
        })
    }

    /// Contact `i` between two of `bodies`: the pair, its law with the derived
    /// parameters filled in, its parameter noise and its effects.
    fn resolve_contact(
        &self,
        i: usize,
        bodies: &[Body],
        invalid: &Invalid<'_>,
    ) -> Result<Contact, ScenarioError> {
        let spec = &self.contacts[i];
        let field = |key: &str| {
            format!(
                "contact #{i} ({} – {}) {key}",
                spec.bodies[0], spec.bodies[1]
            )
        };
        let (body_1, body_2, radius_1) =
            contact_pair(spec, bodies).map_err(|m| invalid.error(field("bodies"), m))?;
        let (b1, b2) = (&bodies[body_1], &bodies[body_2]);
        let (radius, effective_mass) = pair_geometry(radius_1, b1, b2);
        let parameters = derived_parameters(spec, b1, b2, radius, effective_mass)
            .map_err(|m| invalid.error(field("parameters"), m))?;
        let law = law_catalogue::build_from_table(&spec.law, &parameters)
            .map_err(|e| invalid.error(field("law"), e.to_string()))?;
        check_noise(spec).map_err(|m| invalid.error(field("noise"), m))?;
        let noise = spec.noise.iter().map(|(k, v)| (k.clone(), *v)).collect();
        if spec.effects.len() > MAX_EFFECTS {
            return Err(invalid.error(
                field("effects"),
                format!("{} effects; at most {MAX_EFFECTS}", spec.effects.len()),
            ));
        }
        let mut normal = ExtendedLaw::new(law);
        for effect in &spec.effects {
            // Checked above: at most MAX_EFFECTS, so no push fails.
            let _ = normal.effects.push(*effect);
        }
        let mut model = ContactModel::physics(normal).with_residual(None);
        if let Some(friction) = &spec.friction {
            model.friction = Some(
                friction
                    .law()
                    .map_err(|m| invalid.error(field("friction"), m))?,
            );
        }
        spec.tangential
            .validate()
            .map_err(|e| invalid.error(field("tangential"), e.to_string()))?;
        model.tangential = spec.tangential;
        let contact = Contact {
            body_1,
            body_2,
            model,
            effective_mass,
            noise,
        };
        contact
            .model
            .validate()
            .map_err(|e| invalid.error(field("effects"), e.to_string()))?;
        Ok(contact)
    }

    fn check_settings(&self) -> Result<(), (String, String)> {
        let s = &self.simulation;
        let r = &self.record;
        let positive = [
            ("simulation.end_time", s.end_time),
            ("simulation.relative_tolerance", s.relative_tolerance),
            ("simulation.absolute_tolerance", s.absolute_tolerance),
            ("simulation.max_step", s.max_step),
            ("record.contact_sample_period", r.contact_sample_period),
            ("record.flight_sample_period", r.flight_sample_period),
        ];
        for (name, value) in positive {
            if !(value > 0.0 && value.is_finite()) {
                return Err((
                    name.into(),
                    format!("must be a positive finite number, found {value}"),
                ));
            }
        }
        if s.relative_tolerance >= 1.0 {
            return Err((
                "simulation.relative_tolerance".into(),
                format!(
                    "is a fraction of the state, below 1 (e.g. 1e-8), found {}",
                    s.relative_tolerance
                ),
            ));
        }
        if !(r.contact_margin >= 0.0 && r.contact_margin.is_finite()) {
            return Err((
                "record.contact_margin".into(),
                "must be zero or a positive number of s".into(),
            ));
        }
        self.check_experiment()?;
        if !self.gravity.iter().all(|g| g.is_finite()) {
            return Err(("gravity".into(), "must be finite".into()));
        }
        // A mass whose weight overflows makes every force of the run infinite.
        let g = self.gravity.iter().map(|g| g * g).sum::<f64>().sqrt();
        for (k, body) in self.bodies.iter().enumerate() {
            match body.mass {
                Some(m) if !body.fixed && m.is_finite() && !(m * g).is_finite() => {
                    return Err((
                        format!("body `{}` (#{k}) mass", body.name),
                        format!("{m:e} kg weighs more than a float holds under gravity {g} m/s²: give it in kg"),
                    ))
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// The `[experiment]` table: noise σ ≥ 0, sensor lag and filter ≥ 0 (s), a positive
    /// gain, a hold-out share in (0, 1), conditions named once and hold-out conditions
    /// among them; and `[variation]`'s start-state factor ≥ 0.
    fn check_experiment(&self) -> Result<(), (String, String)> {
        let e = &self.experiment;
        let (sd, time) = ("a standard deviation ≥ 0", "a time ≥ 0 (s)");
        for (name, value, what) in [
            ("experiment.force_noise", e.force_noise, sd),
            ("experiment.torque_noise", e.torque_noise, sd),
            ("experiment.position_noise", e.position_noise, sd),
            ("experiment.velocity_noise", e.velocity_noise, sd),
            ("experiment.sensor_delay", e.sensor_delay, time),
            ("experiment.sensor_filter", e.sensor_filter, time),
        ] {
            if !(value >= 0.0 && value.is_finite()) {
                return Err((name.into(), format!("must be {what}, found {value}")));
            }
        }
        let start = self.variation.start_state;
        if !(start >= 0.0 && start.is_finite()) {
            let problem =
                format!("must be a factor ≥ 0 on the fitted start state's σ, found {start}");
            return Err(("variation.start_state".into(), problem));
        }
        let tails = self.variation.tails;
        if !(tails == 0.0 || (tails > 2.0 && tails.is_finite())) {
            let problem = format!(
                "must be 0 (normal draws) or a Student-t's degrees of freedom > 2, found {tails}"
            );
            return Err(("variation.tails".into(), problem));
        }
        if !e.force_nonlinearity.is_finite() {
            return Err((
                "experiment.force_nonlinearity".into(),
                format!("must be a finite κ (1/N), found {}", e.force_nonlinearity),
            ));
        }
        if !(e.force_gain > 0.0 && e.force_gain.is_finite()) {
            return Err((
                "experiment.force_gain".into(),
                format!("must be a positive finite factor, found {}", e.force_gain),
            ));
        }
        if !(e.holdout_fraction > 0.0 && e.holdout_fraction < 1.0) {
            return Err((
                "experiment.holdout_fraction".into(),
                format!("must lie in (0, 1), found {}", e.holdout_fraction),
            ));
        }
        for (i, condition) in e.conditions.iter().enumerate() {
            if condition.name.is_empty() || condition.name.contains('/') {
                return Err((
                    "experiment.condition.name".into(),
                    format!("`{}` must be non-empty and without `/`", condition.name),
                ));
            }
            if e.conditions[..i].iter().any(|c| c.name == condition.name) {
                return Err((
                    "experiment.condition.name".into(),
                    format!("`{}` appears twice", condition.name),
                ));
            }
        }
        for name in &e.holdout_conditions {
            if !e.conditions.iter().any(|c| &c.name == name) {
                let names: Vec<_> = e.conditions.iter().map(|c| c.name.as_str()).collect();
                return Err((
                    "experiment.holdout_conditions".into(),
                    format!("no condition `{name}` (conditions: {})", names.join(", ")),
                ));
            }
        }
        Ok(())
    }
}

/// Builds the [`ScenarioError::Invalid`] of the scenario at this path.
struct Invalid<'a>(&'a Path);

impl Invalid<'_> {
    fn error(&self, field: String, message: String) -> ScenarioError {
        ScenarioError::Invalid {
            path: self.0.to_owned(),
            field,
            message,
        }
    }
}

/// A body's initial state.
struct InitialState {
    /// Position (m).
    position: Vector3<f64>,
    /// Velocity (m/s).
    velocity: Vector3<f64>,
    /// Orientation (body → world).
    orientation: UnitQuaternion<f64>,
    /// Angular velocity (rad/s).
    angular_velocity: Vector3<f64>,
}

/// The initial state of body `spec`, checked finite (its air drag checked on the way):
/// a fixed body may not spin.
fn initial_state(
    spec: &super::BodySpec,
    field: &impl Fn(&str) -> String,
    invalid: &Invalid<'_>,
) -> Result<InitialState, ScenarioError> {
    let (position, velocity) = (Vector3::from(spec.position), Vector3::from(spec.velocity));
    if !position
        .iter()
        .chain(velocity.iter())
        .all(|x| x.is_finite())
    {
        return Err(invalid.error(field("position/velocity"), "must be finite".into()));
    }
    if let Some(drag) = &spec.air_drag {
        drag.validate()
            .map_err(|e| invalid.error(field("air_drag"), e.to_string()))?;
    }
    let orientation = rigid::orientation(spec.orientation.as_ref())
        .map_err(|m| invalid.error(field("orientation"), m))?;
    let angular_velocity = Vector3::from(spec.angular_velocity);
    if !angular_velocity.iter().all(|w| w.is_finite()) {
        return Err(invalid.error(field("angular_velocity"), "must be finite (rad/s)".into()));
    }
    if spec.fixed && angular_velocity != Vector3::zeros() {
        return Err(invalid.error(
            field("angular_velocity"),
            "a fixed body cannot spin; remove it or set fixed = false".into(),
        ));
    }
    Ok(InitialState {
        position,
        velocity,
        orientation,
        angular_velocity,
    })
}

/// The inertia (kg·m²) of body `spec` of `shape` and `mass` (kg): given, else a sphere's
/// or a box's; identity for a fixed body, NaN for a moving plane.
fn body_inertia(spec: &super::BodySpec, shape: &Shape, mass: f64) -> Result<Matrix3<f64>, String> {
    if spec.fixed {
        return Ok(Matrix3::identity());
    }
    let default = match shape {
        Shape::Sphere { radius } => Some(Matrix3::identity() * (0.4 * mass * radius * radius)),
        Shape::Box { half_extents, .. } => Some(rigid::box_inertia(mass, half_extents)),
        _ => None,
    };
    match (spec.inertia.as_ref(), default) {
        // A moving plane (the flat shot's plate) never turns in the 1D
        // simulator; a 3D scenario asks for its inertia (`resolve`).
        (None, None) => Ok(Matrix3::from_element(f64::NAN)),
        (given, default) => rigid::inertia(given, mass, default),
    }
}

/// The body's mass (kg): +∞ for a fixed body, else the given positive finite value.
fn body_mass(spec: &super::BodySpec) -> Result<f64, String> {
    match (spec.fixed, spec.mass) {
        (true, _) => Ok(f64::INFINITY),
        (false, Some(m)) if m > 0.0 && m.is_finite() => Ok(m),
        (false, Some(m)) => Err(format!("must be a positive number of kg, found {m}")),
        (false, None) => Err("is required for a moving body (or set fixed = true)".into()),
    }
}

/// The body's contact geometry, checked; errors name the key at fault.
fn body_shape(spec: &ShapeSpec) -> Result<Shape, (String, String)> {
    match spec {
        ShapeSpec::Sphere { radius } if *radius > 0.0 && radius.is_finite() => {
            Ok(Shape::Sphere { radius: *radius })
        }
        ShapeSpec::Sphere { radius } => Err((
            "shape.sphere.radius".into(),
            format!("must be a positive number of m, found {radius}"),
        )),
        ShapeSpec::Plane { normal, offset } => {
            let n = Vector3::from(*normal);
            if !(n.norm() > 0.0 && n.norm().is_finite() && offset.is_finite()) {
                return Err((
                    "shape.plane".into(),
                    "needs a non-zero finite normal and a finite offset".into(),
                ));
            }
            Ok(Shape::Plane {
                normal: n.normalize(),
                offset: *offset,
            })
        }
        ShapeSpec::Box {
            half_extents,
            rounding,
        } => {
            let half_extents = rigid::half_extents(half_extents)
                .map_err(|m| ("shape.box.half_extents".to_owned(), m))?;
            Ok(Shape::Box {
                rounding: rigid::rounding(*rounding, &half_extents)
                    .map_err(|m| ("shape.box.rounding".to_owned(), m))?,
                half_extents,
            })
        }
        ShapeSpec::Compound { parts } => Ok(Shape::Compound {
            parts: rigid::parts(parts)?,
        }),
    }
}

/// Indices of the contact's two bodies and body 1's radius (m; None for a box): both
/// exist, differ, form a supported pair, and at least one of them moves.
fn contact_pair(
    spec: &super::ContactSpec,
    bodies: &[Body],
) -> Result<(usize, usize, Option<f64>), String> {
    let index = |name: &str| {
        bodies.iter().position(|b| b.name == name).ok_or_else(|| {
            let known: Vec<_> = bodies.iter().map(|b| b.name.as_str()).collect();
            format!("no body `{name}` (bodies: {})", known.join(", "))
        })
    };
    let (body_1, body_2) = (index(&spec.bodies[0])?, index(&spec.bodies[1])?);
    if body_1 == body_2 {
        return Err("a body cannot touch itself".into());
    }
    let (b1, b2) = (&bodies[body_1], &bodies[body_2]);
    let rounded = |shape: &Shape| matches!(shape, Shape::Box { rounding, .. } if *rounding > 0.0);
    if let (
        Shape::Box { .. } | Shape::Compound { .. },
        Shape::Box { .. } | Shape::Compound { .. },
    ) = (&b1.shape, &b2.shape)
    {
        if let Some(b) = [b1, b2].into_iter().find(|b| rounded(&b.shape)) {
            return Err(format!(
                "`{}` has rounded edges (`rounding`), which hcm models against a plane or a \
                 sphere, not against another box: give it `rounding = 0` for this contact's \
                 scene",
                b.name
            ));
        }
    }
    let radius_1 = match (&b1.shape, &b2.shape) {
        (Shape::Sphere { radius }, _) => Some(*radius),
        (Shape::Box { .. }, Shape::Plane { .. } | Shape::Box { .. } | Shape::Compound { .. }) => {
            None
        }
        _ => {
            return Err(format!(
                "`{}` ({}) against `{}` ({}) is not a supported pair: body 1 is a sphere \
                 (against a plane, sphere, box or compound) or a box (against a plane, box or \
                 compound); swap the bodies if body 1 is the plane",
                b1.name,
                shape_name(&b1.shape),
                b2.name,
                shape_name(&b2.shape)
            ))
        }
    };
    if b1.fixed && b2.fixed {
        return Err("both bodies are fixed".into());
    }
    Ok((body_1, body_2, radius_1))
}

fn shape_name(shape: &Shape) -> &'static str {
    match shape {
        Shape::Sphere { .. } => "sphere",
        Shape::Plane { .. } => "plane",
        Shape::Box { .. } => "box",
        Shape::Compound { .. } => "compound",
    }
}

/// The pair's effective radius R (m) — NaN when body 1 is a box, which has no radius
/// of curvature — and its effective mass m_e = m1·m2/(m1 + m2) (kg), the moving
/// body's mass when the other is fixed.
fn pair_geometry(radius_1: Option<f64>, b1: &Body, b2: &Body) -> (f64, f64) {
    let effective_mass = if b1.fixed {
        b2.mass
    } else if b2.fixed {
        b1.mass
    } else {
        b1.mass * b2.mass / (b1.mass + b2.mass)
    };
    let radius = match (radius_1, &b2.shape) {
        (None, _) => f64::NAN,
        (Some(r1), Shape::Sphere { radius: r2 }) => sphere_sphere::effective_radius(r1, *r2),
        (Some(r1), _) => r1,
    };
    (radius, effective_mass)
}

/// Every noise entry names a parameter of the contact's law, or of its friction when
/// it has friction, and is a relative standard deviation ≥ 0.
fn check_noise(spec: &super::ContactSpec) -> Result<(), String> {
    let known = law_catalogue::entry(&spec.law)
        .map(|e| e.parameters)
        .unwrap_or(&[]);
    let joint = super::FRICTION_COEFFICIENT;
    let friction: Vec<&str> = super::FrictionSpec::PARAMETERS
        .into_iter()
        .chain([joint])
        .collect();
    for (name, b) in &spec.noise {
        let of_friction = friction.contains(&name.as_str());
        if of_friction && spec.friction.is_none() {
            return Err(format!(
                "`{name}` is a friction parameter, and this contact has no `friction`; \
                 give it `friction = {{ mu_static, mu_dynamic, v_static, v_dynamic }}` \
                 or leave `{name}` out of `noise` (`{joint}` scatters μ_s and μ_d together)"
            ));
        }
        if !of_friction && !known.iter().any(|p| p.name == name) {
            let mut names: Vec<_> = known.iter().map(|p| p.name).collect();
            if spec.friction.is_some() {
                names.extend(&friction);
            }
            return Err(format!(
                "`{name}` is not a parameter of `{}`{} ({})",
                spec.law,
                if spec.friction.is_some() {
                    " or of its friction"
                } else {
                    ""
                },
                names.join(", ")
            ));
        }
        if !(*b >= 0.0 && b.is_finite()) {
            return Err(format!(
                "`{name}` must be a relative standard deviation ≥ 0, found {b}"
            ));
        }
    }
    Ok(())
}

/// The law's parameter table with the geometric parameters the law can derive
/// from the bodies filled in where the scenario leaves them out.
fn derived_parameters(
    spec: &super::ContactSpec,
    body_1: &Body,
    body_2: &Body,
    radius: f64,
    effective_mass: f64,
) -> Result<toml::Table, String> {
    let mut table = spec.parameters.clone();
    let materials = || match (body_1.material, body_2.material) {
        (Some(m1), Some(m2)) => Ok(effective_modulus(&m1, &m2)),
        _ => Err(format!(
            "law `{}` needs `material` on both bodies (or give its parameters explicitly)",
            spec.law
        )),
    };
    if radius.is_nan() && matches!(spec.law.as_str(), "variable_stiffness" | "hertz") {
        let given = |k: &str| spec.parameters.contains_key(k);
        if !(given("stiffness") || given("radius") && given("effective_modulus")) {
            return Err(format!(
                "law `{}` derives its stiffness from a radius of curvature, and a box has \
                 none: give `stiffness` (N/m^1.5) explicitly",
                spec.law
            ));
        }
    }
    let mut fill = |key: &str, value: f64| {
        table
            .entry(key.to_owned())
            .or_insert(toml::Value::Float(value));
    };
    match spec.law.as_str() {
        "variable_stiffness" => {
            if !spec.parameters.contains_key("effective_modulus") {
                fill("effective_modulus", materials()?);
            }
            fill("radius", radius);
            fill("effective_mass", effective_mass);
        }
        "hertz" => {
            if !spec.parameters.contains_key("stiffness") {
                fill(
                    "stiffness",
                    hcm_core::geometry::hertz_stiffness(materials()?, radius),
                );
            }
            fill("exponent", 1.5);
        }
        _ => {}
    }
    Ok(table)
}
