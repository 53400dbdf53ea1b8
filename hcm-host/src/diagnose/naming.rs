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
//! rig of tests/diagnose/diagnose_rig.rs: p = 0.086 by 6.5 in the criterion).
//!
//! A cause that passes must also predict runs it was not fitted on: its gain over the
//! causes already named on held-out runs, run by run ([`super::held_out`]), at
//! [`GAIN_T`] standard errors of the runs' paired differences — the one rule of both
//! diagnoses, [`super::verdict`] (else not named). Where the runs scatter beyond the
//! sample noise ([`Structure::scattered`]), a run's residuals move together and the
//! criterion over all samples overstates the evidence; there its lead over the best
//! cause of another family is judged on the held-out runs too, at [`RIVAL_T`] (else
//! "ambiguous"), and viscous damping is named only where hysteresis damping does not
//! predict the held-out runs better by [`FAMILY_T`] standard error. (Without scatter
//! the samples are independent and the criterion's margin is the stronger evidence: on
//! 16 runs the runs' own t left a 2 µs delay, a 0.5 % plasticity and a 0.5 % viscous
//! damping of the rig `ambiguous`.) The named causes' intervals are then widened to the
//! folds' grouped jackknife where wider.
//! Wherever there are runs, each named cause's interval also holds the one the same
//! model gives with each run's force scaled by its own factor (`cover_run_scatter`,
//! [`super::select::refit_per_run_scaled`]): a pooled fit of runs whose contact
//! scatters is biased, the same way in every fold.
//!
//! A backward pass then drops any effect the later ones made redundant (its removal
//! costs less than the criterion). Steps stop when the residual left is
//! indistinguishable from noise ([`structure`]'s
//! χ² tests) or no effect passes. Then the rule that keeps a diagnosis from naming the
//! nearest wrong cause: **if the residual is still structured, the causes are withdrawn**
//! — the answer is "unexplained", and the effects that entered are reported as not
//! accepted, with why — **unless one of them alone is nearly the shape**: re-fitted
//! alone it removes at least [`PARTIAL_SHARE`] of the base model's excess RSS over the
//! noise and wins on held-out runs, run by run. Then it alone is named, a *partial
//! answer*, and what it leaves is reported unexplained (a plastic set unloading along
//! another curve is named `plasticity`, 3–5 % left). An effect that explains part of a
//! shape it does not have, or only in combination with others, is not the cause (a
//! ringing sensor mount: 3–48 % by any one effect). This replaces the fixed 2 % share
//! the linear selection required of each effect: a small effect that leaves white
//! noise behind is named however small its share.
//!
//! [`structure`]: super::structure::residual_structure

use super::catalogue::Candidate;
use super::held_out::held_out_rss;
use super::momentum::SensorGain;
use super::nonlinearity::{mimicking_gain_shift, ruled_out, SENSOR_NONLINEARITY};
use super::paired::Paired;
use super::select::{
    candidates, parameters, refit, refit_per_run_scaled, BaseFreedom, Fitted, Refit,
};
use super::structure::{residual_structure, Structure};
use super::verdict::{decide, decide_with, Margins, Verdict, GAIN_T};
use super::ContactSamples;
use hcm_core::effect::ExtendedLaw;
use rayon::prelude::*;

/// The held-out rival margin of a force diagnosis ([`Margins::RUNS`]).
pub const RIVAL_T: f64 = Margins::RUNS.rival_t;
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
    pub(crate) determined: bool,
    /// Whether it entered.
    pub accepted: bool,
}

/// A cause considered and not named, with the reason.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NotAccepted {
    /// Catalogue name.
    pub effect: &'static str,
    /// Its parameters as fitted.
    pub(crate) parameters: Vec<Fitted>,
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
    pub(crate) steps: Vec<Trial>,
    /// Causes that entered but are not named, and the best rejected trial.
    pub(crate) not_accepted: Vec<NotAccepted>,
    /// The residual of `fit`.
    pub(crate) after: Structure,
    /// Whether structure is left that no named cause explains.
    pub unexplained: bool,
    /// Two causes the data cannot tell apart (empty otherwise): neither is named; the
    /// better one stays in `fit` as a provisional term, so that the extended model still
    /// predicts what both would, without claiming which it is.
    pub ambiguous: Vec<&'static str>,
    /// That provisional term.
    pub(crate) provisional: Option<(Candidate, f64)>,
    /// A partial answer: structure is left, yet one cause alone removes at least
    /// [`PARTIAL_SHARE`] of the base model's excess and wins on held-out runs; it alone
    /// is named (`chosen`), and what is left stays unexplained.
    pub partial: bool,
}

