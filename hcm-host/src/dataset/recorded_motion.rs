//! One track's recorded motion through its contacts, as `diagnose` reads data whose
//! every row holds position, velocity and force: each contact's misfit to the motion the
//! force implies ([`super::newton`]'s check) and, when the data fail it, the track with
//! every contact's motion replaced by the force's.
//!
//! The force's offset — what the sensor reads with no contact — is taken off before
//! anything is integrated: first what the record's two ends read (a record starts and
//! ends in flight; an offset above the contact threshold would otherwise make the whole
//! record one contact), then the median between the contacts found.

use super::delay::Delay;
use super::implied::Implied;
use super::newton::{misfit, position_noise, replace, Rows};
use super::reconstruct::TrackReconstruction;
use super::through_contact::ForceSeries;
use super::BodyTrack;

/// Fewest force samples outside the contacts from which their median is taken as the
/// sensor's offset (–).
const MIN_FLIGHT_ROWS: usize = 10;

/// One track's contacts as the check and the replacement read them.
struct TrackContacts {
    time: Vec<f64>,
    position: Vec<[f64; 3]>,
    velocity: Vec<[f64; 3]>,
    series: ForceSeries,
    windows: Vec<(usize, usize)>,
    offset: [f64; 3],
    noise: [f64; 3],
}

impl TrackContacts {
    /// Of a track whose every row holds position, velocity and force.
    fn new(track: &BodyTrack) -> Self {
        let time: Vec<f64> = track.samples.iter().map(|s| s.time).collect();
        let position: Vec<[f64; 3]> = track.samples.iter().map(|s| s.position).collect();
        // An offset larger than the contact threshold would make the whole record one
        // contact: take off first what the record's ends read (a record starts and ends
        // in flight), then the flight's median between the contacts found.
        let edges = edge_reading(&track.samples);
        let series = ForceSeries::new(
            track
                .samples
                .iter()
                .map(|s| (s.time, core::array::from_fn(|k| s.force[k] - edges[k])))
                .collect(),
        );
        let windows = series.contacts(&time);
        TrackContacts {
            velocity: track.samples.iter().map(|s| s.velocity).collect(),
            offset: flight_reading(&series, &windows),
            noise: position_noise(&time, &position),
            time,
            position,
            series,
            windows,
        }
    }

    /// Contact `w`: the force's motion through it, and the rows around it (as far as
    /// its duration each side, not into another contact) — with the window's own rows
    /// (`inside`) or without them.
    fn contact(&self, w: usize, mass: f64, inside: bool) -> (Implied, Rows<'_>) {
        let (first, last) = self.windows[w];
        let implied = Implied::new(&self.series, (first, last), self.offset, mass);
        let (time, reach) = (&self.time, implied.duration());
        let from = w.checked_sub(1).map_or(0, |p| self.windows[p].1 + 1);
        let to = self.windows.get(w + 1).map_or(time.len(), |n| n.0);
        let from = from.max(time.partition_point(|&t| t < time[first] - reach));
        let to = to.min(time.partition_point(|&t| t <= time[last] + reach));
        let rows = (from..to)
            .filter(|&j| inside || j < first || j > last)
            .collect();
        let rows = Rows {
            time,
            position: &self.position,
            velocity: &self.velocity,
            noise: self.noise,
            rows,
        };
        (implied, rows)
    }

    /// Force samples h (s) apart in window `w`, and the mass (kg).
    fn sampling(&self, w: usize, mass: f64) -> (f64, f64) {
        let (first, last) = self.windows[w];
        let span = self.time[last] - self.time[first];
        (span / (last - first).max(1) as f64, mass)
    }
}

/// The check's misfit (–) and fitted delay (s) of each contact of a track whose every
/// row holds position, velocity and force, with gravity g (m/s²) on a body of mass m
/// (kg).
pub(super) fn misfits(track: &BodyTrack, gravity: [f64; 3], mass: f64) -> Vec<(f64, f64)> {
    let contacts = TrackContacts::new(track);
    (0..contacts.windows.len())
        .filter_map(|w| {
            let (implied, rows) = contacts.contact(w, mass, true);
            let sampling = contacts.sampling(w, mass);
            misfit(&rows, &implied, gravity, contacts.series.noise, sampling)
        })
        .collect()
}

/// The track with the motion through every contact replaced by the force's (see the
/// module documentation), and its uncertainty; the rows left as recorded come from the
/// instrument that failed the check, so they carry the error it showed there. With a
/// `delay`, the force is taken as read that late ([`super::newton::replace`]).
pub(super) fn replace_track(
    track: &BodyTrack,
    gravity: [f64; 3],
    mass: f64,
    delay: Option<Delay>,
) -> (BodyTrack, TrackReconstruction) {
    let contacts = TrackContacts::new(track);
    let n = contacts.time.len();
    let mut out = track.clone();
    let mut rec = TrackReconstruction {
        position_variance: vec![[0.0; 3]; n],
        velocity_variance: vec![[0.0; 3]; n],
        contacts: Vec::new(),
    };
    let mut replaced = vec![false; n];
    let mut error = ([0.0_f64; 3], [0.0_f64; 3]);
    for (w, &(first, last)) in contacts.windows.iter().enumerate() {
        let (implied, rows) = contacts.contact(w, mass, true);
        if rows.rows.len() < 3 {
            continue;
        }
        let window = &contacts.time[first..=last];
        let sampling = contacts.sampling(w, mass);
        let noise = contacts.series.noise;
        let motion = replace(&rows, &implied, window, (gravity, noise), sampling, delay);
        for k in 0..3 {
            error.0[k] = error.0[k].max(motion.recorded_error.0[k]);
            error.1[k] = error.1[k].max(motion.recorded_error.1[k]);
        }
        for (i, j) in (first..=last).enumerate() {
            replaced[j] = true;
            out.samples[j].position = motion.position[i];
            out.samples[j].velocity = motion.velocity[i];
            rec.position_variance[j] = motion.position_variance[i];
            rec.velocity_variance[j] = motion.velocity_variance[i];
        }
    }
    for j in (0..n).filter(|&j| !replaced[j]) {
        (rec.position_variance[j], rec.velocity_variance[j]) = error;
    }
    (out, rec)
}

/// The median force (N per axis) of the first and last tenth of `samples`.
fn edge_reading(samples: &[super::Sample]) -> [f64; 3] {
    if samples.is_empty() {
        return [0.0; 3];
    }
    let tenth = (samples.len() / 10).max(1);
    let ends = samples[..tenth]
        .iter()
        .chain(&samples[samples.len() - tenth..]);
    let mut values: Vec<[f64; 3]> = ends.map(|s| s.force).collect();
    core::array::from_fn(|k| {
        let mut axis: Vec<f64> = values.iter_mut().map(|f| f[k]).collect();
        crate::numerics::median(&mut axis)
    })
}

/// What the sensor reads with no contact (N per axis): the median of the force samples
/// outside every contact window; 0 with fewer than [`MIN_FLIGHT_ROWS`] of them.
fn flight_reading(series: &ForceSeries, windows: &[(usize, usize)]) -> [f64; 3] {
    let outside: Vec<usize> = (0..series.time.len())
        .filter(|&j| !windows.iter().any(|&(a, b)| j >= a && j <= b))
        .collect();
    if outside.len() < MIN_FLIGHT_ROWS {
        return [0.0; 3];
    }
    core::array::from_fn(|k| {
        let mut values: Vec<f64> = outside.iter().map(|&j| series.force[j][k]).collect();
        let middle = values.len() / 2;
        let (_, median, _) = values.select_nth_unstable_by(middle, f64::total_cmp);
        *median
    })
}
