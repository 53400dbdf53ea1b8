//! The motion at the force sensor's samples, reconstructed from what a rig measures
//! well: a high-speed camera (10–50 kfps, µm-level noise) sees a 110 µs impact in a few
//! frames and cannot resolve an indentation of tens of µm, while the force sensor
//! samples the contact at 100 kHz–1 MHz.
//!
//! For each moving body of a contact whose rows are not complete (position, velocity and
//! force on every row):
//!
//! 1. the contacts are located in its force samples (`ForceSeries::contacts`);
//! 2. the free flight before each contact is fitted to the camera positions (a parabola
//!    per axis with the scenario's gravity, least squares — [`FlightFit`]); velocity
//!    cells of the frames, differentiated by the rig, are not used;
//! 3. Newton's law m·ẍ = f + m·g is integrated through the contact from that flight
//!    (`integrate`), the measured force taken piecewise linear between its samples;
//! 4. the flight after the contact, fitted the same way, gives the motion after it and a
//!    check of the integration ([`ContactCheck`]).
//!
//! The body's track is replaced by one row per force sample: position and velocity
//! reconstructed, force (and torque, 0 where not measured) as measured, orientation and
//! angular velocity from the nearest frame that has them (identity and 0 without). Each
//! row's uncertainty (variance per axis of position and velocity) comes with it: the
//! flight fit's covariance propagated exactly, plus the force noise integrated.
//!
//! Data whose every row already holds position, velocity and force are returned as they
//! are, borrowed, with no uncertainty: today's simulated data take exactly the path
//! they always took. `complete_with` can ask for more ([`Checks`]): motion recorded on
//! every row checked against Newton's law with the force and replaced where it fails
//! (`super::newton`, a camera splined onto the force rows), and the force integrated as
//! read a given delay late behind the frames (`super::delay`).

use std::borrow::Cow;

use super::channel::Channel;
use super::delay::Delay;
use super::flight::{FlightFit, MIN_FRAMES};
use super::through_contact::{integrate, ForceSeries};
use super::{BodyTrack, Dataset, Run, Sample};

use crate::numerics::median;
use crate::scenario::Model;

/// Frames fitted per flight: the nearest this many to the contact. A long flight adds
/// little precision and lets unmodelled drag bend the parabola.
const MAX_FLIGHT_FRAMES: usize = 200;

/// Why the motion could not be reconstructed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReconstructError {
    /// A moving body of a contact has rows without motion or force and no force samples
    /// to reconstruct them from.
    #[error(
        "run `{run}`, body `{body}`: rows without {missing} and no force samples (fx, fy, fz) \
         on it or its contact partner to reconstruct the motion from; record the force \
         sensor's rows, or give position, velocity and force on every row"
    )]
    NoForce {
        /// The run's id.
        run: String,
        /// The moving body's name.
        body: String,
        /// The first channel some row lacks (`position`, `velocity` or `force`).
        missing: &'static str,
    },
    /// Too few camera frames in a flight before a contact.
    #[error(
        "run `{run}`, body `{body}`: {frames} camera frame(s) (px, py, pz) in the flight before \
         the contact at t = {time} s; the reconstruction fits that flight and needs at least \
         {MIN_FRAMES}"
    )]
    FewFrames {
        /// The run's id.
        run: String,
        /// The moving body's name.
        body: String,
        /// Time of the contact's first force sample (s).
        time: f64,
        /// Camera frames found in the flight before it.
        frames: usize,
    },
}

/// Data with every moving body's motion at its force samples, and what it cost.
#[derive(Clone, Debug)]
pub struct Completed<'a> {
    /// The data: borrowed when they were complete, else with reconstructed tracks.
    pub data: Cow<'a, Dataset>,
    /// Per run, per body (as in `data.runs[r].bodies`): the reconstruction of that
    /// track, None for a track kept as recorded.
    pub(crate) tracks: Vec<Vec<Option<TrackReconstruction>>>,
    /// Where motion recorded on every row was checked against Newton's law
    /// ([`Checks::recorded_motion`]): the median over contacts of its misfit, in
    /// standard deviations (–).
    pub(crate) motion_misfit: Option<f64>,
    /// The sensor delay the reconstruction was done with, if any.
    pub(crate) delay: Option<Delay>,
    /// The delay the check of motion recorded on every row found behind the force,
    /// pooled over its contacts (`dataset::delay::pooled`), where that motion was
    /// replaced: used for the replacement only where real, reported either way (a lag
    /// the replacement does not undo is partly hidden in the motion it gives).
    pub(crate) checked_delay: Option<Delay>,
}

