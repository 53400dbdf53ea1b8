//! Scenario files: the bodies, materials, contacts, initial conditions and solver
//! and recording settings of one experiment, in TOML.
//!
//! A scenario is read in three steps: the TOML text is parsed, `--set key=value`
//! overrides are applied to the parsed document ([`overrides`]), and the result is
//! deserialised and checked ([`Scenario::resolve`]) into a [`Model`] ready to simulate.
//! Every key is documented in the README ("Scenario files").

mod alike;
mod assignment;
mod exact;
mod geometry;
mod joint;
mod joint_term;
mod overrides;
mod residual_fit;
mod resolve;
mod rigid;
mod validate;
mod variation;
pub use geometry::{pair_contacts, pair_kinematics, pair_rate, pair_separation, Pose};

pub use assignment::{Assignment, IntoAssignment};
pub use joint::{Joint, JointKind, JointScales, JointSpec, ASSEMBLY_TOLERANCE};
pub use joint_term::{JointTerm, SMOOTHING_FRACTION};
pub use resolve::{Body, Contact, Model, Shape};
pub use rigid::{FrictionSpec, InertiaSpec, OrientationSpec, Part, PartSpec};
pub use variation::{draw_parameter, drawn_run, shift_surface, tilt_surface, up};
pub use variation::{Draw, FRICTION_COEFFICIENT};

use crate::input;
use hcm_core::effect::{AirDrag, ContactEffect};
use hcm_core::friction::TangentialEffects;
use hcm_core::geometry::Material;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A scenario file as written by a user, before its references are resolved.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// Short name, used as a label in outputs.
    pub name: String,
    /// Free text for people.
    #[serde(default)]
    pub description: String,
    /// Gravitational acceleration **g** (m/s²), world frame.
    #[serde(deserialize_with = "exact::array")]
    pub(crate) gravity: [f64; 3],
    /// Named materials, referred to by bodies.
    #[serde(default, rename = "material")]
    pub(crate) materials: BTreeMap<String, Material<f64>>,
    /// The bodies, moving or fixed.
    #[serde(rename = "body")]
    pub(crate) bodies: Vec<BodySpec>,
    /// The contact pairs and their laws.
    #[serde(rename = "contact")]
    pub(crate) contacts: Vec<ContactSpec>,
    /// Joints between bodies (none by default).
    #[serde(default, rename = "joint")]
    pub(crate) joints: Vec<JointSpec>,
    /// Solver settings and when to stop.
    pub(crate) simulation: SimulationSpec,
    /// What the recorded trajectory holds.
    pub record: RecordSpec,
    /// How noise-added experiments (PM1) are generated from this scenario.
    #[serde(default)]
    pub experiment: ExperimentSpec,
    /// Identification (PM2) settings.
    #[serde(default)]
    pub identify: IdentifySpec,
    /// How a run varies beyond its contacts' parameter scatter: what a forecast's
    /// members draw besides the contacts' `noise`.
    #[serde(default)]
    pub variation: VariationSpec,
    /// The file and parsed document it came from, overrides applied, so that
    /// experimental conditions can be layered on top ([`Scenario::with`]).
    #[serde(skip)]
    pub(crate) source: Source,
}

/// Where a scenario came from.
#[derive(Clone, Debug, Default)]
pub struct Source {
    /// The scenario file (names it in errors).
    pub(crate) path: PathBuf,
    /// The TOML document with every override applied so far.
    pub(crate) document: toml::Table,
}

/// One body.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Unique name, as in the data files' `body` column.
    pub(crate) name: String,
    /// Mass m (kg); required for moving bodies, ignored for fixed ones.
    pub(crate) mass: Option<f64>,
    /// A fixed body never moves (the ground, a hole).
    #[serde(default)]
    pub(crate) fixed: bool,
    /// Contact geometry.
    pub(crate) shape: ShapeSpec,
    /// Name of an entry of `[material.*]`; needed where a law derives parameters
    /// from the materials (variable stiffness, Hertz without `stiffness`).
    pub(crate) material: Option<String>,
    /// Initial position of the body's reference point (its centre of mass) (m).
    #[serde(deserialize_with = "exact::array")]
    pub(crate) position: [f64; 3],
    /// Initial velocity (m/s).
    #[serde(default)]
    #[serde(deserialize_with = "exact::array")]
    pub(crate) velocity: [f64; 3],
    /// Initial orientation (body → world); default: the identity.
    #[serde(default)]
    pub(crate) orientation: Option<OrientationSpec>,
    /// Initial angular velocity ω (rad/s, **world frame**).
    #[serde(default)]
    #[serde(deserialize_with = "exact::array")]
    pub(crate) angular_velocity: [f64; 3],
    /// Inertia tensor about the centre of mass in the body frame (kg·m²): principal
    /// moments `[Ixx, Iyy, Izz]` or a full symmetric 3×3 matrix. Default: the uniform
    /// solid of the shape (a sphere 2/5·m·r², a box m·(b² + c²)/3 with half extents).
    #[serde(default)]
    pub(crate) inertia: Option<InertiaSpec>,
    /// Quadratic air drag on the body, e.g. `air_drag = { coefficient = 1e-4 }` (kg/m).
    #[serde(default)]
    pub(crate) air_drag: Option<AirDrag<f64>>,
}

