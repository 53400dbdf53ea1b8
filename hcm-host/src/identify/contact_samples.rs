//! The measured data of one contact on its line of centres: every sample of every run,
//! in contact or not, with the motion state a contact law needs and the force the
//! sensor recorded. The diagnosis reads all of it; a law is fitted to its in-contact
//! rows ([`super::force_samples`]).

use super::IdentifyError;
use crate::dataset::Dataset;
use crate::dataset::{complete, Completed, TrackReconstruction};
use crate::indicators::{contact_history, event_spans};
use crate::scenario::Model;
use hcm_core::effect::{ContactMemory, ExtendedLaw};
use hcm_core::law::Indentation;
use hcm_core::model::ContactModel;
use nalgebra::Vector3;

/// Column-wise samples of contact `c` over runs (one entry per recorded sample).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactSamples {
    /// Index of the run in the data set.
    pub run: Vec<usize>,
    /// Time (s).
    pub time: Vec<f64>,
    /// Indentation δ from the recorded motion (m), ≤ 0 apart.
    pub depth: Vec<f64>,
    /// Indentation rate δ̇ (m/s), > 0 approaching.
    pub rate: Vec<f64>,
    /// Approach speed δ̇0 of the sample's contact event (m/s); 0 outside events.
    pub approach_speed: Vec<f64>,
    /// Deepest δ so far in the sample's contact event (m); 0 outside events.
    pub(crate) max_depth: Vec<f64>,
    /// Inside a completed contact event (between its δ = 0 crossings).
    pub in_contact: Vec<bool>,
    /// Recorded normal force on body 1 (N).
    pub measured: Vec<f64>,
    /// Standard deviation of `depth` from its reconstruction (m): 0 where the motion was
    /// recorded at the sample, else the flight fit's covariance and the force noise
    /// propagated through Newton's law ([`crate::dataset::complete`]).
    pub depth_sd: Vec<f64>,
    /// Standard deviation of `rate` from its reconstruction (m/s), as `depth_sd`.
    pub rate_sd: Vec<f64>,
    /// Completed contact events over all runs.
    pub events: usize,
}

impl ContactSamples {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// Whether sample `i`'s motion was reconstructed (`dataset::reconstruct`,
    /// `dataset::newton`) rather than recorded there: it carries a standard deviation
    /// (samples built without standard deviations, or `i` out of range: no).
    pub fn reconstructed(&self, i: usize) -> bool {
        let nonzero = |sd: &[f64]| sd.get(i).is_some_and(|s| *s != 0.0);
        nonzero(&self.depth_sd) || nonzero(&self.rate_sd)
    }

    /// `predicted` (N, per sample) with each run's force scaled by its own factor about
    /// the data set's: (Σq·(y − b)/Σq²)_run ÷ (Σq·(y − b)/Σq²)_all, q = predicted − b
    /// over the run's samples (y measured, b the sensor's `offset`, N). Each run's contact
    /// is its own (its stiffness scatters from run to run, 2 % with `hcm generate`'s
    /// scatter), and one law fitted through every run bends to their mixture: the deep
    /// runs are the soft ones, which a pooled fit reads as a force falling off with
    /// depth. Normalised by the pooled factor, so the data set's level stays the law's.
    /// A run without force (Σq² = 0) keeps factor 1.
    pub fn scaled_per_run(&self, predicted: &[f64], offset: f64) -> Vec<f64> {
        let per_run = self.run_scale_sums(predicted, offset, |_| true);
        let (qy, qq) = per_run
            .iter()
            .fold((0.0, 0.0), |(a, b), (_, y, q)| (a + y, b + q));
        let pooled = qy / qq;
        let mut out = predicted.to_vec();
        for (range, y, q) in per_run {
            let factor = y / q / pooled;
            if !(q > 0.0 && factor.is_finite()) {
                continue;
            }
            for i in range {
                out[i] = factor * (predicted[i] - offset) + offset;
            }
        }
        out
    }

    /// Each run's sample range with the sums of the least-squares factor that scales
    /// `predicted` onto the measured force about the sensor's `offset` b (N), over the
    /// run's samples that `counts`: Σq·(y − b) and Σq² (N²), q = predicted − b. The one
    /// per-run scale of a contact whose stiffness scatters from run to run, for the
    /// re-fit ([`Self::scaled_per_run`]) and the held-out score (`held_out`).
    pub(crate) fn run_scale_sums(
        &self,
        predicted: &[f64],
        offset: f64,
        counts: impl Fn(usize) -> bool,
    ) -> Vec<(std::ops::Range<usize>, f64, f64)> {
        self.run_ranges()
            .into_iter()
            .map(|range| {
                let (qy, qq) =
                    range
                        .clone()
                        .filter(|&i| counts(i))
                        .fold((0.0, 0.0), |(qy, qq), i| {
                            let q = predicted[i] - offset;
                            (qy + q * (self.measured[i] - offset), qq + q * q)
                        });
                (range, qy, qq)
            })
            .collect()
    }

