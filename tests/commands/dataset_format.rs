//! The measured-data CSV format end to end: datasets round-trip bit for bit and
//! byte-identically, columns are found in any order next to a rig's own, every malformed
//! input is refused with its file, line and column, and files are written atomically.

use std::fs;
use std::io::Write;
use std::path::Path;

use hcm_host::dataset::{
    sample_values, schema_markdown, BodyTrack, Channel, DataError, Dataset, Run, Sample,
};
use hcm_host::output::{write_atomically, OutputError};

/// The header, spelled out so that a change to the schema shows up here too.
const HEADER: &str = "run,body,time,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,fx,fy,fz,tx,ty,tz";

/// A row of `HEADER` at rest at `time`, with the cells named in `cells` replaced.
fn row(run: &str, body: &str, time: &str, cells: &[(&str, &str)]) -> String {
    HEADER
        .split(',')
        .map(|column| {
            if let Some((_, text)) = cells.iter().find(|(name, _)| *name == column) {
                return (*text).to_owned();
            }
            match column {
                "run" => run.to_owned(),
                "body" => body.to_owned(),
                "time" => time.to_owned(),
                "qw" => "1".to_owned(),
                _ => "0".to_owned(),
            }
        })
        .collect::<Vec<_>>()
        .join(",")
}

/// A file of `HEADER` and `rows`.
fn file(rows: &[String]) -> String {
    let mut text = format!("{HEADER}\n");
    for row in rows {
        text.push_str(row);
        text.push('\n');
    }
    text
}

/// A sample whose every number is a different awkward value.
fn awkward_sample(time: f64, seed: usize) -> Sample {
    const AWKWARD: [f64; 10] = [
        1e-300,
        -0.0,
        1.0 / 3.0,
        1e17,
        5e-324,
        f64::MAX,
        -f64::MIN_POSITIVE,
        0.1 + 0.2,
        -2.5e-7,
        std::f64::consts::PI,
    ];
    let value = |k: usize| AWKWARD[(seed + k) % AWKWARD.len()];
    Sample {
        time,
        position: [value(0), value(1), value(2)],
        orientation: [value(3), value(4), value(5), value(6)],
        velocity: [value(7), value(8), value(9)],
        angular_velocity: [value(1), value(3), value(5)],
        force: [value(2), value(4), value(6)],
        torque: [value(7), value(9), value(0)],
    }
}

/// Two runs of two bodies with awkward values and awkward names. In `trial_03` the first
/// body starts later than the second, so reading back must keep the body order.
fn awkward_dataset() -> Dataset {
    let times = [-0.0, 1e-300, 1.0 / 3.0, 1e17];
    let track = |body: &str, times: &[f64], seed: usize| BodyTrack {
        body: body.to_owned(),
        samples: times
            .iter()
            .enumerate()
            .map(|(i, &time)| awkward_sample(time, seed + i))
            .collect(),
    };
    Dataset {
        runs: vec![
            Run {
                id: "0".to_owned(),
                bodies: vec![track("ball", &times, 0), track("plate", &times, 3)],
            },
            Run {
                id: "trial_03".to_owned(),
                bodies: vec![
                    track("peg, \"left\"", &[0.5, 0.75], 5),
                    track("ball", &[0.0, 0.25, 0.5], 7),
                ],
            },
        ],
    }
}

/// Every number of a dataset as bits, with the names it belongs to.
fn bits(dataset: &Dataset) -> Vec<(String, String, Vec<u64>)> {
    let mut all = Vec::new();
    for run in &dataset.runs {
        for track in &run.bodies {
            for sample in &track.samples {
                let values = sample_values(sample);
                all.push((
                    run.id.clone(),
                    track.body.clone(),
                    values.iter().map(|v| v.to_bits()).collect(),
                ));
            }
        }
    }
    all
}