/// Contact geometry of a body, relative to its reference point.
#[derive(Clone, Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ShapeSpec {
    /// A sphere centred on the reference point.
    Sphere {
        /// Radius r (m).
        radius: f64,
    },
    /// A flat surface (half-space) with outward `normal`, at `offset` (m) from the
    /// reference point along the normal (e.g. half the thickness of a plate).
    Plane {
        /// Outward normal (normalised on load).
        #[serde(deserialize_with = "exact::array")]
        normal: [f64; 3],
        /// Distance from the reference point to the surface along the normal (m).
        #[serde(default)]
        offset: f64,
    },
    /// A rectangular box (cuboid) centred on the reference point, its edges along the
    /// body's axes.
    Box {
        /// Half extents along the body's x, y and z axes (m).
        #[serde(deserialize_with = "exact::array")]
        half_extents: [f64; 3],
        /// Radius of its rounded edges and corners (m, 0 ≤ r < the smallest half
        /// extent; 0, sharp, by default): real boxes are not knife-edged, and the
        /// radius moves the point a box pivots on as it rolls over an edge. Against a
        /// plane or a sphere only.
        #[serde(default)]
        rounding: f64,
    },
    /// Several boxes fixed together (a block with a hole = walls + bottom); only a
    /// fixed body may be compound.
    Compound {
        /// The boxes, each placed in the body's frame.
        parts: Vec<PartSpec>,
    },
}

/// One contact pair.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Body 1 (a sphere) and body 2; the normal points from body 2 to body 1.
    pub(crate) bodies: [String; 2],
    /// Normal law name (see `hcm laws`).
    pub(crate) law: String,
    /// Law parameters (SI). Missing geometric ones are derived where the law allows:
    /// `effective_modulus`, `radius` and `effective_mass` of `variable_stiffness`, and
    /// `stiffness` (Eq 3) and `exponent` (3/2) of `hertz`.
    #[serde(default)]
    pub(crate) parameters: toml::Table,
    /// Parameter scatter from run to run (Eq 18): for each named parameter, b in
    /// η = a + a·b·ζ, ζ ~ N(0, 1) drawn once per run (dimensionless) — by the
    /// noise-added experiment for each generated run, and by a forecast for each of its
    /// members. A name is a parameter of the law or, with `friction`, one of the
    /// friction's (`mu_static`, `mu_dynamic`, `v_static`, `v_dynamic`, or `mu`: both
    /// coefficients by one ζ).
    #[serde(default)]
    pub(crate) noise: BTreeMap<String, f64>,
    /// Physical effects added to the law (`hcm_core::effect`), e.g.
    /// `effects = [{ viscous_damping = { coefficient = 40.0 } }]`; at most one of each
    /// kind, at most four.
    #[serde(default)]
    pub(crate) effects: Vec<ContactEffect<f64>>,
    /// Velocity-based STEP friction (Eq 10–11) at every contact point, e.g.
    /// `friction = { mu_static = 0.3, mu_dynamic = 0.2, v_static = 1e-3, v_dynamic = 1e-2 }`
    /// (–, –, m/s, m/s). None: frictionless.
    #[serde(default)]
    pub(crate) friction: Option<FrictionSpec>,
    /// Tangential effects beside the friction (`hcm_core::friction::TangentialEffects`),
    /// e.g. `tangential = { viscous_friction = { coefficient = 0.5 } }` (N·s/m per
    /// point), `torsional_resistance = { arm = 2e-3, spin_rate = 0.1 }` (m, rad/s),
    /// `rolling_resistance = { arm = 5e-4, roll_rate = 0.1 }` (m, rad/s). None: none.
    #[serde(default)]
    pub(crate) tangential: TangentialEffects<f64>,
}

