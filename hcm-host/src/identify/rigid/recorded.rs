//! A rigid contact as the rig recorded it (for least squares point by
//! point at the recorded poses): at every sample where the moving body's recorded pose touches the
//! other body, the contact points the scenario's geometry gives there — depth δ (m),
//! rate δ̇ (m/s), normal, slip velocity (m/s) — and the wrench the sensor measured on the
//! moving body.
//!
//! The points depend on the poses alone, never on the law's parameters, so they are
//! built once and a candidate law is judged by [`ContactModel::pair_load`] on them:
//! thousands of candidates per second, no simulation.
//!
//! **History.** Each point's approach speed δ̇0 (Lankarani–Nikravesh, Flores) and
//! deepest indentation δ_max (plasticity) are latched along each run in time order, as
//! the simulator latches them after each step ([`crate::simulate::RigidSystem::latch`]);
//! a point's δ̇0 is its δ̇ at the first sample that touches, so with samples sparse
//! against a contact's duration the memory laws read the approach speed late. IMPACT
//! and Hertz-type laws without memory are exact at every sample.
//!
//! **The measured wrench** is the moving body's force and torque channels (N, N·m
//! about its centre of mass, world frame) where it has them, else a force plate's: the
//! fixed body's channels, turned into the wrench on the mover (F_m = −F_p,
//! T_m = −T_p + (p_m − p_p) × F_p, p the bodies' centres (m)). Every instant with a
//! measured force is a row; the mover's state there is its own sample where that has
//! every motion channel, else read from its frames at their own rate
//! ([`crate::dataset::state::Frames`]: velocities differentiated where the tracker
//! gives none).
//!
//! [`ContactModel::pair_load`]: hcm_core::model::ContactModel::pair_load

use super::RigidIdentifyError;
use crate::dataset::state_input;
use crate::dataset::Frames;
use crate::dataset::{BodyTrack, Channel, Dataset, Run, Sample};
use crate::experiment::{read_by_sensor, sensor_is_exact};
use crate::scenario::Model;
use crate::simulate::{RigidLayout, RigidSystem};
use hcm_core::model::Manifold;
use nalgebra::Vector3;
use rayon::prelude::*;

/// Largest time difference (s, relative to the time) between a pose sample and a force
/// plate's sample taken as the same instant.
const SAME_INSTANT: f64 = 1e-9;

/// One touching sample.
#[derive(Clone, Debug)]
pub struct RecordedSample {
    /// Index of its run in the data.
    pub run: usize,
    /// Time (s).
    pub time: f64,
    /// The contact's touching points at the recorded poses, histories latched.
    pub(crate) points: Manifold<f64>,
    /// Body 1's and body 2's centres (m): the torques' reference points.
    pub(crate) references: [Vector3<f64>; 2],
    /// The measured force (N) and torque (N·m, about the mover's centre of mass) on
    /// the mover, world frame; a torque not measured is NaN.
    pub measured: [f64; 6],
    /// The mover's recorded state as the integrator holds it (the residual's Eq 12
    /// input, [`state_input`]).
    pub state: [f64; crate::dataset::STATE_INPUTS],
    /// Whether that state was read between the mover's frames rather than recorded at
    /// this instant.
    pub between_frames: bool,
}

/// Every touching sample of one contact.
#[derive(Clone, Debug)]
pub struct RecordedContact {
    /// Index of the contact in the model.
    pub contact: usize,
    /// Whether the mover is the contact's body 1.
    mover_is_1: bool,
    /// The rows, runs in file order and samples in time order.
    pub samples: Vec<RecordedSample>,
    /// Runs in the data.
    pub runs: usize,
    /// RMS of the measured force's magnitude over the rows (N): the force residuals'
    /// unit.
    pub force_scale: f64,
    /// RMS of the measured torque's magnitude (N·m), 0 when no row has torque.
    pub torque_scale: f64,
}

