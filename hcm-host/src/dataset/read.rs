//! Reading the CSV format: one streaming pass, rows grouped by (run, body), every
//! problem reported with its file, line and column.

use std::collections::{HashMap, VecDeque};
use std::io::Read;

use super::channel::Channel;
use super::schema::{self, Column, BODY, COLUMNS, COLUMN_COUNT, FIRST_NUMERIC, NUMERIC_COUNT, RUN};
use super::{BodyTrack, DataError, Dataset, Run, Sample};

/// Reads a whole dataset from `reader`; `source` names it in errors.
pub(super) fn read(source: &str, reader: impl Read) -> Result<Dataset, DataError> {
    let mut csv = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(false)
        .from_reader(LineCounter::new(reader));
    let mut record = csv::StringRecord::new();
    let Some(header_line) = next_record(source, &mut csv, &mut record)? else {
        return Err(DataError::new(
            source,
            format!(
                "the file is empty; expected a header row `{}`",
                schema::csv_header()
            ),
        ));
    };
    let layout = Layout::from_header(source, header_line, &record)?;
    let mut groups = Groups::default();
    while let Some(line) = next_record(source, &mut csv, &mut record)? {
        groups.push(source, &layout, line, &record)?;
    }
    if groups.dataset.runs.is_empty() {
        return Err(DataError::new(
            source,
            "no data rows after the header; expected at least one sample",
        )
        .at_line(layout.line));
    }
    Ok(groups.dataset)
}

/// Reads the next record into `record` and returns the line it starts on; `None` at
/// the end of the input.
fn next_record<R: Read>(
    source: &str,
    csv: &mut csv::Reader<LineCounter<R>>,
    record: &mut csv::StringRecord,
) -> Result<Option<u64>, DataError> {
    match csv.read_record(record) {
        Ok(true) => {
            let start = record.position().map_or(0, |position| position.byte());
            Ok(Some(csv.get_mut().line_at(start)))
        }
        Ok(false) => Ok(None),
        Err(error) => Err(csv_error(source, csv.get_mut(), error)),
    }
}

/// Translates the csv crate's errors (ragged rows, invalid UTF-8, I/O).
fn csv_error<R>(source: &str, lines: &mut LineCounter<R>, error: csv::Error) -> DataError {
    let mut at = |error: DataError, position: &Option<csv::Position>| match position {
        Some(position) => error.at_line(lines.line_at(position.byte())),
        None => error,
    };
    match error.kind() {
        csv::ErrorKind::UnequalLengths {
            pos,
            expected_len,
            len,
        } => at(
            DataError::new(
                source,
                format!("expected {expected_len} cells as in the header, found {len}"),
            ),
            pos,
        ),
        csv::ErrorKind::Utf8 { pos, err } => at(
            DataError::new(
                source,
                format!(
                    "cell {} is not valid UTF-8 text; expected a UTF-8 CSV file",
                    err.field() + 1
                ),
            ),
            pos,
        ),
        csv::ErrorKind::Io(io) => DataError::new(source, format!("cannot read: {io}")),
        _ => DataError::new(source, error.to_string()),
    }
}

/// Passes the input through to the csv reader and notes where each non-blank line
/// starts, so that a record's line is exact. (The csv crate's own line numbers count a
/// record from the end of the previous one: they are one short after blank lines and
/// for every record of a CRLF file.) Line breaks are `\n`, `\r\n` and a lone `\r`, as
/// for the csv reader.
struct LineCounter<R> {
    inner: R,
    /// Offset of the next byte read.
    offset: u64,
    /// Line of the next byte read (1-based).
    line: u64,
    /// Whether the next byte starts a line.
    at_line_start: bool,
    /// Whether the last byte was `\r` (so that a following `\n` ends no further line).
    after_cr: bool,
    /// `(offset, line)` of the first byte of each non-blank line read and not yet
    /// passed by [`LineCounter::line_at`].
    starts: VecDeque<(u64, u64)>,
    /// Offset of the first byte of the line being read.
    line_start: u64,
}

