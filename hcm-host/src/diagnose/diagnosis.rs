//! The whole diagnosis of one contact: what is wrong, the named causes, the extended
//! model and its gain — the data behind `DIR/report.md` and `DIR/diagnosis.json`.

use super::force_chance::{force_chance, ForceChance};
use super::gain::{gain, group_table, holdout, GainTable, Holdout, Judged};
use super::momentum::{sensor_gain, with_gain, SensorGain};
use super::naming::{name_causes_beside_momentum, unnamed, Naming, NotAccepted, Trial};
use super::noise::effective_sigma;
use super::noise::{noise_floor, NoiseFloor};
use super::quality::{assess, reconstruction_gap, DataQuality, MAX_GAP_SIGMAS};
use super::select::free_parameters;
use super::select::{select, BaseFreedom, Cause, Fitted, Refit, Step};
use super::sensor::Sensor;
use super::structure::{residual_structure, Structure};
use super::ContactSamples;
use crate::dataset::Dataset;
use crate::dataset::{complete_with, Checks, Completed};
use crate::dataset::{Delay, DELAY_SIGMAS};
use crate::export::encode;
use crate::identify::contact_samples_of;
use crate::identify::IdentifyError;
use crate::progress::Silent;
use crate::residual::ContactResidual;
use crate::scenario::{Contact, Model};
use crate::train::{train_force_network, ResidualError};
use hcm_core::effect::ExtendedLaw;
use hcm_core::residual::Quantisation;
use serde::Serialize;

/// How to diagnose.
#[derive(Clone, Debug, PartialEq)]
pub struct DiagnoseSettings {
    /// Contact of the scenario.
    pub contact: usize,
    /// Seed of the hold-out draw and the HCM's training.
    pub seed: u64,
    /// Share of the runs (inside the fitted range) held out for the gain table.
    pub holdout_fraction: f64,
    /// Epochs of the HCM residual network (the comparison model); 0: no HCM (the gain
    /// table without its row, as where the network cannot be trained).
    pub hcm_epochs: usize,
    /// What of the base law the user's fit had free (see [`BaseFreedom`]).
    pub base_freedom: BaseFreedom,
    /// After the deterministic effects, also try chance: each free parameter's scatter
    /// from run to run and the sensor's noise level ([`super::force_chance`]).
    pub chance: bool,
}

impl Default for DiagnoseSettings {
    fn default() -> Self {
        Self {
            contact: 0,
            seed: 1,
            holdout_fraction: 0.25,
            hcm_epochs: 60,
            base_freedom: BaseFreedom::Given,
            chance: false,
        }
    }
}

/// Everything the diagnosis found.
#[derive(Clone, Debug, Serialize)]
pub struct Diagnosis {
    /// Noise floor of the force signal.
    pub noise: NoiseFloor,
    /// Whether the data can support a diagnosis (if not, nothing is named).
    pub data_quality: DataQuality,
    /// Training and held-out runs.
    pub runs: RunSplit,
    /// What is wrong with the base model (training runs).
    pub before: Structure,
    /// What is left with the extended model (training runs).
    pub after: Structure,
    /// The linear forward selection's steps (first-order ranking, for the report).
    pub selection: Vec<Step>,
    /// The decision's steps: at each, the best re-fitted trial (see `naming`).
    pub naming: Vec<Trial>,
    /// Causes considered and not named, with why.
    pub not_accepted: Vec<NotAccepted>,
    /// Two causes the data cannot tell apart (neither named; see `naming`).
    pub ambiguous: Vec<&'static str>,
    /// The force sensor's gain from the momentum balance (named among the causes when
    /// it differs from 1), None where the motion cannot give it.
    pub sensor_gain: Option<SensorGain>,
    /// Named causes with parameters, 95 % intervals and shares.
    pub causes: Vec<Cause>,
    /// Air drag fitted from the flight motion of body 1 (its `share` is of the flight
    /// acceleration's variance, not of the force residual).
    pub drag: Option<super::drag::DragFit>,
    /// The body the drag was fitted for.
    pub drag_body: String,
    /// Share of the structured residual no catalogued effect explains (0 if what is
    /// left is indistinguishable from noise).
    pub unexplained_share: f64,
    /// A partial answer: one cause named, removing most of the base model's excess
    /// (`naming::PARTIAL_SHARE`), with structure left that no catalogued effect explains.
    pub partial: bool,
    /// Whether the base model departs from the data beyond the noise at all (the χ²
    /// test of `before`, which also gates the selection).
    pub base_structured: bool,
    /// Base law parameters after the joint re-fit.
    pub base_parameters: Vec<Fitted>,
    /// What of the base law was re-tuned with the effects: what the user's fit had
    /// free.
    pub base_freedom: BaseFreedom,
    /// The extended law (base + physical effects), f64.
    #[serde(skip)]
    pub extended: ExtendedLaw<f64>,
    /// Held-out comparison of base, extended and HCM.
    pub gain: Vec<GainTable>,
    /// The same comparison on the training runs: what is wrong with the base model's
    /// force and indicators where it was fitted, and what the extension leaves.
    pub in_sample: GainTable,
    /// The chance phase, where it was asked for and the deterministic answer leaves
    /// room for it (not ambiguous, nothing unexplained); None otherwise.
    pub chance: Option<ForceChance>,
}

