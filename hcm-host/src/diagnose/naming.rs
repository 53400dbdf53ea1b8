//! Which causes a diagnosis names: nonlinear forward selection over full re-fits, and
//! a name only for causes that leave nothing but noise.
//!
//! The linear stepwise selection ([`super::select::select`]) ranks the catalogue by a
//! first-order column per effect: quick, and right while the effect is small beside the
//! force. It is wrong for large ones — a 10 µs sensor delay on a 110 µs contact is not
//! −τ·df/dt, and its linear column resembles a stiffness-exponent change more than
//! itself. So the decision is taken on the real model: at each step every catalogued
//! effect not yet chosen is added to the chosen ones and the whole extended model is
//! re-fitted ([`refit`], Levenberg–Marquardt with the base law's own parameters); the
//! one with the lowest information criterion (RSS/σ² + ln(n) per parameter) enters if
//! 1. its RSS drop passes the information criterion with the measured noise σ:
//!    ΔRSS/σ² > ln(n) per added parameter (BIC), and
//! 2. its parameters are determined by the data: every 95 % interval is finite (a
//!    singular covariance means the data cannot tell its strength, so it is not named),
//!    and
//! 3. the data tell it from every other cause: the best trial of another family scores
//!    worse by at least [`EVIDENCE`]. Else the steps stop, the answer names neither
//!    ("ambiguous") and both are reported as not accepted; the better one stays in the
//!    extended model as a provisional term, which predicts what either would (at 1 %
//!    of the peak a stiffness-exponent change and an adhesion fit a ball's contacts
//!    within 0.3 of each other's criterion).
//!
//! Within a family the simpler member is preferred unless the other beats it by the
//! same [`EVIDENCE`]: hysteresis damping's exponent p must earn its place over viscous
//! damping (p = 0) as a rival family would. Motion reconstructed from a few camera
//! frames blurs each run's touch-down by a µm or so, which a small p mimics (the filmed
//! rig of tests/diagnose_rig.rs: p = 0.086 by 6.5 in the criterion).
//!
//! A backward pass then drops any effect the later ones made redundant (its removal
//! costs less than the criterion). Steps stop when the residual left is
//! indistinguishable from noise ([`structure`]'s
//! χ² tests) or no effect passes. Then the rule that keeps a diagnosis from naming the
//! nearest wrong cause: **if the residual is still structured, nothing is named** — the
//! answer is "unexplained", and the effects that entered are reported as not accepted,
//! with why. An effect that explains only part of a shape it does not have is not the
//! cause. This replaces the fixed 2 % share the linear selection required of each
//! effect: a small effect that leaves white noise behind is named however small its
//! share, and one that leaves structure is not named however large.
//!
//! [`structure`]: super::structure::residual_structure

use super::catalogue::{Candidate, CATALOGUE};
use super::select::{parameters, refit, Fitted, Refit};
use super::structure::{residual_structure, Structure};
use super::ContactSamples;
use hcm_core::effect::ExtendedLaw;
use rayon::prelude::*;
use serde::Serialize;

/// Most causes named together.
pub const MAX_CAUSES: usize = 3;

/// Starting exponents p of a hysteresis-damping trial (its re-fit moves p freely in
/// [0, 4]; two starts keep it out of the other's local minimum).
const HYSTERESIS_STARTS: [f64; 2] = [0.5, 1.5];

/// One effect tried at one step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Trial {
    /// Catalogue name.
    pub effect: &'static str,
    /// RSS of the re-fitted model without and with it (N²).
    pub rss: (f64, f64),
    /// ΔRSS/σ² and its threshold ln(n)·(parameters added).
    pub bic: (f64, f64),
    /// Whether every interval of its parameters is finite.
    pub determined: bool,
    /// Whether it entered.
    pub accepted: bool,
}

/// A cause considered and not named, with the reason.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NotAccepted {
    /// Catalogue name.
    pub effect: &'static str,
    /// Its parameters as fitted.
    pub parameters: Vec<Fitted>,
    /// Why it is not named.
    pub reason: String,
}

/// The decision.
#[derive(Clone, Debug)]
pub struct Naming {
    /// The named causes (in order of entry) with their shapes; empty for "none" and for
    /// "unexplained".
    pub chosen: Vec<(Candidate, f64)>,
    /// The re-fit of the base law with the named causes (the base alone if none).
    pub fit: Refit,
    /// The best trial of every step (the last one rejected, unless the steps stopped
    /// because the residual was explained).
    pub steps: Vec<Trial>,
    /// Causes that entered but are not named, and the best rejected trial.
    pub not_accepted: Vec<NotAccepted>,
    /// The residual of `fit`.
    pub after: Structure,
    /// Whether structure is left that no named cause explains.
    pub unexplained: bool,
    /// Two causes the data cannot tell apart (empty otherwise): neither is named; the
    /// better one stays in `fit` as a provisional term, so that the extended model still
    /// predicts what both would, without claiming which it is.
    pub ambiguous: Vec<&'static str>,
    /// That provisional term.
    pub provisional: Option<(Candidate, f64)>,
}