/// The longest line read (bytes): a row of measured data is a few hundred bytes; a
/// file whose line runs past this is not one (a binary file, a file of NUL bytes),
/// and is refused before the csv reader buffers the line whole.
const LINE_LIMIT: u64 = 1 << 16;

impl<R> LineCounter<R> {
    fn new(inner: R) -> Self {
        LineCounter {
            inner,
            offset: 0,
            line: 1,
            at_line_start: true,
            after_cr: false,
            starts: VecDeque::new(),
            line_start: 0,
        }
    }

    /// The line of the first record that begins at or after byte `offset`: a record's
    /// reported start may precede it by blank lines or the `\n` of a `\r\n`, never by
    /// other bytes. Offsets must not decrease from call to call.
    fn line_at(&mut self, offset: u64) -> u64 {
        while self
            .starts
            .front()
            .is_some_and(|&(start, _)| start < offset)
        {
            self.starts.pop_front();
        }
        self.starts.front().map_or(self.line, |&(_, line)| line)
    }
}

impl<R: Read> Read for LineCounter<R> {
    fn read(&mut self, buffer: &mut [u8]) -> std::io::Result<usize> {
        let count = self.inner.read(buffer)?;
        let mut rest = &buffer[..count];
        while let Some((&byte, tail)) = rest.split_first() {
            match byte {
                b'\n' => {
                    if !self.after_cr {
                        self.line += 1;
                    }
                    self.at_line_start = true;
                    self.after_cr = false;
                }
                b'\r' => {
                    self.line += 1;
                    self.at_line_start = true;
                    self.after_cr = true;
                }
                _ => {
                    if self.at_line_start {
                        self.starts.push_back((self.offset, self.line));
                        self.line_start = self.offset;
                    }
                    self.at_line_start = false;
                    self.after_cr = false;
                    // Skip to the next line break in one go.
                    let content = tail
                        .iter()
                        .position(|&b| b == b'\n' || b == b'\r')
                        .unwrap_or(tail.len());
                    self.offset += content as u64;
                    rest = &tail[content..];
                    self.offset += 1;
                    if self.offset - self.line_start > LINE_LIMIT {
                        return Err(std::io::Error::new(
                            std::io::ErrorKind::InvalidData,
                            format!(
                                "line {} is longer than {LINE_LIMIT} bytes; a row of measured \
                                 data is a few hundred: is this a measured-data CSV?",
                                self.line
                            ),
                        ));
                    }
                    continue;
                }
            }
            self.offset += 1;
            rest = tail;
        }
        Ok(count)
    }
}

/// Where each column of the schema is in the file.
struct Layout {
    /// Line of the header.
    line: u64,
    /// `cell[i]` is the position in a row of `COLUMNS[i]`; None for the columns of a
    /// channel the file does not have.
    cell: [Option<usize>; COLUMN_COUNT],
}

