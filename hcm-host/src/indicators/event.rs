//! One contact event, simulated or read back from data, and its two views: the 3D
//! indicators ([`WrenchIndicators`]) and, for a pair touching on its line of centres,
//! the paper's four ([`Indicators`]).

use super::{Indicators, WrenchIndicators};
use nalgebra::Vector3;

/// One contact event of a body pair, simulated or recorded: from the first point's
/// touch-down to the last point's lift-off. Two events are equal when every number is
/// bit for bit the same (a NaN — a speed a pair with a box does not have, a value of an
/// open event — equals itself), so that two runs compare as identical or not.
#[derive(Clone, Debug)]
pub struct ContactEvent {
    /// Index of the contact in the model.
    pub contact: usize,
    /// Touch-down time (s): the separation's zero crossing.
    pub touch_down: f64,
    /// Lift-off time (s); `None` if the run ended in contact.
    pub lift_off: Option<f64>,
    /// Largest ‖**F**‖ on the moving body (N): the maximum normal force of a
    /// frictionless pair touching on its line of centres.
    pub max_force: f64,
    /// Largest ‖**T**‖ on the moving body about its centre of mass (N·m).
    pub max_torque: f64,
    /// ∫**F** dt over the event (N·s), world frame.
    pub linear_impulse: Vector3<f64>,
    /// ∫**T** dt over the event (N·m·s), world frame.
    pub angular_impulse: Vector3<f64>,
    /// Most points touching at once; 0 for a recorded event (data do not say).
    pub max_points: usize,
    /// Indentation rate at touch-down, δ̇_in (m/s), of a pair touching on its line of
    /// centres (a sphere against a plane or a sphere); NaN for a pair with a box.
    pub approach_speed: f64,
    /// −δ̇ at lift-off, δ̇_out (m/s); NaN while open and for a pair with a box.
    pub separation_speed: f64,
    /// Work the contact took from the bodies (J), ∫f_n·δ̇ dt for one point without
    /// friction: the energy it dissipated. Boole's rule on each solver step; NaN for a
    /// recorded event.
    pub work: f64,
    /// Kinetic energy of the pair's moving bodies at touch-down (J); NaN for a recorded
    /// event.
    pub kinetic_energy_in: f64,
    /// Kinetic energy of the pair's moving bodies at lift-off (J); NaN while open and
    /// for a recorded event.
    pub kinetic_energy_out: f64,
    /// Effective mass m_e of the pair (kg).
    pub(crate) effective_mass: f64,
    /// Normal impulse ∫f_n dt (N·s) of a pair touching on its line of centres: in the
    /// simulator ‖∫**F** dt‖ (a frictionless pair's impulse lies along its fixed normal),
    /// from data the recorded normal force's integral (so far, for an event still open
    /// when a run ends); NaN for a pair with a box.
    pub normal_impulse: f64,
}

impl PartialEq for ContactEvent {
    fn eq(&self, other: &Self) -> bool {
        self.bits() == other.bits()
    }
}

impl ContactEvent {
    /// An event of contact `contact` that touched down at `touch_down` (s) and holds
    /// nothing yet: open, zero peaks and impulses, every other value unknown (NaN).
    pub(crate) fn starting(contact: usize, touch_down: f64) -> ContactEvent {
        ContactEvent {
            contact,
            touch_down,
            lift_off: None,
            max_force: 0.0,
            max_torque: 0.0,
            linear_impulse: Vector3::zeros(),
            angular_impulse: Vector3::zeros(),
            normal_impulse: f64::NAN,
            max_points: 0,
            approach_speed: f64::NAN,
            separation_speed: f64::NAN,
            work: f64::NAN,
            kinetic_energy_in: f64::NAN,
            kinetic_energy_out: f64::NAN,
            effective_mass: f64::NAN,
        }
    }