    /// The index ranges of the runs' samples, in order: each a run's consecutive
    /// samples (a run's samples are contiguous and in time order).
    pub fn run_ranges(&self) -> Vec<std::ops::Range<usize>> {
        let mut ranges = Vec::new();
        let mut start = 0;
        while start < self.len() {
            let run = self.run[start];
            let end = (start..self.len())
                .find(|&i| self.run[i] != run)
                .unwrap_or(self.len());
            ranges.push(start..end);
            start = end;
        }
        ranges
    }

    /// The index ranges of the contact events: each a stretch of one run's consecutive
    /// in-contact samples, in order.
    pub fn events(&self) -> Vec<std::ops::Range<usize>> {
        let mut events = Vec::new();
        let mut start = 0;
        while start < self.len() {
            if !self.in_contact[start] {
                start += 1;
                continue;
            }
            let run = self.run[start];
            let end = (start..self.len())
                .find(|&i| !self.in_contact[i] || self.run[i] != run)
                .unwrap_or(self.len());
            events.push(start..end);
            start = end;
        }
        events
    }

    /// The contact state of sample `i` as a law reads it.
    pub fn state(&self, i: usize) -> (Indentation<f64>, ContactMemory<f64>) {
        (
            Indentation {
                depth: self.depth[i],
                rate: self.rate[i],
                approach_speed: self.approach_speed[i],
            },
            ContactMemory {
                max_depth: self.max_depth[i],
            },
        )
    }

    /// The force `law` gives along the recorded motion (N): the law in contact, 0
    /// outside contact events.
    pub fn model_force(&self, law: &ExtendedLaw<f64>) -> Vec<f64> {
        let physics = ContactModel::physics(law.clone());
        (0..self.len())
            .map(|i| {
                if self.in_contact[i] {
                    let (state, memory) = self.state(i);
                    physics.physics_normal_force(&state, &memory)
                } else {
                    0.0
                }
            })
            .collect()
    }

    /// The samples of the runs for which `keep(run index)` holds.
    pub fn select(&self, keep: impl Fn(usize) -> bool) -> ContactSamples {
        let mut out = ContactSamples::default();
        for i in (0..self.len()).filter(|&i| keep(self.run[i])) {
            out.run.push(self.run[i]);
            out.time.push(self.time[i]);
            out.depth.push(self.depth[i]);
            out.rate.push(self.rate[i]);
            out.approach_speed.push(self.approach_speed[i]);
            out.max_depth.push(self.max_depth[i]);
            out.in_contact.push(self.in_contact[i]);
            out.measured.push(self.measured[i]);
            out.depth_sd.push(self.depth_sd[i]);
            out.rate_sd.push(self.rate_sd[i]);
        }
        out
    }
}

/// Every sample of contact `c` of `model` in every run of `data`. A run without a
/// completed contact is an error naming it.
///
/// Motion not recorded at the force samples (camera frames at their own rate) is
/// reconstructed there first ([`complete`]), and each sample's `depth_sd` and
/// `rate_sd` say how well; data with motion and force on every row are read as
/// recorded, with both 0.
pub fn contact_samples(
    model: &Model,
    data: &Dataset,
    c: usize,
) -> Result<ContactSamples, IdentifyError> {
    if data.runs.is_empty() {
        return Err(IdentifyError::NoData);
    }
    contact_samples_of(model, &complete(model, data)?, c)
}