impl Layout {
    fn from_header(source: &str, line: u64, header: &csv::StringRecord) -> Result<Self, DataError> {
        let here = |column: &str, problem: String| {
            DataError::new(source, problem)
                .at_line(line)
                .in_column(column)
        };
        let mut found: [Option<usize>; COLUMN_COUNT] = [None; COLUMN_COUNT];
        for (position, name) in header.iter().enumerate() {
            let name = match position {
                0 => name.trim_start_matches('\u{feff}').trim(),
                _ => name.trim(),
            };
            if let Some(index) = COLUMNS.iter().position(|column| column.name == name) {
                if let Some(first) = found[index] {
                    return Err(here(
                        name,
                        format!(
                            "appears twice in the header (cells {} and {}); expected it once",
                            first + 1,
                            position + 1
                        ),
                    ));
                }
                found[index] = Some(position);
            }
        }
        let near = |name: &str| {
            header
                .iter()
                .map(|cell| cell.trim_start_matches('\u{feff}').trim())
                .find(|cell| cell.eq_ignore_ascii_case(name))
        };
        let missing: Vec<&str> = COLUMNS
            .iter()
            .enumerate()
            .filter(|&(index, _)| {
                found[index].is_none()
                    && match Channel::of_column(index) {
                        // A channel is all there or all absent (a rig without a force
                        // sensor); a misspelt column is not an absent channel.
                        Some(channel) => channel.columns().any(|other| {
                            found[other].is_some() || near(COLUMNS[other].name).is_some()
                        }),
                        None => true,
                    }
            })
            .map(|(_, column)| column.name)
            .collect();
        if let Some(&first) = missing.first() {
            let mut problem = String::from("missing from the header");
            if let Some(near) = near(first) {
                problem.push_str(&format!(" (found `{near}`; names are case-sensitive)"));
            }
            if missing.len() > 1 {
                problem.push_str(&format!("; also missing: {}", missing[1..].join(", ")));
            }
            problem.push_str(&format!(
                "; expected all of {} in any order (a channel the rig does not record \
                 may be left out whole, e.g. all of fx, fy, fz)",
                schema::csv_header()
            ));
            return Err(here(first, problem));
        }
        if !Channel::ALL
            .iter()
            .any(|channel| found[channel.columns().start].is_some())
        {
            return Err(DataError::new(
                source,
                format!(
                    "the header names no channel; expected the columns of at least one of {}",
                    channel_list()
                ),
            )
            .at_line(line));
        }
        Ok(Layout { line, cell: found })
    }
}

/// Every channel with its columns, for messages.
fn channel_list() -> String {
    Channel::ALL.map(Channel::described).join(", ")
}

/// The dataset being assembled, with indexes to group rows in constant time.
#[derive(Default)]
struct Groups {
    dataset: Dataset,
    /// Run id → index in `dataset.runs`.
    runs: HashMap<String, usize>,
    /// Per run: body name → index in that run's `bodies`.
    bodies: Vec<HashMap<String, usize>>,
    /// Per run, per body: the line of its latest sample.
    last_line: Vec<Vec<u64>>,
}

impl Groups {
    /// Parses one data row and appends its sample to its (run, body).
    fn push(
        &mut self,
        source: &str,
        layout: &Layout,
        line: u64,
        record: &csv::StringRecord,
    ) -> Result<(), DataError> {
        let Row { run, body, sample } = parse_row(source, layout, line, record)?;
        let run_index = self.run_index(run);
        let body_index = self.body_index(run_index, body, line);
        let track = &mut self.dataset.runs[run_index].bodies[body_index];
        let last_line = &mut self.last_line[run_index][body_index];
        if let Some(previous) = track.samples.last() {
            if sample.time <= previous.time {
                return Err(DataError::new(
                    source,
                    format!(
                        "within run `{run}`, body `{body}`, time must increase strictly; \
                         found {:?} s after {:?} s on line {}",
                        sample.time, previous.time, last_line
                    ),
                )
                .at_line(line)
                .in_column(COLUMNS[schema::TIME].name));
            }
        }
        track.samples.push(sample);
        *last_line = line;
        Ok(())
    }

    /// The index of run `run` in the dataset; a new, empty run is appended at its first
    /// row.
    fn run_index(&mut self, run: &str) -> usize {
        match self.runs.get(run) {
            Some(&index) => index,
            None => {
                let index = self.dataset.runs.len();
                self.runs.insert(run.to_owned(), index);
                self.dataset.runs.push(Run {
                    id: run.to_owned(),
                    bodies: Vec::new(),
                });
                self.bodies.push(HashMap::new());
                self.last_line.push(Vec::new());
                index
            }
        }
    }

