//! Whether the data can support a diagnosis at all, checked before anything is named.
//!
//! A diagnosis reads the shape of the force residual over each contact; data that
//! cannot show a shape must not be given a cause. Three things make that impossible,
//! each with a floor chosen from what the selection needs:
//! - too few force samples per contact: the structure test bins the residual over the
//!   contact, and an effect's column must vary within the contact; below
//!   [`MIN_CONTACT_SAMPLES`] per contact (median over runs) the contact is a handful of
//!   points (a 110 µs impact at 50 kHz: 5). A force sensor at 100 kHz gives 11–15 on the
//!   ball's contacts, enough to name a 5 % damping (tests/diagnose/diagnose_rig.rs);
//! - too noisy a force: below a peak-to-noise ratio of [`MIN_PEAK_TO_NOISE`], an effect
//!   at a few % of the peak is under the noise in every sample;
//! - too few contacts: fewer than [`MIN_CONTACTS`] runs with a contact leave nothing to
//!   cross-check a cause on.

use super::ContactSamples;
use crate::dataset::Completed;
use crate::dataset::Delay;
use crate::numerics::median;
use serde::Serialize;

/// Least median number of force samples per contact (–).
pub const MIN_CONTACT_SAMPLES: usize = 10;
/// Least median peak force / noise σ (–).
pub const MIN_PEAK_TO_NOISE: f64 = 10.0;
/// Least number of runs with a contact (–).
pub const MIN_CONTACTS: usize = 2;
/// Most standard deviations (median over contacts) by which the motion integrated
/// through a contact may miss the camera's flight after it (–). On consistent data each
/// contact's gap is a half-normal deviate (median 0.67); a median above 3 over several
/// contacts does not happen by chance (one contact exceeds 3 with probability 0.003).
/// Measured on the rig (tests/diagnose/diagnose_rig.rs, camera rows): see README, "Diagnose".
pub const MAX_GAP_SIGMAS: f64 = 3.0;

/// The verdict on the data, with the figures behind it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DataQuality {
    /// Whether a diagnosis may name anything.
    pub sufficient: bool,
    /// Why not, one sentence each (empty when sufficient).
    pub reasons: Vec<String>,
    /// Runs with at least one sample in contact.
    pub(crate) contacts: usize,
    /// Median number of force samples in contact per such run.
    pub(crate) samples_per_contact: usize,
    /// Median over those runs of the peak measured force over σ (–).
    pub(crate) peak_to_noise: f64,
    /// Where the motion was reconstructed from camera frames and the force: the median
    /// over contacts of the largest |integrated − after-flight| position or velocity in
    /// its standard deviations (–), after any sensor delay found; `None` for data whose
    /// motion and force share every row.
    pub(crate) reconstruction_gap: Option<f64>,
    /// Where the motion was recorded on every row: the median over contacts of its
    /// misfit to the motion the force implies, in standard deviations (–); contacts
    /// above [`crate::dataset::newton::MAX_MISFIT`] had their motion replaced by the
    /// force's (`dataset::newton`). `None` where nothing was checked.
    pub(crate) motion_misfit: Option<f64>,
    /// The delay of the force behind the camera the reconstruction found and undid
    /// (`dataset::delay`): when the gap without it was over [`MAX_GAP_SIGMAS`] or it is
    /// over `dataset::delay::DELAY_SIGMAS` of its standard deviations from 0.
    pub sensor_delay: Option<Delay>,
}