/// Run indices used for fitting and for the gain.
#[derive(Clone, Debug, Serialize)]
pub struct RunSplit {
    /// Fitted on.
    pub training: usize,
    /// Held out.
    pub(crate) held_out: usize,
    /// Held-out condition outside the fitted range, if the data have conditions.
    pub(crate) condition: Option<String>,
}

/// What the training runs show before anything is extended: their samples, noise floor
/// and data quality, the base law's residual, the linear selection and the decision.
struct Findings {
    /// The training runs' samples of the contact, their readings divided by the
    /// sensor's gain where one is named.
    samples: ContactSamples,
    /// Noise floor of the force signal.
    noise: NoiseFloor,
    /// Whether the data can support a diagnosis.
    quality: DataQuality,
    /// What is wrong with the base model.
    before: Structure,
    /// The linear forward selection's steps.
    selection: Vec<Step>,
    /// The decision on full re-fits.
    naming: Naming,
}

/// Reconstructs `data` for `base`: motion at a camera's frames and force at the
/// sensor's rate become full rows, re-timed by a fitted sensor delay where that puts
/// the contacts on their flights.
fn reconstruct<'a>(base: &Model, data: &'a Dataset) -> Result<Completed<'a>, IdentifyError> {
    // Motion at a camera's frames and force at the sensor's rate become full rows once,
    // here (`dataset::reconstruct`): the gain, the sensor and the HCM read them too.
    // Motion on every row is checked against the force first: a camera's frames splined
    // onto the force rows are replaced through the contacts (`dataset::newton`).
    let checks = Checks {
        recorded_motion: true,
        sensor_delay: None,
    };
    let mut completed = complete_with(base, data, checks)?;
    // A force sensor lagging the camera lands every contact's motion off the flight
    // after it by Δv·τ: fit τ from those gaps and, when the gaps are too large or τ is
    // significant, reconstruct again with it; keep that only if it puts the contacts on
    // their flights (else the data-quality verdict).
    if let Some(gap) = reconstruction_gap(&completed) {
        let delay = crate::dataset::fit_delay(&completed)
            .filter(|d| gap > MAX_GAP_SIGMAS || d.value.abs() > DELAY_SIGMAS * d.sd);
        if let Some(delay) = delay {
            let retimed = Checks {
                sensor_delay: Some(delay),
                ..checks
            };
            let again = complete_with(base, data, retimed)?;
            if reconstruction_gap(&again).is_some_and(|g| g <= MAX_GAP_SIGMAS) {
                completed = again;
            }
        }
    }
    Ok(completed)
}