    /// The index of `body`'s track in run `run_index`; a new, empty track is appended at
    /// its first row (on line `line`).
    fn body_index(&mut self, run_index: usize, body: &str, line: u64) -> usize {
        let bodies = &mut self.bodies[run_index];
        let tracks = &mut self.dataset.runs[run_index].bodies;
        match bodies.get(body) {
            Some(&index) => index,
            None => {
                let index = tracks.len();
                bodies.insert(body.to_owned(), index);
                tracks.push(BodyTrack {
                    body: body.to_owned(),
                    samples: Vec::new(),
                });
                self.last_line[run_index].push(line);
                index
            }
        }
    }
}

/// One data row parsed: its run, its body and its sample.
struct Row<'r> {
    /// The run identifier.
    run: &'r str,
    /// The body's name.
    body: &'r str,
    /// The sample (SI units).
    sample: Sample,
}

/// Parses the data row `record` (on line `line`) whose columns `layout` places.
fn parse_row<'r>(
    source: &str,
    layout: &'r Layout,
    line: u64,
    record: &'r csv::StringRecord,
) -> Result<Row<'r>, DataError> {
    let cell = |index: usize| {
        layout.cell[index]
            .and_then(|position| record.get(position))
            .unwrap_or("")
            .trim()
    };
    let run = text(source, line, &COLUMNS[RUN], cell(RUN), "a run identifier")?;
    let body = text(source, line, &COLUMNS[BODY], cell(BODY), "a body name")?;
    let mut values = [f64::NAN; NUMERIC_COUNT];
    values[0] = number(source, line, &COLUMNS[schema::TIME], cell(schema::TIME))?;
    if !read_channels(source, line, &cell, &mut values)? {
        return Err(DataError::new(
            source,
            format!(
                "every channel cell of the row is empty; a row holds at least one of {}",
                channel_list()
            ),
        )
        .at_line(line));
    }
    let sample = schema::sample_from_values(values);
    Ok(Row { run, body, sample })
}

/// Reads into `values` every channel the row fills (a channel is filled whole, or left
/// empty whole); whether it fills any.
fn read_channels<'a>(
    source: &str,
    line: u64,
    cell: &impl Fn(usize) -> &'a str,
    values: &mut [f64; NUMERIC_COUNT],
) -> Result<bool, DataError> {
    let mut filled = false;
    for channel in Channel::ALL {
        let columns = channel.columns();
        let empty = columns
            .clone()
            .filter(|&index| cell(index).is_empty())
            .count();
        if empty == columns.len() {
            continue;
        }
        if empty > 0 {
            return Err(partial(source, line, channel, cell));
        }
        for index in columns {
            values[index - FIRST_NUMERIC] = number(source, line, &COLUMNS[index], cell(index))?;
        }
        filled = true;
    }
    Ok(filled)
}

/// The error for a channel only partly filled in a row: its first empty cell.
fn partial<'a>(
    source: &str,
    line: u64,
    channel: Channel,
    cell: &impl Fn(usize) -> &'a str,
) -> DataError {
    let columns = channel.columns();
    let (empty, filled): (Vec<usize>, Vec<usize>) =
        columns.clone().partition(|&index| cell(index).is_empty());
    let first = COLUMNS[empty[0]];
    let names = |indices: &[usize]| {
        indices
            .iter()
            .map(|&index| COLUMNS[index].name)
            .collect::<Vec<_>>()
            .join(", ")
    };
    DataError::new(
        source,
        format!(
            "expected {}, found an empty cell while {} {} filled: the {} channel ({}) is \
             filled whole, or left empty whole where it was not sampled",
            expected(&first),
            names(&filled),
            if filled.len() == 1 { "is" } else { "are" },
            channel.name(),
            channel.column_list(),
        ),
    )
    .at_line(line)
    .in_column(first.name)
}

/// The longest run identifier or body name (characters): names are quoted in
/// messages, and a name longer than this is a misread file, not a name.
const NAME_LIMIT: usize = 200;