impl DataQuality {
    /// Adds the reconstruction's check (`completed`, [`crate::dataset::reconstruct`],
    /// [`reconstruction_gap`]). The force integrated from the flight before must land on
    /// the flight filmed after; a lagging sensor, which only moves the landing, has
    /// been found and undone by then (`dataset::delay`, the diagnosis re-reconstructs
    /// with it). When it still misses by more than [`MAX_GAP_SIGMAS`] the force and the
    /// frames disagree in scale or time — a wrong mass, a sensor's gain — and the
    /// contact's reconstructed motion, which every cause would be judged on, cannot be
    /// trusted. Complete data (nothing reconstructed from frames) add nothing.
    pub fn check_reconstruction(&mut self, completed: &Completed<'_>) {
        self.motion_misfit = completed.motion_misfit;
        self.sensor_delay = completed.delay;
        let Some(gap) = reconstruction_gap(completed) else {
            return;
        };
        self.reconstruction_gap = Some(gap);
        if gap.is_nan() || gap > MAX_GAP_SIGMAS {
            self.reasons.push(format!(
                "the motion integrated through the contacts misses the camera's flight after them by {gap:.1} standard deviations (median), and no sensor delay closes the gap: the force and the frames disagree in scale (a wrong mass, a force sensor's gain) or in time, so the contact's motion cannot be trusted"
            ));
            self.sufficient = false;
        }
    }
}

/// Per contact integrated through from camera frames, the largest |integrated −
/// after-flight| over its standard deviation, of position and velocity on every axis;
/// the median over contacts (–). None where nothing was reconstructed from frames.
pub fn reconstruction_gap(completed: &Completed<'_>) -> Option<f64> {
    let worst = |(gap, sd): ([f64; 3], [f64; 3])| -> f64 {
        gap.iter()
            .zip(sd)
            .filter(|(_, sd)| *sd > 0.0)
            .map(|(g, sd)| g.abs() / sd)
            .fold(0.0, f64::max)
    };
    let mut gaps: Vec<f64> = completed
        .tracks
        .iter()
        .flatten()
        .flatten()
        .flat_map(|track| &track.contacts)
        .filter_map(|check| {
            let position = worst(check.position_gap?);
            Some(
                check
                    .velocity_gap
                    .map_or(position, |v| position.max(worst(v))),
            )
        })
        .collect();
    (!gaps.is_empty()).then(|| median(&mut gaps))
}

/// Checks `samples` (noise σ in N) against the floors of the module documentation.
pub fn assess(samples: &ContactSamples, sigma: f64) -> DataQuality {
    let runs = samples.run.iter().copied().max().map_or(0, |r| r + 1);
    let mut counts = vec![0_usize; runs];
    let mut peaks = vec![0.0_f64; runs];
    for i in (0..samples.len()).filter(|&i| samples.in_contact[i]) {
        let r = samples.run[i];
        counts[r] += 1;
        peaks[r] = peaks[r].max(samples.measured[i].abs());
    }
    let touched: Vec<usize> = (0..runs).filter(|&r| counts[r] > 0).collect();
    // No contact: NaN, which both floors below refuse (NaN as usize is 0).
    let mut per_contact: Vec<f64> = touched.iter().map(|&r| counts[r] as f64).collect();
    let samples_per_contact = median(&mut per_contact) as usize;
    let mut ratios: Vec<f64> = touched.iter().map(|&r| peaks[r] / sigma).collect();
    let peak_to_noise = median(&mut ratios);
    let mut reasons = Vec::new();
    if touched.len() < MIN_CONTACTS {
        reasons.push(format!(
            "too few contacts: {} run(s) touch, at least {MIN_CONTACTS} are needed",
            touched.len()
        ));
    }
    if samples_per_contact < MIN_CONTACT_SAMPLES {
        reasons.push(format!(
            "too few force samples per contact: {samples_per_contact} (median), at least \
             {MIN_CONTACT_SAMPLES} are needed to see the residual's shape — sample the force \
             faster"
        ));
    }
    // NaN (σ = 0) is not a ratio to trust either.
    if peak_to_noise.is_nan() || peak_to_noise < MIN_PEAK_TO_NOISE {
        reasons.push(format!(
            "force too noisy: its peak is {peak_to_noise:.1} σ (median), at least \
             {MIN_PEAK_TO_NOISE} σ are needed for an effect of a few % of it to show"
        ));
    }
    DataQuality {
        sufficient: reasons.is_empty(),
        reasons,
        contacts: touched.len(),
        samples_per_contact,
        peak_to_noise,
        reconstruction_gap: None,
        motion_misfit: None,
        sensor_delay: None,
    }
}
