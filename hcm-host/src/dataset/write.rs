//! Writing the CSV format: the dataset is checked first, then written run by run, and
//! within a run body by body, each body's samples in time order. [`RunWriter`] writes runs
//! as they come, for data too large to hold (`hcm generate`).

use std::collections::HashSet;
use std::fmt::Write as _;
use std::io::Write;

use super::channel::Channel;
use super::schema::{self, COLUMNS, FIRST_NUMERIC};
use super::{DataError, Dataset, Run, Sample};

/// The column an ensemble's file adds after the format's: which member a row belongs
/// to (0, 1, …).
pub const MEMBER_COLUMN: &str = "member";

/// Refuses a dataset the reader would not read back as the same dataset: no samples,
/// empty runs or bodies, empty, whitespace-padded or repeated names, non-finite values
/// other than a whole channel not sampled (NaN), samples with no channel, time not
/// strictly increasing within a body. `destination` names the output in errors.
pub(super) fn check(dataset: &Dataset, destination: &str) -> Result<(), DataError> {
    if dataset.runs.is_empty() {
        return Err(no_runs(destination));
    }
    let mut run_ids = HashSet::new();
    for run in &dataset.runs {
        check_id(run, destination)?;
        if !run_ids.insert(run.id.as_str()) {
            return refuse(
                destination,
                "run",
                format!("run `{}` appears twice", run.id),
            );
        }
        check_bodies(run, destination)?;
    }
    Ok(())
}

fn refuse(destination: &str, column: &str, problem: String) -> Result<(), DataError> {
    Err(DataError::new(destination, format!("cannot write: {problem}")).in_column(column))
}

fn no_runs(destination: &str) -> DataError {
    DataError::new(
        destination,
        "cannot write: the dataset has no runs; a file needs at least one sample",
    )
}

/// Refuses a run identifier that would not read back unchanged.
fn check_id(run: &Run, destination: &str) -> Result<(), DataError> {
    match name_problem(&run.id) {
        Some(problem) => refuse(
            destination,
            "run",
            format!("run identifier `{}` {problem}", run.id),
        ),
        None => Ok(()),
    }
}

/// Refuses a run whose bodies would not read back as they are (see [`check`]).
fn check_bodies(run: &Run, destination: &str) -> Result<(), DataError> {
    let refuse = |column: &str, problem: String| refuse(destination, column, problem);
    if run.bodies.is_empty() {
        return refuse("body", format!("run `{}` has no bodies", run.id));
    }
    let mut body_names = HashSet::new();
    for track in &run.bodies {
        let at = format!("run `{}`, body `{}`", run.id, track.body);
        if let Some(problem) = name_problem(&track.body) {
            return refuse("body", format!("{at}: the name {problem}"));
        }
        if !body_names.insert(track.body.as_str()) {
            return refuse("body", format!("{at} appears twice"));
        }
        if track.samples.is_empty() {
            return refuse("time", format!("{at} has no samples"));
        }
        let mut previous: Option<&Sample> = None;
        for (index, sample) in track.samples.iter().enumerate() {
            if let Some((column, problem)) = sample_problem(sample) {
                return refuse(column, format!("{at}, sample {index}: {problem}"));
            }
            if let Some(previous) = previous {
                if sample.time <= previous.time {
                    return refuse(
                        "time",
                        format!(
                            "{at}, sample {index}: time {:?} s does not come after {:?} s",
                            sample.time, previous.time
                        ),
                    );
                }
            }
            previous = Some(sample);
        }
    }
    Ok(())
}

/// Why a sample would not read back as it is, and the column to blame: a non-finite
/// time, a channel neither all finite nor all NaN (not sampled), or no channel at all.
fn sample_problem(sample: &Sample) -> Option<(&'static str, String)> {
    let values = schema::sample_values(sample);
    if !sample.time.is_finite() {
        let problem = format!("time {:?} s is not a finite number", sample.time);
        return Some((COLUMNS[schema::TIME].name, problem));
    }
    for channel in Channel::ALL {
        if sample.lacks(channel) {
            continue;
        }
        if let Some(offset) = channel.values().find(|&offset| !values[offset].is_finite()) {
            let problem = format!(
                "{:?} is not a finite number (a channel not sampled is NaN in every component: \
                 {})",
                values[offset],
                channel.described()
            );
            return Some((COLUMNS[FIRST_NUMERIC + offset].name, problem));
        }
    }
    if Channel::ALL.iter().all(|&channel| sample.lacks(channel)) {
        let problem = String::from("no channel was sampled (every number but time is NaN)");
        return Some((COLUMNS[schema::TIME].name, problem));
    }
    None
}

/// Why a run or body name would not read back unchanged, if it would not.
fn name_problem(name: &str) -> Option<&'static str> {
    if name.is_empty() {
        Some("is empty")
    } else if name.trim() != name {
        Some("has leading or trailing whitespace, which reading drops")
    } else {
        None
    }
}