impl RecordedContact {
    /// Contact `c`'s touching samples in `data`, with `model`'s geometry. Errors: no
    /// such contact, not one moving body against a fixed one, a run without the
    /// mover's track, or no row with a pose, velocities and a measured force — each
    /// naming the channel or body that is missing.
    pub fn from_data(
        model: &Model,
        data: &Dataset,
        c: usize,
    ) -> Result<RecordedContact, RigidIdentifyError> {
        Self::with_rows(model, data, c, false)
    }

    /// [`Self::from_data`], with the samples out of contact too when `flight` (no
    /// points: the model predicts no wrench there, and a sensor's offset shows alone).
    pub fn with_rows(
        model: &Model,
        data: &Dataset,
        c: usize,
        flight: bool,
    ) -> Result<RecordedContact, RigidIdentifyError> {
        let (mover, plate) = sensor_body(model, data, c)?;
        let mover_name = model.bodies[mover].name.clone();
        let plate_name = &model.bodies[plate].name;
        let mut physics = model.clone();
        physics.contacts[c].model.residual = None;
        let layout = RigidLayout::new(&physics);
        let per_run: Vec<Vec<RecordedSample>> = (data.runs.iter().enumerate())
            .collect::<Vec<_>>()
            .par_iter()
            .map(|&(r, run)| {
                let track = run
                    .body(&mover_name)
                    .ok_or_else(|| missing_body(run, &mover_name))?;
                let others = (0..physics.bodies.len())
                    .filter(|&b| b != mover && !physics.bodies[b].fixed)
                    .map(|b| {
                        let name = &physics.bodies[b].name;
                        let track = run.body(name).ok_or_else(|| missing_body(run, name))?;
                        Ok((b, Frames::of(&track.samples)))
                    })
                    .collect::<Result<Vec<_>, RigidIdentifyError>>()?;
                let rig = Rig {
                    model: &physics,
                    layout: &layout,
                    c,
                    mover,
                    plate: run.body(plate_name),
                    plate_body: plate,
                    others,
                    flight,
                };
                Ok(rig.rows(r, track))
            })
            .collect::<Result<_, RigidIdentifyError>>()?;
        let samples: Vec<RecordedSample> = per_run.into_iter().flatten().collect();
        if samples.is_empty() {
            return Err(RigidIdentifyError::Setup(format!(
                "no instant with a measured force (fx, fy, fz of `{mover_name}` or of \
                 `{plate_name}`) falls within the frames of `{mover_name}` (position and \
                 orientation) while it touches `{plate_name}` at the scenario's geometry: \
                 the fit from force samples has nothing to fit. Check the channels \
                 (each command prints what it found), the bodies' geometry in the scenario, or \
                 fit from the motion alone with `hcm identify-motion`"
            )));
        }
        if !samples.iter().any(|s| !s.points.is_empty()) {
            return Err(RigidIdentifyError::Setup(format!(
                "no sample of body `{mover_name}` touches `{plate_name}` at the scenario's \
                 geometry: check the bodies' shapes and the fixed body's pose"
            )));
        }
        let (force_scale, torque_scale) = (rms(&samples, 0..3), rms(&samples, 3..6));
        Ok(RecordedContact {
            contact: c,
            mover_is_1: mover == model.contacts[c].body_1,
            samples,
            runs: data.runs.len(),
            force_scale,
            torque_scale,
        })
    }

    /// Whether the mover is the contact's body 1 (its centre is `references[0]`).
    pub fn mover_is_1(&self) -> bool {
        self.mover_is_1
    }

    /// The rows of the runs `keep` says to keep, as a contact of their own (the scales
    /// kept: a fit on a part weighs force and torque as on the whole).
    pub fn part(&self, keep: impl Fn(usize) -> bool) -> RecordedContact {
        let mut out = self.clone();
        out.samples.retain(|s| keep(s.run));
        out
    }