/// Least share of the base model's excess RSS over the noise, (RSS_base − RSS)/(RSS_base
/// − n·σ²), one cause alone must remove for a partial answer (–). Measured on the rig
/// (tests/diagnose/diagnose_rig.rs): shapes near a catalogued one — a
/// plastic set unloading along another curve, damping nonlinear in the rate — are
/// removed at 90–99.5 % by their catalogue relative; out-of-catalogue ones at most 72 %
/// by any single effect (a plastic set unloading linearly, which a stiffness-exponent
/// change and a delay mimic only together) and 3–48 % (a ringing sensor mount). A force
/// sensor whose gain grows with the force, g·(f + κ·f²), is the blind spot: its shape
/// is a stiffness-exponent change's (89–94 %), and the force cannot tell them apart.
pub const PARTIAL_SHARE: f64 = 0.9;

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

/// Every (effect, start shape) `candidates` offer for one trial.
fn options(candidates: &[Candidate], chosen: &[(Candidate, f64)]) -> Vec<(Candidate, f64)> {
    candidates
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

/// The fixed inputs of one decision: the samples, the base law, the noise σ (N) and the
/// information criterion's price of one parameter, ln(n) (–).
struct Problem<'a> {
    /// The contact samples.
    samples: &'a ContactSamples,
    /// The base law the causes extend.
    base: &'a ExtendedLaw<f64>,
    /// What of it the user's fit had free.
    freedom: BaseFreedom,
    /// The catalogue's effects that may be named here ([`candidates`]).
    candidates: Vec<Candidate>,
    /// The measured noise σ (N).
    sigma: f64,
    /// ln(n): the criterion's price of one parameter (–).
    threshold: f64,
    /// Whether the runs scatter beyond the sample noise about the re-tuned base
    /// ([`Structure::scattered`]): then rivals are also judged on held-out runs.
    scattered: bool,
}

/// One forward step: every option re-fitted with the causes chosen so far, ranked by
/// information criterion.
struct Ranked {
    /// Each (effect, start shape) with its re-fit, in catalogue order.
    trials: Vec<((Candidate, f64), Refit)>,
    /// Indices into `trials`, lowest criterion first (ties in catalogue order).
    order: Vec<usize>,
    /// RSS of the model before this step (N²).
    reference_rss: f64,
    /// The noise σ (N).
    sigma: f64,
    /// ln(n) (–).
    threshold: f64,
}

impl Ranked {
    /// Trial `k`'s information criterion, RSS/σ² + ln(n) per parameter (–).
    fn criterion(&self, k: usize) -> f64 {
        let ((_, shape), trial) = &self.trials[k];
        trial.rss / (self.sigma * self.sigma) + self.threshold * parameters(*shape)
    }

    /// Trial `k` judged against the model before the step (not yet accepted).
    fn judge(&self, k: usize) -> Trial {
        let ((candidate, shape), trial) = &self.trials[k];
        Trial {
            effect: candidate.name(),
            rss: (self.reference_rss, trial.rss),
            bic: (
                (self.reference_rss - trial.rss) / (self.sigma * self.sigma),
                self.threshold * parameters(*shape),
            ),
            determined: determined(trial),
            accepted: false,
        }
    }

    /// Whether trial `k` passes both tests: its RSS drop beats the criterion and its
    /// parameters are determined.
    fn passes(&self, k: usize) -> bool {
        let t = self.judge(k);
        t.bic.0 > t.bic.1 && t.determined
    }

    /// The best trial that passes both tests, with the simpler member of its family
    /// preferred unless the richer one beats it by [`EVIDENCE`].
    fn passing(&self) -> Option<usize> {
        let passing = self.order.iter().copied().find(|&k| self.passes(k));
        // Within a family the extra shape parameter must earn its place by the margin
        // that tells families apart: hysteresis damping is named over viscous damping
        // (its p = 0) only when its criterion is lower by EVIDENCE.
        passing.map(|k| {
            self.order
                .iter()
                .copied()
                .filter(|&m| {
                    let (a, b) = (self.trials[m].0, self.trials[k].0);
                    same_family(a.0, b.0)
                        && parameters(a.1) < parameters(b.1)
                        && self.criterion(m) - self.criterion(k) < EVIDENCE
                        && self.judge(m).bic.0 > self.judge(m).bic.1
                        && self.judge(m).determined
                })
                .min_by(|&a, &b| self.criterion(a).total_cmp(&self.criterion(b)))
                .unwrap_or(k)
        })
    }