/// What `complete_with` checks beyond [`complete`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Checks {
    /// Check motion recorded on every row against the force through each contact and
    /// replace it where it does not obey Newton's law (`dataset::newton`): a camera's
    /// frames splined onto the force rows.
    pub(crate) recorded_motion: bool,
    /// Integrate the force as read this late behind the camera frames
    /// (`dataset::delay`): the motion as it was, against a lagging sensor.
    pub(crate) sensor_delay: Option<Delay>,
}

impl Completed<'_> {
    /// Whether any track was reconstructed.
    pub fn reconstructed(&self) -> bool {
        self.tracks.iter().flatten().any(Option::is_some)
    }

    /// Runs `runs` (indices) of the data with their reconstructions, in that order.
    pub(crate) fn subset(&self, runs: &[usize]) -> Completed<'static> {
        Completed {
            data: Cow::Owned(Dataset {
                runs: runs.iter().map(|&r| self.data.runs[r].clone()).collect(),
            }),
            tracks: runs.iter().map(|&r| self.tracks[r].clone()).collect(),
            motion_misfit: self.motion_misfit,
            delay: self.delay,
            checked_delay: self.checked_delay,
        }
    }

    /// The reconstruction of body `body` in run `run` (index), if it was reconstructed.
    pub fn track(&self, run: usize, body: &str) -> Option<&TrackReconstruction> {
        let index = self.data.runs[run]
            .bodies
            .iter()
            .position(|track| track.body == body)?;
        self.tracks[run][index].as_ref()
    }
}

/// One reconstructed track: the uncertainty of each row and the checks of its contacts.
#[derive(Clone, Debug, PartialEq)]
pub struct TrackReconstruction {
    /// Variance of the position per axis at each row (m²).
    pub(crate) position_variance: Vec<[f64; 3]>,
    /// Variance of the velocity per axis at each row ((m/s)²).
    pub(crate) velocity_variance: Vec<[f64; 3]>,
    /// One check per contact integrated through.
    pub contacts: Vec<ContactCheck>,
}

/// The integration through one contact against the flight fitted after it.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactCheck {
    /// Start and end of the integration (s).
    pub(crate) span: (f64, f64),
    /// Camera frames fitted before and after the contact.
    pub(crate) frames: (usize, usize),
    /// Integrated minus after-flight velocity at the end (m/s), with its standard
    /// deviation per axis; None without `MIN_FRAMES` frames after the contact.
    pub velocity_gap: Option<([f64; 3], [f64; 3])>,
    /// Integrated minus after-flight position at the end (m), with its standard
    /// deviation per axis; None as for the velocity.
    pub(crate) position_gap: Option<([f64; 3], [f64; 3])>,
    /// The force's velocity change over the contact, ∫f/m (m/s), as read (no delay).
    pub(crate) velocity_change: [f64; 3],
}

/// Whether `track` needs reconstructing: a row without position, velocity or force.
fn incomplete(track: &BodyTrack) -> bool {
    track
        .samples
        .iter()
        .any(|s| !(s.has(Channel::Position) && s.has(Channel::Velocity) && s.has(Channel::Force)))
}

/// The data with every incomplete moving body of a contact reconstructed at its force
/// samples (see the module documentation); complete data come back borrowed.
pub fn complete<'a>(model: &Model, data: &'a Dataset) -> Result<Completed<'a>, ReconstructError> {
    complete_with(model, data, Checks::default())
}