/// [`contact_samples`] of data already completed ([`complete`]): for a caller that needs
/// the completed data too, so that nothing is reconstructed twice.
pub fn contact_samples_of(
    model: &Model,
    completed: &Completed<'_>,
    c: usize,
) -> Result<ContactSamples, IdentifyError> {
    if completed.data.runs.is_empty() {
        return Err(IdentifyError::NoData);
    }
    let mut out = ContactSamples::default();
    for (r, run) in completed.data.runs.iter().enumerate() {
        let history = contact_history(model, run, c)?;
        let spans = event_spans(&history);
        if spans.is_empty() {
            return Err(IdentifyError::NoContact {
                run: run.id.clone(),
                from: history.time.first().copied().unwrap_or(f64::NAN),
                to: history.time.last().copied().unwrap_or(f64::NAN),
            });
        }
        out.events += spans.len();
        let mut event = vec![None; history.time.len()];
        for (e, span) in spans.iter().enumerate() {
            for i in span.inside.clone() {
                event[i] = Some(e);
            }
        }
        let spread = Spread::new(model, completed, r, c);
        let mut deepest = 0.0_f64;
        let mut current = None;
        for (i, &here) in event.iter().enumerate() {
            if here != current {
                (current, deepest) = (here, 0.0);
            }
            let approach_speed = here.map_or(0.0, |e| spans[e].approach_speed());
            if here.is_some() {
                deepest = deepest.max(history.depth[i]);
            }
            out.run.push(r);
            out.time.push(history.time[i]);
            out.depth.push(history.depth[i]);
            out.rate.push(history.rate[i]);
            out.approach_speed.push(approach_speed);
            out.max_depth
                .push(if here.is_some() { deepest } else { 0.0 });
            out.in_contact.push(here.is_some());
            out.measured.push(history.force[i]);
            let (depth_sd, rate_sd) = spread.at(i, &history.normal[i]);
            out.depth_sd.push(depth_sd);
            out.rate_sd.push(rate_sd);
        }
    }
    Ok(out)
}

/// The reconstructions of the two bodies of a contact in one run, read along the
/// contact normal.
pub(crate) struct Spread<'a> {
    bodies: [Option<&'a TrackReconstruction>; 2],
}

impl<'a> Spread<'a> {
    /// Of contact `c` in run `r` of `completed`.
    pub(crate) fn new(model: &Model, completed: &'a Completed<'_>, r: usize, c: usize) -> Self {
        let contact = &model.contacts[c];
        let of = |b: usize| completed.track(r, &model.bodies[b].name);
        Spread {
            bodies: [of(contact.body_1), of(contact.body_2)],
        }
    }

    /// Standard deviations of δ (m) and δ̇ (m/s) at sample `i` along `normal`: the two
    /// bodies' independent variances projected, Σ n_k²·var_k.
    pub(crate) fn at(&self, i: usize, normal: &Vector3<f64>) -> (f64, f64) {
        let mut variance = (0.0, 0.0);
        for track in self.bodies.iter().flatten() {
            let along = |v: &[f64; 3]| (0..3).map(|k| normal[k] * normal[k] * v[k]).sum::<f64>();
            variance.0 += along(&track.position_variance[i]);
            variance.1 += along(&track.velocity_variance[i]);
        }
        (variance.0.sqrt(), variance.1.sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::ContactSamples;

    /// Two runs of three samples, the second run's force `gain` times the first's.
    fn two_runs(measured: Vec<f64>) -> ContactSamples {
        ContactSamples {
            run: vec![0, 0, 0, 1, 1, 1],
            time: vec![0.0, 1e-6, 2e-6, 0.0, 1e-6, 2e-6],
            measured,
            ..ContactSamples::default()
        }
    }

    #[test]
    fn each_run_is_scaled_to_its_own_level_about_the_pooled_one() {
        let predicted = [1.0, 2.0, 1.0, 1.0, 2.0, 1.0];
        // Runs 10 % above and below the prediction: the pooled factor is 1.
        let measured: Vec<f64> = (predicted.iter().enumerate())
            .map(|(i, p)| p * if i < 3 { 1.1 } else { 0.9 })
            .collect();
        let scaled = two_runs(measured.clone()).scaled_per_run(&predicted, 0.0);
        for (s, m) in scaled.iter().zip(&measured) {
            assert!((s - m).abs() < 1e-12, "{scaled:?} against {measured:?}");
        }
        // Both runs 20 % high: the data set's level is the law's, so nothing moves.
        let high: Vec<f64> = predicted.iter().map(|p| 1.2 * p).collect();
        assert_eq!(two_runs(high).scaled_per_run(&predicted, 0.0), predicted);
        // An offset stays out of the factor: b + 1.1·q against b + q.
        let (b, q) = (5.0, [1.0, 2.0, 1.0]);
        let measured: Vec<f64> = (0..6)
            .map(|i| b + q[i % 3] * if i < 3 { 1.1 } else { 0.9 })
            .collect();
        let predicted: Vec<f64> = (0..6).map(|i| b + q[i % 3]).collect();
        let scaled = two_runs(measured.clone()).scaled_per_run(&predicted, b);
        for (s, m) in scaled.iter().zip(&measured) {
            assert!((s - m).abs() < 1e-12, "{scaled:?} against {measured:?}");
        }
    }

    #[test]
    fn a_run_without_force_keeps_its_prediction() {
        let predicted = [0.0, 0.0, 0.0, 1.0, 2.0, 1.0];
        let scaled = two_runs(vec![0.1, 0.0, -0.1, 1.0, 2.0, 1.0]).scaled_per_run(&predicted, 0.0);
        assert_eq!(scaled, predicted);
    }
}