/// The force sensor's gain from the momentum balance of `runs` of `data` (contact `c`),
/// on the motion as recorded: none replaced, a camera's frames (reconstructed motion)
/// giving none. Data that cannot be completed give none either; the diagnosis then
/// says why.
fn recorded_gain(
    base: &Model,
    data: &Dataset,
    runs: &[usize],
    c: usize,
) -> Result<Option<SensorGain>, IdentifyError> {
    let training = Dataset {
        runs: runs.iter().map(|&r| data.runs[r].clone()).collect(),
    };
    let Ok(completed) = complete_with(base, &training, Checks::default()) else {
        return Ok(None);
    };
    let samples = contact_samples_of(base, &completed, c)?;
    Ok(sensor_gain(&samples, base.contacts[c].effective_mass))
}

/// `completed` as the sensor read it: its force re-scaled by the named `gain` it was
/// divided by, or as it is.
fn as_recorded<'a>(
    base: &Model,
    completed: &'a Dataset,
    c: usize,
    gain: Option<SensorGain>,
) -> Result<std::borrow::Cow<'a, Dataset>, IdentifyError> {
    Ok(match gain {
        Some(g) => std::borrow::Cow::Owned(rescaled(base, completed, c, g.value)?),
        None => std::borrow::Cow::Borrowed(completed),
    })
}

/// `data` with the force contact `c` reads multiplied by `factor`.
fn rescaled(base: &Model, data: &Dataset, c: usize, factor: f64) -> Result<Dataset, IdentifyError> {
    let sensor = Sensor {
        gain: 1.0 / factor,
        ..Sensor::default()
    };
    let runs = data
        .runs
        .iter()
        .map(|run| sensor.correct(base, run, c))
        .collect::<Result<_, _>>()?;
    Ok(Dataset { runs })
}

/// Examines contact `c` on the training runs `fitted` (reconstructed from `completed`,
/// their readings divided by the sensor's `gain`): noise, data quality, the base law's
/// residual, and the causes named.
fn examine(
    base: &Model,
    (completed, fitted): (&Completed<'_>, &Completed<'_>),
    (c, momentum): (usize, Option<SensorGain>),
    freedom: BaseFreedom,
) -> Result<Findings, IdentifyError> {
    let gain = momentum.filter(|g| g.named).map_or(1.0, |g| g.value);
    let samples: ContactSamples = contact_samples_of(base, fitted, c)?;
    let noise = noise_floor(&samples);
    let sigma = noise.sigma;
    let law = base.contacts[c].model.normal.clone();
    // What is wrong with the base model as the sensor read it: the readings times the
    // `gain` they were divided by.
    let before = {
        let mut read = samples.clone();
        read.measured.iter_mut().for_each(|y| *y *= gain);
        residual_structure(&read, &read.model_force(&law), gain * sigma)
    };
    // The linear stepwise selection, for the report: what the residual's shape
    // suggests at first order. The decision is taken on full re-fits (`naming`).
    let selection = select(&samples, &law, freedom, sigma);
    // Data that cannot show a shape get no cause, only the reasons why.
    let mut quality = assess(&samples, sigma);
    quality.check_reconstruction(completed);
    // What the contact's reconstruction (camera-rate motion) adds to the noise.
    let judged_sigma = super::noise::effective_sigma(&samples, &law, sigma);
    let naming = if quality.sufficient {
        name_causes_beside_momentum(&samples, &law, freedom, judged_sigma, momentum)
    } else {
        unnamed(&samples, &law, freedom, judged_sigma)
    };
    Ok(Findings {
        samples,
        noise,
        quality,
        before,
        selection: selection.steps,
        naming,
    })
}

