//! Which channels each command needs, and the error that says so before any work: the
//! file, the command, the channel, and what to do.
//!
//! | command | needs, on the bodies of the contact |
//! |---|---|
//! | `identify`, `train`, `diagnose`, `evaluate`, `indicators` (1D) | position somewhere (camera frames) and force somewhere (the sensor's rows); the motion at the force samples is reconstructed |
//! | `identify --method ga`, `indicators` (rigid, 3D) | position, orientation, velocity, angular velocity, force and torque on every row |
//! | `identify --method lsq`, `train`, `diagnose` (rigid, 3D) | position and orientation of the moving body (velocities from them where absent) and a force (its own or a plate's) on some rows, each at its own rate |

use super::channel::Channel;
use super::{DataError, Dataset};
use crate::scenario::Model;

/// How a command needs a channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Need {
    /// On every row of every moving body of the contacts.
    EveryRow,
    /// On some rows of each run: of each moving body for motion channels, of either
    /// body of the contact for force and torque (one sensor measures the pair).
    SomeRows,
}

/// What one command needs of the data.
#[derive(Clone, Copy, Debug)]
pub struct Requirement {
    /// The command, e.g. `hcm identify`.
    pub(crate) command: &'static str,
    /// The channels and how they are needed.
    pub(crate) channels: &'static [(Channel, Need)],
    /// Why, in the command's terms: completes "… needs the force channel because …".
    pub(crate) because: &'static str,
}

impl Requirement {
    /// The 1D commands: motion from camera frames, force from the sensor's rows.
    const CAMERA_AND_SENSOR: &[(Channel, Need)] = &[
        (Channel::Position, Need::SomeRows),
        (Channel::Force, Need::SomeRows),
    ];

    /// The rigid (3D) commands: full states on every row, not reconstructed yet.
    const FULL_STATES: &[(Channel, Need)] = &[
        (Channel::Position, Need::EveryRow),
        (Channel::Orientation, Need::EveryRow),
        (Channel::Velocity, Need::EveryRow),
        (Channel::AngularVelocity, Need::EveryRow),
        (Channel::Force, Need::EveryRow),
        (Channel::Torque, Need::EveryRow),
    ];

    /// `hcm identify` on a 1D contact (least squares or GA on force curves).
    pub const IDENTIFY: Requirement = Requirement {
        command: "hcm identify",
        channels: Self::CAMERA_AND_SENSOR,
        because: "it fits the law's force to the measured contact force along the motion \
                  (camera frames are enough for the motion: it is reconstructed at the force samples)",
    };

    /// `hcm identify` on a rigid (3D) contact.
    pub const IDENTIFY_RIGID: Requirement = Requirement {
        command: "hcm identify (rigid, 3D)",
        channels: Self::FULL_STATES,
        because: "it replays each contact event from its full pre-contact state and compares \
                  wrenches; 3D motion is not reconstructed from camera frames yet, so give every \
                  channel on every row",
    };

    /// The rigid fit from force samples: the mover's poses (velocities, where missing,
    /// from the poses) and a force, each at its own rate.
    const STATES_AND_FORCE: &[(Channel, Need)] = &[
        (Channel::Position, Need::SomeRows),
        (Channel::Orientation, Need::SomeRows),
        (Channel::Force, Need::SomeRows),
    ];

    /// `hcm identify --method lsq` on a rigid (3D) contact, and `hcm train` there.
    pub const IDENTIFY_RIGID_SAMPLES: Requirement = Requirement {
        command: "hcm identify (rigid, 3D, force samples)",
        channels: Self::STATES_AND_FORCE,
        because: "it compares the law's wrench at each recorded pose with the force measured \
                  there (on the moving body, or on the fixed one by a force plate at the same \
                  instant; torque is used where recorded)",
    };

    /// `hcm train` on a rigid (3D) contact.
    pub const TRAIN_RIGID: Requirement = Requirement {
        command: "hcm train (rigid, 3D)",
        channels: Self::STATES_AND_FORCE,
        because: "the residual network learns the measured minus the modelled wrench at each \
                  recorded state",
    };

    /// `hcm train`.
    pub const TRAIN: Requirement = Requirement {
        command: "hcm train",
        channels: Self::CAMERA_AND_SENSOR,
        because: "the residual network learns measured minus modelled contact force",
    };

    /// `hcm diagnose`.
    pub const DIAGNOSE: Requirement = Requirement {
        command: "hcm diagnose",
        channels: Self::CAMERA_AND_SENSOR,
        because: "it compares the model's force with the measured force in contact, along the \
                  motion around it",
    };

    /// `hcm evaluate`.
    pub const EVALUATE: Requirement = Requirement {
        command: "hcm evaluate",
        channels: Self::CAMERA_AND_SENSOR,
        because: "its indicators (maximum force, impulse, energy loss, duration) are read from \
                  the measured force and the motion",
    };

    /// `hcm indicators` on a 1D scenario.
    pub const INDICATORS: Requirement = Requirement {
        command: "hcm indicators",
        channels: Self::CAMERA_AND_SENSOR,
        because: "maximum force and impulse are read from the force, duration and energy loss \
                  from the motion",
    };

