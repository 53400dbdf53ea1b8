//! A recorded sample as the integrator's rigid state (the residual's Eq 12 input and
//! the pose every rigid stage replays from).

use super::Sample;
use hcm_core::rigid::RigidState;
use nalgebra::{UnitQuaternion, Vector3};

/// Components of a rigid state: position (3), quaternion (4), velocity (3), angular
/// velocity (3).
pub const STATE_INPUTS: usize = 13;

/// The residual input of a recorded sample: [`RigidState`]'s components, ω turned from
/// the data's world frame into the body frame.
pub fn state_input(sample: &Sample) -> [f64; STATE_INPUTS] {
    let [w, x, y, z] = sample.orientation;
    let orientation = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
    let omega = orientation.inverse_transform_vector(&Vector3::from(sample.angular_velocity));
    let mut state = RigidState::new(
        Vector3::from(sample.position),
        orientation,
        Vector3::from(sample.velocity),
        omega,
    );
    // Keep the recorded quaternion itself (the integrator's, up to its drift).
    state.components[3..7].copy_from_slice(&sample.orientation);
    state.components
}

/// A body's recorded poses, where its motion is known between them: a camera's
/// frames (position and orientation at its rate, velocities too where the tracker gives
/// them) read at the instants of another instrument, a force sensor's rows.
///
/// Velocities a frame lacks are central differences of its neighbours (one-sided at
/// the ends): v from the positions, ω (world frame) from the rotation between the
/// neighbouring orientations. Between two frames the position follows the cubic
/// Hermite curve through their positions and velocities, the velocities are linear,
/// the orientation is the spherical interpolation. Rates far below a contact's
/// duration blur the contact: the data's limit, not the reader's.
#[derive(Clone, Debug, Default)]
pub struct Frames {
    /// The frames with position and orientation, time ascending.
    frames: Vec<Sample>,
    /// Whether each frame came with both velocities (none differentiated).
    complete: Vec<bool>,
}

impl Frames {
    /// The frames of `samples` (those with position and orientation), velocities
    /// completed.
    pub fn of(samples: &[Sample]) -> Frames {
        use super::Channel;
        let mut frames: Vec<Sample> = (samples.iter())
            .filter(|s| s.has(Channel::Position) && s.has(Channel::Orientation))
            .cloned()
            .collect();
        let n = frames.len();
        let complete: Vec<bool> = (frames.iter())
            .map(|f| f.has(Channel::Velocity) && f.has(Channel::AngularVelocity))
            .collect();
        for i in 0..n {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            let dt = frames[b].time - frames[a].time;
            if a == b || dt <= 0.0 {
                continue;
            }
            if !frames[i].has(Channel::Velocity) {
                let (pa, pb) = (
                    Vector3::from(frames[a].position),
                    Vector3::from(frames[b].position),
                );
                frames[i].velocity = ((pb - pa) / dt).into();
            }
            if !frames[i].has(Channel::AngularVelocity) {
                let turn = orientation(&frames[b]) * orientation(&frames[a]).inverse();
                frames[i].angular_velocity = (turn.scaled_axis() / dt).into();
            }
        }
        Frames { frames, complete }
    }

    /// Whether a frame was recorded at `t` (s) with every motion channel (velocities
    /// from the tracker, not differentiated).
    pub fn recorded_at(&self, t: f64) -> bool {
        let b = self.frames.partition_point(|f| f.time < t);
        (self.frames.get(b).zip(self.complete.get(b))).is_some_and(|(f, c)| f.time == t && *c)
    }

    /// The state at `t` (s): the frame itself at its time, else interpolated between
    /// the two around `t`; `None` outside the frames' span or without velocities.
    pub fn at(&self, t: f64) -> Option<Sample> {
        use super::Channel;
        let b = self.frames.partition_point(|f| f.time < t);
        let after = self.frames.get(b)?;
        let complete = |s: &Sample| s.has(Channel::Velocity) && s.has(Channel::AngularVelocity);
        if after.time == t {
            return complete(after).then(|| after.clone());
        }
        let before = self.frames.get(b.checked_sub(1)?)?;
        if !(complete(before) && complete(after)) {
            return None;
        }
        let h = after.time - before.time;
        let x = (t - before.time) / h;
        let v = |s: &Sample| Vector3::from(s.velocity);
        let p = |s: &Sample| Vector3::from(s.position);
        let (x2, x3) = (x * x, x * x * x);
        let position = p(before) * (2.0 * x3 - 3.0 * x2 + 1.0)
            + v(before) * (h * (x3 - 2.0 * x2 + x))
            + p(after) * (-2.0 * x3 + 3.0 * x2)
            + v(after) * (h * (x3 - x2));
        let turned = orientation(before).slerp(&orientation(after), x);
        let w = |s: &Sample| Vector3::from(s.angular_velocity);
        let mut out = Sample::unsampled(t);
        out.position = position.into();
        out.orientation = [turned.w, turned.i, turned.j, turned.k];
        out.velocity = (v(before) * (1.0 - x) + v(after) * x).into();
        out.angular_velocity = (w(before) * (1.0 - x) + w(after) * x).into();
        Some(out)
    }
}

/// A sample's orientation as a unit quaternion.
fn orientation(s: &Sample) -> UnitQuaternion<f64> {
    let [w, x, y, z] = s.orientation;
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z))
}
