//! The measured-data CSV format: one format for everything that carries motion and
//! force — what `hcm simulate` writes, what an experiment generator writes, and what a
//! user brings from a real rig (high-speed camera plus force sensor).
//!
//! One row per sample per body. The header row is the schema; SI units, every vector in
//! the world frame:
//!
//! | column | unit | meaning |
//! |---|---|---|
//! | `run` | – | run identifier (text), e.g. `0`, `trial_03` |
//! | `body` | – | body name (text), e.g. `ball` |
//! | `time` | s | sample time, strictly increasing within one (run, body) |
//! | `px` | m | position of the centre of mass, x |
//! | `py` | m | position of the centre of mass, y |
//! | `pz` | m | position of the centre of mass, z |
//! | `qw` | – | orientation (body to world) unit quaternion, scalar w |
//! | `qx` | – | orientation unit quaternion, x |
//! | `qy` | – | orientation unit quaternion, y |
//! | `qz` | – | orientation unit quaternion, z |
//! | `vx` | m/s | linear velocity of the centre of mass, x |
//! | `vy` | m/s | linear velocity of the centre of mass, y |
//! | `vz` | m/s | linear velocity of the centre of mass, z |
//! | `wx` | rad/s | angular velocity, x |
//! | `wy` | rad/s | angular velocity, y |
//! | `wz` | rad/s | angular velocity, z |
//! | `fx` | N | contact force on the body, x |
//! | `fy` | N | contact force on the body, y |
//! | `fz` | N | contact force on the body, z |
//! | `tx` | N·m | contact torque on the body about its centre of mass, x |
//! | `ty` | N·m | contact torque on the body about its centre of mass, y |
//! | `tz` | N·m | contact torque on the body about its centre of mass, z |
//!
//! Channels ([`Channel`]) are the groups of columns an instrument fills together:
//! position `px py pz`, orientation `qw qx qy qz`, velocity `vx vy vz`, angular velocity
//! `wx wy wz`, force `fx fy fz`, torque `tx ty tz`. A rig's camera and force sensor run
//! on different clocks, so a row may fill some channels and leave the others' cells
//! empty, meaning "not sampled at this row": camera frames (position, orientation,
//! perhaps velocity) and force-sensor rows (force, torque) in one file, or no force at
//! all (tosses filmed without a sensor). Motion is position with orientation.
//!
//! Reading ([`Dataset::read`], [`Dataset::from_reader`]):
//!
//! - Columns may come in any order. Columns the format does not define are ignored, so a
//!   rig may keep its own (frame numbers, raw sensor channels). Names are case-sensitive.
//!   `run`, `body` and `time` are required, and at least one channel; a channel's
//!   columns are all there or all left out (a channel left out is never sampled). A
//!   missing column is an error naming it.
//! - Cells are trimmed of surrounding whitespace; a leading UTF-8 byte-order mark is
//!   skipped. Every row has as many cells as the header.
//! - A channel is filled whole or left empty whole in each row; empty is "not
//!   sampled here" and reads as NaN in every component of the [`Sample`] (see
//!   [`channel`] for why NaN). A row fills at least one channel and always has a time.
//! - Every filled numeric cell is a finite number (`1.5`, `-2e-7`); text, `NaN`, `inf`,
//!   an empty `time`, or an empty cell in a channel whose other cells are filled is an
//!   error naming the file, the line (1-based, the header is line 1; blank lines count,
//!   and `\n`, `\r\n` and `\r` all end a line), the column and the offending text.
//!   `run` and `body` are non-empty text.
//! - Rows of different runs and bodies may interleave. They are grouped by (run, body):
//!   runs in order of first appearance, and within a run, bodies in order of first
//!   appearance. Within one (run, body) time increases strictly — camera frames and
//!   force rows of one body are merged in time order, one row per instant; the same
//!   time in another body or run is fine.
//! - The quaternion is taken as written: it is neither checked for unit norm nor
//!   renormalised. 1D and planar scenarios fill the components they use and leave the
//!   rest 0 (quaternion 1, 0, 0, 0) — see [`Sample::at_rest`].
//! - A file with no header, or a header with no data rows, is an error.
//!
//! Each command says which channels it needs ([`needs`]); `identify`, `diagnose` and
//! `train` reconstruct the motion at the force sensor's samples themselves
//! ([`reconstruct`]), so camera frames need not be interpolated by the user.
//!
//! Writing ([`Dataset::write`], [`Dataset::to_writer`]) emits the columns in the order of
//! the table, run by run, and within a run body by body, each body's samples in time
//! order. That block layout reads back into exactly the same [`Dataset`] (an interleaved
//! layout would reorder bodies whose first samples are not in body order). Numbers use
//! Rust's shortest round-trip formatting, so they read back bit for bit; a channel not
//! sampled (NaN in every component) is written as empty cells; rows end in `\n`,
//! names holding commas, quotes or line breaks are quoted, and the same dataset always
//! gives the same bytes. The writer refuses what the reader would refuse (non-finite
//! values other than a whole channel not sampled, a sample with no channel, time not
//! increasing, empty or whitespace-padded names, empty runs or bodies, repeated names)
//! before writing anything, and [`Dataset::write`] goes through
//! [`crate::output::write_atomically`], so a failed write leaves no file behind.