    /// The best determined trial of another family than `k`'s, if it scores within
    /// [`EVIDENCE`] of `k`: a rival the data cannot tell from it.
    fn rival(&self, k: usize) -> Option<usize> {
        self.best_other(k, false)
            .filter(|&m| self.criterion(m) - self.criterion(k) < EVIDENCE)
    }

    /// The best determined trial of `k`'s family (`family`) or of another (else), other
    /// than `k`'s own effect.
    fn best_other(&self, k: usize, family: bool) -> Option<usize> {
        let own = self.trials[k].0 .0;
        self.order.iter().copied().find(|&m| {
            let other = self.trials[m].0 .0;
            other != own && same_family(other, own) == family && self.judge(m).determined
        })
    }
}

/// How much better the richer member of a family (hysteresis damping) may predict
/// held-out runs than the simpler one (viscous damping, its p = 0) for the simpler to
/// be named (paired t, –): naming viscous damping claims p = 0, so the richer one must
/// not do better by even one standard error; between that and [`RIVAL_T`] the data
/// lean to p > 0 without telling, and neither is named.
pub const FAMILY_T: f64 = 1.0;

impl Problem<'_> {
    /// The base law re-fitted with `causes`.
    fn refit(&self, causes: &[(Candidate, f64)]) -> Refit {
        refit(self.samples, (self.base, self.freedom), causes, self.sigma)
    }

    /// The residual structure `fit` leaves.
    fn structure_of(&self, fit: &Refit) -> Structure {
        structure_of(self.samples, fit, self.sigma)
    }

    /// Every option not yet chosen re-fitted with the chosen ones (in parallel), ranked
    /// by information criterion against the model whose RSS is `reference_rss` (N²).
    fn rank(&self, chosen: &[(Candidate, f64)], reference_rss: f64) -> Ranked {
        let trials: Vec<((Candidate, f64), Refit)> = options(&self.candidates, chosen)
            .into_par_iter()
            .map(|option| {
                let mut with = chosen.to_vec();
                with.push(option);
                (option, self.refit(&with))
            })
            .collect();
        let mut ranked = Ranked {
            trials,
            order: Vec::new(),
            reference_rss,
            sigma: self.sigma,
            threshold: self.threshold,
        };
        // Lowest information criterion first, RSS/σ² + ln(n) per parameter: at equal
        // RSS the simpler effect (viscous damping is hysteresis damping with p = 0);
        // ties keep catalogue order (a stable sort).
        let mut order: Vec<usize> = (0..ranked.trials.len()).collect();
        order.sort_by(|&a, &b| ranked.criterion(a).total_cmp(&ranked.criterion(b)));
        ranked.order = order;
        ranked
    }

    /// Per-run held-out RSS of the base re-fitted with `causes` (N²).
    fn held_out(&self, causes: &[(Candidate, f64)]) -> Vec<f64> {
        held_out_rss(self.samples, (self.base, self.freedom), causes, self.sigma).rss
    }

    /// The held-out test of trial `k` of `ranked`, entering after `naming.chosen`
    /// whose per-run held-out RSS is `before`: None if it passes — its held-out gain is
    /// significant and, where the runs scatter, no cause of another family predicts the
    /// held-out runs as well and within its family the other member does not tell
    /// against it — else why not, and the rival the data cannot tell it from (if any).
    /// Its per-run RSS is returned too.
    fn held_out_test(
        &self,
        naming: &Naming,
        ranked: &Ranked,
        k: usize,
        before: &[f64],
    ) -> (Vec<f64>, Option<(String, Option<usize>)>) {
        let with = |m: usize| {
            let mut causes = naming.chosen.clone();
            causes.push(ranked.trials[m].0);
            self.held_out(&causes)
        };
        let own = with(k);
        let name = |m: usize| ranked.trials[m].0 .0.name();
        // The one rule (`verdict`) on the trial and the best of another family.
        let rival = ranked.best_other(k, false).filter(|_| self.scattered);
        let other = rival.map(with);
        let mut contenders = vec![Some(own.as_slice())];
        contenders.extend(other.as_deref().map(Some));
        // Both in the model, whichever is the best (the only pair there is).
        let both = |_: usize, _: usize| {
            let mut causes = naming.chosen.clone();
            causes.push(ranked.trials[k].0);
            causes.extend(rival.map(|m| ranked.trials[m].0));
            Some(self.held_out(&causes))
        };
        let decision = decide_with(before, &contenders, (0.0, Margins::RUNS), both);
        match decision.verdict {
            Verdict::Named(0) => {}
            Verdict::Nothing => {
                let gain = decision.gains[0];
                let why = format!(
                    "its gain on held-out runs, {:.3e} ± {:.3e} N² per run, is {:.1} standard \
                     errors, less than {GAIN_T}",
                    gain.mean,
                    gain.standard_error,
                    gain.t()
                );
                return (own, Some((why, None)));
            }
            // A rival of another family the held-out runs do not tell from it (with it
            // in the model, this one adds nothing more) — or prefer, though the
            // criterion preferred this one: the two evidences disagree, and neither is
            // named.
            _ => {
                let m = rival.unwrap_or(k);
                let lead = Paired::of(other.as_deref().unwrap_or(&[]), &own);
                let why = format!(
                    "on held-out runs `{}` predicts better than `{}` by {:.1} standard \
                     errors (not {RIVAL_T}): the data cannot tell them apart",
                    name(k),
                    name(m),
                    lead.t()
                );
                return (own, Some((why, Some(m))));
            }
        }
        if let Some(j) = ranked.best_other(k, true).filter(|_| self.scattered) {
            let richer = parameters(ranked.trials[k].0 .1) > parameters(ranked.trials[j].0 .1);
            let other = with(j);
            let (lead, bar) = if richer {
                (Paired::of(&other, &own).t(), RIVAL_T)
            } else {
                (-Paired::of(&own, &other).t(), -FAMILY_T)
            };
            if lead < bar {
                let why = format!(
                    "on held-out runs `{}` and `{}` (one family) are {:.1} standard errors \
                     apart: the data cannot tell its shape",
                    name(k),
                    name(j),
                    lead.abs()
                );
                return (own, Some((why, Some(j))));
            }
        }
        (own, None)
    }

    /// Forward selection: add the best passing cause per step until the residual is
    /// noise, [`MAX_CAUSES`] are in, nothing passes, or two causes are indistinguishable.
    fn forward(&self, naming: &mut Naming) {
        // The chosen causes' per-run held-out RSS, computed when first needed.
        let mut before: Option<Vec<f64>> = None;
        while naming.after.structured && naming.chosen.len() < MAX_CAUSES {
            let ranked = self.rank(&naming.chosen, naming.fit.rss);
            // The best trial that passes both tests; else the best one, rejected.
            let Some(k) = ranked.passing() else {
                if let Some(&best) = ranked.order.first() {
                    let t = ranked.judge(best);
                    naming
                        .not_accepted
                        .push(rejected(&ranked.trials[best].1, &t));
                    naming.steps.push(t);
                }
                break;
            };
            // The data must tell it from every other single cause: the best rival of
            // another family must score worse by the margin, else the answer would be a
            // coin toss between two names.
            if let Some(m) = ranked.rival(k) {
                let gap = ranked.criterion(m) - ranked.criterion(k);
                let why =
                    format!("their information criteria differ by {gap:.1}, less than {EVIDENCE}");
                self.keep_provisional(naming, &ranked, (k, m), &why);
                break;
            }
            // Then on held-out runs, run by run (`held_out`): it must predict runs it was
            // not fitted on. Where the runs scatter their residuals move together, and the
            // criterion's evidence over all samples is not the data's: there the rivals
            // are judged on held-out runs too. Without scatter the samples are
            // independent and the criterion's margin is the stronger evidence.
            let reference = before.get_or_insert_with(|| self.held_out(&naming.chosen));
            if reference.len() >= 2 {
                let (own, failed) = self.held_out_test(naming, &ranked, k, reference);
                match failed {
                    Some((why, Some(m))) => {
                        self.keep_provisional(naming, &ranked, (k, m), &why);
                        break;
                    }
                    Some((why, None)) => {
                        let t = ranked.judge(k);
                        naming.not_accepted.push(NotAccepted {
                            reason: why,
                            ..rejected(&ranked.trials[k].1, &t)
                        });
                        naming.steps.push(t);
                        break;
                    }
                    None => before = Some(own),
                }
            }
            let mut t = ranked.judge(k);
            t.accepted = true;
            naming.steps.push(t);
            naming.chosen.push(ranked.trials[k].0);
            naming.fit = ranked.trials[k].1.clone();
            naming.after = self.structure_of(&naming.fit);
        }
    }

    /// Two causes `k` and `m` the data cannot tell apart (`because`): name neither,
    /// report both as not accepted, and keep the better, `k`, in the fit as a
    /// provisional term.
    fn keep_provisional(
        &self,
        naming: &mut Naming,
        ranked: &Ranked,
        (k, m): (usize, usize),
        because: &str,
    ) {
        let (best, other) = (ranked.judge(k), ranked.judge(m));
        let why = |a: &str, b: &str| format!("the data cannot tell `{a}` from `{b}`: {because}");
        naming.not_accepted.push(NotAccepted {
            reason: why(best.effect, other.effect),
            ..rejected(&ranked.trials[k].1, &best)
        });
        naming.not_accepted.push(NotAccepted {
            reason: why(other.effect, best.effect),
            ..rejected(&ranked.trials[m].1, &other)
        });
        naming.ambiguous = vec![best.effect, other.effect];
        naming.provisional = Some(ranked.trials[k].0);
        naming.steps.push(best);
        naming.fit = ranked.trials[k].1.clone();
        naming.after = self.structure_of(&naming.fit);
    }

    /// A partial answer where the chosen causes leave structure (`naming.unexplained`):
    /// each chosen cause re-fitted alone; the best one is named alone when it removes at
    /// least [`PARTIAL_SHARE`] of the base model's excess over the noise (`base_fit`) and
    /// its gain on held-out runs, run by run, is at least [`GAIN_T`] standard errors
    /// (a misfit shape leaves residuals that move together within a run, so the samples
    /// are not independent evidence). The others, and a later step's provisional term,
    /// are reported as not accepted. False (nothing changed) otherwise.
    fn partial(&self, naming: &mut Naming, base_fit: &Refit) -> bool {
        let excess = base_fit.rss - self.samples.len() as f64 * self.sigma * self.sigma;
        if naming.chosen.is_empty() || excess <= 0.0 {
            return false;
        }
        let alone: Vec<((Candidate, f64), Refit)> = (naming.chosen.par_iter())
            .map(|&cause| (cause, self.refit(&[cause])))
            .collect();
        let Some((cause, fit)) = alone.into_iter().min_by(|a, b| a.1.rss.total_cmp(&b.1.rss))
        else {
            return false;
        };
        if (base_fit.rss - fit.rss) / excess < PARTIAL_SHARE {
            return false;
        }
        let alone = self.held_out(&[cause]);
        let verdict = decide(&self.held_out(&[]), &[Some(&alone)], (0.0, Margins::RUNS)).verdict;
        if verdict != Verdict::Named(0) {
            return false;
        }
        let after = self.structure_of(&fit);
        for other in naming.fit.causes.iter().take(naming.chosen.len()) {
            if other.effect != cause.0.name() {
                naming.not_accepted.push(NotAccepted {
                    effect: other.effect,
                    parameters: other.parameters.clone(),
                    reason: format!(
                        "it entered after `{}` to fit the structure that one leaves (χ² {:.0} > {:.0}), which no catalogued effect explains",
                        cause.0.name(),
                        after.chi_squared,
                        after.threshold
                    ),
                });
            }
        }
        // One verdict: a later step's rivals (`ambiguous`) fitted what is left, which
        // stays unexplained; their `not_accepted` entries say so.
        naming.ambiguous.clear();
        naming.provisional = None;
        naming.chosen = vec![cause];
        naming.fit = fit;
        naming.after = after;
        naming.partial = true;
        true
    }

    /// Backward pass: an effect taken early can be made redundant by later ones (a
    /// plasticity step mimics part of damping plus adhesion until both are in); drop the
    /// weakest while its removal costs less than the information criterion.
    fn backward(&self, naming: &mut Naming) {
        let sigma = self.sigma;
        while naming.chosen.len() > 1 {
            let chosen = &naming.chosen;
            let provisional = naming.provisional;
            let without: Vec<(usize, Refit)> = (0..chosen.len())
                .into_par_iter()
                .map(|k| {
                    let mut fewer = chosen.clone();
                    fewer.remove(k);
                    fewer.extend(provisional);
                    (k, self.refit(&fewer))
                })
                .collect();
            let Some((k, weaker)) = without
                .into_iter()
                .min_by(|a, b| a.1.rss.total_cmp(&b.1.rss))
            else {
                break;
            };
            let penalty = self.threshold * parameters(naming.chosen[k].1);
            let loss = (weaker.rss - naming.fit.rss) / (sigma * sigma);
            if loss > penalty {
                break;
            }
            naming.steps.push(Trial {
                effect: naming.chosen[k].0.name(),
                rss: (weaker.rss, naming.fit.rss),
                bic: (loss, penalty),
                determined: true,
                accepted: false,
            });
            naming.chosen.remove(k);
            naming.fit = weaker;
            naming.after = self.structure_of(&naming.fit);
        }
    }
}

