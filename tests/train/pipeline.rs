//! `hcm reproduce`'s pipeline as a library (`hcm_host::pipeline::reproduce`): its stages
//! report to the caller's progress in order, with their steps, and a second run repeats
//! the first bit for bit. (Moved from the library's unit tests: at the unit tests'
//! opt-level 0 it took 8 s; here the library is optimised.)

use hcm_host::pipeline::{reproduce, write_reproduction, Example, Pm2Method, ReproduceSettings};
use hcm_host::progress::{Progress, Silent, Stage};
use std::sync::Mutex;

/// Progress that keeps what it is told.
#[derive(Default)]
struct Log {
    /// (stage, true at its begin / false at its end, steps).
    stages: Mutex<Vec<(Stage, bool, u64)>>,
    /// Every (done, steps) with done > steps.
    overruns: Mutex<Vec<(u64, u64)>>,
    /// The largest `done` of the generation.
    generated: Mutex<u64>,
}

impl Progress for Log {
    fn begin(&self, stage: Stage, steps: u64) {
        self.stages.lock().unwrap().push((stage, true, steps));
    }
    fn advance(&self, done: u64, steps: u64) {
        if done > steps {
            self.overruns.lock().unwrap().push((done, steps));
        }
        let stages = self.stages.lock().unwrap();
        if stages.last().map(|s| s.0) == Some(Stage::Generate) {
            let mut generated = self.generated.lock().unwrap();
            *generated = (*generated).max(done);
        }
    }
    fn end(&self, stage: Stage) {
        self.stages.lock().unwrap().push((stage, false, 0));
    }
}

fn settings() -> ReproduceSettings {
    ReproduceSettings {
        runs: 12,
        method: Pm2Method::Lsq,
        seed: 4,
        ..ReproduceSettings::paper(Example::BouncingBall)
    }
}

#[test]
fn the_stages_report_in_order_and_repeat_bit_for_bit() {
    let log = Log::default();
    let first = reproduce(&settings(), &log).unwrap();
    let stages = log.stages.into_inner().unwrap();
    let order = [
        Stage::Generate,
        Stage::Identify,
        Stage::Train,
        Stage::Int8Twin,
        Stage::Evaluate,
    ];
    let expected: Vec<(Stage, bool)> = order
        .iter()
        .flat_map(|&s| [(s, true), (s, false)])
        .collect();
    let told: Vec<(Stage, bool)> = stages.iter().map(|&(s, b, _)| (s, b)).collect();
    assert_eq!(told, expected);
    assert_eq!(stages[0].2, 12, "12 runs of the ball's one condition");
    assert_eq!(log.generated.into_inner().unwrap(), 12);
    assert!(log.overruns.into_inner().unwrap().is_empty());

    // The same files again, bit for bit but for the wall-clock times.
    let mut first = first;
    let mut again = reproduce(&settings(), &Silent).unwrap();
    let dirs = [tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap()];
    write_reproduction(&mut first, dirs[0].path()).unwrap();
    write_reproduction(&mut again, dirs[1].path()).unwrap();
    let mut names: Vec<String> = std::fs::read_dir(dirs[0].path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    for figure in [
        "contact_force.svg",
        "contact_force.png",
        "force_error.svg",
        "force_error.png",
    ] {
        assert!(names.iter().any(|n| n == figure), "{figure} in {names:?}");
    }
    for name in &names {
        let [a, b] = [0, 1].map(|i| std::fs::read(dirs[i].path().join(name)).unwrap());
        match name.as_str() {
            "report.md" => {}
            "results.json" => {
                let [a, b] = [a, b].map(|t| untimed(serde_json::from_slice(&t).unwrap()));
                assert_eq!(a, b, "{name}");
            }
            _ if name.ends_with(".toml") => {
                let [a, b] = [a, b].map(|t| {
                    let text = String::from_utf8(t).unwrap();
                    text.lines()
                        .filter(|l| !l.starts_with("seconds"))
                        .map(str::to_owned)
                        .collect::<Vec<_>>()
                });
                assert_eq!(a, b, "{name}");
            }
            _ => assert!(a == b, "{name} differs"),
        }
    }
}

/// `value` without its wall-clock times (`timings`, `seconds`).
fn untimed(value: serde_json::Value) -> serde_json::Value {
    match value {
        serde_json::Value::Object(map) => map
            .into_iter()
            .filter(|(k, _)| k != "timings" && k != "seconds")
            .map(|(k, v)| (k, untimed(v)))
            .collect(),
        serde_json::Value::Array(items) => items.into_iter().map(untimed).collect(),
        other => other,
    }
}