    /// `hcm indicators` on a rigid (3D) scenario.
    pub const INDICATORS_RIGID: Requirement = Requirement {
        command: "hcm indicators (rigid, 3D)",
        channels: Self::FULL_STATES,
        because: "each event's wrench and poses are read row by row; 3D motion is not \
                  reconstructed from camera frames yet, so give every channel on every row",
    };
}

impl Dataset {
    /// Checks that the data hold what `requirement` needs for the contacts `contacts` of
    /// `model`; `file` names the data in the error.
    pub fn require(
        &self,
        file: &str,
        model: &Model,
        contacts: &[usize],
        requirement: &Requirement,
    ) -> Result<(), DataError> {
        for run in &self.runs {
            known_bodies(file, model, run)?;
            for &c in contacts {
                let contact = &model.contacts[c];
                let pair = [contact.body_1, contact.body_2];
                for &(channel, need) in requirement.channels {
                    let motion = !matches!(channel, Channel::Force | Channel::Torque);
                    let bodies: Vec<&str> = pair
                        .iter()
                        .filter(|&&b| !(motion && model.bodies[b].fixed))
                        .map(|&b| model.bodies[b].name.as_str())
                        .collect();
                    let tracks: Vec<_> = bodies.iter().filter_map(|&b| run.body(b)).collect();
                    let problem = match need {
                        Need::SomeRows if motion => tracks
                            .iter()
                            .find(|t| !t.samples.iter().any(|s| s.has(channel)))
                            .map(|t| {
                                format!("run `{}` never fills it for body `{}`", run.id, t.body)
                            }),
                        Need::SomeRows => (!tracks
                            .iter()
                            .any(|t| t.samples.iter().any(|s| s.has(channel))))
                        .then(|| {
                            format!(
                                "run `{}` never fills it for body `{}`",
                                run.id,
                                bodies.join("` or `")
                            )
                        }),
                        Need::EveryRow => tracks.iter().find_map(|t| {
                            let s = t.samples.iter().find(|s| !s.has(channel))?;
                            Some(format!(
                                "run `{}`, body `{}` leaves it empty at t = {:?} s",
                                run.id, t.body, s.time
                            ))
                        }),
                    };
                    if let Some(problem) = problem {
                        return Err(missing(file, requirement, channel, need, &problem));
                    }
                }
            }
        }
        Ok(())
    }
}

/// An error unless every track of `run` is a body of `model` and every moving body of
/// a contact has a track: a name the scenario does not know (a misspelt body, a sensor
/// on a body the scenario lacks) would otherwise be read as no data at all.
fn known_bodies(file: &str, model: &Model, run: &super::Run) -> Result<(), DataError> {
    let names = |it: &mut dyn Iterator<Item = &str>| {
        it.map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
    };
    let scenario = names(&mut model.bodies.iter().map(|b| b.name.as_str()));
    if let Some(track) =
        (run.bodies.iter()).find(|t| !model.bodies.iter().any(|b| b.name == t.body))
    {
        return Err(DataError::new(
            file,
            format!(
                "run `{}` holds body `{}`, which scenario `{}` does not have (its bodies: \
                 {scenario}): rename it in the `body` column, or add the body to the \
                 scenario (a force plate is the fixed body it is bolted to)",
                run.id, track.body, model.scenario.name
            ),
        )
        .in_column("body"));
    }
    let in_contact = |b: usize| {
        model
            .contacts
            .iter()
            .any(|c| c.body_1 == b || c.body_2 == b)
    };
    for (b, body) in model.bodies.iter().enumerate() {
        if !body.fixed && in_contact(b) && run.body(&body.name).is_none() {
            return Err(DataError::new(
                file,
                format!(
                    "run `{}` has no rows of body `{}`, the scenario's moving body (the run's \
                     bodies: {}): name it `{}` in the `body` column",
                    run.id,
                    body.name,
                    names(&mut run.bodies.iter().map(|t| t.body.as_str())),
                    body.name
                ),
            )
            .in_column("body"));
        }
    }
    Ok(())
}

/// The error for a channel a command needs and the data lack.
fn missing(
    file: &str,
    requirement: &Requirement,
    channel: Channel,
    need: Need,
    problem: &str,
) -> DataError {
    let todo = match (channel, need) {
        (Channel::Force | Channel::Torque, Need::SomeRows) => format!(
            "add the force sensor's rows ({} at its own rate, the other cells empty)",
            channel.column_list()
        ),
        (_, Need::SomeRows) => format!(
            "add the camera's frames ({} at its frame rate, the other cells empty)",
            channel.column_list()
        ),
        (_, Need::EveryRow) => format!("fill {} on every row", channel.column_list()),
    };
    DataError::new(
        file,
        format!(
            "{} needs the {} channel ({}) because {}, but {}; {}",
            requirement.command,
            channel.name(),
            channel.column_list(),
            requirement.because,
            problem,
            todo
        ),
    )
    .in_column(crate::dataset::schema::COLUMNS[channel.columns().start].name)
}
