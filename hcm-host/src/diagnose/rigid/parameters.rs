//! What a force diagnosis of a rigid contact fits: the base's own free parameters, the
//! effects of the one catalogue (`crate::diagnose::effects`) judged from a wrench on top,
//! and one more kind of candidate only a fitted base can take, another normal law of
//! the core in the model's place (`law: <name>`, every parameter of it fitted, scaled as
//! the base's; one swap, [`Extended::with_law`]).
//!
//! With a fitted base (PM2 from `hcm identify`) the friction's coefficients are free
//! already: a scale or a Coulomb law of them changes nothing the fit cannot, and they
//! are not candidates then ([`crate::diagnose::Effect::within_base_fit`]).

use crate::dataset::Evidence;
use crate::diagnose::{Effect, Scales, Site};
use crate::identify::BoundsOverrides;
use crate::identify::{with_law, RigidParameters};
use crate::numerics::optimize::{Bound, Parameters};
use crate::scenario::Model;
use hcm_core::law::LawKind;
use std::sync::Arc;

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
    pub(crate) effects: Vec<(&'static dyn Effect, Vec<Bound>)>,
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
    pub fn with(&self, effect: &'static dyn Effect, scales: &Scales) -> Extended {
        let mut out = self.clone();
        out.effects
            .push((effect, effect.bounds(Evidence::Wrench, scales)));
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
            all.extend(effect.neutral(model, Site::of(model, self.contact)));
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
            effect.apply(&mut out, Site::of(model, self.contact), mine);
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
