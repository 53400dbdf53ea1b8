//! A toss's window: the frames a prediction is judged on. It starts
//! [`LEAD_FRAMES`] frames before the body's centre first comes within its circumscribed
//! radius of a fixed body it can touch (0.0524·√3 m of the table for the ContactNets
//! cube) — before that frame no corner can touch, so the motion is free flight, which
//! the simulator predicts exactly and which would flatter any score — and to run to the
//! toss's last frame. A plane's clearance is measured from its reference point (the
//! table of the data's frame, z = 0 for the tosses), not from its contact surface, which
//! a fitted offset moves: the frames scored are the data's, whatever the model
//! ([`super::partner`]). With several moving bodies, the first contact of any
//! of them starts the window, one instant for all; a contact already within reach in
//! the first frame (a block resting on the table) does not.

use super::initial_state::orientation;
use super::partner::Partner;
use super::{TossError, TossSetup};
use crate::dataset::{BodyTrack, Channel, Sample};
use nalgebra::Vector3;

/// The fewest frames a window holds (–): its start, from which the replay runs, and
/// one frame to compare the replay with.
pub const MIN_FRAMES: usize = 2;

/// Frames the window starts before the first frame within reach of a fixed body (–).
pub const LEAD_FRAMES: usize = 3;

/// One toss's window, as indices into its body track's samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    /// First frame of the window: [`LEAD_FRAMES`] before `near`, or the toss's first
    /// frame if it has fewer before `near`.
    pub start: usize,
    /// First frame whose centre lies within the circumscribed radius of a fixed body.
    pub near: usize,
    /// Frames in the toss (the window runs from `start` to the last).
    pub frames: usize,
}

impl Window {
    /// Frames in the window (–).
    pub fn len(&self) -> usize {
        self.frames - self.start
    }