impl Naming {
    /// The base law's re-fit `fit` and its residual `after`, with nothing named or tried.
    fn base(fit: Refit, after: Structure) -> Self {
        Naming {
            chosen: Vec::new(),
            fit,
            steps: Vec::new(),
            not_accepted: Vec::new(),
            after,
            unexplained: false,
            ambiguous: Vec::new(),
            provisional: None,
            partial: false,
        }
    }

    /// A named `stiffness_exponent` a force-dependent sensor gain could have made
    /// ([`super::nonlinearity`]): unless the momentum balance's `gain` rules that sensor
    /// out, the change is not named — "ambiguous" between it and `sensor_nonlinearity`,
    /// its term kept in the extended model as a provisional one; in a partial answer,
    /// withdrawn with the rest (`base` gives the base re-fit and its residual).
    fn doubt_stiffness(
        &mut self,
        samples: &ContactSamples,
        gain: Option<SensorGain>,
        base: impl FnOnce() -> (Refit, Structure),
    ) {
        let stiffness = |(c, _): &(Candidate, f64)| *c == Candidate::StiffnessExponent;
        let Some(index) = self.chosen.iter().position(stiffness) else {
            return;
        };
        let Some(shift) = mimicking_gain_shift(samples, &self.fit.law) else {
            return;
        };
        if ruled_out(shift, gain) {
            return;
        }
        if self.partial {
            let (fit, after) = base();
            self.withdraw(fit, after);
            self.partial = false;
            return;
        }
        let balance = match gain {
            Some(g) if g.named => format!(
                "found the sensor's gain {:.4} ≠ 1, so it cannot rule that out",
                g.value
            ),
            Some(g) => format!(
                "measured the gain at {:.4} ± {:.4}, too uncertain to rule that out",
                g.value, g.standard_error
            ),
            None => "could not measure (no motion recorded through the contacts)".to_owned(),
        };
        let cause = self.fit.causes.remove(index);
        self.not_accepted.push(NotAccepted {
            effect: cause.effect,
            parameters: cause.parameters.clone(),
            reason: format!(
                "a force sensor whose gain grows with the force (f + κ·f²) has its shape and would \
                 read impulses {:+.2} % off, which the momentum balance {balance}",
                100.0 * shift
            ),
        });
        self.fit.causes.push(cause);
        self.chosen.remove(index);
        self.provisional = self
            .provisional
            .or(Some((Candidate::StiffnessExponent, f64::NAN)));
        self.ambiguous
            .extend([Candidate::StiffnessExponent.name(), SENSOR_NONLINEARITY]);
    }

