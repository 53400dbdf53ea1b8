//! The C examples (`examples/c/ball_hcm.c`, `examples/c/peg_hcm.c`) end to end: build
//! hcm-ffi's static library, compile each example with the system's `cc` against the
//! checked-in header, run it on the exported files (examples/blobs), and recompute every
//! value it prints in Rust through hcm_core: for the ball the law, the extended law and
//! the hybrid model (f32 and int8 residual), for the peg the contact model of the body
//! pair (`ContactModel::pair_load`: IMPACT + STEP friction at every contact point plus
//! the 13-32-32-6 wrench residual, f32 and int8) must agree **bit for bit**, and every
//! refusal must carry its error code.
//!
//! The examples print their inputs as raw bits, so this test reads the inputs from their
//! output rather than repeating their tables; the law's constants and status codes are
//! read from the header, so neither is repeated here either.

use hcm_core::effect::{Adhesion, ContactEffect, ContactMemory, ExtendedLaw, ViscousDamping};
use hcm_core::friction::VelocityStepFriction;
use hcm_core::law::{AnyNormalLaw, Impact, Indentation, LawKind, NormalLaw};
use hcm_core::model::{ContactModel, ContactPoint, Evaluated, Residual};
use hcm_core::residual::{decode, Envelope, F32Weights, Int8Weights, Mlp};
use nalgebra::Vector3;
use std::collections::HashMap;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// [`build_static_library`], once for all the tests of this file.
fn static_library() -> &'static Path {
    static LIBRARY: OnceLock<PathBuf> = OnceLock::new();
    LIBRARY.get_or_init(build_static_library)
}