    /// Every number of the event as its bits (the lift-off's presence first).
    fn bits(&self) -> Vec<u64> {
        let [l, a] = [self.linear_impulse, self.angular_impulse];
        [
            self.contact as u64,
            self.lift_off.is_some().into(),
            self.lift_off.unwrap_or(0.0).to_bits(),
            self.max_points as u64,
        ]
        .into_iter()
        .chain(
            [
                self.touch_down,
                self.max_force,
                self.max_torque,
                l.x,
                l.y,
                l.z,
                a.x,
                a.y,
                a.z,
                self.normal_impulse,
                self.approach_speed,
                self.separation_speed,
                self.work,
                self.kinetic_energy_in,
                self.kinetic_energy_out,
                self.effective_mass,
            ]
            .map(f64::to_bits),
        )
        .collect()
    }

    /// The event's indicators; `None` while it has not ended.
    pub fn indicators(&self) -> Option<WrenchIndicators> {
        let lift_off = self.lift_off?;
        Some(self.indicators_until(lift_off))
    }

    /// The indicators as if the event ended at `end` (s) (for an event still open).
    pub fn indicators_until(&self, end: f64) -> WrenchIndicators {
        WrenchIndicators::new(
            self.max_force,
            self.max_torque,
            self.linear_impulse.into(),
            self.angular_impulse.into(),
            end - self.touch_down,
        )
    }

    /// The paper's four indicators of a pair touching on its line of centres without
    /// friction (the 1D examples): maximum normal force (max ‖**F**‖), normal impulse,
    /// energy loss ½·m_e·(δ̇_in² − δ̇_out²) and duration. `None` if the contact never
    /// ended or the pair has a box.
    pub fn normal_indicators(&self) -> Option<Indicators> {
        self.lift_off?;
        if self.approach_speed.is_nan() {
            return None;
        }
        Some(self.line_indicators())
    }

    /// [`ContactEvent::normal_indicators`] unchecked: NaN where a value is missing (the
    /// duration of an open event, the speeds of a pair with a box).
    pub(crate) fn line_indicators(&self) -> Indicators {
        Indicators {
            max_force: self.max_force,
            impulse: self.normal_impulse,
            energy_loss: 0.5
                * self.effective_mass
                * (self.approach_speed.powi(2) - self.separation_speed.powi(2)),
            duration: self.lift_off.unwrap_or(f64::NAN) - self.touch_down,
        }
    }
}

/// A contact event found in one run of a data set, and where: its run, contact and
/// number. Only completed events are recorded: the lift-off is always known.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordedEvent {
    /// Run id.
    pub run: String,
    /// Contact label, `body1–body2`.
    pub label: String,
    /// Event number within this contact and run (0 = first).
    pub number: usize,
    /// The event.
    pub event: ContactEvent,
}

impl RecordedEvent {
    /// Touch-down time (s).
    pub fn touch_down(&self) -> f64 {
        self.event.touch_down
    }

    /// The 3D indicators.
    pub fn wrench(&self) -> WrenchIndicators {
        (self.event).indicators_until(self.event.lift_off.unwrap_or(f64::NAN))
    }

    /// The paper's four indicators (of a contact on its line of centres).
    pub fn line(&self) -> Indicators {
        self.event.line_indicators()
    }
}

/// Every run's events found by `find` (the 1D [`super::from_run`] or the 3D
/// [`super::pair_events_from_run`]), in run order, and the ids of the runs without a
/// completed contact.
pub fn events_of_runs<E>(
    runs: &[crate::dataset::Run],
    mut find: impl FnMut(&crate::dataset::Run) -> Result<Vec<RecordedEvent>, E>,
) -> Result<(Vec<RecordedEvent>, Vec<String>), E> {
    let (mut events, mut without_contact) = (Vec::new(), Vec::new());
    for run in runs {
        let found = find(run)?;
        if found.is_empty() {
            without_contact.push(run.id.clone());
        }
        events.extend(found);
    }
    Ok((events, without_contact))
}
