//! What a force diagnosis of a rigid contact may name (the 3D catalogue): each
//! candidate a small change of the model with its own parameters, every one of which
//! has a neutral value that changes nothing, fitted to the wrench at the recorded
//! poses together with the model's own free parameters.
//!
//! | family | effect | parameters (box) |
//! |---|---|---|
//! | friction | `friction_coefficient`: μ_s, μ_d × s | s ∈ [0.2, 5] |
//! | friction | `coulomb_friction`: μ_s = μ_d = μ | μ ∈ [0.01, 1.5] |
//! | friction | `viscous_friction` −c_v·v_t per point | c_v ∈ [0, F̂/v̂] N·s/m |
//! | resistance | `torsional_resistance`, `rolling_resistance` (ω₀ = 0.1 rad/s) | a ∈ [0, L/2] m |
//! | normal | `viscous_damping` c·δ̇ | c ∈ [0, 10·F̂/δ̇̂] N·s/m |
//! | normal | `hysteresis_damping` c·δⁿ·δ̇, n the law's exponent (Hunt–Crossley's damping; Lankarani–Nikravesh's at one approach speed) | c ∈ [0, 10·F̂/(δ̂ⁿ·δ̇̂)] |
//! | normal | `adhesion` −a in contact | a ∈ [0, F̂/2] N |
//! | normal | `plasticity` ρ·δ_max on unloading | ρ ∈ [0, 0.9] |
//! | normal law | `law: <name>`: another law of the core in the model's place, every parameter of it fitted ([`Extended::with_law`]; a fitted base only, one swap) | the law's boxes, scaled as the base's |
//! | measurement | `force_gain`: the sensor reads g × the wrench | g ∈ [0.5, 2] |
//! | measurement | `force_offset`: the sensor reads F + b | b ∈ [−F̂/10, F̂/10]³ N |
//! | measurement | `sensor_delay`: the sensor reads the wrench at t − τ | τ ∈ [0, 20·Δt] s |
//!
//! F̂ the largest measured normal force, v̂ and δ̇̂ the fastest slip and approach of a
//! point, δ̂ the deepest, L the largest lever arm of a point about the moving body's centre, Δt the
//! median sample interval: every box from the data ([`Scales`]), none from an example.
//!
//! With a fitted base (PM2 from `hcm identify`) the friction's coefficients are free
//! already: a scale or a Coulomb law of them changes nothing the fit cannot, and they
//! are not candidates then.

use super::super::Family;
use crate::identify::BoundsOverrides;
use crate::identify::{with_law, ContactScales, RecordedContact, RigidParameters};
use crate::numerics::optimize::{Bound, Parameters};
use crate::scenario::Model;
use hcm_core::effect::{Adhesion, ContactEffect, HysteresisDamping, Plasticity, ViscousDamping};
use hcm_core::friction::{RollingResistance, TorsionalResistance, ViscousFriction};
use hcm_core::law::LawKind;
use std::sync::Arc;

/// Rotation rate (rad/s) below which the resistance couples fade.
const RESISTANCE_RATE: f64 = 0.1;

/// One candidate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ForceEffect {
    /// Both friction coefficients μ_s, μ_d scaled by s (–), s ∈ [0.2, 5].
    FrictionCoefficient,
    /// A Coulomb law: μ_s = μ_d = μ (–), μ ∈ [0.01, 1.5].
    CoulombFriction,
    /// Viscous friction −c_v·v_t per touching point, c_v (N·s/m) ∈ [0, F̂/v̂].
    ViscousFriction,
    /// A couple against the spin about the normal, lever arm a (m) ∈ [0, L/2].
    TorsionalResistance,
    /// A couple against rolling, lever arm a (m) ∈ [0, L/2].
    RollingResistance,
    /// Viscous damping c·δ̇ added to the normal law, c (N·s/m) ∈ [0, 10·F̂/δ̇̂].
    ViscousDamping,
    /// Hysteresis damping c·δⁿ·δ̇ added to the normal law, n the law's exponent
    /// (Hunt–Crossley's damping), c ∈ [0, 10·F̂/(δ̂ⁿ·δ̇̂)].
    HysteresisDamping,
    /// A constant pull-off force −a while in contact, a (N) ∈ [0, F̂/2].
    Adhesion,
    /// Permanent indentation ρ·δ_max on unloading, ρ (–) ∈ [0, 0.9].
    Plasticity,
    /// The sensor reads g × the wrench, g (–) ∈ [0.5, 2].
    ForceGain,
    /// The sensor reads F + b, b (N) ∈ [−F̂/10, F̂/10]³.
    ForceOffset,
    /// The sensor reads the wrench at t − τ, τ (s) ∈ [0, 20·Δt].
    SensorDelay,
}

