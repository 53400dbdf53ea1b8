//! A power study's rows: one per data set, what was hidden and what the diagnosis
//! answered, as CSV after a line that says which study they belong to. A shard's file
//! holds its data sets' rows under the same line, so that the rows of every shard, in
//! order, are those of the whole study, byte for byte.

use super::PowerError;
use serde::{Deserialize, Serialize};
use std::io::{BufRead, Write};

/// What one data set of a power study held and what `hcm diagnose` named in it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PowerRow {
    /// The data set's index in the study.
    pub data_set: usize,
    /// The hidden effect's catalogue name; `none` for nothing hidden.
    pub effect: String,
    /// Its strength, a share of the peak force (–); 0 with nothing hidden.
    pub level: f64,
    /// The data set's seed (`hcm generate --seed`).
    pub seed: u64,
    /// The hidden effect's first parameter (its name); empty with nothing hidden.
    pub parameter: String,
    /// Its true value (the parameter's unit); NaN with nothing hidden.
    pub truth: f64,
    /// The diagnosis's answer in one line (`hcm_host::diagnose::answer`).
    pub answer: String,
    /// The causes it named, joined by `+`; empty for none.
    pub named: String,
    /// The hidden effect named and nothing else (no cause, ambiguity or unexplained
    /// share beside it); with nothing hidden, nothing named.
    pub exact: bool,
    /// A cause named that was not hidden.
    pub wrong: bool,
    /// The named hidden effect's estimate of the parameter; NaN if not named.
    pub value: f64,
    /// Its 95 % interval's lower end; NaN if not named or not determined.
    pub low: f64,
    /// Its 95 % interval's upper end.
    pub high: f64,
}

impl PowerRow {
    /// Whether the named hidden effect's 95 % interval holds the truth.
    pub fn covered(&self) -> bool {
        self.low <= self.truth && self.truth <= self.high
    }
}

/// The first line of a study's file: `# hcm power: ` and the study's key.
fn key_line(key: &str) -> String {
    format!("# hcm power: {key}")
}

/// Writes the study's line for `key` and `rows` (CSV with a header) to `out`.
pub fn write_rows(out: &mut dyn Write, key: &str, rows: &[PowerRow]) -> Result<(), PowerError> {
    let csv_error = |e: csv::Error| PowerError::Setup(format!("cannot write the rows: {e}"));
    writeln!(out, "{}", key_line(key))
        .map_err(|e| PowerError::Setup(format!("cannot write the rows: {e}")))?;
    let mut writer = csv::WriterBuilder::new().has_headers(true).from_writer(out);
    if rows.is_empty() {
        // A shard with no data set still says which columns a row has.
        writer.write_record(HEADER).map_err(csv_error)?;
    }
    for row in rows {
        writer.serialize(row).map_err(csv_error)?;
    }
    writer.flush().map_err(|e| csv_error(e.into()))?;
    Ok(())
}

/// The CSV header: [`PowerRow`]'s fields in order.
const HEADER: [&str; 13] = [
    "data_set",
    "effect",
    "level",
    "seed",
    "parameter",
    "truth",
    "answer",
    "named",
    "exact",
    "wrong",
    "value",
    "low",
    "high",
];

/// The rows in `text` (a file named `name`) of the study keyed `key`: refused, with the
/// line at fault, if the file belongs to another study or a row does not read.
pub fn read_rows(name: &str, text: &[u8], key: &str) -> Result<Vec<PowerRow>, PowerError> {
    let fail = |line: usize, what: String| PowerError::Rows {
        file: name.to_owned(),
        line,
        what,
    };
    let mut reader = std::io::BufReader::new(text);
    let mut first = String::new();
    reader
        .read_line(&mut first)
        .map_err(|e| fail(1, e.to_string()))?;
    let first = first.trim_end_matches(['\n', '\r']);
    if first != key_line(key) {
        return Err(fail(
            1,
            format!(
                "it is not a shard of this study: it reads `{first}`, this study is \
                 `{}` (run each shard with the same --scenario, --set and options)",
                key_line(key)
            ),
        ));
    }
    let mut csv = csv::ReaderBuilder::new().from_reader(reader);
    let header: Vec<String> = (csv.headers())
        .map_err(|e| fail(2, e.to_string()))?
        .iter()
        .map(str::to_owned)
        .collect();
    if header != HEADER {
        return Err(fail(
            2,
            format!(
                "the header reads `{}`, expected `{}`",
                header.join(","),
                HEADER.join(",")
            ),
        ));
    }
    csv.deserialize()
        .enumerate()
        .map(|(k, row)| row.map_err(|e| fail(k + 3, e.to_string())))
        .collect()
}