/// Writes a dataset that passed [`check`]. `destination` names the output in errors.
pub(super) fn write(
    dataset: &Dataset,
    destination: &str,
    writer: impl Write,
) -> Result<(), DataError> {
    let mut out = RunWriter::new(writer, destination)?;
    for run in &dataset.runs {
        out.write_rows(run)?;
    }
    out.finish().map(drop)
}

/// Writes the measured-data format one run at a time, so that memory holds one run, not
/// the dataset: the same bytes as [`Dataset::write`] of the runs written. Each run is
/// checked as that checks a dataset, except that run identifiers are not compared across
/// runs (that would hold them all): the caller keeps them unique, as generated ids are.
pub struct RunWriter<W: Write> {
    csv: csv::Writer<W>,
    destination: String,
    runs: usize,
    /// The `member` column's value for the rows being written, when the file has one.
    member: Option<usize>,
    /// A reused buffer for one number's text.
    number: String,
}

impl<W: Write> RunWriter<W> {
    /// Starts the file with its header row. `destination` names the output in errors.
    pub fn new(writer: W, destination: &str) -> Result<Self, DataError> {
        Self::started(writer, destination, None)
    }

    /// Starts a file of an ensemble's members: the format's columns and then
    /// [`MEMBER_COLUMN`], the member's number (0, 1, …) on every row; runs are written
    /// with [`Self::write_member`]. Such a file holds a run id once per member, so it
    /// is not read back as one dataset.
    pub fn with_members(writer: W, destination: &str) -> Result<Self, DataError> {
        Self::started(writer, destination, Some(0))
    }

    fn started(writer: W, destination: &str, member: Option<usize>) -> Result<Self, DataError> {
        let mut out = RunWriter {
            csv: csv::Writer::from_writer(writer),
            destination: destination.to_owned(),
            runs: 0,
            member,
            number: String::new(),
        };
        let member_column = member.map(|_| MEMBER_COLUMN);
        let header = (COLUMNS.iter().map(|column| column.name)).chain(member_column);
        out.csv.write_record(header).map_err(|e| out.failed(e))?;
        Ok(out)
    }

    /// Checks and writes one run as member `member` of a file started
    /// [`Self::with_members`].
    pub fn write_member(&mut self, run: &Run, member: usize) -> Result<(), DataError> {
        if self.member.is_none() {
            return Err(DataError::new(
                &self.destination,
                "cannot write a member's run: the file has no `member` column",
            ));
        }
        self.member = Some(member);
        self.write_run(run)
    }

    /// Checks and writes one run.
    pub fn write_run(&mut self, run: &Run) -> Result<(), DataError> {
        check_id(run, &self.destination)?;
        check_bodies(run, &self.destination)?;
        self.write_rows(run)
    }

    /// Writes one checked run.
    fn write_rows(&mut self, run: &Run) -> Result<(), DataError> {
        for track in &run.bodies {
            for sample in &track.samples {
                self.write_sample(&run.id, &track.body, sample)
                    .map_err(|e| self.failed(e))?;
            }
        }
        self.runs += 1;
        Ok(())
    }

    fn write_sample(&mut self, run: &str, body: &str, sample: &Sample) -> csv::Result<()> {
        self.csv.write_field(run)?;
        self.csv.write_field(body)?;
        let values = schema::sample_values(sample);
        self.write_number(values[0])?;
        for channel in Channel::ALL {
            let unsampled = sample.lacks(channel);
            for &value in &values[channel.values()] {
                if unsampled {
                    // An empty cell: not sampled at this row.
                    self.csv.write_field("")?;
                } else {
                    self.write_number(value)?;
                }
            }
        }
        if let Some(member) = self.member {
            self.csv.write_field(member.to_string())?;
        }
        self.csv.write_record(None::<&[u8]>)
    }

    fn write_number(&mut self, value: f64) -> csv::Result<()> {
        self.number.clear();
        // `{:?}` is the shortest text that parses back to the same bits, with an
        // exponent for very large and small magnitudes (`1e-300`, `1e17`).
        let _ = write!(self.number, "{value:?}");
        self.csv.write_field(&self.number)
    }

    /// Flushes the rows and hands back the writer; refuses a file without runs.
    pub fn finish(self) -> Result<W, DataError> {
        if self.runs == 0 {
            return Err(no_runs(&self.destination));
        }
        let destination = self.destination;
        self.csv.into_inner().map_err(|error| {
            DataError::new(&destination, format!("cannot write: {}", error.error()))
        })
    }

    fn failed(&self, error: csv::Error) -> DataError {
        DataError::new(&self.destination, format!("cannot write: {error}"))
    }
}