    /// The wrench (force (N), torque (N·m) about the mover's centre, world frame) that
    /// `candidate`'s contact (physics only) exerts on the mover at `sample`.
    pub fn predicted(&self, candidate: &Model, sample: &RecordedSample) -> [f64; 6] {
        let contact = &candidate.contacts[self.contact].model;
        let [r1, r2] = &sample.references;
        let load = contact.pair_load(&sample.points, r1, r2, &[]);
        let w = &load.wrench;
        let (f, t) = if self.mover_is_1 {
            (w.force_1, w.torque_1)
        } else {
            (w.force_2, w.torque_2)
        };
        [f.x, f.y, f.z, t.x, t.y, t.z]
    }

    /// What `candidate`'s sensor reads at every row: its contact's wrench on the mover
    /// ([`Self::predicted`]) read, run by run over the run's rows, by the sensor the
    /// scenario's `[experiment]` keys describe — the one `hcm generate` records
    /// through ([`read_by_sensor`]). An exact sensor reads the wrench itself.
    pub fn readings(&self, candidate: &Model) -> Vec<[f64; 6]> {
        let mut read: Vec<[f64; 6]> = (self.samples.iter())
            .map(|s| self.predicted(candidate, s))
            .collect();
        let sensor = &candidate.scenario.experiment;
        if sensor_is_exact(sensor) {
            return read;
        }
        let mut first = 0;
        while first < self.samples.len() {
            let run = self.samples[first].run;
            let end = first
                + (self.samples[first..].iter())
                    .take_while(|s| s.run == run)
                    .count();
            let mut track: Vec<Sample> = (self.samples[first..end].iter())
                .zip(&read[first..end])
                .map(|(s, r)| {
                    let mut sample = Sample::unsampled(s.time);
                    sample.force = [r[0], r[1], r[2]];
                    sample.torque = [r[3], r[4], r[5]];
                    sample
                })
                .collect();
            read_by_sensor(sensor, &mut track);
            for (r, s) in read[first..end].iter_mut().zip(&track) {
                *r = [
                    s.force[0],
                    s.force[1],
                    s.force[2],
                    s.torque[0],
                    s.torque[1],
                    s.torque[2],
                ];
            }
            first = end;
        }
        read
    }

    /// The weighted residuals of `candidate`: per row, (measured − read) force over
    /// [`Self::force_scale`] and torque over [`Self::torque_scale`] (0 where the
    /// torque was not measured); `out` holds 6 per row. See [`Self::readings`].
    pub fn residuals(&self, candidate: &Model, out: &mut [f64]) {
        let read = self.readings(candidate);
        for ((sample, got), row) in self.samples.iter().zip(&read).zip(out.chunks_exact_mut(6)) {
            for k in 0..6 {
                let scale = if k < 3 {
                    self.force_scale
                } else {
                    self.torque_scale
                };
                let error = sample.measured[k] - got[k];
                row[k] = if error.is_finite() && scale > 0.0 {
                    error / scale
                } else {
                    0.0
                };
            }
        }
    }
}

/// RMS over `samples` of the magnitude of `part` of the measured wrench (0..3 the
/// force, 3..6 the torque), over the rows that have it; 0 for none.
fn rms(samples: &[RecordedSample], part: std::ops::Range<usize>) -> f64 {
    let rows = samples
        .iter()
        .filter(|s| s.measured[part.clone()][0].is_finite());
    let (sum, n) = rows.fold((0.0, 0usize), |(sum, n), s| {
        let v = &s.measured[part.clone()];
        (sum + v.iter().map(|x| x * x).sum::<f64>(), n + 1)
    });
    if n == 0 {
        0.0
    } else {
        (sum / n as f64).sqrt()
    }
}

/// What the rows of one run are built from.
struct Rig<'a> {
    model: &'a Model,
    layout: &'a RigidLayout,
    c: usize,
    mover: usize,
    /// The other body's track (a force plate, or a moving partner), if the run has one.
    plate: Option<&'a BodyTrack>,
    /// The other body's index.
    plate_body: usize,
    /// Every other moving body with its frames: their states at each row are read
    /// from them (a moving partner's, and those of the mover's other contacts).
    others: Vec<(usize, Frames)>,
    /// Whether samples out of contact are rows too.
    flight: bool,
}