/// What the data say about the sizes the boxes are scaled by.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scales {
    /// The contact's scales (peak force (N), depth (m), approach (m/s)).
    pub contact: ContactScales,
    /// Fastest slip of a touching point (m/s).
    pub slip: f64,
    /// Largest lever arm of a touching point about the moving body's centre (m).
    pub arm: f64,
    /// Median interval between a run's rows (s).
    pub interval: f64,
    /// The law's elastic exponent n (–): hysteresis damping's depth exponent.
    pub exponent: f64,
}

impl Scales {
    /// The scales of `recorded` (law exponent `exponent`).
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
        }
    }
}

impl ForceEffect {
    /// The catalogue, in report order.
    pub const ALL: [ForceEffect; 12] = [
        ForceEffect::FrictionCoefficient,
        ForceEffect::CoulombFriction,
        ForceEffect::ViscousFriction,
        ForceEffect::TorsionalResistance,
        ForceEffect::RollingResistance,
        ForceEffect::ViscousDamping,
        ForceEffect::HysteresisDamping,
        ForceEffect::Adhesion,
        ForceEffect::Plasticity,
        ForceEffect::ForceGain,
        ForceEffect::ForceOffset,
        ForceEffect::SensorDelay,
    ];

    /// Its catalogue name.
    pub fn name(self) -> &'static str {
        match self {
            ForceEffect::FrictionCoefficient => "friction_coefficient",
            ForceEffect::CoulombFriction => "coulomb_friction",
            ForceEffect::ViscousFriction => "viscous_friction",
            ForceEffect::TorsionalResistance => "torsional_resistance",
            ForceEffect::RollingResistance => "rolling_resistance",
            ForceEffect::ViscousDamping => "viscous_damping",
            ForceEffect::HysteresisDamping => "hysteresis_damping",
            ForceEffect::Adhesion => "adhesion",
            ForceEffect::Plasticity => "plasticity",
            ForceEffect::ForceGain => "force_gain",
            ForceEffect::ForceOffset => "force_offset",
            ForceEffect::SensorDelay => "sensor_delay",
        }
    }

    /// Its family.
    pub fn family(self) -> Family {
        match self {
            ForceEffect::FrictionCoefficient
            | ForceEffect::CoulombFriction
            | ForceEffect::ViscousFriction => Family::Friction,
            ForceEffect::TorsionalResistance | ForceEffect::RollingResistance => Family::Resistance,
            ForceEffect::ViscousDamping
            | ForceEffect::HysteresisDamping
            | ForceEffect::Adhesion
            | ForceEffect::Plasticity => Family::Normal,
            ForceEffect::ForceGain | ForceEffect::ForceOffset | ForceEffect::SensorDelay => {
                Family::Measurement
            }
        }
    }

    /// Whether it can change contact `c` of `model` beyond what the base's own free
    /// parameters do (`fitted_base`): friction candidates need friction, and rescale
    /// nothing a fitted base does not; a normal effect needs room in the law's list.
    pub fn applies(self, model: &Model, c: usize, fitted_base: bool) -> bool {
        let physics = &model.contacts[c].model;
        let friction = physics.friction;
        match self {
            ForceEffect::FrictionCoefficient => friction.is_some() && !fitted_base,
            ForceEffect::CoulombFriction => {
                !fitted_base
                    && friction.is_some_and(|f| f.static_coefficient != f.dynamic_coefficient)
            }
            ForceEffect::ViscousDamping
            | ForceEffect::HysteresisDamping
            | ForceEffect::Adhesion
            | ForceEffect::Plasticity => !physics.normal.effects.is_full(),
            _ => true,
        }
    }

    /// The box of its parameters, scaled by the data (see the module docs).
    pub fn bounds(self, s: &Scales) -> Vec<Bound> {
        let linear = |name: &str, lower: f64, upper: f64| Bound::linear(name, lower, upper);
        let force = s.contact.peak_force.max(f64::MIN_POSITIVE);
        let per = |speed: f64| force / speed.max(1e-6);
        match self {
            ForceEffect::FrictionCoefficient => vec![Bound {
                log_scale: true,
                ..linear("scale", 0.2, 5.0)
            }],
            ForceEffect::CoulombFriction => vec![linear("mu", 0.01, 1.5)],
            ForceEffect::ViscousFriction => vec![linear("coefficient", 0.0, per(s.slip))],
            ForceEffect::TorsionalResistance | ForceEffect::RollingResistance => {
                vec![linear("arm", 0.0, 0.5 * s.arm.max(1e-6))]
            }
            ForceEffect::ViscousDamping => {
                vec![linear("coefficient", 0.0, 10.0 * per(s.contact.peak_rate))]
            }
            ForceEffect::HysteresisDamping => {
                let depth = s.contact.peak_depth.max(f64::MIN_POSITIVE).powf(s.exponent);
                vec![linear(
                    "coefficient",
                    0.0,
                    10.0 * per(s.contact.peak_rate) / depth,
                )]
            }
            ForceEffect::Adhesion => vec![linear("pull_off_force", 0.0, 0.5 * force)],
            ForceEffect::Plasticity => vec![linear("permanent_ratio", 0.0, 0.9)],
            ForceEffect::ForceGain => vec![linear("gain", 0.5, 2.0)],
            ForceEffect::ForceOffset => ["x", "y", "z"]
                .iter()
                .map(|a| linear(&format!("offset_{a}"), -0.1 * force, 0.1 * force))
                .collect(),
            ForceEffect::SensorDelay => {
                vec![linear("delay", 0.0, 20.0 * s.interval.max(1e-7))]
            }
        }
    }

    /// The parameters that change nothing (Coulomb's: the model's μ_d).
    pub fn neutral(self, model: &Model, c: usize) -> Vec<f64> {
        let friction = model.contacts[c].model.friction;
        match self {
            ForceEffect::FrictionCoefficient | ForceEffect::ForceGain => vec![1.0],
            ForceEffect::CoulombFriction => {
                vec![friction.map_or(0.1, |f| f.dynamic_coefficient)]
            }
            ForceEffect::ForceOffset => vec![0.0; 3],
            _ => vec![0.0],
        }
    }

    /// `model` with the change `values` stand for at contact `c`.
    pub fn apply(self, model: &mut Model, c: usize, values: &[f64]) {
        let first = values.first().copied().unwrap_or(0.0);
        let physics = &mut model.contacts[c].model;
        let push = |physics: &mut hcm_core::model::ContactModel<f64, _>, e| {
            // `applies` checked the room: a full list leaves the model as it is.
            let _ = physics.normal.effects.push(e);
        };
        match self {
            ForceEffect::FrictionCoefficient => {
                if let Some(f) = physics.friction.as_mut() {
                    f.static_coefficient *= first;
                    f.dynamic_coefficient *= first;
                }
            }
            ForceEffect::CoulombFriction => {
                if let Some(f) = physics.friction.as_mut() {
                    (f.static_coefficient, f.dynamic_coefficient) = (first, first);
                }
            }
            ForceEffect::ViscousFriction => {
                physics.tangential.viscous_friction = Some(ViscousFriction { coefficient: first });
            }
            ForceEffect::TorsionalResistance => {
                physics.tangential.torsional_resistance = Some(TorsionalResistance {
                    arm: first,
                    spin_rate: RESISTANCE_RATE,
                });
            }
            ForceEffect::RollingResistance => {
                physics.tangential.rolling_resistance = Some(RollingResistance {
                    arm: first,
                    roll_rate: RESISTANCE_RATE,
                });
            }
            ForceEffect::ViscousDamping => push(
                physics,
                ContactEffect::ViscousDamping(ViscousDamping { coefficient: first }),
            ),
            ForceEffect::HysteresisDamping => {
                // Hunt–Crossley's damping c·δ^n·δ̇, n the law's own exponent.
                let exponent = physics.normal.base.get("exponent").unwrap_or(1.5);
                push(
                    physics,
                    ContactEffect::HysteresisDamping(HysteresisDamping {
                        coefficient: first,
                        exponent,
                    }),
                )
            }
            ForceEffect::Adhesion => push(
                physics,
                ContactEffect::Adhesion(Adhesion {
                    pull_off_force: first,
                }),
            ),
            ForceEffect::Plasticity => push(
                physics,
                ContactEffect::Plasticity(Plasticity {
                    permanent_ratio: first,
                }),
            ),
            ForceEffect::ForceGain => model.scenario.experiment.force_gain = first,
            ForceEffect::ForceOffset => {
                let b = &mut model.scenario.experiment.force_offset;
                for (k, v) in b.iter_mut().enumerate() {
                    *v = values.get(k).copied().unwrap_or(0.0);
                }
            }
            ForceEffect::SensorDelay => model.scenario.experiment.sensor_delay = first,
        }
    }
}