    /// Structure is left: report every cause that entered as not accepted, with the
    /// residual's χ², and fall back to the base re-fit `base_fit` and its residual; the
    /// answer is then "unexplained" alone, not also "ambiguous".
    fn withdraw(&mut self, base_fit: Refit, base_after: Structure) {
        for cause in self.fit.causes.iter().take(self.chosen.len()) {
            self.not_accepted.push(NotAccepted {
                effect: cause.effect,
                parameters: cause.parameters.clone(),
                reason: format!(
                    "with it the residual is still structured (χ² {:.0} > {:.0}): it would \
                     explain part of a shape it does not have",
                    self.after.chi_squared, self.after.threshold
                ),
            });
        }
        self.chosen.clear();
        // One verdict: the rivals the data could not tell apart did not explain the
        // residual either (their `not_accepted` entries say both).
        self.ambiguous.clear();
        self.provisional = None;
        self.fit = base_fit;
        self.after = base_after;
    }
}

/// Names the causes of `measured − base` on `samples` (noise σ in N); see the module
/// documentation. Deterministic: trials are re-fitted in parallel but compared in
/// catalogue order.
pub fn name_causes(
    samples: &ContactSamples,
    base: &ExtendedLaw<f64>,
    freedom: BaseFreedom,
    sigma: f64,
) -> Naming {
    let problem = Problem {
        samples,
        base,
        freedom,
        candidates: candidates(freedom, &base.base),
        sigma,
        threshold: (samples.len().max(2) as f64).ln(),
        scattered: false,
    };
    // The base re-tuned alone: the first step's reference, and the answer when nothing
    // is named.
    let base_fit = problem.refit(&[]);
    let base_after = problem.structure_of(&base_fit);
    let problem = Problem {
        scattered: base_after.scattered,
        ..problem
    };
    let mut naming = Naming::base(base_fit.clone(), base_after.clone());
    problem.forward(&mut naming);
    problem.backward(&mut naming);
    naming.unexplained = naming.after.structured;
    if naming.unexplained
        && !(naming.chosen.is_empty() && naming.provisional.is_none())
        && !problem.partial(&mut naming, &base_fit)
    {
        naming.withdraw(base_fit, base_after);
    }
    // Where the runs scatter, the named causes' intervals know it (`HeldOut::widen`).
    if problem.scattered && !naming.chosen.is_empty() {
        let mut causes = naming.chosen.clone();
        causes.extend(naming.provisional);
        held_out_rss(samples, (base, freedom), &causes, sigma).widen(&mut naming.fit);
    }
    cover_run_scatter(&problem, &mut naming);
    naming
}