    /// Whether the window holds no frame (never, for a window [`find_window`] made).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The window of `run`'s track of the primary body alone ([`find_windows`] with one
/// track: its fixed partners only).
pub fn find_window(setup: &TossSetup, run: &str, track: &BodyTrack) -> Result<Window, TossError> {
    Ok(windows(setup, run, &[track])?[0].0)
}

/// The windows of `run`'s tracks, `tracks[m]` of `setup.movers[m]` (a mover past the
/// end of `tracks` is left out), as indices into each track. The window starts
/// [`LEAD_FRAMES`] frames before the first frame where a body comes within its
/// circumscribed radius of a body it can touch (a fixed partner, or another mover at
/// its recorded pose in the frame nearest in time), or turned away from one within a
/// frame's travel of touching it (a bounce between two frames); contacts already within
/// reach in a body's first frame, or within `RESTING` of its radius (a block or a ball
/// resting on the table), do not start it, unless no other contact ever comes. Every mover's window starts at the same time; a toss
/// with no contact at all is an error naming the run and the primary's lowest
/// clearance.
pub fn find_windows(
    setup: &TossSetup,
    run: &str,
    tracks: &[&BodyTrack],
) -> Result<Vec<Window>, TossError> {
    Ok(windows(setup, run, tracks)?
        .into_iter()
        .map(|w| w.0)
        .collect())
}

/// [`find_windows`], each window with whether its body is within reach of another at
/// the window start, or within [`RESTING`] of its radius (supported: resting, rolling
/// or sliding on it, not in free flight).
pub(crate) fn windows(
    setup: &TossSetup,
    run: &str,
    tracks: &[&BodyTrack],
) -> Result<Vec<(Window, bool)>, TossError> {
    // Earliest (time, mover, frame) of a new contact, and of any contact.
    let mut fresh: Option<(f64, usize, usize)> = None;
    let mut any: Option<(f64, usize, usize)> = None;
    let mut lowest = (f64::INFINITY, f64::NAN);
    let mut reach = Vec::with_capacity(tracks.len());
    for (m, track) in tracks.iter().enumerate() {
        let pairs = pair_margins(setup, m, tracks, run)?;
        let frames = track.samples.len();
        let nearest = |keep: &dyn Fn(&Vec<f64>) -> bool| -> Vec<f64> {
            (0..frames)
                .map(|k| {
                    (pairs.iter().filter(|p| keep(p)))
                        .map(|p| p[k])
                        .fold(f64::INFINITY, f64::min)
                })
                .collect()
        };
        let all = nearest(&|_| true);
        let resting = RESTING * setup.movers[m].radius;
        let new = nearest(&|p| p.first().is_some_and(|&c| c >= resting));
        if m == 0 {
            for (k, &c) in all.iter().enumerate() {
                if c + setup.radius < lowest.0 {
                    lowest = (c + setup.radius, track.samples[k].time);
                }
            }
        }
        let earliest = |best: &mut Option<(f64, usize, usize)>, k: Option<usize>| {
            if let Some(k) = k {
                let time = track.samples[k].time;
                if best.is_none_or(|b| time < b.0) {
                    *best = Some((time, m, k));
                }
            }
        };
        earliest(&mut fresh, first_near(&new, track));
        earliest(&mut any, first_near(&all, track));
        reach.push(all);
    }
    let Some((near_time, m, k)) = fresh.or(any) else {
        return Err(TossError::NoContact {
            run: run.to_owned(),
            body: setup.name.clone(),
            threshold: setup.radius,
            lowest: lowest.0,
            lowest_time: lowest.1,
        });
    };
    let start_time = tracks[m].samples[k.saturating_sub(LEAD_FRAMES)].time;
    (tracks.iter().zip(&setup.movers).zip(&reach))
        .map(|((track, mover), all)| {
            let at = |t: f64| (track.samples).partition_point(|s| s.time < t - SAME_TIME);
            let start = at(start_time);
            if start == track.samples.len() {
                return Err(TossError::Frame {
                    run: run.to_owned(),
                    time: start_time,
                    problem: format!(
                        "body `{}` has no frame at or after the window start; every moving \
                         body needs the camera's pose through the toss",
                        mover.name
                    ),
                });
            }
            let window = Window {
                start,
                near: at(near_time).max(start),
                frames: track.samples.len(),
            };
            long_enough(&window, run, start_time, &mover.name)?;
            Ok((window, all[start] < RESTING * mover.radius))
        })
        .collect()
}

/// Refuses a window of fewer than [`MIN_FRAMES`] frames of `body` in `run`, starting
/// at `time` (s): a toss of one frame would score a perfect 0.
fn long_enough(window: &Window, run: &str, time: f64, body: &str) -> Result<(), TossError> {
    if window.len() >= MIN_FRAMES {
        return Ok(());
    }
    Err(TossError::Frame {
        run: run.to_owned(),
        time,
        problem: format!(
            "body `{body}` has {} frame from the window start on; a toss is scored on the \
             frames after its start and needs at least {MIN_FRAMES} there (the start and \
             one to compare): leave the run out or give it its whole recording",
            window.len()
        ),
    })
}

/// A pair whose margin in a body's first frame is below this share of the body's
/// radius (–) is resting, not about to touch: a ball laid on a table is tracked a
/// fraction of a millimetre above it as often as below.
const RESTING: f64 = 0.02;

/// Two frames' times closer than this are the same instant (s): the data's times are
/// rounded to 1e-12 s.
const SAME_TIME: f64 = 1e-9;

/// How far mover `m` is, frame by frame, from touching each body it can touch (m): a
/// lower bound on the gap, negative when the bodies may touch. From a fixed partner: the
/// clearance of its centre less its circumscribed radius. From another mover (at its
/// recorded pose in the frame nearest in time): the larger of the two such bounds, each
/// body's centre from the other's surface less its own radius (a ball beside a block
/// is judged by the ball's centre and radius, not by the block's corners). Every frame
/// of `m` must hold a position.
fn pair_margins(
    setup: &TossSetup,
    m: usize,
    tracks: &[&BodyTrack],
    run: &str,
) -> Result<Vec<Vec<f64>>, TossError> {
    let mover = &setup.movers[m];
    let mut positions = Vec::with_capacity(tracks[m].samples.len());
    for sample in &tracks[m].samples {
        if !sample.has(Channel::Position) {
            return Err(TossError::Frame {
                run: run.to_owned(),
                time: sample.time,
                problem: format!(
                    "body `{}` has no position (px, py, pz empty): a toss needs the camera's \
                     pose in every frame",
                    mover.name
                ),
            });
        }
        positions.push(Vector3::from(sample.position));
    }
    let mut pairs: Vec<Vec<f64>> = (mover.partners.iter())
        .map(|p| {
            (positions.iter())
                .map(|x| p.clearance(x) - mover.radius)
                .collect()
        })
        .collect();
    for &j in mover.touches.iter().filter(|&&j| j < tracks.len()) {
        let other = &setup.movers[j];
        let mut series = Vec::with_capacity(positions.len());
        for (sample, x) in tracks[m].samples.iter().zip(&positions) {
            let missing = || TossError::MissingBody {
                run: run.to_owned(),
                body: other.name.clone(),
            };
            let frame = nearest_frame(tracks[j], sample.time).ok_or_else(missing)?;
            let y = Vector3::from(frame.position);
            let theirs = orientation(&other.name, run, frame)?;
            let mine = orientation(&mover.name, run, sample)?;
            let from_them = Partner::at(other.body, other.shape.clone(), y, theirs);
            let from_me = Partner::at(mover.body, mover.shape.clone(), *x, mine);
            let gap =
                (from_them.clearance(x) - mover.radius).max(from_me.clearance(&y) - other.radius);
            series.push(gap);
        }
        pairs.push(series);
    }
    Ok(pairs)
}

/// The frame of `track` nearest in time to `time` (s); `None` for an empty track.
fn nearest_frame(track: &BodyTrack, time: f64) -> Option<&Sample> {
    let after = track.samples.partition_point(|s| s.time < time);
    let candidates = [after.checked_sub(1), Some(after)];
    (candidates.into_iter().flatten())
        .filter_map(|k| track.samples.get(k))
        .min_by(|a, b| (a.time - time).abs().total_cmp(&(b.time - time).abs()))
}

/// The first frame of `track` whose margin (m, per frame: [`pair_margins`]) says it may
/// touch, or where the body turned away within a frame's travel of touching.
fn first_near(margins: &[f64], track: &BodyTrack) -> Option<usize> {
    let position = |k: usize| Vector3::from(track.samples[k].position);
    (0..margins.len()).find(|&k| {
        let c = margins[k];
        // A contact shorter than a frame (a ball's bounce) may fall between two frames
        // that both lie beyond reach: the frame where the body turned away from its
        // partner within one frame's travel of touching it counts too.
        let turned = k > 0
            && k + 1 < margins.len()
            && margins[k - 1] >= c
            && c < margins[k + 1]
            && c < (position(k + 1) - position(k)).norm();
        c < 0.0 || turned
    })
}