/// Another normal law in place of the model's: the normal-law family's candidates.
#[derive(Clone, Debug)]
pub struct LawSwap {
    /// The diagnosed model with that law installed, at its start values (the
    /// parameters it shares with the model's law kept).
    pub(crate) model: Arc<Model>,
}

/// The candidate name of the law `kind` in place of the model's (`law: <name>`).
pub fn law_label(kind: LawKind) -> &'static str {
    match kind {
        LawKind::Hertz => "law: hertz",
        LawKind::LankaraniNikravesh => "law: lankarani_nikravesh",
        LawKind::VariableStiffness => "law: variable_stiffness",
        LawKind::Impact => "law: impact",
        LawKind::HuntCrossley => "law: hunt_crossley",
        LawKind::Flores => "law: flores",
    }
}

/// The base's free parameters (none for a given base) and the effects on top, as one
/// parameter vector: the base's genes, then each effect's.
#[derive(Clone, Debug)]
pub struct Extended {
    /// The base's free parameters, when the base is fitted.
    pub(crate) base: Option<RigidParameters>,
    /// The contact.
    pub(crate) contact: usize,
    /// Each effect with its box.
    pub(crate) effects: Vec<(ForceEffect, Vec<Bound>)>,
    /// Another law in place of the model's, its parameters the base's genes.
    pub(crate) law: Option<LawSwap>,
}