/// Solver settings and the stop condition.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimulationSpec {
    /// Latest simulated time (s); the run starts at t = 0.
    pub(crate) end_time: f64,
    /// Stop `record.contact_margin` after the lift-off of this many contact events
    /// (0: run to `end_time`).
    #[serde(default)]
    pub(crate) stop_after_contacts: usize,
    /// Relative tolerance of the adaptive Runge–Kutta solver.
    #[serde(default = "default_relative_tolerance")]
    pub(crate) relative_tolerance: f64,
    /// Absolute tolerance (state units: m, m/s, N·s, J).
    #[serde(default = "default_absolute_tolerance")]
    pub(crate) absolute_tolerance: f64,
    /// Longest solver step (s).
    #[serde(default = "default_max_step")]
    pub(crate) max_step: f64,
    /// Solver steps allowed before the run is abandoned as stiff or diverging.
    #[serde(default = "default_max_steps")]
    pub(crate) max_steps: u64,
}

/// What gets sampled into the trajectory.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordSpec {
    /// Sample period inside contacts and their margins (s).
    pub contact_sample_period: f64,
    /// Sample period elsewhere (s).
    pub(crate) flight_sample_period: f64,
    /// Time recorded at the contact rate before touch-down and after lift-off (s).
    pub contact_margin: f64,
    /// Bodies to record (default: all). Leaving out a fixed body halves a file.
    #[serde(default)]
    pub(crate) bodies: Vec<String>,
}

/// How a run differs from the model beyond its contacts' parameter scatter (each
/// contact's `noise`): what the members of a forecast (`hcm predict --members`) draw.
/// All zero (the default): the model forecasts one path per start.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct VariationSpec {
    /// Factor on the standard deviations of a replay's start state (–, ≥ 0), whose
    /// covariance is its free-flight fit's (`replay::initial_state`): 1 draws the
    /// state as uncertain as the tracker's noise left it; 0 starts every member from
    /// the fitted state.
    #[serde(default)]
    pub start_state: f64,
    /// σ of every fixed body's height from run to run (m, ≥ 0): its surface moved
    /// along the up direction by σ·ζ per run (a table that is not where it was
    /// calibrated, a tracker's frame that drifts).
    #[serde(default)]
    pub fixed_height: f64,
    /// σ of every fixed body's tilt from run to run (rad, ≥ 0): its surface turned by
    /// σ·ζ₁ about the world x axis and σ·ζ₂ about y per run.
    #[serde(default)]
    pub fixed_tilt: f64,
    /// Degrees of freedom ν of the run-to-run draws (–, > 2; 0, the default, is the
    /// normal law): every ζ of a run's contact scatter (`noise`), fixed height and
    /// tilt is a normal draw × one scale per run, √((ν − 2)/χ²_ν), so that the run's
    /// draws are Student-t of unit variance — the same σ, heavier tails: most runs
    /// nearer the model than a normal spread puts them, a few much further (a scale
    /// mixture of normals, as contacts that are mostly alike and now and then not).
    #[serde(default)]
    pub tails: f64,
    /// Factor on the tracker's noise each member's frames carry (–, ≥ 0): every frame's
    /// centre and orientation moved by the residual σ of the toss's own free-flight
    /// fits × this, per axis — a forecast of what the tracker records rather than of the
    /// path. 0: the members are the simulated paths.
    #[serde(default)]
    pub tracker: f64,
}