/// A non-empty text cell of at most [`NAME_LIMIT`] characters.
fn text<'a>(
    source: &str,
    line: u64,
    column: &Column,
    cell: &'a str,
    expected: &str,
) -> Result<&'a str, DataError> {
    if cell.is_empty() {
        return Err(
            DataError::new(source, format!("expected {expected}, found an empty cell"))
                .at_line(line)
                .in_column(column.name),
        );
    }
    if cell.chars().count() > NAME_LIMIT {
        return Err(DataError::new(
            source,
            format!(
                "expected {expected} of at most {NAME_LIMIT} characters, found {} \
                 starting `{}`",
                cell.chars().count(),
                crate::input::excerpt(cell)
            ),
        )
        .at_line(line)
        .in_column(column.name));
    }
    Ok(cell)
}

/// What a numeric cell of `column` should hold, e.g. `a finite number in N`.
fn expected(column: &Column) -> String {
    match column.unit {
        "–" => String::from("a finite number"),
        unit => format!("a finite number in {unit}"),
    }
}

/// A finite number cell.
fn number(source: &str, line: u64, column: &Column, cell: &str) -> Result<f64, DataError> {
    let expected = expected(column);
    let found = match cell.parse::<f64>() {
        Ok(value) if value.is_finite() => return Ok(value),
        _ if cell.is_empty() => String::from("an empty cell"),
        _ => format!("`{}`", crate::input::excerpt(cell)),
    };
    Err(
        DataError::new(source, format!("expected {expected}, found {found}"))
            .at_line(line)
            .in_column(column.name),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_byte_order_mark_before_the_header_is_skipped() {
        let header = schema::csv_header();
        let text = format!("\u{feff}{header}\n0,ball,0,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n");
        let dataset = read("bom.csv", text.as_bytes()).unwrap();
        assert_eq!(dataset.runs[0].bodies[0].samples.len(), 1);
    }

    /// The line `read` blames for a repeated time in the last of `rows`, given with
    /// `separator` after each.
    fn line_of_repeated_time(rows: &[&str], separator: &str) -> Option<u64> {
        let mut text = schema::csv_header() + separator;
        for row in rows {
            text.push_str(row);
            text.push_str(separator);
        }
        let error = read("lines.csv", text.as_bytes()).unwrap_err();
        assert_eq!(error.column.as_deref(), Some("time"), "{error}");
        error.line
    }

    const ROW: &str = "0,ball,0,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0";
    const QUOTED: &str = "0,\"ball\",0,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0";

    #[test]
    fn line_numbers_are_exact_for_every_line_ending() {
        for separator in ["\n", "\r\n", "\r"] {
            assert_eq!(line_of_repeated_time(&[ROW, ROW], separator), Some(3));
            // Blank lines still count.
            assert_eq!(
                line_of_repeated_time(&[ROW, "", "", ROW], separator),
                Some(5),
                "{separator:?}"
            );
        }
        // Without a final line break.
        let text = format!("{}\n{ROW}\n\n{ROW}", schema::csv_header());
        assert_eq!(
            read("lines.csv", text.as_bytes()).unwrap_err().line,
            Some(4)
        );
    }

    #[test]
    fn a_line_break_inside_quotes_counts_as_a_line() {
        let two_lines = "0,\"ba\nll\",0,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0";
        let text = format!(
            "{}\n{two_lines}\n{QUOTED}\n{two_lines}\n",
            schema::csv_header()
        );
        let error = read("lines.csv", text.as_bytes()).unwrap_err();
        assert_eq!(error.line, Some(5), "{error}");
        let dataset = read(
            "lines.csv",
            format!("{}\n{two_lines}\n", schema::csv_header()).as_bytes(),
        );
        assert_eq!(dataset.unwrap().runs[0].bodies[0].body, "ba\nll");
    }

    #[test]
    fn a_short_row_is_reported_with_its_line() {
        let header = schema::csv_header();
        let text = format!("{header}\n0,ball,0,0,0\n");
        let error = read("short.csv", text.as_bytes()).unwrap_err();
        assert_eq!(error.line, Some(2), "{error}");
        assert!(error.problem.contains("22"), "{error}");
    }
}