/// The names of the entries of `directory`, sorted.
fn entries(directory: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(directory)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn a_dataset_round_trips_bit_for_bit_and_byte_for_byte() {
    let dataset = awkward_dataset();
    let directory = tempfile::tempdir().unwrap();
    let path = directory.path().join("traj.csv");

    dataset.write(&path).unwrap();
    let first = fs::read(&path).unwrap();
    dataset.write(&path).unwrap();
    let second = fs::read(&path).unwrap();
    assert_eq!(first, second, "writing twice must give identical bytes");
    let mut in_memory = Vec::new();
    dataset.to_writer(&mut in_memory).unwrap();
    assert_eq!(
        first, in_memory,
        "file and writer must give identical bytes"
    );

    let text = String::from_utf8(first).unwrap();
    assert_eq!(text.lines().next(), Some(HEADER));
    assert_eq!(text.lines().count(), 1 + 4 + 4 + 2 + 3);

    let read = Dataset::read(&path).unwrap();
    assert_eq!(read, dataset);
    assert_eq!(
        bits(&read),
        bits(&dataset),
        "-0.0 and friends must keep their bits"
    );
    assert_eq!(entries(directory.path()), ["traj.csv"]);
}

#[test]
fn lookups_find_runs_and_bodies_by_name() {
    let dataset = awkward_dataset();
    let run = dataset.run("trial_03").unwrap();
    assert_eq!(run.body("ball").unwrap().samples.len(), 3);
    assert_eq!(run.body("peg, \"left\"").unwrap().samples.len(), 2);
    assert!(run.body("plate").is_none());
    assert!(dataset.run("trial_04").is_none());
    assert_eq!(Sample::at_rest(2.0).orientation, [1.0, 0.0, 0.0, 0.0]);
    assert_eq!(Sample::at_rest(2.0).time, 2.0);
}

#[test]
fn columns_in_any_order_next_to_a_rigs_own_columns_read_correctly() {
    // Schema reversed, with unknown columns at the start, middle and end.
    let mut columns: Vec<&str> = HEADER.split(',').rev().collect();
    columns.insert(0, "frame");
    columns.insert(9, "strain_gauge_raw");
    columns.push("note");
    let value = |column: &str, body: usize, step: usize| -> String {
        let index = HEADER.split(',').position(|name| name == column);
        match (column, index) {
            ("run", _) => "trial_03".to_owned(),
            ("body", _) => ["ball", "plate"][body].to_owned(),
            ("time", _) => format!(" {} ", step as f64 * 1e-3),
            (_, Some(index)) => format!("{}", (100 * body + 10 * step + index) as f64 / 8.0),
            // The rig's own cells are never parsed: even NaN or nothing is fine there.
            ("frame", _) => step.to_string(),
            ("strain_gauge_raw", _) => "NaN".to_owned(),
            _ => String::new(),
        }
    };
    let mut text = columns.join(",") + "\n";
    for step in 0..3 {
        for body in 0..2 {
            let cells: Vec<String> = columns.iter().map(|c| value(c, body, step)).collect();
            text.push_str(&cells.join(","));
            text.push('\n');
        }
    }

    let dataset = Dataset::from_reader("rig.csv", text.as_bytes()).unwrap();
    assert_eq!(dataset.runs.len(), 1);
    let run = dataset.run("trial_03").unwrap();
    let names: Vec<&str> = run.bodies.iter().map(|t| t.body.as_str()).collect();
    assert_eq!(names, ["ball", "plate"]);
    for (body, track) in run.bodies.iter().enumerate() {
        assert_eq!(track.samples.len(), 3);
        for (step, sample) in track.samples.iter().enumerate() {
            assert_eq!(sample.time, step as f64 * 1e-3);
            let expected = |column: &str| value(column, body, step).parse::<f64>().unwrap();
            assert_eq!(
                sample.position,
                [expected("px"), expected("py"), expected("pz")]
            );
            assert_eq!(
                sample.orientation,
                [
                    expected("qw"),
                    expected("qx"),
                    expected("qy"),
                    expected("qz")
                ]
            );
            assert_eq!(
                sample.velocity,
                [expected("vx"), expected("vy"), expected("vz")]
            );
            assert_eq!(
                sample.angular_velocity,
                [expected("wx"), expected("wy"), expected("wz")]
            );
            assert_eq!(
                sample.force,
                [expected("fx"), expected("fy"), expected("fz")]
            );
            assert_eq!(
                sample.torque,
                [expected("tx"), expected("ty"), expected("tz")]
            );
        }
    }
}

#[test]
fn interleaved_rows_are_grouped_by_run_then_body_in_order_of_first_appearance() {
    // Many rows, every (run, body) interleaved with the others, as a rig logging
    // several bodies at once would write them.
    let runs = ["b", "a", "c"];
    let bodies = ["peg", "hole", "gripper", "table"];
    let steps = 2000;
    let mut rows = Vec::with_capacity(runs.len() * bodies.len() * steps);
    for step in 0..steps {
        for run in runs {
            for body in bodies {
                let time = format!("{:?}", step as f64 * 1e-4);
                let fz = format!("{step}");
                rows.push(row(run, body, &time, &[("fz", &fz), ("pz", "-1e-3")]));
            }
        }
    }
    let dataset = Dataset::from_reader("log.csv", file(&rows).as_bytes()).unwrap();
    let run_ids: Vec<&str> = dataset.runs.iter().map(|r| r.id.as_str()).collect();
    assert_eq!(run_ids, runs);
    for run in &dataset.runs {
        let names: Vec<&str> = run.bodies.iter().map(|t| t.body.as_str()).collect();
        assert_eq!(names, bodies);
        for track in &run.bodies {
            assert_eq!(track.samples.len(), steps);
            for (step, sample) in track.samples.iter().enumerate() {
                assert_eq!(sample.time, step as f64 * 1e-4);
                assert_eq!(sample.force, [0.0, 0.0, step as f64]);
                assert_eq!(sample.position, [0.0, 0.0, -1e-3]);
            }
        }
    }

    // Written back in blocks, it reads back as the same dataset.
    let mut bytes = Vec::new();
    dataset.to_writer(&mut bytes).unwrap();
    assert_eq!(
        Dataset::from_reader("log.csv", &bytes[..]).unwrap(),
        dataset
    );
}

/// Reads `text` as `rig.csv`, expecting an error.
fn refused(text: &str) -> DataError {
    match Dataset::from_reader("rig.csv", text.as_bytes()) {
        Ok(dataset) => panic!("should have been refused, read {dataset:?}"),
        Err(error) => error,
    }
}

/// Checks that `error` names `rig.csv`, `line` and `column` and mentions each of `words`.
fn assert_names(error: &DataError, line: u64, column: &str, words: &[&str]) {
    let message = error.to_string();
    assert_eq!(error.file, "rig.csv", "{message}");
    assert_eq!(error.line, Some(line), "{message}");
    assert_eq!(error.column.as_deref(), Some(column), "{message}");
    let place = format!("rig.csv, line {line}, column `{column}`: ");
    assert!(
        message.starts_with(&place),
        "`{message}` should start with `{place}`"
    );
    for word in words {
        assert!(
            message.contains(word),
            "`{message}` should mention `{word}`"
        );
    }
}

#[test]
fn a_missing_column_is_named() {
    let header: Vec<&str> = HEADER.split(',').filter(|c| *c != "fy").collect();
    let text = format!(
        "{}\n{}\n",
        header.join(","),
        vec!["0"; header.len()].join(",")
    );
    assert_names(&refused(&text), 1, "fy", &["missing", "fy"]);

    // Several missing: the first is the column, the others are listed.
    let header: Vec<&str> = HEADER
        .split(',')
        .filter(|c| !["qx", "body", "tz"].contains(c))
        .collect();
    let text = format!(
        "{}\n{}\n",
        header.join(","),
        vec!["0"; header.len()].join(",")
    );
    assert_names(&refused(&text), 1, "body", &["missing", "qx", "tz"]);

    // Names are case-sensitive, and the message says so.
    let text = file(&[row("0", "ball", "0", &[])]).replace(",time,", ",Time,");
    assert_names(&refused(&text), 1, "time", &["`Time`", "case-sensitive"]);
}

#[test]
fn a_repeated_column_is_refused() {
    let text = format!("{HEADER},fx\n{},0\n", row("0", "ball", "0", &[]));
    assert_names(&refused(&text), 1, "fx", &["twice"]);
}

#[test]
fn a_non_numeric_cell_is_refused_with_its_text() {
    let text = file(&[
        row("0", "ball", "0", &[]),
        row("0", "ball", "0.001", &[("fx", "12.5 N")]),
    ]);
    assert_names(
        &refused(&text),
        3,
        "fx",
        &["`12.5 N`", "finite number", "in N"],
    );

    let text = file(&[row("0", "ball", "0,5", &[])]);
    // `0,5` is two cells: the row is one cell too long.
    let error = refused(&text);
    assert_eq!(
        (error.file.as_str(), error.line),
        ("rig.csv", Some(2)),
        "{error}"
    );
    assert!(error.problem.contains("23"), "{error}");

    let text = file(&[row("0", "ball", "zero", &[])]);
    assert_names(
        &refused(&text),
        2,
        "time",
        &["`zero`", "finite number in s"],
    );
}

#[test]
fn an_empty_cell_in_a_channel_otherwise_filled_is_refused() {
    let text = file(&[
        row("0", "ball", "0", &[]),
        row("0", "ball", "1", &[]),
        row("0", "ball", "2", &[("vz", "")]),
    ]);
    assert_names(&refused(&text), 4, "vz", &["empty cell", "m/s"]);

    let text = file(&[row("0", "", "0", &[])]);
    assert_names(&refused(&text), 2, "body", &["empty cell", "body name"]);

    let text = file(&[row(" ", "ball", "0", &[])]);
    assert_names(&refused(&text), 2, "run", &["empty cell", "run identifier"]);
}

/// `cells` of a row with every channel but `keep` left empty.
fn only(channels: &[&str], time: &str) -> String {
    let keep = |column: &str| channels.iter().any(|c| column.starts_with(c));
    let cells: Vec<(&str, &str)> = HEADER
        .split(',')
        .skip(3)
        .filter(|c| !keep(c))
        .map(|c| (c, ""))
        .collect();
    row("0", "ball", time, &cells)
}

#[test]
fn camera_frames_and_force_rows_read_as_channels_not_sampled() {
    let text = file(&[
        only(&["p", "q"], "0"),
        only(&["f", "t"], "0.00001"),
        only(&["f"], "0.00002"),
        only(&["p", "q", "v", "w"], "0.00005"),
    ]);
    let dataset = Dataset::from_reader("rig.csv", text.as_bytes()).unwrap();
    let samples = &dataset.runs[0].bodies[0].samples;
    let has = |i: usize| -> Vec<Channel> {
        Channel::ALL
            .into_iter()
            .filter(|&c| samples[i].has(c))
            .collect()
    };
    use Channel::*;
    assert_eq!(has(0), [Position, Orientation]);
    assert_eq!(has(1), [Force, Torque]);
    assert_eq!(has(2), [Force]);
    assert_eq!(has(3), [Position, Orientation, Velocity, AngularVelocity]);
    assert!(samples[0].force.iter().all(|f| f.is_nan()));
    assert!(samples[1].lacks(Velocity) && samples[1].lacks(Position));
    assert_eq!(samples[0].orientation, [1.0, 0.0, 0.0, 0.0]);
}

#[test]
fn a_channel_left_out_of_the_header_is_never_sampled() {
    // Tosses filmed without a force sensor: no f* and t* columns at all.
    let header: Vec<&str> = HEADER
        .split(',')
        .filter(|c| !c.starts_with('f') && !c.starts_with('t') || *c == "time")
        .collect();
    let values = [
        "toss_0", "cube", "0.5", "1", "2", "3", "1", "0", "0", "0", "0", "0", "0", "0", "0", "0",
    ];
    assert_eq!(header.len(), values.len());
    let text = format!("{}\n{}\n", header.join(","), values.join(","));
    let dataset = Dataset::from_reader("rig.csv", text.as_bytes()).unwrap();
    let sample = &dataset.runs[0].bodies[0].samples[0];
    assert_eq!(sample.position, [1.0, 2.0, 3.0]);
    assert!(sample.lacks(Channel::Force) && sample.lacks(Channel::Torque));

    // The shipped cube tosses read (their force cells are empty).
    let tosses =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/contactnets-cube/tosses.csv");
    if tosses.exists() {
        let tosses = Dataset::read(&tosses).unwrap();
        let samples = &tosses.runs[0].bodies[0].samples;
        assert!(samples
            .iter()
            .all(|s| s.has(Channel::Position) && s.lacks(Channel::Force)));
    }

    // A channel with only some of its columns is a missing column, and a header
    // with no channel at all is refused.
    let header = HEADER.replace(",tz", "");
    let text = format!("{header}\n{}\n", vec!["0"; 21].join(","));
    assert_names(
        &refused(&text),
        1,
        "tz",
        &["missing", "tz", "left out whole"],
    );
    let error = refused("run,body,time\n0,ball,0\n");
    assert_eq!(
        (error.line, error.column.as_deref()),
        (Some(1), None),
        "{error}"
    );
    assert!(error.to_string().contains("names no channel"), "{error}");
}

#[test]
fn a_row_without_any_channel_or_time_is_refused() {
    let text = file(&[row("0", "ball", "0", &[]), only(&[], "1")]);
    let error = refused(&text);
    assert_eq!(
        (error.line, error.column.as_deref()),
        (Some(3), None),
        "{error}"
    );
    assert!(
        error
            .to_string()
            .contains("every channel cell of the row is empty"),
        "{error}"
    );

    let text = file(&[only(&["f"], "")]);
    assert_names(&refused(&text), 2, "time", &["empty cell", "in s"]);

    let text = file(&[row("0", "ball", "0", &[("px", ""), ("pz", "")])]);
    assert_names(
        &refused(&text),
        2,
        "px",
        &["empty cell", "py is filled", "position"],
    );
}

#[test]
fn channels_not_sampled_are_written_as_empty_cells_and_read_back_bit_for_bit() {
    let mut dataset = awkward_dataset();
    for run in &mut dataset.runs {
        for track in &mut run.bodies {
            for (i, sample) in track.samples.iter_mut().enumerate() {
                // Alternate camera frames and force rows, and a row with only velocity.
                let cleared: &[Channel] = match i % 3 {
                    0 => &[Channel::Force, Channel::Torque, Channel::Velocity],
                    1 => &[
                        Channel::Position,
                        Channel::Orientation,
                        Channel::AngularVelocity,
                    ],
                    _ => &[
                        Channel::Position,
                        Channel::Orientation,
                        Channel::Force,
                        Channel::Torque,
                        Channel::AngularVelocity,
                    ],
                };
                for &channel in cleared {
                    sample.clear(channel);
                }
            }
        }
    }
    let mut bytes = Vec::new();
    dataset.to_writer(&mut bytes).unwrap();
    let text = String::from_utf8(bytes.clone()).unwrap();
    let first = text.lines().nth(1).unwrap();
    assert!(
        first.ends_with(",,,,,,") && !first.ends_with(",,,,,,,"),
        "{first}"
    );
    let read = Dataset::from_reader("rig.csv", &bytes[..]).unwrap();
    assert_eq!(read, dataset);
    assert_eq!(
        bits(&read),
        bits(&Dataset::from_reader("again", &bytes[..]).unwrap())
    );
    let mut again = Vec::new();
    read.to_writer(&mut again).unwrap();
    assert_eq!(again, bytes, "written twice, the same bytes");
    // Every number that was sampled keeps its bits.
    for (a, b) in bits(&read).iter().zip(bits(&dataset)) {
        for (x, y) in a.2.iter().zip(&b.2) {
            assert!(x == y || (f64::from_bits(*x).is_nan() && f64::from_bits(*y).is_nan()));
        }
    }

    // A sample with no channel at all would not read back.
    let mut empty = dataset.clone();
    empty.runs[0].bodies[0].samples[0] = Sample::unsampled(-0.0);
    let error = empty.to_writer(Vec::new()).unwrap_err();
    assert!(error.to_string().contains("no channel"), "{error}");
}

#[test]
fn nan_is_refused() {
    for nan in ["NaN", "nan", "-NaN"] {
        let text = file(&[row("0", "ball", "0", &[("qy", nan)])]);
        assert_names(&refused(&text), 2, "qy", &[&format!("`{nan}`"), "finite"]);
    }
}

#[test]
fn infinity_is_refused() {
    for inf in ["inf", "-inf", "+infinity", "1e400"] {
        let text = file(&[
            row("0", "ball", "0", &[]),
            row("0", "ball", "1", &[("tx", inf)]),
        ]);
        assert_names(
            &refused(&text),
            3,
            "tx",
            &[&format!("`{inf}`"), "finite", "N·m"],
        );
    }
}

#[test]
fn time_must_increase_within_a_run_and_body_only() {
    // The same time in another body or another run is fine.
    let text = file(&[
        row("0", "ball", "0.5", &[]),
        row("0", "plate", "0.5", &[]),
        row("1", "ball", "0.5", &[]),
        row("1", "ball", "0.75", &[]),
        row("0", "ball", "0.75", &[]),
    ]);
    let dataset = Dataset::from_reader("rig.csv", text.as_bytes()).unwrap();
    assert_eq!(
        dataset
            .run("0")
            .unwrap()
            .body("ball")
            .unwrap()
            .samples
            .len(),
        2
    );

    // Repeated within one (run, body), with other rows between.
    let text = file(&[
        row("0", "ball", "0.5", &[]),
        row("0", "plate", "0.5", &[]),
        row("0", "ball", "0.75", &[]),
        row("0", "plate", "0.75", &[]),
        row("0", "ball", "0.75", &[]),
    ]);
    assert_names(
        &refused(&text),
        6,
        "time",
        &["0.75 s after 0.75 s on line 4"],
    );

    // Going back.
    let text = file(&[
        row("trial_03", "ball", "0.002", &[]),
        row("trial_03", "ball", "0.001", &[]),
    ]);
    assert_names(
        &refused(&text),
        3,
        "time",
        &["0.001 s after 0.002 s on line 2", "trial_03", "ball"],
    );
}

#[test]
fn an_empty_file_is_refused() {
    for text in ["", "\n\n"] {
        let error = refused(text);
        assert_eq!(error.file, "rig.csv");
        assert_eq!(error.line, None);
        assert_eq!(error.column, None);
        let message = error.to_string();
        assert!(
            message.starts_with("rig.csv: the file is empty"),
            "{message}"
        );
        assert!(message.contains(HEADER), "{message}");
    }
}

#[test]
fn a_header_without_rows_is_refused() {
    let error = refused(&format!("{HEADER}\n"));
    assert_eq!(
        (error.line, error.column.as_deref()),
        (Some(1), None),
        "{error}"
    );
    let message = error.to_string();
    assert!(message.starts_with("rig.csv, line 1: "), "{message}");
    assert!(message.contains("no data rows"), "{message}");
}

#[test]
fn errors_from_files_name_the_path() {
    let directory = tempfile::tempdir().unwrap();
    let path = directory.path().join("rig.csv");
    let error = Dataset::read(&path).unwrap_err();
    assert_eq!(error.file, path.display().to_string());
    assert!(error.to_string().contains("cannot open"), "{error}");

    fs::write(&path, file(&[row("0", "ball", "0", &[("fz", "oops")])])).unwrap();
    let error = Dataset::read(&path).unwrap_err();
    let place = format!("{}, line 2, column `fz`: ", path.display());
    assert!(error.to_string().starts_with(&place), "{error}");
}

#[test]
fn the_writer_refuses_what_the_reader_would_refuse_and_writes_nothing() {
    let good = awkward_dataset();
    let mut nan = good.clone();
    nan.runs[1].bodies[0].samples[1].force[2] = f64::NAN;
    let mut backwards = good.clone();
    backwards.runs[0].bodies[1].samples[2].time = 0.0;
    let mut padded = good.clone();
    padded.runs[0].bodies[0].body = " ball".to_owned();
    let mut repeated = good.clone();
    repeated.runs[1].id = "0".to_owned();
    let mut empty_track = good.clone();
    empty_track.runs[0].bodies[0].samples.clear();
    let cases = [
        (nan, "fz"),
        (backwards, "time"),
        (padded, "body"),
        (repeated, "run"),
        (empty_track, "time"),
    ];
    for (dataset, column) in cases {
        let mut bytes = Vec::new();
        let error = dataset.to_writer(&mut bytes).unwrap_err();
        assert_eq!(error.column.as_deref(), Some(column), "{error}");
        assert!(
            bytes.is_empty(),
            "nothing may be written before refusing: {error}"
        );
    }
    let error = Dataset::default().to_writer(Vec::new()).unwrap_err();
    assert!(error.to_string().contains("no runs"), "{error}");
}

#[test]
fn a_failed_dataset_write_leaves_no_file() {
    let directory = tempfile::tempdir().unwrap();
    let path = directory.path().join("traj.csv");
    let mut dataset = awkward_dataset();
    dataset.runs[0].bodies[0].samples[0].velocity[0] = f64::INFINITY;
    let error = dataset.write(&path).unwrap_err();
    assert_eq!(error.file, path.display().to_string());
    assert!(entries(directory.path()).is_empty());

    fs::write(&path, "old").unwrap();
    dataset.write(&path).unwrap_err();
    assert_eq!(fs::read_to_string(&path).unwrap(), "old");
    assert_eq!(entries(directory.path()), ["traj.csv"]);
}

#[test]
fn an_atomic_write_that_fails_midway_leaves_nothing_behind() {
    let directory = tempfile::tempdir().unwrap();
    let path = directory.path().join("out.csv");
    let fail = |out: &mut dyn Write| -> anyhow::Result<()> {
        out.write_all(&[b'x'; 100_000])?;
        anyhow::bail!("the simulation diverged")
    };

    // No previous file: none afterwards, and no temporary file.
    let error = write_atomically(&path, fail).unwrap_err();
    assert_eq!(error.to_string(), "the simulation diverged");
    assert!(entries(directory.path()).is_empty());

    // A previous file keeps its content.
    fs::write(&path, "previous").unwrap();
    write_atomically(&path, fail).unwrap_err();
    assert_eq!(fs::read_to_string(&path).unwrap(), "previous");
    assert_eq!(entries(directory.path()), ["out.csv"]);

    // A panic midway is no different.
    let panicked = std::panic::catch_unwind(|| {
        let _ = write_atomically(&path, |out: &mut dyn Write| -> anyhow::Result<()> {
            out.write_all(b"half")?;
            panic!("bug in the writer");
        });
    });
    assert!(panicked.is_err());
    assert_eq!(fs::read_to_string(&path).unwrap(), "previous");
    assert_eq!(entries(directory.path()), ["out.csv"]);

    // Success replaces the content, again without leftovers.
    write_atomically(&path, |out: &mut dyn Write| -> anyhow::Result<()> {
        out.write_all(b"complete")?;
        Ok(())
    })
    .unwrap();
    assert_eq!(fs::read_to_string(&path).unwrap(), "complete");
    assert_eq!(entries(directory.path()), ["out.csv"]);
}

#[test]
fn an_atomic_write_into_a_missing_directory_names_the_destination() {
    let directory = tempfile::tempdir().unwrap();
    let path = directory.path().join("no_such_directory").join("out.csv");
    let error: OutputError =
        write_atomically(&path, |_: &mut dyn Write| Ok::<(), OutputError>(())).unwrap_err();
    assert_eq!(error.path, path);
    assert!(error.to_string().contains("out.csv"), "{error}");
    assert!(entries(directory.path()).is_empty());
}

#[test]
fn the_readme_documents_this_schema_with_a_readable_example() {
    let readme = include_str!("../../README.md");
    let (_, section) = readme
        .split_once("## Measured-data format")
        .expect("README section `## Measured-data format`");
    assert!(
        section.contains(&schema_markdown()),
        "update the README table to:\n{}",
        schema_markdown()
    );
    let (_, example) = section.split_once("```csv\n").expect("a ```csv example");
    let (example, _) = example.split_once("```").unwrap();
    assert_eq!(example.lines().next(), Some(HEADER));
    // The example is what the writer makes of a ball dropped from 10 cm.
    let mut released = Sample::at_rest(0.0);
    released.position[2] = 0.1;
    let mut after_1_ms = Sample::at_rest(0.001);
    after_1_ms.position[2] = 0.099995095;
    after_1_ms.velocity[2] = -0.00981;
    let dropped = Dataset {
        runs: vec![Run {
            id: "0".to_owned(),
            bodies: vec![BodyTrack {
                body: "ball".to_owned(),
                samples: vec![released, after_1_ms],
            }],
        }],
    };
    assert_eq!(
        Dataset::from_reader("README.md", example.as_bytes()).unwrap(),
        dropped
    );
    let mut written = Vec::new();
    dropped.to_writer(&mut written).unwrap();
    assert_eq!(String::from_utf8(written).unwrap(), example);
}