/// [`complete`], and what `checks` asks for.
pub(crate) fn complete_with<'a>(
    model: &Model,
    data: &'a Dataset,
    checks: Checks,
) -> Result<Completed<'a>, ReconstructError> {
    let gravity = [model.gravity.x, model.gravity.y, model.gravity.z];
    let mut misfits = Vec::new();
    // Complete tracks checked against Newton's law: (run, body, mass (kg)).
    let mut recorded = Vec::new();
    let mut tracks: Vec<Vec<Option<TrackReconstruction>>> = data
        .runs
        .iter()
        .map(|run| vec![None; run.bodies.len()])
        .collect();
    let mut runs: Vec<Option<Run>> = vec![None; data.runs.len()];
    for (r, run) in data.runs.iter().enumerate() {
        for (b, track) in run.bodies.iter().enumerate() {
            let Some(body) = model.body_index(&track.body) else {
                continue;
            };
            if model.bodies[body].fixed {
                continue;
            }
            let Some(partner) = contact_partner(model, body) else {
                continue;
            };
            if !incomplete(track) {
                if checks.recorded_motion {
                    let mass = model.bodies[body].mass;
                    misfits.extend(super::recorded_motion::misfits(track, gravity, mass));
                    recorded.push((r, b, mass));
                }
                continue;
            }
            let (rebuilt, reconstruction) =
                reconstruct_track(model, (run, track), (body, partner), checks.sensor_delay)?;
            runs[r].get_or_insert_with(|| run.clone()).bodies[b] = rebuilt;
            tracks[r][b] = Some(reconstruction);
        }
    }
    let mut values: Vec<f64> = misfits.iter().map(|m| m.0).collect();
    let motion_misfit = (!values.is_empty()).then(|| median(&mut values));
    // One instrument recorded every track: when its motion fails the check (median over
    // contacts), every contact's motion is replaced — on the clock the checks' pooled
    // delay puts the force on, where that delay is real (a sensor lagging the camera;
    // replaced on the force's own clock, the motion would lag with it and hide it).
    let (mut checked_delay, mut splined_delay) = (None, None);
    if motion_misfit.is_some_and(|m| m > super::newton::MAX_MISFIT) {
        let delays: Vec<f64> = misfits.iter().map(|m| m.1).collect();
        checked_delay = super::delay::pooled(&delays);
        splined_delay = checked_delay.filter(Delay::real);
        for (r, b, mass) in recorded {
            let track = &data.runs[r].bodies[b];
            let (rebuilt, reconstruction) =
                super::recorded_motion::replace_track(track, gravity, mass, splined_delay);
            runs[r].get_or_insert_with(|| data.runs[r].clone()).bodies[b] = rebuilt;
            tracks[r][b] = Some(reconstruction);
        }
    }
    if runs.iter().all(Option::is_none) {
        return Ok(Completed {
            data: Cow::Borrowed(data),
            tracks,
            motion_misfit,
            delay: None,
            checked_delay: None,
        });
    }
    let runs = runs
        .into_iter()
        .zip(&data.runs)
        .map(|(rebuilt, run)| rebuilt.unwrap_or_else(|| run.clone()))
        .collect();
    Ok(Completed {
        data: Cow::Owned(Dataset { runs }),
        tracks,
        motion_misfit,
        delay: checks.sensor_delay.or(splined_delay),
        checked_delay,
    })
}

/// The body across the first contact of `body`, if it is in one.
fn contact_partner(model: &Model, body: usize) -> Option<usize> {
    model
        .contacts
        .iter()
        .find_map(|c| match (c.body_1, c.body_2) {
            (one, two) if one == body => Some(two),
            (one, two) if two == body => Some(one),
            _ => None,
        })
}

/// The force samples on `track`'s body: its own, else the reaction of its partner's.
fn force_samples(run: &Run, track: &BodyTrack, partner: &str) -> Vec<(f64, [f64; 3])> {
    let of = |track: &BodyTrack, sign: f64| -> Vec<(f64, [f64; 3])> {
        track
            .samples
            .iter()
            .filter(|s| s.has(Channel::Force))
            .map(|s| (s.time, s.force.map(|f| sign * f)))
            .collect()
    };
    let own = of(track, 1.0);
    match run.body(partner) {
        Some(other) if own.is_empty() => of(other, -1.0),
        _ => own,
    }
}