/// Widens each named cause's 95 % interval to hold also the interval the same model
/// gives with each run's force scaled by its own factor
/// ([`super::select::refit_per_run_scaled`]). Runs whose contact scatters (a stiffness
/// 2 % apart) bias a pooled fit's effect in a direction set by the draw, the same at
/// every strength and in every fold, which neither the covariance nor the folds'
/// jackknife sees: on the power table's fitted bases 14 of 86 adhesions missed the
/// truth before this, every one high, by 2.9–5.2 N. Where the runs do not scatter the
/// factors are ≈ 1 and the two intervals agree.
fn cover_run_scatter(problem: &Problem<'_>, naming: &mut Naming) {
    if naming.chosen.is_empty() || problem.samples.run_ranges().len() < 2 {
        return;
    }
    let mut causes = naming.chosen.clone();
    causes.extend(naming.provisional);
    let scaled = refit_per_run_scaled(
        problem.samples,
        (problem.base, problem.freedom),
        &causes,
        problem.sigma,
    );
    for (cause, other) in naming.fit.causes.iter_mut().zip(&scaled.causes) {
        for (p, q) in cause.parameters.iter_mut().zip(&other.parameters) {
            if q.ci.0.is_finite() && q.ci.1.is_finite() {
                p.ci = (p.ci.0.min(q.ci.0), p.ci.1.max(q.ci.1));
            }
        }
    }
}

