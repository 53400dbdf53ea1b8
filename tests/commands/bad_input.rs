//! Every bad input answered: a value that parses but is physically
//! impossible, an error in a physics file, a `--set` or numeric option of the wrong
//! kind, a damaged weights blob, a run without contact. Each message must name the
//! file, key or option and what was expected, and a refused command must leave
//! nothing behind.

use hcm_host::scenario::Scenario;
use hcm_tests::cli::Hcm;
use hcm_tests::scenario;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The names of the files in the fixture's directory.
fn files(hcm: &Hcm) -> BTreeSet<String> {
    std::fs::read_dir(hcm.dir())
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

/// Runs `call` (which must fail) and asserts that it wrote nothing: its `--out`
/// absent, and no other file (S1/S2 files, temporaries) in the directory.
fn refused(hcm: &Hcm, out: &Path, call: hcm_tests::cli::Call) -> String {
    let before = files(hcm);
    let stderr = call.fails();
    assert!(!out.exists(), "{} was written:\n{stderr}", out.display());
    assert_eq!(files(hcm), before, "something was left behind:\n{stderr}");
    stderr
}

/// `hcm simulate --scenario scenario --out out`.
fn simulate(
    hcm: &Hcm,
    scenario: impl AsRef<std::ffi::OsStr>,
    out: impl AsRef<std::ffi::OsStr>,
) -> hcm_tests::cli::Call {
    hcm.run("simulate")
        .opt("--scenario", scenario)
        .opt("--out", out)
}

/// Asserts that `message` contains every one of `parts`.
fn says(message: &str, parts: &[&str]) {
    for part in parts {
        assert!(message.contains(part), "no `{part}` in:\n{message}");
    }
}

/// The bouncing-ball scenario with `from` replaced by `to`, written to the fixture's
/// directory as `name`.
fn edited_ball(hcm: &Hcm, name: &str, from: &str, to: &str) -> PathBuf {
    edited(hcm, "bouncing_ball.toml", name, from, to)
}

#[test]
fn an_impossible_material_is_refused_by_key_with_its_allowed_range() {
    let hcm = Hcm::new();
    let out = hcm.path("trajectory.csv");
    let cases = [
        (
            "poisson_ratio = 0.3",
            "poisson_ratio = 0.5",
            "material.steel.poisson_ratio",
            "(-1, 0.5)",
            "found 0.5",
        ),
        (
            "poisson_ratio = 0.25",
            "poisson_ratio = -1.2",
            "material.concrete.poisson_ratio",
            "(-1, 0.5)",
            "found -1.2",
        ),
        (
            "youngs_modulus = 2.06e11",
            "youngs_modulus = -2.06e11",
            "material.steel.youngs_modulus",
            "greater than zero",
            "found -2.06e11",
        ),
        (
            "youngs_modulus = 2.5193e10",
            "youngs_modulus = 0.0",
            "material.concrete.youngs_modulus",
            "greater than zero",
            "found 0",
        ),
    ];
    for (i, (from, to, key, expected, found)) in cases.into_iter().enumerate() {
        let path = edited_ball(&hcm, &format!("ball{i}.toml"), from, to);
        let stderr = refused(&hcm, &out, simulate(&hcm, &path, &out));
        says(&stderr, &[&format!("ball{i}.toml"), key, expected, found]);
    }
    // Also through --set: the same check, whatever set the value.
    let stderr = refused(
        &hcm,
        &out,
        hcm.run("simulate")
            .opt("--scenario", scenario("bouncing_ball.toml"))
            .opt("--set", "material.steel.poisson_ratio=0.7")
            .opt("--out", &out),
    );
    says(
        &stderr,
        &["material.steel.poisson_ratio", "(-1, 0.5)", "found 0.7"],
    );
}

#[test]
fn bodies_starting_inside_each_other_are_refused_with_the_fix() {
    let hcm = Hcm::new();
    let out = hcm.path("trajectory.csv");
    // Today's culprit: 0.5 m inside the ground simulated 300,001 rows of free fall.
    let stderr = refused(
        &hcm,
        &out,
        hcm.run("simulate")
            .opt("--scenario", scenario("bouncing_ball.toml"))
            .opt("--set", "body.ball.position=[0, 0, -0.5]")
            .opt("--out", &out),
    );
    says(
        &stderr,
        &[
            "bouncing_ball.toml",
            "body.ball.position",
            "0.5127 m inside `ground`",
            "at most 1.27e-5 m deep",
            "position = [0, 0, 0.0127] starts it touching",
        ],
    );
    // The plate pushed 5 mm into the resting ball of the flat shot.
    let stderr = refused(
        &hcm,
        &out,
        hcm.run("simulate")
            .opt("--scenario", scenario("flat_shot.toml"))
            .opt("--set", "body.plate.position=[0, -0.005, 0]")
            .opt("--out", &out),
    );
    says(
        &stderr,
        &[
            "flat_shot.toml",
            "body.ball.position",
            "0.005 m inside `plate`",
            "position = [0, 0.0177, 0]",
        ],
    );
}

#[test]
fn touching_and_slightly_preloaded_starts_still_load() {
    // The flat shot starts touching (δ = 0); a preload below 10⁻³·R is a contact
    // state, not an overlap; a little deeper is refused.
    let flat_shot = scenario("flat_shot.toml");
    Scenario::load(&flat_shot, &[]).unwrap().model().unwrap();
    let ball = scenario("bouncing_ball.toml");
    Scenario::load(&ball, &[]).unwrap().model().unwrap();
    let at = |height: f64| {
        let set = [format!("body.ball.position=[0, 0, {height}]")];
        Scenario::load(&ball, &set).unwrap().model()
    };
    at(0.0127 - 1.2e-5).unwrap();
    let error = at(0.0127 - 1.3e-5).unwrap_err().to_string();
    says(&error, &["body.ball.position", "1.3e-5 m inside `ground`"]);
}

/// The bouncing ball's S1 and S2 files (10 runs), generated in `hcm`'s directory.
fn ball_data(hcm: &Hcm) -> (PathBuf, PathBuf) {
    hcm.run("generate")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--runs", "10")
        .opt("--seed", "3")
        .opt("--out", hcm.path("data.csv"))
        .ok();
    (hcm.path("data.s1.csv"), hcm.path("data.s2.csv"))
}

/// A Lankarani–Nikravesh physics file with `parameters` (an inline TOML table's
/// inside) and `law`.
fn physics_file(hcm: &Hcm, name: &str, law: &str, parameters: &str) -> PathBuf {
    let path = hcm.path(name);
    let text = format!(
        "[[contact]]\nbodies = [\"ball\", \"ground\"]\nlaw = \"{law}\"\nparameters = {{ {parameters} }}\n"
    );
    std::fs::write(&path, text).unwrap();
    path
}

const LN: &str = "stiffness = 6.86e9, exponent = 1.489, restitution = 0.929";

#[test]
fn a_malformed_set_in_a_physics_file_is_refused_where_it_is_read() {
    let hcm = Hcm::new();
    let (_, s2) = ball_data(&hcm);
    let path = hcm.path("sets.toml");
    let contact =
        std::fs::read_to_string(physics_file(&hcm, "pm2.toml", "lankarani_nikravesh", LN)).unwrap();
    std::fs::write(&path, format!("sets = [\"body.ball.velocity\"]\n{contact}")).unwrap();
    let evaluate = hcm
        .run("evaluate")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--data", &s2)
        .opt("--physics", &path);
    says(
        &refused(&hcm, &hcm.path("none"), evaluate),
        &["physics file", "sets.toml", "line 1", "expected key=value"],
    );
}

#[test]
fn a_physics_file_error_names_the_physics_file_and_its_key() {
    let hcm = Hcm::new();
    let (s1, s2) = ball_data(&hcm);
    let ball = scenario("bouncing_ball.toml");
    let good = physics_file(&hcm, "pm2.toml", "lankarani_nikravesh", LN);
    hcm.run("evaluate")
        .opt("--scenario", &ball)
        .opt("--data", &s2)
        .opt("--physics", &good)
        .ok();

    let unknown = physics_file(&hcm, "unknown.toml", "lankarani", LN);
    let domain = physics_file(
        &hcm,
        "domain.toml",
        "lankarani_nikravesh",
        &LN.replace("0.929", "1.5"),
    );
    let other = physics_file(
        &hcm,
        "other.toml",
        "lankarani_nikravesh",
        "stiffness = 6.86e9, exponent = 1.489, restitution = 0.9, damping = 3.0",
    );
    // Only once applied can a derived parameter's law be checked: still the physics file's.
    let derived = physics_file(
        &hcm,
        "derived.toml",
        "variable_stiffness",
        "surface_loading = 2.0, damping = -5.0",
    );
    let cases: [(&Path, &[&str]); 4] = [
        (
            &unknown,
            &[
                "physics file",
                "unknown.toml",
                "contact.0.law",
                "unknown law `lankarani`",
                "the laws are: hertz",
            ],
        ),
        (
            &domain,
            &[
                "physics file",
                "domain.toml",
                "contact.0.parameters.restitution",
                "must lie in (0, 1]",
                "found 1.5",
            ],
        ),
        (
            &other,
            &[
                "physics file",
                "other.toml",
                "contact.0.parameters.damping",
                "its parameters are: stiffness, exponent, restitution",
            ],
        ),
        (
            &derived,
            &[
                "physics file",
                "derived.toml",
                "does not fit the scenario",
                "`damping` must be a finite number, zero or greater",
            ],
        ),
    ];
    for (physics, parts) in cases {
        let evaluate = hcm
            .run("evaluate")
            .opt("--scenario", &ball)
            .opt("--data", &s2)
            .opt("--physics", physics);
        let stderr = refused(&hcm, &hcm.path("none"), evaluate);
        says(&stderr, parts);
        // Named first: the scenario file is not what is wrong.
        assert!(stderr.starts_with("error: physics file"), "{stderr}");
    }
    let out = hcm.path("residual.json");
    let train = hcm
        .run("train")
        .opt("--scenario", &ball)
        .opt("--data", &s1)
        .opt("--physics", &domain)
        .opt("--out", &out);
    says(
        &refused(&hcm, &out, train),
        &["domain.toml", "contact.0.parameters.restitution"],
    );
    let out = hcm.path("diagnosis");
    let diagnose = hcm
        .run("diagnose")
        .opt("--scenario", &ball)
        .opt("--data", &s1)
        .opt("--physics", &unknown)
        .opt("--out", &out);
    says(
        &refused(&hcm, &out, diagnose),
        &["unknown.toml", "contact.0.law"],
    );
}

#[test]
fn a_set_of_the_wrong_kind_names_the_key_and_what_it_expects() {
    let hcm = Hcm::new();
    let out = hcm.path("trajectory.csv");
    let cases: [(&str, &[&str]); 4] = [
        (
            "body.ball.mass=abc",
            &[
                "--set body.ball.mass=abc",
                "`body.ball.mass` expects a number",
                "found string \"abc\"",
            ],
        ),
        (
            "body.ball.velocity=[0,0]",
            &[
                "`body.ball.velocity` expects an array of 3 numbers",
                "found 2 values",
            ],
        ),
        (
            "simulation.max_steps=-3",
            &["`simulation.max_steps` expects a whole number ≥ 0"],
        ),
        (
            "body.ground.fixed=1",
            &["`body.ground.fixed` expects a boolean"],
        ),
    ];
    for (set, parts) in cases {
        let simulate = hcm
            .run("simulate")
            .opt("--scenario", scenario("bouncing_ball.toml"))
            .opt("--set", set)
            .opt("--out", &out);
        says(&refused(&hcm, &out, simulate), parts);
    }
}

#[test]
fn numeric_options_say_what_they_take() {
    let hcm = Hcm::new();
    let out = hcm.path("data.csv");
    let ball = scenario("bouncing_ball.toml");
    let cases: [(&str, &str, &[&str]); 5] = [
        (
            "--runs",
            "1e9",
            &[
                "'--runs <RUNS>'",
                "a whole number of runs ≥ 1, e.g. --runs 100",
                "write its digits, 1000000000",
            ],
        ),
        (
            "--runs",
            "-5",
            &["a whole number of runs ≥ 1", "-5 is negative"],
        ),
        (
            "--runs",
            "0",
            &["a whole number of runs ≥ 1", "0 is below 1"],
        ),
        (
            "--seed",
            "-1",
            &[
                "'--seed <SEED>'",
                "a whole number from 0 to 18446744073709551615",
                "-1 is negative",
            ],
        ),
        ("--seed", "1.5", &["1.5 is not a whole number"]),
    ];
    for (option, value, parts) in cases {
        let mut generate = hcm
            .run("generate")
            .opt("--scenario", &ball)
            .opt("--out", &out);
        generate = match option {
            "--runs" => generate.opt("--runs", value),
            _ => generate.opt("--runs", "2").opt(option, value),
        };
        says(&refused(&hcm, &out, generate), parts);
    }
    // The other counts share the parsers.
    let out = hcm.path("residual.json");
    let train = hcm
        .run("train")
        .opt("--scenario", &ball)
        .opt("--data", "s1.csv")
        .opt("--physics", "pm2.toml")
        .opt("--contact", "-1")
        .opt("--out", &out);
    says(
        &refused(&hcm, &out, train),
        &["'--contact <CONTACT>'", "counted from 0", "-1 is negative"],
    );
    let out = hcm.path("pm2.toml");
    let identify = hcm
        .run("identify")
        .opt("--scenario", &ball)
        .opt("--data", "s1.csv")
        .opt("--law", "hertz")
        .opt("--population", "1")
        .opt("--out", &out);
    says(
        &refused(&hcm, &out, identify),
        &["'--population <POPULATION>'", "≥ 2", "1 is below 2"],
    );
}

#[test]
fn identify_on_force_data_needs_a_law_and_a_method_for_force() {
    let hcm = Hcm::new();
    let (s1, _) = ball_data(&hcm);
    let out = hcm.path("pm2.toml");
    let ball = scenario("bouncing_ball.toml");
    // Only a fit from poses defaults to the scenario's law.
    let no_law = hcm
        .run("identify")
        .opt("--scenario", &ball)
        .opt("--data", &s1)
        .opt("--out", &out);
    says(
        &refused(&hcm, &out, no_law),
        &["data.s1.csv", "--law", "`hcm laws`"],
    );
    // A fit from poses on a 1D scene: refused, naming the methods that apply.
    for method in ["motion", "both"] {
        let from_poses = hcm
            .run("identify")
            .opt("--scenario", &ball)
            .opt("--data", &s1)
            .opt("--law", "hertz")
            .opt("--method", method)
            .opt("--out", &out);
        says(
            &refused(&hcm, &out, from_poses),
            &[&format!("--method {method}"), "is 1D", "--method lsq or ga"],
        );
    }
}

#[test]
fn diagnose_on_force_data_needs_a_base_model_and_refuses_poses_on_a_1d_scene() {
    let hcm = Hcm::new();
    let (s1, _) = ball_data(&hcm);
    let out = hcm.path("diagnosis");
    let ball = scenario("bouncing_ball.toml");
    // Only a diagnosis from poses defaults to the scenario's own model.
    let no_base = hcm
        .run("diagnose")
        .opt("--scenario", &ball)
        .opt("--data", &s1)
        .opt("--out", &out);
    says(
        &refused(&hcm, &out, no_base),
        &["data.s1.csv", "needs the base model", "--physics"],
    );
    // `diagnose-motion` is `diagnose --from-poses`: a 1D scene has no poses to replay.
    let motion = hcm
        .run("diagnose-motion")
        .opt("--scenario", &ball)
        .opt("--data", &s1)
        .opt("--out", &out);
    says(
        &refused(&hcm, &out, motion),
        &["--from-poses", "`bouncing_ball` is 1D", "drop --from-poses"],
    );
}

#[test]
fn a_reproduce_option_the_example_does_not_read_is_refused() {
    let hcm = Hcm::new();
    let out = hcm.path("peg");
    let peg = hcm
        .run("reproduce")
        .arg("peg-in-hole")
        .opt("--method", "lsq")
        .opt("--out", &out);
    says(
        &refused(&hcm, &out, peg),
        &[
            "`hcm reproduce peg-in-hole` does not read --method",
            "--generations",
        ],
    );
    let out = hcm.path("ball");
    let ball = hcm
        .run("reproduce")
        .arg("bouncing-ball")
        .opt("--generations", "3")
        .opt("--polish", "4")
        .opt("--out", &out);
    says(
        &refused(&hcm, &out, ball),
        &["does not read --generations, --polish: it reads --runs, --method"],
    );
}

/// A residual blob of the bouncing ball's HCM, through generate → train → export, with
/// the data and physics file it goes with.
fn ball_blob(hcm: &Hcm) -> (PathBuf, PathBuf, Vec<u8>) {
    let (s1, s2) = ball_data(hcm);
    let ball = scenario("bouncing_ball.toml");
    let pm2 = physics_file(hcm, "pm2.toml", "lankarani_nikravesh", LN);
    let residual = hcm.path("residual.json");
    hcm.run("train")
        .opt("--scenario", &ball)
        .opt("--data", &s1)
        .opt("--physics", &pm2)
        .opt("--epochs", "2")
        .opt("--int8-epochs", "0")
        .opt("--out", &residual)
        .ok();
    let blob = hcm.path("residual.hcm");
    hcm.run("export")
        .opt("--residual", &residual)
        .opt("--out", &blob)
        .ok();
    (s2, pm2, std::fs::read(blob).unwrap())
}

#[test]
fn each_damage_to_a_blob_has_its_own_message() {
    let hcm = Hcm::new();
    let (s2, pm2, blob) = ball_blob(&hcm);
    let length = blob.len();
    let evaluate = |name: &str, bytes: &[u8]| {
        let path = hcm.path(name);
        std::fs::write(&path, bytes).unwrap();
        let call = hcm
            .run("evaluate")
            .opt("--scenario", scenario("bouncing_ball.toml"))
            .opt("--data", &s2)
            .opt("--physics", &pm2)
            .opt("--residual", &path);
        refused(&hcm, &hcm.path("none"), call)
    };
    evaluate_ok(&hcm, &s2, &pm2, &blob);

    let mut trailing = blob.clone();
    trailing.extend_from_slice(&[0, 0]);
    says(
        &evaluate("trailing.hcm", &trailing),
        &[
            "trailing.hcm",
            "2 unexpected byte(s) after the end of the network",
            &format!("announces {length} bytes"),
        ],
    );
    says(
        &evaluate("short.hcm", &blob[..length - 100]),
        &[
            "short.hcm",
            &format!(
                "cut short: {} bytes, but its header announces {length}",
                length - 100
            ),
        ],
    );
    let mut flipped = blob.clone();
    flipped[length / 2] ^= 0x10;
    says(
        &evaluate("flipped.hcm", &flipped),
        &[
            "flipped.hcm",
            "corrupted: its checksum does not match its contents",
        ],
    );
    // A valid start (magic, version) and random bytes: corrupted, never "cut short".
    let mut state = 0x9e37_79b9_u32;
    for seed in 0..20 {
        let mut random = blob[..5].to_vec();
        while random.len() < length {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            random.push((state >> 24) as u8);
        }
        let stderr = evaluate(&format!("random{seed}.hcm"), &random);
        says(&stderr, &["corrupted: its checksum does not match"]);
    }
}

/// The unchanged blob is accepted: the damage, not the test's setup, is refused.
fn evaluate_ok(hcm: &Hcm, s2: &Path, pm2: &Path, blob: &[u8]) {
    let path = hcm.path("intact.hcm");
    std::fs::write(&path, blob).unwrap();
    let stdout = hcm
        .run("evaluate")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--data", s2)
        .opt("--physics", pm2)
        .opt("--residual", &path)
        .ok();
    assert!(stdout.contains("HCM"), "{stdout}");
}

#[test]
fn runs_without_contact_are_named_apart_from_their_count() {
    let hcm = Hcm::new();
    let ball = scenario("bouncing_ball.toml");
    let data = hcm.path("flight.csv");
    // 50 ms of a 143 ms fall: run `0` never touches the ground.
    hcm.run("simulate")
        .opt("--scenario", &ball)
        .opt("--set", "simulation.end_time=0.05")
        .opt("--out", &data)
        .ok();
    let stdout = hcm
        .run("indicators")
        .opt("--scenario", &ball)
        .opt("--data", &data)
        .ok();
    says(
        &stdout,
        &[
            "1 run without a completed contact: `0`",
            "no completed contact in the data (1 run read)",
        ],
    );
    assert!(
        !stdout.contains("runs without a completed contact: 0"),
        "{stdout}"
    );
}

/// Every command's outputs are checked against its inputs before any work:
/// an output naming a file the command reads and two outputs naming one file are
/// refused, naming the options, and the input is left as it was; an output that is a
/// device is refused too (`tests/commands/outputs.rs` has the pipes and sockets).
#[test]
fn an_output_that_is_an_input_or_a_device_is_refused_before_any_work() {
    let hcm = Hcm::new();
    let ball = hcm.path("ball.toml");
    std::fs::copy(scenario("bouncing_ball.toml"), &ball).unwrap();
    let text = std::fs::read(&ball).unwrap();
    let message = (hcm.run("simulate"))
        .opt("--scenario", &ball)
        .opt("--out", &ball)
        .fails();
    says(
        &message,
        &["--out", "is the file --scenario reads", "another path"],
    );
    assert_eq!(
        std::fs::read(&ball).unwrap(),
        text,
        "the scenario was changed"
    );

    let (s1, _) = ball_data(&hcm);
    let data = std::fs::read(&s1).unwrap();
    let message = (hcm.run("identify"))
        .opt("--scenario", &ball)
        .opt("--data", &s1)
        .opt("--law", "hertz")
        .opt("--out", &s1)
        .fails();
    says(&message, &["--out", "is the file --data reads"]);
    assert_eq!(std::fs::read(&s1).unwrap(), data, "the data were changed");

    let out = hcm.path("p.csv");
    let message = refused(
        &hcm,
        &out,
        (hcm.run("predict"))
            .opt("--scenario", scenario("cube_toss.toml"))
            .opt(
                "--data",
                Path::new(env!("CARGO_MANIFEST_DIR")).join("data/contactnets-cube/tosses.csv"),
            )
            .opt("--out", &out)
            .opt("--scores", &out),
    );
    says(&message, &["--out and --scores name the same file"]);

    let message = (hcm.run("simulate"))
        .opt("--scenario", &ball)
        .opt("--out", "/dev/null")
        .fails();
    says(&message, &["/dev/null", "not a regular file"]);
}

/// A record or a number of runs that memory cannot hold is refused before the work,
/// with the figure and what lowers it — never an allocation failure.
#[test]
fn what_memory_cannot_hold_is_refused_with_the_figure() {
    let hcm = Hcm::new();
    let out = hcm.path("y.csv");
    let message = refused(
        &hcm,
        &out,
        (hcm.run("simulate"))
            .opt("--scenario", scenario("bouncing_ball.toml"))
            .opt("--set", "record.contact_sample_period=1e-15")
            .opt("--out", &out),
    );
    says(
        &message,
        &[
            "record would take up to",
            "of memory available",
            "raise record.contact_sample_period",
        ],
    );
    let out = hcm.path("ball");
    let message = refused(
        &hcm,
        &out,
        (hcm.run("reproduce"))
            .arg("bouncing-ball")
            .opt("--runs", "1000000000000")
            .opt("--out", &out),
    );
    says(
        &message,
        &[
            "--runs 1000000000000",
            "of memory available",
            "ask for at most",
        ],
    );
}

/// A residual blob of the wrong kind for the scenario — the peg's 13-input wrench
/// network on the 1D ball — is refused naming the blob and what the scenario takes,
/// where before it was evaluated with its envelope shut (HCM = PM2, no word).
#[test]
fn a_blob_of_the_wrong_kind_for_the_scenario_is_refused() {
    let hcm = Hcm::new();
    let (_, s2) = ball_data(&hcm);
    let blobs = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/blobs");
    let message = (hcm.run("evaluate"))
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--data", &s2)
        .opt("--physics", blobs.join("bouncing_ball.pm2.toml"))
        .opt("--residual", blobs.join("peg_in_hole.f32.hcm"))
        .fails();
    says(
        &message,
        &[
            "peg_in_hole.f32.hcm",
            "13-input, 6-output",
            "a 1D scenario",
            "3 inputs",
        ],
    );
}

/// A data set too small for the command: the diagnosis fits on some runs and judges on
/// others, so one run is refused with what it needs, before any work and with no
/// report written.
#[test]
fn a_diagnosis_of_one_run_is_refused_with_what_it_needs() {
    let hcm = Hcm::new();
    let (s1, _) = ball_data(&hcm);
    let data = hcm_host::dataset::Dataset::read(&s1).unwrap();
    let one = hcm_host::dataset::Dataset {
        runs: data.runs[..1].to_vec(),
    };
    let path = hcm.path("one_run.csv");
    one.write(&path).unwrap();
    let out = hcm.path("diagnosis");
    let blobs = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/blobs");
    let message = refused(
        &hcm,
        &out,
        (hcm.run("diagnose"))
            .opt("--scenario", scenario("bouncing_ball.toml"))
            .opt("--data", &path)
            .opt("--physics", blobs.join("bouncing_ball.pm2.toml"))
            .opt("--out", &out),
    );
    says(&message, &["--data holds 1 run(s)", "give at least 2"]);
}

/// `shipped` (a scenario of `scenarios/`) with `from` replaced by `to`, written to the
/// fixture's directory as `name`.
fn edited(hcm: &Hcm, shipped: &str, name: &str, from: &str, to: &str) -> PathBuf {
    let text = std::fs::read_to_string(scenario(shipped)).unwrap();
    assert!(text.contains(from), "{from}");
    let path = hcm.path(name);
    std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
    path
}

#[test]
fn every_vector_of_the_wrong_length_is_refused_at_its_line() {
    let hcm = Hcm::new();
    let out = hcm.path("trajectory.csv");
    let q = "quaternion = [0.43199, 0.23028, 0.87130, -0.034527]";
    // (scenario, from, to, the line, what the message must say)
    let cases = [
        (
            "cube_toss.toml",
            "-9.81]",
            "-9.81, 1.0]",
            "line 24",
            "invalid length 4, expected an array of 3 numbers",
        ),
        (
            "cube_toss.toml",
            "velocity = [-1.0452, -0.8475, -0.0259]",
            "velocity = [-1.0452, -0.8475]",
            "line 33",
            "invalid length 2, expected an array of 3 numbers",
        ),
        (
            "cube_toss.toml",
            "4.2734, -2.9658, 0.0381]",
            "4.2734, -2.9658, 0.0381, 0.0]",
            "line 34",
            "invalid length 4",
        ),
        (
            "cube_toss.toml",
            "normal = [0.0, 0.0, 1.0]",
            "normal = [0.0, 0.0, 1.0, 0.0]",
            "line 39",
            "invalid length 4",
        ),
        (
            "cube_toss.toml",
            "0.0524, 0.0524]",
            "0.0524, 0.0524, 0.1]",
            "line 29",
            "invalid length 4",
        ),
        (
            "cube_toss.toml",
            q,
            "quaternion = [0.43199, 0.23028, 0.87130, -0.034527, 1.0]",
            "line 32",
            "quaternion [w, x, y, z]: expected an array of 4 numbers, found 5 numbers",
        ),
        (
            "cube_toss.toml",
            q,
            "quaternion = [1.0, 0.0, 0.0, 0.0], roll_pitch_yaw = [0.0, 0.0, 0.0]",
            "line 32",
            "gives both `quaternion` and `roll_pitch_yaw`: keep one",
        ),
        (
            "cube_toss.toml",
            "8.1e-4, 8.1e-4, 8.1e-4]",
            "8.1e-4, 8.1e-4]",
            "line 30",
            "principal moments [Ixx, Iyy, Izz] or a 3×3 tensor",
        ),
        (
            "cube_toss.toml",
            "[8.1e-4, 8.1e-4, 8.1e-4]",
            "[[8.1e-4, 0, 0], [0, 8.1e-4, 0, 0], [0, 0, 8.1e-4]]",
            "line 30",
            "a row expected an array of 3 numbers, found 4",
        ),
        (
            "peg_in_hole.toml",
            "roll_pitch_yaw = [0.0, 0.0087, 0.0]",
            "roll_pitch_yaw = [0.0, 0.0087]",
            "line 36",
            "roll_pitch_yaw [roll, pitch, yaw] (rad): expected an array of 3 numbers, found 2",
        ),
        (
            "peg_in_hole.toml",
            "position = [0.0, 0.0, -0.005]",
            "position = [0.0, 0.0, -0.005, 0.0]",
            "line 48",
            "invalid length 4",
        ),
    ];
    for (shipped, from, to, line, what) in cases {
        let path = edited(&hcm, shipped, "edited.toml", from, to);
        let stderr = refused(&hcm, &out, simulate(&hcm, &path, &out));
        says(&stderr, &["edited.toml", line, what]);
    }
}

#[test]
fn a_huge_binary_or_cut_file_is_refused_from_its_size_or_its_first_bad_byte() {
    let hcm = Hcm::new();
    let out = hcm.path("out.csv");

    // A gigabyte (sparse: no disk is written) is refused from its size, unread.
    let huge = hcm.path("huge.toml");
    std::fs::File::create(&huge)
        .unwrap()
        .set_len(1 << 30)
        .unwrap();
    let stderr = refused(&hcm, &out, simulate(&hcm, &huge, &out));
    says(
        &stderr,
        &["huge.toml", "is 1.1 GB", "a scenario is at most 16.8 MB"],
    );
    // NUL bytes: a binary file, named by line.
    let nul = edited(
        &hcm,
        "bouncing_ball.toml",
        "nul.toml",
        "[[body]]",
        "[[body]]\0",
    );
    says(
        &refused(&hcm, &out, simulate(&hcm, &nul, &out)),
        &["nul.toml", "a NUL byte", "binary"],
    );
    // A line of 200 kB: the message quotes an excerpt, not the line.
    let long = format!("name = \"{}\n", "x".repeat(200_000));
    let long_toml = hcm.path("long.toml");
    std::fs::write(&long_toml, long).unwrap();
    let stderr = refused(&hcm, &out, simulate(&hcm, &long_toml, &out));
    says(
        &stderr,
        &["long.toml", "line 1, column 200009", "near `xxx"],
    );
    assert!(stderr.len() < 600, "{} bytes:\n{stderr}", stderr.len());
    // A data file whose second line is 200 kB of NUL bytes.
    let data = hcm.path("nul.csv");
    let mut bytes = b"run,body,time,px,py,pz\n".to_vec();
    bytes.extend(std::iter::repeat_n(0u8, 200_000));
    std::fs::write(&data, bytes).unwrap();
    let stderr = hcm
        .run("predict")
        .opt("--scenario", scenario("cube_toss.toml"))
        .opt("--data", &data)
        .opt("--out", &out)
        .fails();
    says(&stderr, &["nul.csv", "line 2 is longer than 65536 bytes"]);
    assert!(stderr.len() < 600 && !out.exists(), "{stderr}");
}

#[test]
fn an_empty_or_cut_trained_residual_is_said_to_be_so() {
    let hcm = Hcm::new();
    ball_blob(&hcm);
    let whole = std::fs::read_to_string(hcm.path("residual.json")).unwrap();
    let blob = hcm.path("cut.hcm");
    for (text, what) in [
        (
            String::new(),
            "the file is empty; write it again with `hcm train`",
        ),
        (
            whole[..whole.len() / 2].to_owned(),
            "before its JSON does: it was cut short",
        ),
    ] {
        let cut = hcm.path("cut.json");
        std::fs::write(&cut, text).unwrap();
        let stderr = refused(
            &hcm,
            &blob,
            hcm.run("export")
                .opt("--residual", &cut)
                .opt("--out", &blob),
        );
        says(&stderr, &["cut.json", what]);
    }
}

#[test]
fn an_existing_output_of_the_other_kind_is_refused_before_any_work() {
    let hcm = Hcm::new();
    let cube = scenario("cube_toss.toml");
    let (file, folder) = (hcm.path("taken.svg"), hcm.path("folder"));
    std::fs::write(&file, "mine").unwrap();
    std::fs::create_dir(&folder).unwrap();
    let out = hcm.path("trajectory.csv");
    // A directory option given a file: refused before the trajectory is written.
    let call = simulate(&hcm, &cube, &out);
    let stderr = refused(&hcm, &out, call.opt("--figures", &file));
    says(
        &stderr,
        &["--figures", "taken.svg: is a file", "names a directory"],
    );
    let stderr = refused(
        &hcm,
        &out,
        hcm.run("reproduce")
            .arg("bouncing-ball")
            .opt("--out", &file),
    );
    says(
        &stderr,
        &["--out", "taken.svg: is a file", "names a directory"],
    );
    // A file option given a directory.
    let stderr = simulate(&hcm, &cube, &folder).fails();
    says(
        &stderr,
        &["--out", "folder: is a directory", "names a file"],
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
    assert_eq!(std::fs::read_dir(&folder).unwrap().count(), 0);
}

#[test]
fn a_toss_of_one_frame_is_refused_not_scored() {
    let hcm = Hcm::new();
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("data/contactnets-cube/tosses.csv"),
    )
    .unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    // toss_000's first frame below 6 cm: within reach of the table, the last frame kept.
    let low = lines
        .find(|l| {
            l.starts_with("toss_000,")
                && l.split(',').nth(5).unwrap().parse::<f64>().unwrap() < 0.06
        })
        .unwrap();
    let data = hcm.path("one.csv");
    std::fs::write(&data, format!("{header}\n{low}\n")).unwrap();
    let out = hcm.path("predicted.csv");
    let call = hcm
        .run("predict")
        .opt("--scenario", scenario("cube_toss.toml"))
        .opt("--data", &data)
        .opt("--out", &out)
        .opt("--scores", hcm.path("scores.csv"));
    let stderr = refused(&hcm, &out, call);
    says(
        &stderr,
        &[
            "run `toss_000`",
            "has 1 frame from the window start on",
            "needs at least 2",
        ],
    );
}

#[test]
fn a_relative_tolerance_of_one_or_a_weight_past_a_float_is_refused() {
    let hcm = Hcm::new();
    let out = hcm.path("trajectory.csv");
    let text = std::fs::read_to_string(scenario("bouncing_ball.toml")).unwrap();
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with("relative_tolerance"))
        .unwrap();
    let path = edited_ball(&hcm, "loose.toml", line, "relative_tolerance = 1.0");
    let call = simulate(&hcm, &path, &out);
    says(
        &refused(&hcm, &out, call),
        &[
            "loose.toml",
            "simulation.relative_tolerance",
            "below 1",
            "found 1",
        ],
    );
    let heavy = edited(
        &hcm,
        "cube_toss.toml",
        "heavy.toml",
        "mass = 0.37",
        "mass = 1e308",
    );
    let call = simulate(&hcm, &heavy, &out);
    says(
        &refused(&hcm, &out, call),
        &[
            "heavy.toml",
            "body `cube` (#0) mass",
            "1e308 kg weighs more than a float holds",
        ],
    );
}

