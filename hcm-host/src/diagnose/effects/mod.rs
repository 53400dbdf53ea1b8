//! The one catalogue of what a diagnosis may name: each effect a small change of the
//! model (or of how the data are read) with its own parameters, every one of which has a
//! neutral value that changes nothing. One file per effect, one line in [`CATALOGUE`];
//! each says from which evidence it can be judged ([`Effect::evidence`]).
//!
//! | family | effect | evidence | parameters (box) |
//! |---|---|---|---|
//! | friction | `friction_coefficient`: μ_s, μ_d × s | wrench, poses | s ∈ [0.2, 5] |
//! | friction | `coulomb_friction`: μ_s = μ_d = μ | wrench, poses | μ ∈ [0.01, 1.5] |
//! | friction | `viscous_friction` −c_v·v_t per point | wrench, poses | c_v ∈ [0, F̂/v̂] (wrench), [0, 5·m] (poses) N·s/m |
//! | resistance | `torsional_resistance`, `rolling_resistance` (ω₀ = 0.1 rad/s) | wrench, poses | a ∈ [0, L/2] m |
//! | normal | `viscous_damping` c·δ̇ | line, wrench | c ∈ [0, 10·F̂/δ̇̂] N·s/m |
//! | normal | `hysteresis_damping` c·δⁿ·δ̇ | line, wrench | c ∈ [0, 10·F̂/(δ̂ⁿ·δ̇̂)] |
//! | normal | `stiffness_exponent` n → n + Δ | line | – |
//! | normal | `adhesion` −a in contact | line, wrench | a ∈ [0, F̂/2] N |
//! | normal | `plasticity` ρ·δ_max on unloading | line, wrench | ρ ∈ [0, 0.9] |
//! | normal | `speed_dependent_restitution` χ·k·δⁿ·δ̇ | poses | χ ∈ [0, 3] s/m |
//! | measurement | `force_gain`: the sensor reads g × the wrench | wrench | g ∈ [0.5, 2] |
//! | measurement | `force_offset`: the sensor reads F + b | line, wrench | b ∈ [−F̂/10, F̂/10]³ N |
//! | measurement | `sensor_delay`: the sensor reads the force at t − τ | line, wrench | τ ∈ [0, 20·Δt] s |
//! | measurement | `sensor_filter`: a first-order low-pass of time constant T | line | T ∈ [0, 20·Δt] s |
//! | measurement | `table_offset`, `table_tilt`: the fixed surface moved or tilted | poses | Δz ∈ ±L/20 m; ±0.05 rad |
//! | measurement | `length_scale`: the tracker's lengths × s | poses | s ∈ [0.9, 1.1] |
//! | body | `inertia_scale`: the inertia tensor × k | poses | k ∈ [0.5, 2] |
//! | body | `edge_rounding`: a box's edges rounded to r | poses | r ∈ [0, L/5] m |
//! | joint | `joint_viscous_friction` −c·θ̇ in every joint | poses | c ∈ [0, 4·I·ω̂] N·m·s/rad |
//! | joint | `joint_coulomb_friction` τ_c, STEP-smoothed | poses | τ_c ∈ [0, 2·τ̂] N·m |
//! | joint | `joint_stiffness` −k·(θ − θ₀) | poses | k ∈ [0, 4·τ̂] N·m/rad |
//! | joint | `joint_offset`: the joint's point on the child moved along its lever | poses | d ∈ ±L/5 m |
//! | chance | `contact_scatter`: stiffness, damping, friction × (1 + σ·ζ) per run | poses | σ ∈ [0, 0.6] |
//! | chance | `start_uncertainty`: the start state's fit σ × k | poses | k ∈ [0, 2.2] |
//! | chance | `fixed_height`, `fixed_tilt`: the fixed body moved or tilted by σ·ζ per run | poses | σ ∈ [0, min(L/20, h̄)] m; [0, min(0.05, θ̄)] rad |
//!
//! F̂ the largest measured normal force, v̂ and δ̇̂ the fastest slip and approach of a
//! point, δ̂ the deepest, L the largest lever arm of a point about the moving body's
//! centre (poses: the body's largest half extent), θ̄ and h̄ the largest RMS tilt and
//! height change per run a body resting at the end of its recordings shows beyond the
//! tracker's noise, m the body's mass, Δt the median sample interval, I, τ̂ and ω̂ the
//! (first) joint's child's inertia about it, its weight's torque about it and its
//! pendulum rate ([`crate::scenario::JointScales`]): every box from the data ([`Scales`]), none from an example. On a line of
//! force (1D) an effect is judged through its linear column at small strength
//! ([`Effect::column`], the fast pre-ranking of `select`).

mod chance;
mod coulomb_friction;
mod edge_rounding;
mod force_gain;
mod force_offset;
mod friction_coefficient;
mod inertia_scale;
mod joint;
mod law_term;
mod length_scale;
mod resistance;
mod sensor_lag;
mod speed_dependent_restitution;
mod stiffness_exponent;
mod table;
mod viscous_friction;