/// How much lower a cause's information criterion must be than that of the best cause
/// of another family for the data to tell them apart (–): a difference above 10 is
/// "very strong" evidence on the scale of Kass & Raftery (1995, *Bayes factors*, JASA
/// 90), a posterior odds of about 150 : 1.
pub const EVIDENCE: f64 = 10.0;

/// Whether two effects are one family, where naming either names the same physics:
/// viscous damping is hysteresis damping with p = 0.
fn same_family(a: Candidate, b: Candidate) -> bool {
    let damping =
        |c: Candidate| matches!(c, Candidate::ViscousDamping | Candidate::HysteresisDamping);
    a == b || (damping(a) && damping(b))
}

/// Every (effect, start shape) the catalogue offers for one trial.
fn options(chosen: &[(Candidate, f64)]) -> Vec<(Candidate, f64)> {
    CATALOGUE
        .iter()
        .filter(|c| !chosen.iter().any(|(d, _)| d == *c))
        .flat_map(|&c| match c {
            Candidate::HysteresisDamping => HYSTERESIS_STARTS.iter().map(|&p| (c, p)).collect(),
            _ => vec![(c, f64::NAN)],
        })
        .collect()
}

/// The re-fit's last cause has every interval finite.
fn determined(fit: &Refit) -> bool {
    fit.causes.last().is_some_and(|cause| {
        cause
            .parameters
            .iter()
            .all(|p| p.ci.0.is_finite() && p.ci.1.is_finite())
    })
}

/// The residual structure the sensor-corrected prediction of `fit` leaves.
fn structure_of(samples: &ContactSamples, fit: &Refit, sigma: f64) -> Structure {
    residual_structure(samples, &fit.sensor.reads(samples, &fit.law), sigma)
}