#[test]
fn a_run_or_body_name_past_200_characters_is_refused_with_an_excerpt() {
    let hcm = Hcm::new();
    let header = "run,body,time,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,fx,fy,fz,tx,ty,tz";
    let long = "x".repeat(1_000);
    let data = hcm.path("long_names.csv");
    let row = format!("toss_{long},cube,0.0,0,0,0.1,1,0,0,0,0,0,0,0,0,0,,,,,,");
    std::fs::write(&data, format!("{header}\n{row}\n")).unwrap();
    let out = hcm.path("predicted.csv");
    let call = hcm
        .run("predict")
        .opt("--scenario", scenario("cube_toss.toml"))
        .opt("--data", &data)
        .opt("--out", &out);
    let stderr = refused(&hcm, &out, call);
    says(
        &stderr,
        &[
            "long_names.csv, line 2, column `run`",
            "at most 200 characters, found 1005",
        ],
    );
    assert!(stderr.len() < 600, "{} bytes:\n{stderr}", stderr.len());
    let named = edited(
        &hcm,
        "cube_toss.toml",
        "named.toml",
        "name = \"cube\"",
        &format!("name = \"{long}\""),
    );
    let call = simulate(&hcm, &named, &out);
    let stderr = refused(&hcm, &out, call);
    says(
        &stderr,
        &[
            "named.toml",
            "body #0 name",
            "must be 1 to 200 characters, found 1000",
        ],
    );
    assert!(stderr.len() < 600, "{} bytes:\n{stderr}", stderr.len());
}