/// [`name_causes`] beside the momentum balance's `gain` (None where the motion cannot
/// give one): a named stiffness-exponent change the balance cannot tell from a force
/// sensor whose gain grows with the force is not named but "ambiguous" with it
/// ([`super::nonlinearity`]). What `hcm diagnose` decides.
pub fn name_causes_beside_momentum(
    samples: &ContactSamples,
    base: &ExtendedLaw<f64>,
    freedom: BaseFreedom,
    sigma: f64,
    gain: Option<SensorGain>,
) -> Naming {
    let mut naming = name_causes(samples, base, freedom, sigma);
    // A sensor that reads beyond its offset in flight gives no gain to rule anything
    // out with.
    let gain = gain.filter(|g| g.rings.is_none());
    naming.doubt_stiffness(samples, gain, || {
        let unnamed = unnamed(samples, base, freedom, sigma);
        (unnamed.fit, unnamed.after)
    });
    naming
}

/// No decision at all: the base law re-fitted alone, nothing named, nothing tried (for
/// data that cannot support a diagnosis, `super::quality`).
pub fn unnamed(
    samples: &ContactSamples,
    base: &ExtendedLaw<f64>,
    freedom: BaseFreedom,
    sigma: f64,
) -> Naming {
    let fit = refit(samples, (base, freedom), &[], sigma);
    let after = structure_of(samples, &fit, sigma);
    Naming::base(fit, after)
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
