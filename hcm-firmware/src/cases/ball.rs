//! A whole bouncing-ball run in f32 with the core's integrator, as a controller's
//! model-predictive loop would run it: the ball (scenarios/bouncing_ball.toml) falls
//! from a 0.1 m gap, touches down, is pushed back by the HCM, lifts off and rises to
//! its apex.
//!
//! State [z (m), v (m/s)]: z is the gap between the ball and the ground (δ = −z in
//! contact), v its rate. Three phases, each ended by [`locate_crossing`]: flight until
//! z = 0 (the approach speed δ̇0 = −v is latched there), contact until z = 0 again
//! (lift-off), flight until v = 0 (apex).

use super::table::{BALL_MASS, DROP_GAP, GRAVITY};
use super::{hcm_force, Emit};
use hcm_core::integrate::{locate_crossing, Dopri5, IntegrationError, OdeSystem, Settings};
use hcm_core::model::{ContactModel, Residual};

/// Longest step (s) in contact: a fraction of the ≈ 50 µs contact, so that a step
/// cannot leap from touch-down past lift-off.
const CONTACT_STEP_LIMIT: f32 = 2e-6;
/// Longest step (s) anywhere (scenarios/bouncing_ball.toml's `max_step`).
const MAX_STEP: f32 = 1e-3;
/// No phase lasts longer than this (s); a run that needs it is an error.
const PHASE_LIMIT: f32 = 1.0;

/// The ball under gravity, with the HCM's normal force while in contact.
struct Ball<'a, R> {
    model: &'a ContactModel<f32, R>,
    in_contact: bool,
    /// Approach speed δ̇0 (m/s) latched at touch-down.
    approach_speed: f32,
}

impl<R: Residual<f32>> Ball<'_, R> {
    /// The contact force on the ball (N, upwards) at gap z (m) and rate v (m/s).
    fn force(&self, y: &[f32; 2]) -> (f32, bool) {
        if !self.in_contact {
            return (0.0, false);
        }
        hcm_force(self.model, &[-y[0], -y[1], self.approach_speed])
    }
}

impl<R: Residual<f32>> OdeSystem<f32, [f32; 2]> for Ball<'_, R> {
    fn derivative(&mut self, _time: f32, y: &[f32; 2], dy: &mut [f32; 2]) {
        *dy = [y[1], self.force(y).0 / BALL_MASS - GRAVITY];
    }

    fn step_limit(&self, _time: f32, _y: &[f32; 2]) -> f32 {
        if self.in_contact {
            CONTACT_STEP_LIMIT
        } else {
            f32::MAX
        }
    }
}

/// What one run found.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BallRun {
    /// Touch-down, lift-off and apex times (s).
    pub events: [f32; 3],
    /// Approach speed δ̇0 at touch-down and rebound speed at lift-off (m/s).
    pub speeds: [f32; 2],
    /// Largest contact force at an accepted step (N).
    pub peak_force: f32,
    /// Accepted contact steps at which the residual took part.
    pub residual_steps: u32,
    /// Final time (s), gap (m) and rate (m/s), at the apex.
    pub last: [f32; 3],
    /// Accepted and rejected steps in total.
    pub steps: [u32; 2],
}

/// Runs drop, contact, lift-off and rise to the apex with `model` as the contact.
pub fn simulate<R: Residual<f32>>(
    model: &ContactModel<f32, R>,
) -> Result<BallRun, IntegrationError> {
    let mut ball = Ball {
        model,
        in_contact: false,
        approach_speed: 0.0,
    };
    let mut settings = Settings::new(1e-6, 1e-9);
    settings.max_step = MAX_STEP;
    let mut stepper = Dopri5::new(&mut ball, 0.0, [DROP_GAP, 0.0], settings);
    let mut run = BallRun::default();
    let mut y = [0.0_f32; 2];

    let touch_down = phase(&mut stepper, &mut ball, |_, y| y[0], |_| {})?;
    stepper.dense_output(touch_down, &mut y);
    (ball.in_contact, ball.approach_speed) = (true, -y[1]);
    stepper.restart(&mut ball, touch_down, y);

    let lift_off = phase(
        &mut stepper,
        &mut ball,
        |_, y| y[0],
        |(force, residual_on)| {
            run.peak_force = run.peak_force.max(force);
            run.residual_steps += u32::from(residual_on);
        },
    )?;
    stepper.dense_output(lift_off, &mut y);
    ball.in_contact = false;
    let rebound = y[1];
    stepper.restart(&mut ball, lift_off, y);

    let apex = phase(&mut stepper, &mut ball, |_, y| y[1], |_| {})?;
    stepper.dense_output(apex, &mut y);

    run.events = [touch_down, lift_off, apex];
    run.speeds = [ball.approach_speed, rebound];
    run.last = [apex, y[0], y[1]];
    let count = |n: u64| u32::try_from(n).unwrap_or(u32::MAX);
    run.steps = [
        count(stepper.accepted_steps()),
        count(stepper.rejected_steps()),
    ];
    Ok(run)
}

/// Steps until `event` changes sign; returns its time (s). `each` sees the contact
/// force (N) and whether the residual took part after every accepted step.
fn phase<R: Residual<f32>>(
    stepper: &mut Dopri5<f32, [f32; 2]>,
    ball: &mut Ball<'_, R>,
    mut event: impl FnMut(f32, &[f32; 2]) -> f32,
    mut each: impl FnMut((f32, bool)),
) -> Result<f32, IntegrationError> {
    let until = stepper.time() + PHASE_LIMIT;
    let mut scratch = [0.0_f32; 2];
    loop {
        stepper.step(ball, until)?;
        if let Some(time) = locate_crossing(stepper, &mut event, 0.0, &mut scratch) {
            return Ok(time);
        }
        each(ball.force(stepper.state()));
        if stepper.time() >= until {
            return Err(IntegrationError::TooManySteps {
                time: f64::from(stepper.time()),
                steps: stepper.accepted_steps() + stepper.rejected_steps(),
            });
        }
    }
}

/// Runs [`simulate`] and emits `ball.events` [touch-down, lift-off, apex (s),
/// δ̇0, rebound speed (m/s), peak force (N)] and `ball.final` [t (s), z (m), v (m/s),
/// accepted, rejected, residual steps]; or `ball.error` [1] if the run failed.
pub fn emit_run<R: Residual<f32>>(model: &ContactModel<f32, R>, emit: Emit<'_>) {
    match simulate(model) {
        Ok(run) => {
            let [t1, t2, t3] = run.events.map(f32::to_bits);
            let [s1, s2] = run.speeds.map(f32::to_bits);
            emit(
                "ball",
                "events",
                &[t1, t2, t3, s1, s2, run.peak_force.to_bits()],
            );
            let [t, z, v] = run.last.map(f32::to_bits);
            let [accepted, rejected] = run.steps;
            emit(
                "ball",
                "final",
                &[t, z, v, accepted, rejected, run.residual_steps],
            );
        }
        Err(_) => emit("ball", "error", &[1]),
    }
}