mod channel;
mod needs;
mod reconstruct;
mod schema;
pub use schema::{csv_header, sample_values, schema_markdown};

mod delay;
mod evidence;
mod flight;
mod force_sample;
mod implied;
mod newton;
mod read;
mod recorded_motion;
mod through_contact;
mod write;

pub use channel::Channel;
pub use evidence::{DataUse, Evidence};
mod inventory;
pub use inventory::{inventory_summary, motion_only};
mod state;
pub(crate) use delay::DELAY_SIGMAS;
pub use delay::{fit_delay, Delay};
pub use flight::FlightFit;
pub use force_sample::ForceSample;
pub use needs::{Need, Requirement};
pub(crate) use newton::MAX_MISFIT;
pub(crate) use reconstruct::complete_with;
pub use reconstruct::{complete, Checks, Completed, ReconstructError, TrackReconstruction};
pub use state::state_input;
pub use state::{Frames, STATE_INPUTS};
pub use write::{RunWriter, MEMBER_COLUMN};

use std::fmt::Write as _;
use std::path::Path;

use crate::output::{self, OutputError};

/// The state of one body at one instant (one row of the file). SI units, world frame.
/// A channel not sampled at this instant is NaN in every component ([`channel`]).
#[derive(Clone, Debug)]
pub struct Sample {
    /// Time, s.
    pub time: f64,
    /// Position of the centre of mass, m.
    pub position: [f64; 3],
    /// Orientation, body to world, as a unit quaternion scalar first `[w, x, y, z]`, –.
    pub orientation: [f64; 4],
    /// Linear velocity of the centre of mass, m/s.
    pub velocity: [f64; 3],
    /// Angular velocity, rad/s.
    pub angular_velocity: [f64; 3],
    /// Contact force on the body, N.
    pub force: [f64; 3],
    /// Contact torque on the body about its centre of mass, N·m.
    pub torque: [f64; 3],
}

impl Sample {
    /// A body at the origin with identity orientation, at rest and without contact, at
    /// `time` (s). The starting point for 1D and planar samples: set the components
    /// used and leave the rest.
    pub fn at_rest(time: f64) -> Self {
        Sample {
            time,
            position: [0.0; 3],
            orientation: [1.0, 0.0, 0.0, 0.0],
            velocity: [0.0; 3],
            angular_velocity: [0.0; 3],
            force: [0.0; 3],
            torque: [0.0; 3],
        }
    }
}

/// The samples of one body in one run, time strictly increasing.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyTrack {
    /// Body name, e.g. `ball`.
    pub body: String,
    /// Samples in time order.
    pub samples: Vec<Sample>,
}