/// Names the causes of `measured − base` on `samples` (noise σ in N); see the module
/// documentation. Deterministic: trials are re-fitted in parallel but compared in
/// catalogue order.
pub fn name_causes(samples: &ContactSamples, base: &ExtendedLaw<f64>, sigma: f64) -> Naming {
    let threshold = (samples.len().max(2) as f64).ln();
    let mut chosen: Vec<(Candidate, f64)> = Vec::new();
    // The base re-tuned alone: the first step's reference, and the answer when nothing
    // is named.
    let base_fit = refit(samples, base, &chosen, sigma);
    let base_after = structure_of(samples, &base_fit, sigma);
    let mut fit = base_fit.clone();
    let mut after = base_after.clone();
    let mut steps = Vec::new();
    let mut not_accepted = Vec::new();
    let mut ambiguous = Vec::new();
    let mut provisional = None;
    while after.structured && chosen.len() < MAX_CAUSES {
        let trials: Vec<((Candidate, f64), Refit)> = options(&chosen)
            .into_par_iter()
            .map(|option| {
                let mut with = chosen.clone();
                with.push(option);
                (option, refit(samples, base, &with, sigma))
            })
            .collect();
        // Lowest information criterion first, RSS/σ² + ln(n) per parameter: at equal
        // RSS the simpler effect (viscous damping is hysteresis damping with p = 0);
        // ties keep catalogue order (a stable sort).
        let criterion = |k: usize| {
            let ((_, shape), trial) = &trials[k];
            trial.rss / (sigma * sigma) + threshold * parameters(*shape)
        };
        let mut order: Vec<usize> = (0..trials.len()).collect();
        order.sort_by(|&a, &b| criterion(a).total_cmp(&criterion(b)));
        let judge = |k: usize| {
            let ((candidate, shape), trial) = &trials[k];
            Trial {
                effect: candidate.name(),
                rss: (fit.rss, trial.rss),
                bic: (
                    (fit.rss - trial.rss) / (sigma * sigma),
                    threshold * parameters(*shape),
                ),
                determined: determined(trial),
                accepted: false,
            }
        };
        // The best trial that passes both tests; else the best one, rejected.
        let passing = order.iter().copied().find(|&k| {
            let t = judge(k);
            t.bic.0 > t.bic.1 && t.determined
        });
        // Within a family the extra shape parameter must earn its place by the margin
        // that tells families apart: hysteresis damping is named over viscous damping
        // (its p = 0) only when its criterion is lower by EVIDENCE.
        let passing = passing.map(|k| {
            order
                .iter()
                .copied()
                .filter(|&m| {
                    let (a, b) = (trials[m].0, trials[k].0);
                    same_family(a.0, b.0)
                        && parameters(a.1) < parameters(b.1)
                        && criterion(m) - criterion(k) < EVIDENCE
                        && judge(m).bic.0 > judge(m).bic.1
                        && judge(m).determined
                })
                .min_by(|&a, &b| criterion(a).total_cmp(&criterion(b)))
                .unwrap_or(k)
        });
        let Some(k) = passing else {
            if let Some(&best) = order.first() {
                let t = judge(best);
                not_accepted.push(rejected(&trials[best].1, &t));
                steps.push(t);
            }
            break;
        };
        // The data must tell it from every other single cause: the best rival of
        // another family must score worse by the margin, else the answer would be a
        // coin toss between two names.
        let rival = order
            .iter()
            .copied()
            .find(|&m| !same_family(trials[m].0 .0, trials[k].0 .0) && judge(m).determined);
        if let Some(m) = rival.filter(|&m| criterion(m) - criterion(k) < EVIDENCE) {
            let (best, other) = (judge(k), judge(m));
            let gap = criterion(m) - criterion(k);
            let why = |a: &str, b: &str| {
                format!(
                    "the data cannot tell `{a}` from `{b}`: their information criteria differ \
                     by {gap:.1}, less than {EVIDENCE}"
                )
            };
            not_accepted.push(NotAccepted {
                reason: why(best.effect, other.effect),
                ..rejected(&trials[k].1, &best)
            });
            not_accepted.push(NotAccepted {
                reason: why(other.effect, best.effect),
                ..rejected(&trials[m].1, &other)
            });
            ambiguous = vec![best.effect, other.effect];
            provisional = Some(trials[k].0);
            steps.push(best);
            fit = trials[k].1.clone();
            after = structure_of(samples, &fit, sigma);
            break;
        }
        let mut t = judge(k);
        t.accepted = true;
        steps.push(t);
        chosen.push(trials[k].0);
        fit = trials[k].1.clone();
        after = structure_of(samples, &fit, sigma);
    }
    // Backward pass: an effect taken early can be made redundant by later ones (a
    // plasticity step mimics part of damping plus adhesion until both are in); drop the
    // weakest while its removal costs less than the information criterion.
    while chosen.len() > 1 {
        let without: Vec<(usize, Refit)> = (0..chosen.len())
            .into_par_iter()
            .map(|k| {
                let mut fewer = chosen.clone();
                fewer.remove(k);
                fewer.extend(provisional);
                (k, refit(samples, base, &fewer, sigma))
            })
            .collect();
        let Some((k, weaker)) = without
            .into_iter()
            .min_by(|a, b| a.1.rss.total_cmp(&b.1.rss))
        else {
            break;
        };
        let penalty = threshold * parameters(chosen[k].1);
        let loss = (weaker.rss - fit.rss) / (sigma * sigma);
        if loss > penalty {
            break;
        }
        steps.push(Trial {
            effect: chosen[k].0.name(),
            rss: (weaker.rss, fit.rss),
            bic: (loss, penalty),
            determined: true,
            accepted: false,
        });
        chosen.remove(k);
        fit = weaker;
        after = structure_of(samples, &fit, sigma);
    }
    let unexplained = after.structured;
    if unexplained && !(chosen.is_empty() && provisional.is_none()) {
        for cause in fit.causes.iter().take(chosen.len()) {
            not_accepted.push(NotAccepted {
                effect: cause.effect,
                parameters: cause.parameters.clone(),
                reason: format!(
                    "with it the residual is still structured (χ² {:.0} > {:.0}): it would \
                     explain part of a shape it does not have",
                    after.chi_squared, after.threshold
                ),
            });
        }
        chosen.clear();
        provisional = None;
        fit = base_fit;
        after = base_after;
    }
    Naming {
        chosen,
        fit,
        steps,
        not_accepted,
        after,
        unexplained,
        ambiguous,
        provisional,
    }
}

/// No decision at all: the base law re-fitted alone, nothing named, nothing tried (for
/// data that cannot support a diagnosis, `super::quality`).
pub fn unnamed(samples: &ContactSamples, base: &ExtendedLaw<f64>, sigma: f64) -> Naming {
    let fit = refit(samples, base, &[], sigma);
    let after = structure_of(samples, &fit, sigma);
    Naming {
        chosen: Vec::new(),
        fit,
        steps: Vec::new(),
        not_accepted: Vec::new(),
        after,
        unexplained: false,
        ambiguous: Vec::new(),
        provisional: None,
    }
}

/// The best trial of a step that stopped, as not accepted.
fn rejected(trial: &Refit, t: &Trial) -> NotAccepted {
    let reason = if t.bic.0 <= t.bic.1 {
        format!(
            "its RSS drop, {:.1}·σ², is below the information criterion's {:.1}·σ²",
            t.bic.0, t.bic.1
        )
    } else {
        "its parameters are not determined by the data (singular covariance)".to_owned()
    };
    NotAccepted {
        effect: t.effect,
        parameters: trial
            .causes
            .last()
            .map_or_else(Vec::new, |c| c.parameters.clone()),
        reason,
    }
}