impl Extended {
    /// The model the genes apply to: `model`, or the law swap's.
    fn start<'a>(&'a self, model: &'a Model) -> &'a Model {
        self.law.as_ref().map_or(model, |l| l.model.as_ref())
    }

    /// `self` with `kind` in place of `model`'s law — its parameters, exponent
    /// included, fitted in the base's place (boxes scaled by `scales` as the base's
    /// were) — or `None`: a given base (nothing of the law is fitted), or a law that
    /// cannot stand in (its parameters need what the scenario does not give).
    pub fn with_law(
        &self,
        model: &Model,
        kind: LawKind,
        overrides: &BoundsOverrides,
        scales: &Scales,
    ) -> Option<Extended> {
        self.base.as_ref()?;
        let c = self.contact;
        let swapped = with_law(self.start(model), c, kind.name(), None).ok()?;
        let mut base = RigidParameters::new(&swapped, c, overrides)
            .ok()?
            .with_exponent(&swapped, overrides)
            .ok()?;
        scales.contact.apply(&swapped, c, &mut base);
        swapped.contacts[c].model.validate().ok()?;
        Some(Extended {
            base: Some(base),
            contact: c,
            effects: self.effects.clone(),
            law: Some(LawSwap {
                model: Arc::new(swapped),
            }),
        })
    }

    /// The base's gene count.
    fn base_len(&self) -> usize {
        self.base.as_ref().map_or(0, |b| b.bounds().len())
    }

    /// `self` with `effect` added (its box from `scales`).
    pub fn with(&self, effect: ForceEffect, scales: &Scales) -> Extended {
        let mut out = self.clone();
        out.effects.push((effect, effect.bounds(scales)));
        out
    }
}

impl Parameters for Extended {
    type Target = Model;

    fn bounds(&self) -> Vec<Bound> {
        let mut all = self.base.as_ref().map_or_else(Vec::new, |b| b.bounds());
        all.extend(self.effects.iter().flat_map(|(_, b)| b.iter().cloned()));
        all
    }

    /// The base's values, then each effect's neutral ones.
    fn values(&self, model: &Model) -> Vec<f64> {
        let model = self.start(model);
        let mut all = self
            .base
            .as_ref()
            .map_or_else(Vec::new, |b| b.values(model));
        for (effect, _) in &self.effects {
            all.extend(effect.neutral(model, self.contact));
        }
        all
    }

    fn apply(&self, model: &Model, genes: &[f64]) -> Model {
        let model = self.start(model);
        let split = self.base_len().min(genes.len());
        let (base, mut rest) = genes.split_at(split);
        let mut out = match &self.base {
            Some(b) => b.apply(model, base),
            None => model.clone(),
        };
        for (effect, bounds) in &self.effects {
            let (mine, others) = rest.split_at(bounds.len().min(rest.len()));
            effect.apply(&mut out, self.contact, mine);
            rest = others;
        }
        out
    }

    fn named(&self, genes: &[f64]) -> Vec<(String, f64)> {
        let split = self.base_len().min(genes.len());
        let (base, mut rest) = genes.split_at(split);
        let mut out = self.base.as_ref().map_or_else(Vec::new, |b| b.named(base));
        for (effect, bounds) in &self.effects {
            let (mine, others) = rest.split_at(bounds.len().min(rest.len()));
            for (b, v) in bounds.iter().zip(mine) {
                out.push((format!("{}.{}", effect.name(), b.name), *v));
            }
            rest = others;
        }
        out
    }
}