/// The named causes: the `chosen` ones, their intervals widened by the sd of a `delay`
/// the reconstruction aligned the motion with, and air drag if its fit is significant.
fn named_causes(
    mut causes: Vec<Cause>,
    (delay, checked): (Option<Delay>, Option<Delay>),
    drag: Option<&super::drag::DragFit>,
) -> Vec<Cause> {
    let lags = causes
        .iter_mut()
        .filter(|c| matches!(c.effect, "sensor_delay" | "sensor_filter"))
        .flat_map(|c| c.parameters.iter_mut());
    for p in lags {
        match (delay, checked) {
            // A delay found by the reconstruction: the motion was aligned with it, so the
            // lag named is that alignment, uncertain by the reconstruction's own sd too.
            (Some(delay), _) => {
                let half = (0.5 * (p.ci.1 - p.ci.0)).hypot(1.96 * delay.sd);
                p.ci = (p.value - half, p.value + half);
            }
            // Motion recorded on every row, replaced on the force's own clock (the
            // check's delay was not beyond noise): the motion follows part of the lag,
            // and the lag named is that much short. The check measured the whole lag
            // against the frames: the interval holds its 95 % too.
            (None, Some(check)) => {
                let (lo, hi) = (check.value - 1.96 * check.sd, check.value + 1.96 * check.sd);
                p.ci = (p.ci.0.min(lo), p.ci.1.max(hi));
            }
            (None, None) => {}
        }
    }
    if let Some(d) = drag.filter(|d| d.significant) {
        causes.push(Cause {
            effect: "air_drag",
            family: super::Family::Body,
            parameters: vec![Fitted {
                name: "coefficient".into(),
                value: d.coefficient,
                ci: (
                    d.coefficient - 1.96 * d.standard_error,
                    d.coefficient + 1.96 * d.standard_error,
                ),
            }],
            share: d.share,
        });
    }
    causes
}

/// The models the gain compares beside the base: the extended one with its sensor
/// correction, and the HCM if it could be trained.
struct Models {
    /// The base with the re-fitted law and, if fitted, body 1's air drag.
    extended: Model,
    /// The sensor correction the extended model is judged with.
    sensor: Sensor,
    /// The base with a trained residual network, if any.
    hcm: Option<Model>,
}

impl Models {
    /// Builds the extended model from `fit`'s law and sensor and `drag`, and trains the
    /// HCM on `fit_data` (contact `settings.contact`).
    fn new(
        base: &Model,
        fit_data: &Dataset,
        fit: &Refit,
        drag: Option<&super::drag::DragFit>,
        settings: &DiagnoseSettings,
    ) -> Result<Self, IdentifyError> {
        let (law, sensor) = (&fit.law, fit.sensor);
        let c = settings.contact;
        let mut extended = base.clone();
        extended.contacts[c].model.normal = law.clone();
        if let Some(air_drag) = drag.and_then(|d| d.air_drag()) {
            extended.bodies[base.contacts[c].body_1].air_drag = Some(air_drag);
        }
        let hcm = hcm_contact(base, fit_data, c, settings)?.map(|contact| {
            let mut model = base.clone();
            model.contacts[c] = contact;
            model
        });
        Ok(Self {
            extended,
            sensor,
            hcm,
        })
    }

    /// The gain: base, extended and HCM on `split`'s held-out runs of `data`, and the
    /// same on its training runs (contact `c`, noise σ in N).
    fn gain(
        &self,
        base: &Model,
        (data, split): (&Dataset, &Holdout),
        sigma: f64,
        c: usize,
    ) -> Result<(Vec<GainTable>, GainTable), IdentifyError> {
        let judged = self.judged(base);
        let held_out = gain(base, data, &split.held_out, c, sigma, &judged)?;
        let runs = &split.training;
        let training = group_table("training runs".into(), base, data, runs, c, sigma, &judged)?;
        Ok((held_out, training))
    }

    /// The rows of the gain tables: base, extended and (if trained) HCM.
    fn judged<'a>(&'a self, base: &'a Model) -> Vec<Judged<'a>> {
        let ideal = Sensor::default();
        let mut judged = vec![
            Judged {
                label: "base",
                physics: base,
                sensor: ideal,
            },
            Judged {
                label: "extended",
                physics: &self.extended,
                sensor: self.sensor,
            },
        ];
        if let Some(h) = &self.hcm {
            judged.push(Judged {
                label: "HCM",
                physics: h,
                sensor: ideal,
            });
        }
        judged
    }
}

