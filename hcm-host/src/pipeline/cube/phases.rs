//! The phases of a recorded toss, from the recorded poses alone (never from a
//! prediction, so that every model is judged on the same frames):
//!
//! - **flight**: the window's frames before the centre first comes within the body's
//!   circumscribed radius of the table (no corner can touch yet);
//! - **first impact**: from that frame to `IMPACT_AFTER` frames after the recorded
//!   centre stops falling (its first frame whose height the next frame does not go
//!   below): the landing and the rebound that follows it;
//! - **sliding/tumbling**: from there until the body settles;
//! - **settling**: the frames from which the recorded motion stays nearly at rest to the
//!   toss's end — every later frame is followed, over `REST_SPAN` frames, by a centre
//!   moving less than `REST_DISTANCE` of the body's width and an orientation turning
//!   less than `REST_ANGLE`.
//!
//! Each frame of the window is in exactly one phase; a phase may be empty for a toss
//! (a body still moving at the end of its recording never settles).

use crate::dataset::Sample;
use crate::replay::rotation_angle;
use crate::replay::{orientation, TossError, TossSetup, Window};
use nalgebra::Vector3;
use serde::Serialize;

/// Frames of the first impact after the centre stops falling (–): 20 ms at 148 Hz,
/// the rebound of a body that lands with restitution about 0.1.
pub(crate) const IMPACT_AFTER: usize = 3;
/// Frames ahead a frame must stay still over to be at rest (–): 47 ms at 148 Hz,
/// several times the tracker's frame-to-frame jitter.
pub(crate) const REST_SPAN: usize = 7;
/// The centre's largest move over [`REST_SPAN`] frames at rest, as a fraction of the
/// body's width (–): 2.1 mm for the ContactNets cube, 0.04 m/s.
pub(crate) const REST_DISTANCE: f64 = 0.02;
/// The orientation's largest turn over [`REST_SPAN`] frames at rest (°).
pub(crate) const REST_ANGLE: f64 = 2.0;

/// A phase of a toss.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Phase {
    /// Before any corner can touch.
    Flight,
    /// The landing and its rebound.
    FirstImpact,
    /// Between the first impact and settling.
    SlidingTumbling,
    /// Nearly at rest to the end.
    Settling,
}

impl Phase {
    /// The phases in the order a toss goes through them.
    pub const ALL: [Phase; 4] = [
        Phase::Flight,
        Phase::FirstImpact,
        Phase::SlidingTumbling,
        Phase::Settling,
    ];

    /// The name the report uses.
    pub fn label(self) -> &'static str {
        match self {
            Phase::Flight => "flight",
            Phase::FirstImpact => "first impact",
            Phase::SlidingTumbling => "sliding/tumbling",
            Phase::Settling => "settling",
        }
    }
}

/// The phase of each of the window's frames (`measured` is the window's recorded
/// frames, `window` the toss's window).
pub fn phases(
    setup: &TossSetup,
    run: &str,
    window: &Window,
    measured: &[Sample],
) -> Result<Vec<Phase>, TossError> {
    let n = measured.len();
    let near = (window.near - window.start).min(n);
    let height = |k: usize| setup.clearance(&Vector3::from(measured[k].position));
    let mut low = near;
    while low + 1 < n && height(low + 1) < height(low) {
        low += 1;
    }
    let settle = settling_start(setup, run, measured)?.max(near);
    let impact_end = (low + IMPACT_AFTER + 1).min(settle).max(near);
    Ok((0..n)
        .map(|k| match k {
            _ if k < near => Phase::Flight,
            _ if k < impact_end => Phase::FirstImpact,
            _ if k < settle => Phase::SlidingTumbling,
            _ => Phase::Settling,
        })
        .collect())
}

/// The first frame from which every frame is at rest; `measured.len()` if the last one
/// is not (or the window is shorter than [`REST_SPAN`] + 1 frames).
fn settling_start(setup: &TossSetup, run: &str, measured: &[Sample]) -> Result<usize, TossError> {
    let n = measured.len();
    if n <= REST_SPAN {
        return Ok(n);
    }
    let still = |j: usize| -> Result<bool, TossError> {
        let (p, q) = (
            Vector3::from(measured[j].position),
            orientation(&setup.name, run, &measured[j])?,
        );
        for later in &measured[j + 1..=j + REST_SPAN] {
            let moved = (Vector3::from(later.position) - p).norm();
            let turned = rotation_angle(&q, &orientation(&setup.name, run, later)?).to_degrees();
            if moved > REST_DISTANCE * setup.width || turned > REST_ANGLE {
                return Ok(false);
            }
        }
        Ok(true)
    };
    // The last REST_SPAN frames have no full span ahead: they share the verdict of the
    // last frame that has one.
    let last_full = n - 1 - REST_SPAN;
    if !still(last_full)? {
        return Ok(n);
    }
    let mut start = last_full;
    while start > 0 && still(start - 1)? {
        start -= 1;
    }
    Ok(start)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::preset::shipped_scenario;
    use crate::pipeline::Shipped;

    /// A cube falling at 1.5 m/s onto the table (flat, no bounce) while moving 5 mm per
    /// frame along x, stopping dead at frame 30; 50 frames at 148 Hz.
    fn toss() -> Vec<Sample> {
        (0..50)
            .map(|k| {
                let time = k as f64 / 148.0;
                let mut sample = Sample::at_rest(time);
                let z = (0.2 - 1.5 * time).max(0.0524);
                sample.position = [0.005 * k.min(30) as f64, 0.0, z];
                sample
            })
            .collect()
    }

    #[test]
    fn the_phases_follow_the_recorded_fall_landing_slide_and_stop() {
        let scenario = shipped_scenario(Shipped::CubeToss);
        let setup = TossSetup::new(&scenario.model().unwrap()).unwrap();
        let samples = toss();
        // Within 0.0524·√3 m from frame 11 (0.2 − 1.5·11/148 = 0.0885 m); the window
        // starts 3 frames before.
        let window = Window {
            start: 8,
            near: 11,
            frames: samples.len(),
        };
        let found = phases(&setup, "toss", &window, &samples[8..]).unwrap();
        let count = |phase| found.iter().filter(|&&p| p == phase).count();
        // Flight: frames 8–10. The centre stops falling at frame 15 (on the table from
        // there): first impact 11–18. Still from frame 30: sliding 19–29, settling 30–49.
        assert_eq!(count(Phase::Flight), 3, "{found:?}");
        assert_eq!(count(Phase::FirstImpact), 8, "{found:?}");
        assert_eq!(count(Phase::SlidingTumbling), 11, "{found:?}");
        assert_eq!(count(Phase::Settling), 20, "{found:?}");
        // In order.
        assert!(found
            .windows(2)
            .all(|w| Phase::ALL.iter().position(|&p| p == w[0])
                <= Phase::ALL.iter().position(|&p| p == w[1])));
    }

    #[test]
    fn a_toss_still_moving_at_its_end_never_settles() {
        let scenario = shipped_scenario(Shipped::CubeToss);
        let setup = TossSetup::new(&scenario.model().unwrap()).unwrap();
        let samples = toss();
        let window = Window {
            start: 8,
            near: 11,
            frames: 30,
        };
        let found = phases(&setup, "toss", &window, &samples[8..30]).unwrap();
        assert!(!found.contains(&Phase::Settling), "{found:?}");
        assert_eq!(found.len(), 22);
    }
}