use super::{Candidate, Family};
use crate::dataset::{Dataset, Evidence};
use crate::identify::{ContactScales, RecordedContact};
use crate::numerics::optimize::Bound;
use crate::scenario::Model;

/// Where an effect acts: a contact of the model and the body it is judged against
/// (the fixed partner of a replayed body; for force data the contact's second body).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Site {
    /// Index of the contact.
    pub contact: usize,
    /// Index of the partner's body.
    pub partner: usize,
}

impl Site {
    /// Contact `contact` of `model`, judged against its fixed body (body 2 if neither
    /// or both are fixed).
    pub fn of(model: &Model, contact: usize) -> Site {
        let c = &model.contacts[contact];
        let partner = if model.bodies[c.body_1].fixed && !model.bodies[c.body_2].fixed {
            c.body_1
        } else {
            c.body_2
        };
        Site { contact, partner }
    }
}

/// What the data say about the size of things, for the boxes effects are searched in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scales {
    /// The contact's force, rate and depth scales (force evidence; zero from poses).
    pub contact: ContactScales,
    /// Fastest slip of a point (m/s).
    pub slip: f64,
    /// Largest lever arm of a point about the moving body's centre (m); from poses the
    /// body's largest half extent.
    pub arm: f64,
    /// Median interval between samples (s).
    pub interval: f64,
    /// The law's elastic exponent (–).
    pub exponent: f64,
    /// The moving body's mass (kg); NaN from force evidence, where no box needs it.
    pub mass: f64,
    /// The largest RMS tilt (rad) a per-run tilt of the fixed body could have, as a box
    /// resting at the end of its recordings shows it beyond the tracker's noise
    /// (`diagnose::motion::rest`). NaN where none is known (no box, none at rest, force
    /// evidence).
    pub rest_tilt: f64,
    /// The largest RMS height change (m) a per-run move of the fixed body could have, as
    /// the body's centre resting at the end of its recordings shows it beyond the
    /// tracker's noise. NaN where none is known.
    pub rest_height: f64,
    /// The (first) joint's scales, where the model has joints (the joint effects'
    /// boxes).
    pub joint: Option<crate::scenario::JointScales>,
}

impl Scales {
    /// The scales of a recorded contact with the law's exponent `exponent` (–).
    pub fn of(recorded: &RecordedContact, exponent: f64) -> Scales {
        let (mut slip, mut arm) = (0.0_f64, 0.0_f64);
        for sample in &recorded.samples {
            for p in sample.points.iter() {
                let n = p.normal;
                let v = p.relative_velocity - n * p.relative_velocity.dot(&n);
                slip = slip.max(v.norm());
                let centre = &sample.references[usize::from(!recorded.mover_is_1())];
                arm = arm.max((p.position - centre).norm());
            }
        }
        let mut gaps: Vec<f64> = (recorded.samples.windows(2))
            .filter(|w| w[0].run == w[1].run)
            .map(|w| w[1].time - w[0].time)
            .filter(|d| *d > 0.0)
            .collect();
        gaps.sort_by(f64::total_cmp);
        Scales {
            contact: ContactScales::of(recorded, exponent),
            slip,
            arm,
            interval: gaps.get(gaps.len() / 2).copied().unwrap_or(0.0),
            exponent,
            mass: f64::NAN,
            rest_tilt: f64::NAN,
            rest_height: f64::NAN,
            joint: None,
        }
    }

    /// The scales of a replayed body of mass `mass` (kg) and largest half extent `size`
    /// (m): poses say nothing of forces.
    pub fn of_body(mass: f64, size: f64) -> Scales {
        let zero = ContactScales {
            stiffness: f64::NAN,
            peak_force: 0.0,
            peak_rate: 0.0,
            peak_depth: 0.0,
        };
        Scales {
            contact: zero,
            slip: 0.0,
            arm: size,
            interval: 0.0,
            exponent: f64::NAN,
            mass,
            rest_tilt: f64::NAN,
            rest_height: f64::NAN,
            joint: None,
        }
    }
}

/// One effect a diagnosis may name. Adding one: a file in this folder implementing this
/// trait, and its line in [`CATALOGUE`] (or, for a caller's own effect, a
/// [`Catalogue::with`]).
pub trait Effect: std::fmt::Debug + Sync + Send {
    /// The name a report prints (snake case).
    fn name(&self) -> &'static str;
    /// What part of the model (or of the measurement) it changes.
    fn family(&self) -> Family;
    /// Whether it can be judged from `evidence`.
    fn evidence(&self, evidence: Evidence) -> bool;
    /// Whether it changes `model` at `site` at all (a coefficient needs a friction law,
    /// an added law term room among the law's effects, …).
    fn applies(&self, _model: &Model, _site: Site) -> bool {
        true
    }
    /// Whether a fit of the base model's own parameters already frees this change (it
    /// is then a better optimum of the base, not a cause, on a fitted base).
    fn within_base_fit(&self, _model: &Model, _site: Site) -> bool {
        false
    }
    /// The box its parameters are searched in, from `scales`, for `evidence`.
    fn bounds(&self, evidence: Evidence, scales: &Scales) -> Vec<Bound>;
    /// Whether it is chance: a spread from run to run, judged by the proper score of
    /// the ensemble it makes (`Family::Chance`), after the deterministic effects.
    fn stochastic(&self) -> bool {
        false
    }
    /// The parameters that change nothing.
    fn neutral(&self, _model: &Model, _site: Site) -> Vec<f64> {
        vec![0.0]
    }
    /// `model` with the change `values` stand for at `site`.
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]);
    /// Whether it changes the site's contact or its moving body, so that on a scene
    /// whose contacts are alike (a mechanism's links on one table) [`apply_at`] makes
    /// it on each of them; false for a change of the partner, the joints or the whole
    /// model, made once.
    fn per_contact(&self) -> bool {
        true
    }
    /// The data as the effect reads them (a tracker's length scale); `None`: as recorded.
    fn read(&self, _data: &Dataset, _values: &[f64]) -> Option<Dataset> {
        None
    }
    /// Its column in the linear model of a 1D force residual (`None`: not judged on a
    /// line of force).
    fn column(&self) -> Option<Candidate> {
        None
    }
}