/// The causes `naming` chose, re-fitted in `fit` on `samples`: the sensor's gain first
/// where named (`fit` then reads with it, its shares rescaled), then the chosen causes
/// in order of entry (a provisional term is in the extended law and the sensor, not
/// among them). Where what is left is judged noise and scatter, nothing is
/// unexplained: the shares are of what the causes explain together.
fn chosen_causes(
    naming: &mut Naming,
    fit: &mut Refit,
    samples: &ContactSamples,
    named_gain: Option<SensorGain>,
) -> Vec<Cause> {
    let gain_cause = named_gain.map(|g| with_gain(fit, samples, &g));
    // The gain obeys the rule every cause does: beside a residual that no cause
    // explains it is not named (its correction stays in the model, as a provisional
    // term does). A mount that rings through the contact reads as a gain in the
    // momentum balance — 1.003 for one ringing at 5 % of the peak at 40 kHz on the rig
    // — and leaves the shape only a ringing has.
    let gain_cause = match gain_cause {
        Some(cause) if naming.unexplained && !naming.partial => {
            // What it removes is not explained by a named cause: it is left unexplained.
            fit.left_share += cause.share;
            naming.not_accepted.push(NotAccepted {
                effect: cause.effect,
                parameters: cause.parameters,
                reason: "with it the residual is still structured, and no cause explains what \
                         is left: a sensor that rings or drifts also reads as a gain in the \
                         momentum balance"
                    .to_owned(),
            });
            None
        }
        other => other,
    };
    let mut chosen: Vec<Cause> = gain_cause
        .into_iter()
        .chain(fit.causes.iter().take(naming.chosen.len()).cloned())
        .collect();
    let explained: f64 = chosen.iter().map(|c| c.share).sum();
    if !naming.unexplained && explained > 0.0 {
        chosen.iter_mut().for_each(|c| c.share /= explained);
    }
    chosen
}

/// Refuses a hold-out with nothing to fit or nothing to judge: one run cannot be both,
/// and a gain judged on the runs fitted is no evidence.
fn both_parts(split: &Holdout, data: &Dataset) -> Result<(), IdentifyError> {
    if split.training.is_empty() || split.held_out.is_empty() {
        return Err(IdentifyError::Setup(format!(
            "the diagnosis fits its candidates on some runs and judges them on others it \
             never saw, and --data holds {} run(s): give at least 2 (e.g. `hcm generate \
             --runs 10`)",
            data.runs.len()
        )));
    }
    Ok(())
}