/// The noise-added experiment (paper Section 4, Eq 14, 18, 19).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExperimentSpec {
    /// σ of the output noise σ·ζ on every sampled force component (N), Eq 19.
    #[serde(default = "default_force_noise")]
    pub force_noise: f64,
    /// σ of the noise on every sampled torque component (N·m).
    #[serde(default)]
    pub torque_noise: f64,
    /// σ of the noise on every sampled position component (m).
    #[serde(default)]
    pub(crate) position_noise: f64,
    /// σ of the noise on every sampled velocity component (m/s).
    #[serde(default)]
    pub(crate) velocity_noise: f64,
    /// Force-sensor bias added to every recorded force sample, in flight too (N, world
    /// components): a measurement effect, for testing `hcm diagnose`.
    #[serde(default)]
    #[serde(deserialize_with = "exact::array")]
    pub(crate) force_offset: [f64; 3],
    /// Force-sensor lag τ (s, ≥ 0): the force recorded at time t is the true force at
    /// t − τ (linear interpolation between the simulation's samples; the first sample's
    /// value before it). A measurement effect, for testing `hcm diagnose`.
    #[serde(default)]
    pub(crate) sensor_delay: f64,
    /// Force-sensor low-pass time constant T (s, ≥ 0): the recorded force y follows
    /// T·ẏ + y = f (after the lag, before gain and offset; exact for a force linear
    /// between the simulation's samples, at rest on the first). A measurement effect,
    /// for testing `hcm diagnose`.
    #[serde(default)]
    pub(crate) sensor_filter: f64,
    /// Force-sensor nonlinearity κ (1/N): the sensor element reads f + κ·|f|·f, a gain
    /// growing with the force (before the lag and the filter). A measurement effect,
    /// for testing `hcm diagnose`.
    #[serde(default)]
    pub(crate) force_nonlinearity: f64,
    /// Force-sensor gain g (–, > 0): every recorded force component is g times the
    /// true one (after the lag, before the offset), torques too. A measurement effect,
    /// for testing `hcm diagnose`.
    #[serde(default = "unit_gain")]
    pub(crate) force_gain: f64,
    /// Experimental conditions; `--runs` runs are made of each. None: one condition,
    /// the scenario as written.
    #[serde(default, rename = "condition")]
    pub(crate) conditions: Vec<ConditionSpec>,
    /// Conditions whose runs form S2 (validation). Empty: S2 is a random
    /// `holdout_fraction` of all runs.
    #[serde(default)]
    pub(crate) holdout_conditions: Vec<String>,
    /// Share of runs drawn at random into S2 when no holdout condition is named.
    #[serde(default = "default_holdout_fraction")]
    pub(crate) holdout_fraction: f64,
}

impl Default for ExperimentSpec {
    fn default() -> Self {
        ExperimentSpec {
            force_noise: default_force_noise(),
            torque_noise: 0.0,
            position_noise: 0.0,
            velocity_noise: 0.0,
            force_offset: [0.0; 3],
            sensor_delay: 0.0,
            sensor_filter: 0.0,
            force_nonlinearity: 0.0,
            force_gain: unit_gain(),
            conditions: Vec::new(),
            holdout_conditions: Vec::new(),
            holdout_fraction: default_holdout_fraction(),
        }
    }
}

/// An ideal sensor's gain, 1.
fn unit_gain() -> f64 {
    1.0
}

/// Identification settings.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IdentifySpec {
    /// Search intervals per law and parameter: `[identify.bounds.lankarani_nikravesh]
    /// stiffness = [1e9, 1e10]`. Parameters not named keep hcm's defaults.
    #[serde(default, deserialize_with = "exact::intervals")]
    pub bounds: BTreeMap<String, BTreeMap<String, [f64; 2]>>,
}

/// One experimental condition: a name (the run-id prefix) and the scenario
/// overrides that make it.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConditionSpec {
    /// Name, used as the prefix of the condition's run ids (`name/007`).
    pub(crate) name: String,
    /// `key=value` overrides, as for `--set`.
    #[serde(default)]
    pub(crate) set: Vec<String>,
}

fn default_relative_tolerance() -> f64 {
    1e-10
}
fn default_absolute_tolerance() -> f64 {
    1e-14
}
fn default_max_step() -> f64 {
    1e-3
}
fn default_max_steps() -> u64 {
    1_000_000
}
fn default_force_noise() -> f64 {
    15.0
}
fn default_holdout_fraction() -> f64 {
    0.1
}

/// Why a scenario could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read, is not text or not TOML, or a key has the wrong
    /// type or is missing.
    #[error("scenario {}: {}", path.display(), input::bounded(message))]
    Syntax {
        /// The scenario file's path.
        path: PathBuf,
        /// What is wrong, as the reader or TOML parser put it.
        message: String,
    },
    /// A `--set` override could not be applied.
    #[error("--set {}: {}", input::shorten(assignment), input::shorten(message))]
    Override {
        /// The override as given (`key=value`).
        assignment: String,
        /// Why it could not be applied.
        message: String,
    },
    /// The scenario parses but does not describe a simulable setup.
    #[error("scenario {}: {}: {}", path.display(), input::shorten(field), input::shorten(message))]
    Invalid {
        /// The scenario file's path.
        path: PathBuf,
        /// The offending key, dotted (`material.steel.poisson_ratio`).
        field: String,
        /// What is wrong with its value.
        message: String,
    },
}