/// Builds hcm-ffi with this test's profile and returns its static library, as Cargo
/// reports it (so any target directory works). The whole workspace's libraries, so
/// that features resolve as in the test build and its artifacts serve.
fn build_static_library() -> PathBuf {
    let exe = std::env::current_exe().expect("the test executable's path");
    // <target>/<profile folder>/deps/<test>: `debug` holds the dev and test profiles.
    let folder = exe
        .parent()
        .and_then(Path::parent)
        .and_then(Path::file_name);
    let profile = match folder.and_then(OsStr::to_str) {
        Some("debug") => "dev",
        Some(other) => other,
        None => panic!("the test executable lies in <target>/<profile>/deps"),
    };
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let output = Command::new(cargo)
        .current_dir(root())
        .args(["build", "--workspace", "--lib", "--profile", profile])
        .arg("--message-format=json-render-diagnostics")
        .output()
        .expect("cargo runs");
    assert!(
        output.status.success(),
        "building hcm-ffi failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .filter_map(|line| serde_json::from_str::<serde_json::Value>(line).ok())
        .filter(|message| message["reason"] == "compiler-artifact")
        .filter(|message| message["target"]["name"] == "hcm_ffi")
        .flat_map(|message| message["filenames"].as_array().cloned().unwrap_or_default())
        .filter_map(|name| name.as_str().map(PathBuf::from))
        .find(|path| path.extension() == Some(OsStr::new("a")))
        .expect("cargo reports libhcm_ffi.a")
}

/// Compiles the example `name` (`examples/c/<name>.c`) as the README says and runs it;
/// its standard output.
fn run_example(library: &Path, folder: &Path, name: &str) -> String {
    let exe = folder.join(name);
    let compile = Command::new("cc")
        .args([
            "-std=c11",
            "-O2",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-pedantic",
        ])
        .arg("-I")
        .arg(root().join("hcm-ffi/include"))
        .arg("-o")
        .arg(&exe)
        .arg(root().join(format!("examples/c/{name}.c")))
        .arg(library)
        .args(["-lpthread", "-ldl", "-lm"])
        .output()
        .expect("cc runs");
    assert!(
        compile.status.success(),
        "cc failed:\n{}",
        String::from_utf8_lossy(&compile.stderr)
    );
    let run = Command::new(&exe)
        .arg(root().join("examples/blobs"))
        .output()
        .expect("the example runs");
    assert!(
        run.status.success(),
        "{name} failed:\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8(run.stdout).expect("UTF-8 output")
}

/// The header's `#define NAME integer` and `  NAME = integer,` (enum) values.
fn header_values() -> HashMap<String, i64> {
    let header = std::fs::read_to_string(root().join("hcm-ffi/include/hcm.h")).unwrap();
    let mut values = HashMap::new();
    for line in header.lines() {
        let (name, value) = if let Some(rest) = line.strip_prefix("#define ") {
            match rest.split_once(' ') {
                Some(pair) => pair,
                None => continue,
            }
        } else if let Some((name, value)) = line.trim().split_once(" = ") {
            (name, value.trim_end_matches(','))
        } else {
            continue;
        };
        if let Ok(value) = value.parse() {
            values.insert(name.to_owned(), value);
        }
    }
    values
}

/// One printed record: its kind and its `key=value` fields (before ` # `).
struct Record {
    kind: String,
    fields: HashMap<String, String>,
}

impl Record {
    fn parse(line: &str) -> Record {
        let data = line.split(" # ").next().unwrap_or_default();
        let mut words = data.split_whitespace();
        let kind = words.next().unwrap_or_default().to_owned();
        let fields = words
            .filter_map(|word| word.split_once('='))
            .map(|(key, value)| (key.to_owned(), value.to_owned()))
            .collect();
        Record { kind, fields }
    }

    fn text(&self, key: &str) -> &str {
        self.fields
            .get(key)
            .unwrap_or_else(|| panic!("{}: no {key}", self.kind))
    }

    fn integer(&self, key: &str) -> i64 {
        self.text(key).parse().unwrap()
    }

    /// A float printed as its bits, `0x…`.
    fn float(&self, key: &str) -> f32 {
        bits_to_float(self.text(key))
    }

    /// Floats printed as their bits, `0x…,0x…`.
    fn floats(&self, key: &str) -> Vec<f32> {
        self.text(key).split(',').map(bits_to_float).collect()
    }

    /// [`Record::floats`] of exactly `N` floats.
    fn array<const N: usize>(&self, key: &str) -> [f32; N] {
        let values = self.floats(key);
        values
            .try_into()
            .unwrap_or_else(|v: Vec<f32>| panic!("{}: {key} has {} values", self.kind, v.len()))
    }

    /// The contact the record was evaluated at.
    fn contact(&self) -> (Indentation<f32>, ContactMemory<f32>) {
        let state = Indentation {
            depth: self.float("depth"),
            rate: self.float("rate"),
            approach_speed: self.float("approach_speed"),
        };
        let memory = ContactMemory {
            max_depth: self.float("max_depth"),
        };
        (state, memory)
    }

    /// [`Record::contact`] for a record that has one, else NaN (never read).
    fn contact_if_any(&self) -> (Indentation<f32>, ContactMemory<f32>) {
        if self.fields.contains_key("depth") {
            return self.contact();
        }
        let nan = Indentation {
            depth: f32::NAN,
            rate: f32::NAN,
            approach_speed: f32::NAN,
        };
        (
            nan,
            ContactMemory {
                max_depth: f32::NAN,
            },
        )
    }
}

/// `0x…` as the float of those bits.
fn bits_to_float(text: &str) -> f32 {
    let hex = text.trim_start_matches("0x");
    f32::from_bits(u32::from_str_radix(hex, 16).unwrap())
}

/// The ball's PM2 as the controller holds it: the TOML's f64 parameters rounded to f32.
fn pm2_law() -> AnyNormalLaw<f32> {
    let text = std::fs::read_to_string(root().join("examples/blobs/bouncing_ball.pm2.toml"));
    let pm2: toml::Table = toml::from_str(&text.unwrap()).unwrap();
    let contact = &pm2["contact"].as_array().unwrap()[0];
    let kind = LawKind::from_name(contact["law"].as_str().unwrap()).unwrap();
    let parameters = contact["parameters"].as_table().unwrap();
    let values: Vec<f32> = kind
        .parameters()
        .iter()
        .map(|p| parameters[p.name].as_float().unwrap() as f32)
        .collect();
    AnyNormalLaw::from_values(kind, &values).unwrap()
}

/// The hybrid model of the printed `record` recomputed with `residual`: each field.
fn check_hybrid<R: Residual<f32>>(
    record: &Record,
    law: &ExtendedLaw<f32>,
    residual: &R,
    envelope: &Envelope<3>,
) {
    let (state, memory) = record.contact();
    let input = [state.depth, state.rate, state.approach_speed];
    let model = ContactModel::physics(law.clone()).with_residual(residual);
    let (force, evaluated) = model.normal_force(&state, &memory, &input);
    let physics = model.physics_normal_force(&state, &memory);
    assert_eq!(
        record.float("force").to_bits(),
        force.to_bits(),
        "{input:?}"
    );
    assert_eq!(
        record.float("physics").to_bits(),
        physics.to_bits(),
        "{input:?}"
    );
    let used = evaluated == Evaluated::PhysicsAndResidual;
    assert_eq!(record.integer("residual_used") == 1, used, "{input:?}");
    let outside = (0..3)
        .filter(|&i| !(envelope.min[i] <= input[i] && input[i] <= envelope.max[i]))
        .fold(0, |mask, i| mask | 1 << i);
    assert_eq!(record.integer("outside"), outside, "{input:?}");
}

/// What the example's records are checked against: the core's own objects.
struct Reference {
    header: HashMap<String, i64>,
    law: AnyNormalLaw<f32>,
    /// The extended law, as the example's `effect` records build it.
    extended: ExtendedLaw<f32>,
    f32_mlp: Mlp<3, 16, 1, 2, F32Weights>,
    int8_mlp: Mlp<3, 16, 1, 2, Int8Weights>,
}

impl Reference {
    fn new() -> Reference {
        let blobs = root().join("examples/blobs");
        let read = |name: &str| std::fs::read(blobs.join(name)).unwrap();
        let law = pm2_law();
        Reference {
            header: header_values(),
            law,
            extended: ExtendedLaw::new(law),
            f32_mlp: decode(&read("bouncing_ball.f32.hcm")).unwrap(),
            int8_mlp: decode(&read("bouncing_ball.int8.hcm")).unwrap(),
        }
    }

    /// Checks one printed record (an `effect` record extends the extended law).
    fn check(&mut self, record: &Record, line: &str) {
        let (state, memory) = record.contact_if_any();
        let bits = |key: &str| record.float(key).to_bits();
        match record.kind.as_str() {
            "law" => self.check_law(record),
            "effect" => self.push_effect(record),
            "residual" => self.check_residual(record),
            "law_force" => assert_eq!(bits("force"), self.law.normal_force(&state).to_bits()),
            "extended_force" => {
                let model = ContactModel::physics(self.extended.clone());
                let force = model.physics_normal_force(&state, &memory);
                assert_eq!(bits("force"), force.to_bits(), "{line}");
            }
            "hybrid" => {
                let pm2 = ExtendedLaw::new(self.law);
                match record.text("weights") {
                    "f32" => check_hybrid(record, &pm2, &self.f32_mlp, &self.f32_mlp.envelope),
                    "int8" => check_hybrid(record, &pm2, &self.int8_mlp, &self.int8_mlp.envelope),
                    other => panic!("unknown weights {other}"),
                }
            }
            "check" => self.check_status(record),
            other => panic!("unknown record {other}: {line}"),
        }
    }

    /// The PM2 law's kind (the header's constant) and parameters, bit for bit.
    fn check_law(&self, record: &Record) {
        let name = format!("HCM_LAW_{}", self.law.name().to_uppercase());
        assert_eq!(record.integer("kind"), self.header[&name], "{name}");
        for (i, value) in self.law.values().iter().enumerate() {
            let printed = record.float(&format!("p{i}"));
            assert_eq!(printed.to_bits(), value.to_bits(), "parameter {i}");
        }
    }

    fn push_effect(&mut self, record: &Record) {
        let (kind, value) = (record.integer("kind"), record.float("p0"));
        let effect: ContactEffect<f32> = if kind == self.header["HCM_EFFECT_VISCOUS_DAMPING"] {
            ViscousDamping { coefficient: value }.into()
        } else if kind == self.header["HCM_EFFECT_ADHESION"] {
            Adhesion {
                pull_off_force: value,
            }
            .into()
        } else {
            panic!("the example uses another effect: kind {kind}")
        };
        self.extended.effects.push(effect).unwrap();
    }

    fn check_residual(&self, record: &Record) {
        let (quantisation, envelope) = match record.text("file") {
            "bouncing_ball.f32.hcm" => (0, self.f32_mlp.envelope),
            "bouncing_ball.int8.hcm" => (1, self.int8_mlp.envelope),
            other => panic!("unknown blob {other}"),
        };
        assert_eq!(record.integer("quantisation"), quantisation);
        for i in 0..3 {
            assert_eq!(record.float(&format!("min{i}")), envelope.min[i]);
            assert_eq!(record.float(&format!("max{i}")), envelope.max[i]);
        }
    }

    /// Each refusal the example shows returned its code (the header's value).
    fn check_status(&self, record: &Record) {
        let expected = match record.text("what") {
            "bit_flip" => "HCM_STATUS_BLOB_BAD_CRC",
            "truncated" => "HCM_STATUS_BLOB_TRUNCATED",
            "not_decoded" => "HCM_STATUS_NOT_DECODED",
            "null_blob" => "HCM_STATUS_NULL_POINTER",
            "unknown_law" => "HCM_STATUS_BAD_PARAMETER",
            "decode_again" => "HCM_STATUS_OK",
            other => panic!("unknown check {other}"),
        };
        assert_eq!(
            record.integer("status"),
            self.header[expected],
            "{expected}"
        );
    }
}

#[test]
fn the_c_example_matches_rusts_evaluation_bit_for_bit() {
    let folder = tempfile::tempdir().unwrap();
    let output = run_example(static_library(), folder.path(), "ball_hcm");
    let mut reference = Reference::new();
    let mut counts: HashMap<String, usize> = HashMap::new();
    for line in output.lines() {
        let record = Record::parse(line);
        reference.check(&record, line);
        *counts.entry(record.kind).or_default() += 1;
    }
    // Everything was there: the residual took part in most contacts and was off in one
    // outside its envelope and one out of contact, for both weight formats.
    assert_eq!(reference.extended.effects.len(), 2);
    let used = output
        .lines()
        .filter(|l| l.contains("residual_used=1"))
        .count();
    let off = output
        .lines()
        .filter(|l| l.contains("residual_used=0"))
        .count();
    assert_eq!((used, off), (8, 4), "{output}");
    for (kind, count) in [("law_force", 6), ("extended_force", 6), ("check", 6)] {
        assert_eq!(counts.get(kind), Some(&count), "{kind}");
    }
}

/// The peg's PM2 as the controller holds it: IMPACT and STEP friction, the TOML's f64
/// parameters rounded to f32.
fn peg_pm2() -> (Impact<f32>, VelocityStepFriction<f32>) {
    let text = std::fs::read_to_string(root().join("examples/blobs/peg_in_hole.pm2.toml"));
    let pm2: toml::Table = toml::from_str(&text.unwrap()).unwrap();
    let contact = &pm2["contact"].as_array().unwrap()[0];
    assert_eq!(contact["law"].as_str(), Some("impact"));
    let value = |table: &str, key: &str| contact[table][key].as_float().unwrap() as f32;
    let law = Impact {
        stiffness: value("parameters", "stiffness"),
        exponent: value("parameters", "exponent"),
        max_damping: value("parameters", "max_damping"),
        full_damping_depth: value("parameters", "full_damping_depth"),
    };
    let friction = VelocityStepFriction {
        static_coefficient: value("friction", "mu_static"),
        dynamic_coefficient: value("friction", "mu_dynamic"),
        stiction_speed: value("friction", "v_static"),
        dynamic_speed: value("friction", "v_dynamic"),
    };
    (law, friction)
}

/// A contact point as the peg example prints it: δ, δ̇, δ̇0, δ_max, then normal,
/// position, relative velocity and relative angular velocity.
fn printed_point(values: [f32; 16]) -> ContactPoint<f32> {
    let vector = |at: usize| Vector3::new(values[at], values[at + 1], values[at + 2]);
    ContactPoint {
        indentation: Indentation {
            depth: values[0],
            rate: values[1],
            approach_speed: values[2],
        },
        memory: ContactMemory {
            max_depth: values[3],
        },
        normal: vector(4),
        position: vector(7),
        relative_velocity: vector(10),
        relative_angular_velocity: vector(13),
    }
}

/// One `pair` record recomputed through `ContactModel::pair_load` with `residual`:
/// every printed result, bit for bit; whether the residual took part.
fn check_pair<R: Residual<f32>>(
    record: &Record,
    model: &ContactModel<f32, R>,
    envelope: &Envelope<13>,
) -> bool {
    let input: [f32; 13] = record.array("input");
    let count = usize::try_from(record.integer("count")).unwrap();
    let points: Vec<ContactPoint<f32>> = (0..count)
        .map(|i| printed_point(record.array(&format!("p{i}"))))
        .collect();
    let reference = Vector3::new(input[0], input[1], input[2]);
    let load = model.pair_load(&points, &reference, &Vector3::zeros(), &input);
    let bits = |values: &[f32]| values.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let state = record.text("state");
    let w = &load.wrench;
    assert_eq!(
        bits(&record.floats("force")),
        bits(w.force_1.as_slice()),
        "{state}"
    );
    assert_eq!(
        bits(&record.floats("torque")),
        bits(w.torque_1.as_slice()),
        "{state}"
    );
    let normal_force = record.float("normal_force");
    assert_eq!(
        normal_force.to_bits(),
        load.normal_force.to_bits(),
        "{state}"
    );
    let touching = points.iter().filter(|p| p.indentation.depth > 0.0).count();
    assert_eq!(record.integer("points_used"), touching as i64, "{state}");
    let used = load.evaluated == Evaluated::PhysicsAndResidual;
    assert_eq!(record.integer("residual_used") == 1, used, "{state}");
    let outside = envelope
        .distances(&input)
        .iter()
        .enumerate()
        .filter(|(_, d)| **d != 0.0)
        .fold(0, |mask, (i, _)| mask | 1 << i);
    assert_eq!(record.integer("outside"), outside, "{state}");
    used
}

/// What the peg example's records are checked against: the core's own objects.
struct PegReference {
    header: HashMap<String, i64>,
    law: Impact<f32>,
    friction: VelocityStepFriction<f32>,
    f32_mlp: Mlp<13, 32, 6, 2, F32Weights>,
    int8_mlp: Mlp<13, 32, 6, 2, Int8Weights>,
}

impl PegReference {
    fn new() -> PegReference {
        let blobs = root().join("examples/blobs");
        let read = |name: &str| std::fs::read(blobs.join(name)).unwrap();
        let (law, friction) = peg_pm2();
        PegReference {
            header: header_values(),
            law,
            friction,
            f32_mlp: decode(&read("peg_in_hole.f32.hcm")).unwrap(),
            int8_mlp: decode(&read("peg_in_hole.int8.hcm")).unwrap(),
        }
    }

    /// Checks one printed record; for a `pair` record, whether the residual took part.
    fn check(&self, record: &Record, line: &str) -> Option<bool> {
        let physics = ContactModel::physics(AnyNormalLaw::from(self.law));
        let physics = physics.with_friction(self.friction);
        match record.kind.as_str() {
            "physics" => self.check_physics(record),
            "residual" => self.check_residual(record),
            "pair" => {
                return Some(match record.text("weights") {
                    "f32" => {
                        let model = physics.with_residual(&self.f32_mlp);
                        check_pair(record, &model, &self.f32_mlp.envelope)
                    }
                    "int8" => {
                        let model = physics.with_residual(&self.int8_mlp);
                        check_pair(record, &model, &self.int8_mlp.envelope)
                    }
                    other => panic!("unknown weights {other}"),
                })
            }
            "check" => self.check_status(record),
            other => panic!("unknown record {other}: {line}"),
        }
        None
    }

    /// IMPACT and STEP (the header's constants) with the TOML's parameters, bit for bit.
    fn check_physics(&self, record: &Record) {
        assert_eq!(record.integer("law"), self.header["HCM_LAW_IMPACT"]);
        assert_eq!(record.integer("friction"), self.header["HCM_FRICTION_STEP"]);
        let law = self.law;
        let expected = [
            law.stiffness,
            law.exponent,
            law.max_damping,
            law.full_damping_depth,
        ];
        assert_eq!(record.array::<4>("law_parameters"), expected);
        let f = self.friction;
        let expected = [
            f.static_coefficient,
            f.dynamic_coefficient,
            f.stiction_speed,
            f.dynamic_speed,
        ];
        assert_eq!(record.array::<4>("friction_parameters"), expected);
    }

    fn check_residual(&self, record: &Record) {
        let (quantisation, envelope) = match record.text("file") {
            "peg_in_hole.f32.hcm" => (0, self.f32_mlp.envelope),
            "peg_in_hole.int8.hcm" => (1, self.int8_mlp.envelope),
            other => panic!("unknown blob {other}"),
        };
        assert_eq!(record.integer("quantisation"), quantisation);
        assert_eq!(record.text("shape"), "13-32-32-6");
        assert_eq!(record.array::<13>("min"), envelope.min);
        assert_eq!(record.array::<13>("max"), envelope.max);
    }

    /// Each refusal the example shows returned its code (the header's value).
    fn check_status(&self, record: &Record) {
        let expected = match record.text("what") {
            "nine_points" => "HCM_STATUS_BAD_PARAMETER",
            "not_decoded" => "HCM_STATUS_NOT_DECODED",
            "ball_blob" => "HCM_STATUS_BLOB_WRONG_SHAPE",
            "null_points" => "HCM_STATUS_NULL_POINTER",
            "unknown_friction" => "HCM_STATUS_BAD_PARAMETER",
            other => panic!("unknown check {other}"),
        };
        assert_eq!(
            record.integer("status"),
            self.header[expected],
            "{expected}"
        );
    }
}

#[test]
fn the_peg_example_matches_pair_load_bit_for_bit() {
    let folder = tempfile::tempdir().unwrap();
    let output = run_example(static_library(), folder.path(), "peg_hcm");
    let reference = PegReference::new();
    let mut counts: HashMap<String, usize> = HashMap::new();
    let mut used = [0_usize; 2];
    for line in output.lines() {
        let record = Record::parse(line);
        if let Some(residual_used) = reference.check(&record, line) {
            used[usize::from(residual_used)] += 1;
        }
        *counts.entry(record.kind).or_default() += 1;
    }
    // Six states, each with both weight formats: the residual took part at the four wall
    // states, not in flight (no point touches) nor at −3 m/s (outside its envelope).
    assert_eq!(used, [4, 8], "{output}");
    for (kind, count) in [("physics", 1), ("residual", 2), ("pair", 12), ("check", 5)] {
        assert_eq!(counts.get(kind), Some(&count), "{kind}");
    }
    assert!(output.contains(" count=4 "), "a state with four points");
}