/// One track rebuilt at its force samples, and its uncertainty.
fn reconstruct_track(
    model: &Model,
    (run, track): (&Run, &BodyTrack),
    (body, partner): (usize, usize),
    delay: Option<Delay>,
) -> Result<(BodyTrack, TrackReconstruction), ReconstructError> {
    let missing = Channel::ALL
        .into_iter()
        .filter(|&c| matches!(c, Channel::Position | Channel::Velocity | Channel::Force))
        .find(|&c| track.samples.iter().any(|s| !s.has(c)))
        .map_or("force", Channel::name);
    let forces = force_samples(run, track, &model.bodies[partner].name);
    if forces.is_empty() {
        return Err(ReconstructError::NoForce {
            run: run.id.clone(),
            body: track.body.clone(),
            missing,
        });
    }
    let frames: Vec<(f64, [f64; 3])> = track
        .samples
        .iter()
        .filter(|s| s.has(Channel::Position))
        .map(|s| (s.time, s.position))
        .collect();
    let series = ForceSeries::new(forces);
    let gravity = [model.gravity.x, model.gravity.y, model.gravity.z];
    let mass = model.bodies[body].mass;
    let frame_times: Vec<f64> = frames.iter().map(|f| f.0).collect();
    let windows = series.contacts(&frame_times);
    let few = |time: f64, frames: usize| ReconstructError::FewFrames {
        run: run.id.clone(),
        body: track.body.clone(),
        time,
        frames,
    };
    let states = motion(&series, &frames, &windows, (gravity, mass, delay), &few)?;
    let recorded = Recorded::new(track);
    let rows = (0..series.time.len())
        .map(|j| {
            let motion = (states.position[j], states.velocity[j]);
            recorded.row(series.time[j], motion, series.force[j])
        })
        .collect();
    Ok((
        BodyTrack {
            body: track.body.clone(),
            samples: rows,
        },
        TrackReconstruction {
            position_variance: states.position_variance,
            velocity_variance: states.velocity_variance,
            contacts: states.checks,
        },
    ))
}

/// Position, velocity and their variances at every force sample, and the checks.
struct Motion {
    position: Vec<[f64; 3]>,
    velocity: Vec<[f64; 3]>,
    position_variance: Vec<[f64; 3]>,
    velocity_variance: Vec<[f64; 3]>,
    checks: Vec<ContactCheck>,
}

/// The flight fitted to the frames strictly between `from` and `to` (s), the nearest
/// [`MAX_FLIGHT_FRAMES`] to `t_ref`, and how many frames there were.
fn flight(
    frames: &[(f64, [f64; 3])],
    (from, to): (f64, f64),
    gravity: [f64; 3],
    t_ref: f64,
) -> (Option<FlightFit>, usize) {
    let mut inside: Vec<(f64, [f64; 3])> = frames
        .iter()
        .copied()
        .filter(|f| f.0 > from && f.0 < to)
        .collect();
    inside.sort_by(|a, b| (a.0 - t_ref).abs().total_cmp(&(b.0 - t_ref).abs()));
    inside.truncate(MAX_FLIGHT_FRAMES);
    (FlightFit::fit(&inside, gravity, t_ref), inside.len())
}

/// The motion at every force sample: flight fits between contacts, Newton's law
/// through them.
fn motion(
    series: &ForceSeries,
    frames: &[(f64, [f64; 3])],
    windows: &[(usize, usize)],
    (gravity, mass, delay): ([f64; 3], f64, Option<Delay>),
    few: &dyn Fn(f64, usize) -> ReconstructError,
) -> Result<Motion, ReconstructError> {
    let n = series.time.len();
    let mut out = Motion {
        position: vec![[0.0; 3]; n],
        velocity: vec![[0.0; 3]; n],
        position_variance: vec![[0.0; 3]; n],
        velocity_variance: vec![[0.0; 3]; n],
        checks: Vec::new(),
    };
    let time = |j: usize| series.time[j];
    let set_flight = |out: &mut Motion, fit: &FlightFit, range: std::ops::Range<usize>| {
        for j in range {
            (out.position[j], out.velocity[j]) = fit.state(time(j));
            (out.position_variance[j], out.velocity_variance[j]) = fit.variance(time(j));
        }
    };
    let mut previous_end = f64::NEG_INFINITY;
    let mut next_row = 0;
    for (w, &(first, last)) in windows.iter().enumerate() {
        let next_start = windows.get(w + 1).map_or(f64::INFINITY, |x| time(x.0));
        let (before, count) = flight(frames, (previous_end, time(first)), gravity, time(first));
        let before = before.ok_or_else(|| few(time(first), count))?;
        set_flight(&mut out, &before, next_row..first);
        let mut through = integrate(series, (first, last), &before, mass);
        let velocity_change = core::array::from_fn(|k| {
            through.velocity[last - first][k] - before.state(time(last)).1[k]
        });
        if let Some(delay) = delay {
            let acceleration: Vec<[f64; 3]> = (first..=last)
                .map(|j| core::array::from_fn(|k| series.force[j][k] / mass + gravity[k]))
                .collect();
            let times = &series.time[first..=last];
            super::delay::shift(&mut through, times, &acceleration, &before, delay);
        }
        for (i, j) in (first..=last).enumerate() {
            out.position[j] = through.position[i];
            out.velocity[j] = through.velocity[i];
            out.position_variance[j] = through.position_variance[i];
            out.velocity_variance[j] = through.velocity_variance[i];
        }
        let (after, after_count) = flight(frames, (time(last), next_start), gravity, time(last));
        let mut checked = check(
            &through,
            after.as_ref(),
            (time(first), time(last)),
            (count, after_count),
        );
        checked.velocity_change = velocity_change;
        out.checks.push(checked);
        next_row = last + 1;
        previous_end = time(last);
        if let Some(after) = after {
            // Up to half-way to the next contact; its own flight fit takes over there.
            let half = 0.5 * (time(last) + next_start);
            let end = (next_row..n).find(|&j| time(j) > half).unwrap_or(n);
            set_flight(&mut out, &after, next_row..end);
            next_row = end;
        }
    }
    if next_row < n {
        // Beyond the last contact without frames after it, or no contact at all: the
        // flight through the frames there.
        let (fit, count) = flight(
            frames,
            (previous_end, f64::INFINITY),
            gravity,
            time(next_row),
        );
        let fit = fit.ok_or_else(|| few(time(next_row), count))?;
        set_flight(&mut out, &fit, next_row..n);
    }
    Ok(out)
}