/// Every built-in effect, in the order a report lists it.
pub static CATALOGUE: [&dyn Effect; 24] = [
    &friction_coefficient::FrictionCoefficient,
    &coulomb_friction::CoulombFriction,
    &viscous_friction::ViscousFriction,
    &resistance::TORSIONAL,
    &resistance::ROLLING,
    &law_term::VISCOUS_DAMPING,
    &law_term::HYSTERESIS_DAMPING,
    &stiffness_exponent::StiffnessExponent,
    &law_term::ADHESION,
    &law_term::PLASTICITY,
    &force_gain::ForceGain,
    &force_offset::ForceOffset,
    &sensor_lag::DELAY,
    &sensor_lag::FILTER,
    &speed_dependent_restitution::SpeedDependentRestitution,
    &table::OFFSET,
    &table::TILT,
    &length_scale::LengthScale,
    &inertia_scale::InertiaScale,
    &edge_rounding::EdgeRounding,
    &joint::VISCOUS,
    &joint::COULOMB,
    &joint::STIFFNESS,
    &joint::JointOffset,
];

/// The chances a diagnosis from poses tries when asked ([`Catalogue::with_chance`]):
/// on poses without true run-to-run variation a spread still covers a deterministic
/// misfit the fit left (measured: a fitted ball's 0.5 % + ° residual "named" a table
/// height scattering by 0.25 mm), so chance is a question the user asks, not a
/// default.
pub static CHANCES: [&dyn Effect; 4] = [
    &chance::CONTACT_SCATTER,
    &chance::START_UNCERTAINTY,
    &chance::FIXED_HEIGHT,
    &chance::FIXED_TILT,
];

/// The effects one diagnosis tries: the built-in [`CATALOGUE`] unless a caller adds its
/// own or leaves some out.
#[derive(Clone, Debug)]
pub struct Catalogue(Vec<&'static dyn Effect>);

impl Default for Catalogue {
    fn default() -> Catalogue {
        Catalogue(CATALOGUE.to_vec())
    }
}

impl Catalogue {
    /// This catalogue and `effect`, listed last.
    pub fn with(mut self, effect: &'static dyn Effect) -> Catalogue {
        self.0.push(effect);
        self
    }

    /// This catalogue and the [`CHANCES`], listed last.
    pub fn with_chance(mut self) -> Catalogue {
        self.0.extend(CHANCES);
        self
    }

    /// This catalogue with only the effects `keep` keeps.
    pub fn retain(mut self, keep: impl Fn(&dyn Effect) -> bool) -> Catalogue {
        self.0.retain(|e| keep(*e));
        self
    }

    /// The effects judged from `evidence`, in order.
    pub fn for_evidence(
        &self,
        evidence: Evidence,
    ) -> impl Iterator<Item = &'static dyn Effect> + '_ {
        self.0.iter().copied().filter(move |e| e.evidence(evidence))
    }
}

/// `effect` with `values` made on `model` at `site`: on every contact alike with the
/// site's ([`Model::alike_contacts`]) where it changes a contact or its body
/// ([`Effect::per_contact`]), once otherwise. A lone body's contact is alike only with
/// itself: then the same as [`Effect::apply`].
pub fn apply_at(effect: &dyn Effect, model: &mut Model, site: Site, values: &[f64]) {
    if !effect.per_contact() {
        return effect.apply(model, site, values);
    }
    for contact in model.alike_contacts(site.contact) {
        let at = Site { contact, ..site };
        effect.apply(model, at, values);
    }
}

/// Rotation rate (rad/s) below which the resistance couples fade: slow against a
/// tumbling cube (rad/s to tens of rad/s), fast against a body at rest.
const RESISTANCE_RATE: f64 = 0.1;

/// The first of `values` (0 if none).
fn first(values: &[f64]) -> f64 {
    values.first().copied().unwrap_or(0.0)
}

/// Whether `model`'s `contact` law has room for one more effect term.
fn has_room(model: &Model, site: Site) -> bool {
    !model.contacts[site.contact].model.normal.effects.is_full()
}