/// One run (one simulation, one trial on the rig): the tracks of its bodies.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// Run identifier, e.g. `0` or `trial_03`.
    pub id: String,
    /// One track per body, in order of first appearance in the file.
    pub bodies: Vec<BodyTrack>,
}

impl Run {
    /// The track of the body called `name`.
    pub fn body(&self, name: &str) -> Option<&BodyTrack> {
        self.bodies.iter().find(|track| track.body == name)
    }
}

/// The contents of one measured-data file: its runs in order of first appearance.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Dataset {
    /// The runs.
    pub runs: Vec<Run>,
}

impl Dataset {
    /// Reads the CSV file at `path`; errors name it as given.
    pub fn read(path: &Path) -> Result<Dataset, DataError> {
        let name = path.display().to_string();
        let file = std::fs::File::open(path)
            .map_err(|error| DataError::new(&name, format!("cannot open the file: {error}")))?;
        read::read(&name, file)
    }

    /// Reads CSV from `reader`; `source_name` (usually a file name) names it in errors.
    /// The reader is streamed through an internal buffer; it need not be buffered.
    pub fn from_reader(
        source_name: &str,
        reader: impl std::io::Read,
    ) -> Result<Dataset, DataError> {
        read::read(source_name, reader)
    }

    /// Writes the dataset as CSV to `path`, atomically: the file appears complete or not
    /// at all (an existing file keeps its old content on failure).
    pub fn write(&self, path: &Path) -> Result<(), DataError> {
        let name = path.display().to_string();
        write::check(self, &name)?;
        output::write_atomically(path, |out| write::write(self, &name, out))
    }

    /// Writes the dataset as CSV to `writer` (buffered internally). Nothing is written if
    /// the dataset cannot be represented; errors name the destination `<writer>`.
    pub fn to_writer(&self, writer: impl std::io::Write) -> Result<(), DataError> {
        const NAME: &str = "<writer>";
        write::check(self, NAME)?;
        write::write(self, NAME, writer)
    }

    /// The run with identifier `id`.
    pub fn run(&self, id: &str) -> Option<&Run> {
        self.runs.iter().find(|run| run.id == id)
    }
}

/// Why a dataset could not be read or written: where (file, line, column) and what.
///
/// Displays as e.g. ``traj.csv, line 12, column `fx`: expected a finite number in N,
/// found `NaN` ``.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{file}{}: {problem}", location(.line, .column))]
pub struct DataError {
    /// The file (or source) name, as given by the caller.
    pub file: String,
    /// 1-based line number (the header is line 1), when the problem is on one line.
    pub line: Option<u64>,
    /// The column's header name, when the problem is in one column.
    pub column: Option<String>,
    /// What is wrong and what was expected.
    pub problem: String,
}

impl DataError {
    /// A problem with the file as a whole.
    pub(crate) fn new(file: &str, problem: impl Into<String>) -> Self {
        DataError {
            file: file.to_owned(),
            line: None,
            column: None,
            // Cells and names are quoted in problems: a long one is cut.
            problem: crate::input::shorten(&problem.into()),
        }
    }

    /// Places the problem on a line.
    pub(crate) fn at_line(mut self, line: u64) -> Self {
        self.line = Some(line);
        self
    }

    /// Places the problem in a column.
    pub(crate) fn in_column(mut self, column: &str) -> Self {
        self.column = Some(column.to_owned());
        self
    }
}

fn location(line: &Option<u64>, column: &Option<String>) -> String {
    let mut text = String::new();
    if let Some(line) = line {
        let _ = write!(text, ", line {line}");
    }
    if let Some(column) = column {
        let _ = write!(text, ", column `{column}`");
    }
    text
}

impl From<OutputError> for DataError {
    fn from(error: OutputError) -> Self {
        DataError::new(
            &error.path.display().to_string(),
            format!("cannot {} it: {}", error.action, error.error),
        )
    }
}