/// The integrated end state against the flight after the contact.
fn check(
    through: &super::through_contact::Integrated,
    after: Option<&FlightFit>,
    span: (f64, f64),
    frames: (usize, usize),
) -> ContactCheck {
    let gap = |after: &FlightFit| {
        let (p, v) = after.state(span.1);
        let (var_p, var_v) = after.variance(span.1);
        let end = through.position.len() - 1;
        let sd = |a: [f64; 3], b: [f64; 3]| -> [f64; 3] {
            core::array::from_fn(|k| (a[k] + b[k]).sqrt())
        };
        (
            (
                core::array::from_fn(|k| through.velocity[end][k] - v[k]),
                sd(var_v, through.velocity_variance[end]),
            ),
            (
                core::array::from_fn(|k| through.position[end][k] - p[k]),
                sd(var_p, through.position_variance[end]),
            ),
        )
    };
    let gaps = after.map(gap);
    ContactCheck {
        span,
        frames,
        velocity_gap: gaps.map(|g| g.0),
        position_gap: gaps.map(|g| g.1),
        velocity_change: [0.0; 3],
    }
}

/// What a reconstructed row takes from the recorded rows: orientation and angular
/// velocity from the nearest frame that has them, torque where it was measured.
struct Recorded {
    orientation: Vec<(f64, [f64; 4])>,
    angular_velocity: Vec<(f64, [f64; 3])>,
    torque: Vec<(f64, [f64; 3])>,
}

impl Recorded {
    fn new(track: &BodyTrack) -> Self {
        let with = |channel: Channel| track.samples.iter().filter(move |s| s.has(channel));
        Recorded {
            orientation: with(Channel::Orientation)
                .map(|s| (s.time, s.orientation))
                .collect(),
            angular_velocity: with(Channel::AngularVelocity)
                .map(|s| (s.time, s.angular_velocity))
                .collect(),
            torque: with(Channel::Torque).map(|s| (s.time, s.torque)).collect(),
        }
    }

    /// The row at `time` (s) with the reconstructed motion and the measured force (N).
    fn row(
        &self,
        time: f64,
        (position, velocity): ([f64; 3], [f64; 3]),
        force: [f64; 3],
    ) -> Sample {
        fn nearest<T: Copy>(values: &[(f64, T)], time: f64) -> Option<T> {
            let after = values.partition_point(|v| v.0 <= time);
            let before = after.checked_sub(1).and_then(|i| values.get(i));
            before.or(values.get(after)).map(|v| v.1)
        }
        let mut sample = Sample::at_rest(time);
        sample.position = position;
        sample.velocity = velocity;
        sample.force = force;
        if let Some(orientation) = nearest(&self.orientation, time) {
            sample.orientation = orientation;
        }
        if let Some(omega) = nearest(&self.angular_velocity, time) {
            sample.angular_velocity = omega;
        }
        let at = self.torque.partition_point(|v| v.0 < time);
        if let Some(&(_, torque)) = self.torque.get(at).filter(|v| v.0 == time) {
            sample.torque = torque;
        }
        sample
    }
}