impl Rig<'_> {
    /// The run's touching rows, its point histories latched sample by sample: one row
    /// per instant a force was measured (the mover's own rows, or the plate's), with
    /// the mover's state there — its own sample where it has every motion channel,
    /// else read from its frames ([`Frames`]).
    fn rows(&self, run: usize, track: &BodyTrack) -> Vec<RecordedSample> {
        let mut system = RigidSystem::new(self.model, self.layout);
        let mut y = self.layout.initial_state(self.model).0;
        let Some(slot) = self.layout.slot(self.mover) else {
            return Vec::new();
        };
        let frames = Frames::of(&track.samples);
        let mut rows = Vec::new();
        for (time, reading) in self.readings(track) {
            let (state_sample, between_frames) = match reading {
                Reading::Own(sample) if full_state(sample) => (sample.clone(), false),
                _ => match frames.at(time) {
                    Some(s) => {
                        let recorded = frames.recorded_at(time);
                        (s, !recorded)
                    }
                    None => continue,
                },
            };
            let state = state_input(&state_sample);
            y[slot..slot + state.len()].copy_from_slice(&state);
            if !self.place_others(&mut y, time) {
                continue;
            }
            let manifold = system.manifold(&y, self.c);
            system.latch(&y);
            if manifold.points.is_empty() && !self.flight {
                continue;
            }
            let plate_position = self.position_of(&y, self.plate_body);
            let mut measured = self.measured(&reading, &state_sample, plate_position);
            self.subtract_other_contacts(&system, &y, &mut measured);
            rows.push(RecordedSample {
                run,
                time,
                points: manifold.points,
                references: [manifold.pose_1.position, manifold.pose_2.position],
                measured,
                state,
                between_frames,
            });
        }
        rows
    }

    /// Every instant with a measured force, in time order: the mover's own rows with
    /// a force, and the plate's rows with a force at instants the mover has no force.
    fn readings<'t>(&'t self, track: &'t BodyTrack) -> Vec<(f64, Reading<'t>)> {
        let mut out: Vec<(f64, Reading<'t>)> = (track.samples.iter())
            .filter(|s| s.has(Channel::Force))
            .map(|s| (s.time, Reading::Own(s)))
            .collect();
        let own = out.len();
        if let Some(plate) = self.plate {
            let taken = |t: f64| {
                let at = out[..own]
                    .partition_point(|(time, _)| *time < t - SAME_INSTANT * t.abs().max(1.0));
                out[..own]
                    .get(at)
                    .is_some_and(|(time, _)| (time - t).abs() <= SAME_INSTANT * t.abs().max(1.0))
            };
            let extra: Vec<(f64, Reading<'t>)> = (plate.samples.iter())
                .filter(|s| s.has(Channel::Force) && !taken(s.time))
                .map(|s| (s.time, Reading::Plate(s)))
                .collect();
            out.extend(extra);
            out.sort_by(|a, b| a.0.total_cmp(&b.0));
        }
        out
    }

    /// Puts every other moving body at its state at `time`, read from its frames;
    /// false where one has no frame around `time` (the row is skipped).
    fn place_others(&self, y: &mut [f64], time: f64) -> bool {
        for (body, frames) in &self.others {
            let (Some(slot), Some(sample)) = (self.layout.slot(*body), frames.at(time)) else {
                return false;
            };
            let state = state_input(&sample);
            y[slot..slot + state.len()].copy_from_slice(&state);
        }
        true
    }

    /// Centre (m) of body `b` in state `y`: its slot's position, or the scenario's
    /// where it is fixed.
    fn position_of(&self, y: &[f64], b: usize) -> Vector3<f64> {
        match self.layout.slot(b) {
            Some(slot) => Vector3::new(y[slot], y[slot + 1], y[slot + 2]),
            None => self.model.bodies[b].position,
        }
    }

    /// Removes from `measured` (the wrench on the mover) what the mover's other
    /// contacts exert at `y` with the scenario's physics: a body touching two others
    /// feels both, and the fitted contact is the rest.
    fn subtract_other_contacts(
        &self,
        system: &RigidSystem<'_>,
        y: &[f64],
        measured: &mut [f64; 6],
    ) {
        for (oc, contact) in self.model.contacts.iter().enumerate() {
            let on_mover_1 = contact.body_1 == self.mover;
            if oc == self.c || !(on_mover_1 || contact.body_2 == self.mover) {
                continue;
            }
            let load = system.contact_load(y, oc);
            let w = &load.load.wrench;
            let (f, t) = if on_mover_1 {
                (w.force_1, w.torque_1)
            } else {
                (w.force_2, w.torque_2)
            };
            for (k, v) in [f.x, f.y, f.z, t.x, t.y, t.z].into_iter().enumerate() {
                measured[k] -= v;
            }
        }
    }

    /// The wrench measured on the mover by `reading`, the mover at `state`: its own
    /// channels, or the plate's (at `plate_position`, m) turned onto the mover.
    fn measured(
        &self,
        reading: &Reading<'_>,
        state: &Sample,
        plate_position: Vector3<f64>,
    ) -> [f64; 6] {
        match reading {
            Reading::Own(sample) => {
                let [fx, fy, fz] = sample.force;
                let [tx, ty, tz] = sample.torque;
                [fx, fy, fz, tx, ty, tz]
            }
            Reading::Plate(reading) => {
                let force = Vector3::from(reading.force);
                let arm = Vector3::from(state.position) - plate_position;
                let torque = -Vector3::from(reading.torque) + arm.cross(&force);
                [-force.x, -force.y, -force.z, torque.x, torque.y, torque.z]
            }
        }
    }
}

/// The body of contact `c` whose wrench the rows hold (the *mover*) and the other: the
/// moving one against a fixed body; of two moving bodies, the first whose track in
/// `data` has a force channel (body 1 first), the other's sensor read as a force plate
/// on the partner otherwise.
fn sensor_body(
    model: &Model,
    data: &Dataset,
    c: usize,
) -> Result<(usize, usize), RigidIdentifyError> {
    let contact = model
        .contacts
        .get(c)
        .ok_or(RigidIdentifyError::NoSuchContact(c))?;
    let (b1, b2) = (contact.body_1, contact.body_2);
    let has_force = |b: usize| {
        let name = &model.bodies[b].name;
        (data.runs.iter())
            .filter_map(|r| r.body(name))
            .any(|t| t.samples.iter().any(|s| s.has(Channel::Force)))
    };
    match (model.bodies[b1].fixed, model.bodies[b2].fixed) {
        (false, true) => Ok((b1, b2)),
        (true, false) => Ok((b2, b1)),
        (false, false) if has_force(b1) || !has_force(b2) => Ok((b1, b2)),
        (false, false) => Ok((b2, b1)),
        (true, true) => Err(RigidIdentifyError::NotOneMover(format!(
            "{}–{}",
            model.bodies[b1].name, model.bodies[b2].name
        ))),
    }
}

/// Where a row's force comes from.
enum Reading<'a> {
    /// The mover's own sample.
    Own(&'a Sample),
    /// The plate's (the fixed body's) sample.
    Plate(&'a Sample),
}

/// Whether `sample` has every motion channel of a rigid state.
fn full_state(sample: &Sample) -> bool {
    [
        Channel::Position,
        Channel::Orientation,
        Channel::Velocity,
        Channel::AngularVelocity,
    ]
    .iter()
    .all(|&ch| sample.has(ch))
}

/// The error for a run without the mover's track.
fn missing_body(run: &Run, body: &str) -> RigidIdentifyError {
    RigidIdentifyError::Setup(format!(
        "run `{}` has no samples of body `{body}`, the contact's moving body: the data's \
         `body` column names it differently, or the run does not record it (bodies in the \
         run: {})",
        run.id,
        run.bodies
            .iter()
            .map(|b| format!("`{}`", b.body))
            .collect::<Vec<_>>()
            .join(", ")
    ))
}