/// Diagnoses contact `settings.contact` of `base` (the scenario with the base physics
/// applied) against `data`.
pub fn diagnose(
    base: &Model,
    data: &Dataset,
    settings: &DiagnoseSettings,
) -> Result<Diagnosis, IdentifyError> {
    let c = settings.contact;
    let split = holdout(base, data, settings.seed, settings.holdout_fraction);
    both_parts(&split, data)?;
    // Measurement before physics: the sensor's gain, from the training runs' momentum
    // balance, comes off the force readings before anything else reads them (a gain
    // would otherwise show as motion that disobeys Newton's law, and as physics).
    let momentum_gain = recorded_gain(base, data, &split.training, c)?;
    let named_gain = momentum_gain.filter(|g| g.named);
    let corrected;
    let read = match named_gain {
        Some(g) => {
            corrected = rescaled(base, data, c, 1.0 / g.value)?;
            &corrected
        }
        None => data,
    };
    let completed = reconstruct(base, read)?;
    // The gain is judged on the data as recorded (re-scaled back where corrected).
    let recorded = as_recorded(base, &completed.data, c, named_gain)?;
    let data: &Dataset = &recorded;
    // The training runs with their reconstructions, so that each sample carries its
    // reconstruction's uncertainty (0 where motion and force share every row).
    let fitted = completed.subset(&split.training);
    let findings = examine(
        base,
        (&completed, &fitted),
        (c, momentum_gain),
        settings.base_freedom,
    )?;
    let (mut naming, sigma) = (findings.naming, findings.noise.sigma);
    let mut fit = naming.fit.clone();
    let chosen = chosen_causes(&mut naming, &mut fit, &findings.samples, named_gain);
    let body = &base.bodies[base.contacts[c].body_1];
    let drag = super::drag::fit_drag(&findings.samples, body.mass, base.gravity.norm());
    let lags = (completed.delay, completed.checked_delay);
    let causes = named_causes(chosen, lags, drag.as_ref());
    let unexplained_share = if naming.unexplained {
        fit.left_share
    } else {
        0.0
    };
    let models = Models::new(base, &fitted.data, &fit, drag.as_ref(), settings)?;
    let (gain, in_sample) = models.gain(base, (data, &split), sigma, c)?;
    let chance = match settings.chance && naming.ambiguous.is_empty() && !naming.unexplained {
        true => Some(chance_phase(
            base,
            (&completed, &split),
            (&findings.samples, sigma, &fit),
            settings,
        )?),
        false => None,
    };
    Ok(Diagnosis {
        noise: findings.noise,
        data_quality: findings.quality,
        runs: RunSplit {
            training: split.training.len(),
            held_out: split.held_out.len(),
            condition: split.condition,
        },
        base_structured: findings.before.structured,
        before: findings.before,
        after: naming.after,
        selection: findings.selection,
        naming: naming.steps,
        not_accepted: naming.not_accepted,
        ambiguous: naming.ambiguous,
        sensor_gain: momentum_gain,
        causes,
        drag,
        drag_body: body.name.clone(),
        unexplained_share,
        partial: naming.partial,
        base_parameters: fit.base_parameters,
        base_freedom: settings.base_freedom,
        extended: fit.law,
        gain,
        in_sample,
        chance,
    })
}

/// Chance on what the deterministic phase left (`fit`, on the training `samples`, whose
/// noise floor is `sigma`, N),
/// judged on the held-out runs of `split`. Asked only where the deterministic answer
/// leaves no doubt: beside an ambiguity or a structure no cause explains, a spread
/// would cover a misfit.
fn chance_phase(
    base: &Model,
    (completed, split): (&Completed<'_>, &Holdout),
    (samples, sigma, fit): (&ContactSamples, f64, &Refit),
    settings: &DiagnoseSettings,
) -> Result<ForceChance, IdentifyError> {
    let c = settings.contact;
    let held_out = contact_samples_of(base, &completed.subset(&split.held_out), c)?;
    let noise = effective_sigma(samples, &fit.law, sigma);
    let free = free_parameters(samples, &fit.law.base, settings.base_freedom);
    Ok(force_chance(
        (samples, &held_out),
        (&fit.law, fit.sensor),
        noise,
        &free,
        (&split.training, &split.held_out),
    ))
}

/// The HCM of the base model: a residual network trained on the training runs,
/// exported as f32 and decoded by the core, attached to the base contact. None when
/// the shipped architecture cannot be trained on these data.
fn hcm_contact(
    base: &Model,
    data: &Dataset,
    c: usize,
    settings: &DiagnoseSettings,
) -> Result<Option<Contact>, IdentifyError> {
    if settings.hcm_epochs == 0 {
        return Ok(None);
    }
    let trained = train_force_network(base, data, c, settings.hcm_epochs, settings.seed, &Silent);
    let network = match trained {
        Ok((network, _, _)) => network,
        Err(ResidualError::Samples(error)) => return Err(error),
        Err(_) => return Ok(None),
    };
    let Ok(bytes) = encode(&network, Quantisation::F32) else {
        return Ok(None);
    };
    let Ok(residual) = ContactResidual::decode(&bytes) else {
        return Ok(None);
    };
    let mut contact = base.contacts[c].clone();
    contact.model.residual = Some(residual);
    Ok(Some(contact))
}