impl Scenario {
    /// Reads a scenario file and applies `key=value` overrides (values in TOML syntax).
    pub fn load(path: &Path, assignments: &[String]) -> Result<Scenario, ScenarioError> {
        let text = input::read_text(path, input::TEXT_LIMIT, "a scenario").map_err(|message| {
            ScenarioError::Syntax {
                path: path.to_owned(),
                message,
            }
        })?;
        Self::parse(path, &text, assignments)
    }

    /// Parses scenario text (`path` names it in errors) and applies overrides.
    pub fn parse(
        path: &Path,
        text: &str,
        assignments: &[String],
    ) -> Result<Scenario, ScenarioError> {
        let syntax = |message: String| ScenarioError::Syntax {
            path: path.to_owned(),
            message,
        };
        let mut document: toml::Table = text
            .parse()
            .map_err(|e: toml::de::Error| syntax(input::toml_error(text, &e)))?;
        let mut scenario: Scenario = if assignments.is_empty() {
            // Straight from the text, so that errors carry line and column.
            toml::from_str(text)
                .map_err(|e: toml::de::Error| syntax(input::toml_error(text, &e)))?
        } else {
            let base = document.clone();
            apply_all(&mut document, assignments)?;
            Self::from_overridden(path, &base, &document, assignments)?
        };
        scenario.source = Source {
            path: path.to_owned(),
            document,
        };
        Ok(scenario)
    }

    /// The file the scenario was read from (or the name its text was given).
    pub fn path(&self) -> &Path {
        &self.source.path
    }

    /// The scenario as TOML text, every override applied: [`Scenario::parse`] of it
    /// (with [`Scenario::path`]) gives this scenario back.
    pub fn to_toml(&self) -> String {
        self.source.document.to_string()
    }

    /// This scenario with more `key=value` overrides applied.
    pub fn with(&self, assignments: &[String]) -> Result<Scenario, ScenarioError> {
        self.with_any(assignments)
    }

    /// This scenario with typed assignments applied (what the library builds).
    pub(crate) fn with_assignments(
        &self,
        assignments: &[Assignment],
    ) -> Result<Scenario, ScenarioError> {
        self.with_any(assignments)
    }

    /// [`Self::with`] for `key=value` texts or typed assignments alike.
    fn with_any<A: IntoAssignment>(&self, assignments: &[A]) -> Result<Scenario, ScenarioError> {
        let mut document = self.source.document.clone();
        apply_all(&mut document, assignments)?;
        let base = &self.source.document;
        let mut scenario = Self::from_overridden(&self.source.path, base, &document, assignments)?;
        scenario.source = Source {
            path: self.source.path.clone(),
            document,
        };
        Ok(scenario)
    }

    /// [`Self::from_document`] for `document`, which is `base` with `assignments`
    /// applied; a failure caused by one assignment alone names its key.
    fn from_overridden<A: IntoAssignment>(
        path: &Path,
        base: &toml::Table,
        document: &toml::Table,
        assignments: &[A],
    ) -> Result<Scenario, ScenarioError> {
        Self::from_document(path, document).map_err(|error| {
            let check = |candidate: &toml::Table| {
                toml::Value::Table(candidate.clone())
                    .try_into::<Scenario>()
                    .map(drop)
                    .map_err(|e| e.message().to_owned())
            };
            overrides::blame(base, assignments, check).unwrap_or(error)
        })
    }

    fn from_document(path: &Path, document: &toml::Table) -> Result<Scenario, ScenarioError> {
        toml::Value::Table(document.clone())
            .try_into()
            .map_err(|e: toml::de::Error| ScenarioError::Syntax {
                path: path.to_owned(),
                message: format!("{} (after the --set overrides)", e.message().trim()),
            })
    }
}

/// Applies `assignments` to `document` in order; the first that fails is the error,
/// quoting it as given.
fn apply_all<A: IntoAssignment>(
    document: &mut toml::Table,
    assignments: &[A],
) -> Result<(), ScenarioError> {
    for given in assignments {
        let assignment = given.assignment()?;
        overrides::apply(document, &assignment).map_err(|error| match error {
            ScenarioError::Override { message, .. } => ScenarioError::Override {
                assignment: given.to_string(),
                message,
            },
            other => other,
        })?;
    }
    Ok(())
}
