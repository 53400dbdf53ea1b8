//! Writing the CSV format: the dataset is checked first, then written run by run, and
//! within a run body by body, each body's samples in time order.

use std::collections::HashSet;
use std::fmt::Write as _;
use std::io::Write;

use super::schema::{self, COLUMNS, FIRST_NUMERIC};
use super::{DataError, Dataset, Sample};

/// Refuses a dataset the reader would not read back as the same dataset: no samples,
/// empty runs or bodies, empty, whitespace-padded or repeated names, non-finite values,
/// time not strictly increasing within a body. `destination` names the output in errors.
pub(super) fn check(dataset: &Dataset, destination: &str) -> Result<(), DataError> {
    let refuse = |column: &str, problem: String| {
        Err(DataError::new(destination, format!("cannot write: {problem}")).in_column(column))
    };
    if dataset.runs.is_empty() {
        return Err(DataError::new(
            destination,
            "cannot write: the dataset has no runs; a file needs at least one sample",
        ));
    }
    let mut run_ids = HashSet::new();
    for run in &dataset.runs {
        if let Some(problem) = name_problem(&run.id) {
            return refuse("run", format!("run identifier `{}` {problem}", run.id));
        }
        if !run_ids.insert(run.id.as_str()) {
            return refuse("run", format!("run `{}` appears twice", run.id));
        }
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
                let values = schema::sample_values(sample);
                if let Some(offset) = values.iter().position(|value| !value.is_finite()) {
                    return refuse(
                        COLUMNS[FIRST_NUMERIC + offset].name,
                        format!(
                            "{at}, sample {index}: {:?} is not a finite number",
                            values[offset]
                        ),
                    );
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
    }
    Ok(())
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
    let failed = |error: csv::Error| DataError::new(destination, format!("cannot write: {error}"));
    let mut csv = csv::Writer::from_writer(writer);
    csv.write_record(COLUMNS.iter().map(|column| column.name))
        .map_err(failed)?;
    let mut number = String::new();
    for run in &dataset.runs {
        for track in &run.bodies {
            for sample in &track.samples {
                csv.write_field(&run.id).map_err(failed)?;
                csv.write_field(&track.body).map_err(failed)?;
                for value in schema::sample_values(sample) {
                    number.clear();
                    // `{:?}` is the shortest text that parses back to the same bits, with
                    // an exponent for very large and small magnitudes (`1e-300`, `1e17`).
                    let _ = write!(number, "{value:?}");
                    csv.write_field(&number).map_err(failed)?;
                }
                csv.write_record(None::<&[u8]>).map_err(failed)?;
            }
        }
    }
    csv.flush()
        .map_err(|error| DataError::new(destination, format!("cannot write: {error}")))
}
