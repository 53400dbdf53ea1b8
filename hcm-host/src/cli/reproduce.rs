//! `hcm reproduce`: the paper's whole method for one example — the library's pipeline
//! ([`hcm_host::pipeline`]: generate (PM1) → split → identify (PM2) → train → export →
//! evaluate) with progress bars, and every stage's output, the report, `results.json`
//! and the figures written to the output directory.

use super::progress::Bars;
use hcm_host::output::StagedDirectory;
use hcm_host::pipeline::PegSettings;
use hcm_host::pipeline::{reproduce_cube, CubeSettings, Peers};
use hcm_host::pipeline::{
    write_reproduction, Example, Pm2Method, Preset, ReproduceSettings, Reproduced, ScenarioChoice,
    Shipped,
};
use std::path::PathBuf;

/// The paper's examples.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub(super) enum ExampleArg {
    /// The paper's Section 5.1 (Table 5): a steel ball dropped on concrete.
    BouncingBall,
    /// The paper's Section 5.2 (Table 10): a plate hits a resting ball at ten speeds.
    FlatShot,
    /// The paper's Section 5.3 (Table 15): a peg falls tilted into a hole.
    PegInHole,
    /// Real filmed tosses of a cube (--data), fitted and predicted held out.
    CubeToss,
    /// Real filmed tosses of a two-link elbow on a hinge (--data), the same way.
    ElbowToss,
}

/// Reproduce one of the paper's examples end to end, with report and figures.
///
/// Example: `hcm reproduce bouncing-ball --out results/ball`
///
/// Example: `hcm reproduce cube-toss --data data/contactnets-cube/tosses.csv --out results/cube`
///
/// Example: `hcm reproduce elbow-toss --data data/contactnets-elbow/tosses.csv --out results/elbow`
///
/// Runs generate (PM1) → split (S1, S2) → identify (PM2) → train → export → evaluate
/// and writes to OUT: s1.csv, s2.csv, pm2.toml, residual.json, residual.bin,
/// residual.int8.bin, report.md (read it first), results.json and the figures.
/// On two cores the run takes about 30 s for bouncing-ball, 3–4 minutes for flat-shot and
/// 1 minute for peg-in-hole (400 runs; PM2 by the GA, so --method is refused; its OUT
/// holds s1.csv, s2.csv, pm2.toml with friction, residual.json, the wrench residual's
/// blobs, report.md, results.json and the figures).
///
/// cube-toss works on real data, not on PM1: it splits the tosses of --data by toss
/// number (even train, odd are held out), fits the contact and the body's inertia from
/// motion alone (GA + Nelder–Mead), predicts the held-out tosses, fits again on the odd
/// tosses and predicts the even ones (cross-validated scores: every toss predicted by a
/// fit that never saw it), measures the held-out error over time and per phase, runs the
/// diagnosis from motion on the fitted model, and writes to OUT: physics.toml,
/// training.csv, held_out.csv, predicted_held_out.csv, report.md, results.json and the
/// figures (the 456 tosses: about 10 minutes on two cores, 20 minutes of processor time).
///
/// elbow-toss does the same on the tosses of a two-link elbow on a hinge
/// (data/contactnets-elbow/tosses.csv of the source; scenarios/elbow_toss.toml, a free
/// hinge): both links' contacts fitted as one, each link scored, the diagnosis with the
/// joint's candidates; its fits see every fourth toss of their part (a mechanism replays
/// 20 times slower), no faces, no chance (the 433 tosses: about 9 minutes on two cores).
///
/// The scenarios are built into hcm (copies of scenarios/bouncing_ball.toml,
/// scenarios/flat_shot.toml and scenarios/peg_in_hole.toml of the source), so it runs
/// from any directory and always
/// runs the same scenario; `--scenario FILE` runs another, e.g. an edited copy.
///
/// Terms:
///   PM1       the example's contact simulated with noise, standing in for measurements
///   S1, S2    the runs split into a training set (S1) and a validation set (S2)
///   PM2       a physics law (Lankarani–Nikravesh) identified on S1
///   HCM       hybrid contact model: PM2 plus a residual network trained on S1
///   residual  the network's output: the force PM2 gets wrong (measured − PM2)
///   int8      the network with 8-bit integer weights, as a controller stores it
///   error     the paper's Eq 20: |S2 mean − model| / S2 mean, per indicator
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    /// Which example.
    pub(super) example: ExampleArg,
    /// Peg-in-hole, cube-toss: generations of the genetic algorithm that identifies PM2
    /// (the cube's contact).
    #[arg(long)]
    pub(super) generations: Option<usize>,
    /// Peg-in-hole, cube-toss: individuals per generation of that algorithm.
    #[arg(long)]
    pub(super) population: Option<usize>,
    /// Cube-toss: fitness evaluations of the Nelder–Mead polish after the GA.
    #[arg(long)]
    pub(super) polish: Option<usize>,
    /// Cube-toss: the filmed tosses (measured-data CSV).
    #[arg(long)]
    pub(super) data: Option<PathBuf>,
    /// Cube-toss: use only the first N runs of --data (before the split).
    #[arg(long, value_name = "N")]
    pub(super) first: Option<usize>,
    /// Cube-toss: skip the diagnosis of the fitted model (most of the run's time).
    #[arg(long)]
    pub(super) no_diagnosis: bool,
    /// Cube-toss: replays per toss in the final faces' ensembles (default 16; 0 skips
    /// the stage).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(0..=1000))]
    pub(super) face_members: Option<u16>,
    /// Cube-toss and elbow-toss: also fit and score MuJoCo and PyBullet the same way,
    /// side by side (benches/peers/peers.py, the elbow's benches/peers/elbow.py, run from
    /// the repository's root with their virtual environment: `bash benches/peers/run.sh
    /// OUT --quick` installs it; about 12 more minutes on the full cube data).
    #[arg(long)]
    pub(super) peers: bool,
    /// Output directory (created): data, pm2.toml, residual blobs, report.md,
    /// results.json, figures.
    #[arg(long, value_hint = clap::ValueHint::DirPath)]
    pub(super) out: PathBuf,
    /// Seed of the experiment, the GA and the training.
    #[arg(long, default_value_t = 1)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::seed)]
    pub(super) seed: u64,
    /// Runs per condition (default: the paper's).
    #[arg(long)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::runs)]
    pub(super) runs: Option<usize>,
    /// Identification method of PM2: `ga` (the paper's, polished by LM) or `lsq`
    /// (1D examples; the peg-in-hole's PM2 is always found by the GA).
    /// [default: ga]
    #[arg(long, value_parser = ["ga", "lsq"])]
    pub(super) method: Option<String>,
    /// Scenario file to run instead of the example's built-in one (which is a copy of
    /// scenarios/<example>.toml of the source).
    #[arg(long)]
    pub(super) scenario: Option<PathBuf>,
    /// Override a scenario value, e.g. `--set 'contact.0.noise={}'` (no parameter
    /// scatter between runs). Repeatable; the report names them.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub(super) overrides: Vec<String>,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let preset = preset(&args)?;
    // Built as a hidden directory beside --out and renamed into place at the end, so
    // that --out appears complete or not at all; made before the minutes of work, so
    // that an unwritable place or an --out that may not be replaced fails at once.
    let peers = match (&preset, args.peers) {
        (Preset::CubeToss(settings), true) => Some(Peers::locate(settings.name)?),
        _ => None,
    };
    let staged = StagedDirectory::create(&args.out, "results.json")?;
    if let (Some(peers), Preset::CubeToss(settings)) = (&peers, &preset) {
        let mut reproduction = reproduce_cube(settings, &Bars::default())?;
        eprintln!(
            "peers: {} (MuJoCo and PyBullet fitted on the training tosses)",
            peers.command_line()
        );
        reproduction.appendix = Some(peers.run(staged.path(), &reproduction, settings)?);
        return finish(staged, Box::new(reproduction));
    }
    let reproduction = preset.reproduce(&Bars::default())?;
    finish(staged, reproduction)
}

/// The example's preset with the options given; an option the example does not
/// read is refused, not ignored.
fn preset(args: &Args) -> anyhow::Result<Preset> {
    /// The options of the filmed tosses' examples, those only the cube's reads last.
    const TOSSES_OPTIONS: [&str; 8] = [
        "--generations",
        "--population",
        "--polish",
        "--data",
        "--first",
        "--no-diagnosis",
        "--peers",
        "--face-members",
    ];
    let given = [
        ("--generations", args.generations.is_some()),
        ("--population", args.population.is_some()),
        ("--polish", args.polish.is_some()),
        ("--data", args.data.is_some()),
        ("--first", args.first.is_some()),
        ("--no-diagnosis", args.no_diagnosis),
        ("--face-members", args.face_members.is_some()),
        ("--peers", args.peers),
        ("--runs", args.runs.is_some()),
        ("--method", args.method.is_some()),
    ];
    let (name, reads): (&str, &[&str]) = match args.example {
        ExampleArg::BouncingBall => ("bouncing-ball", &["--runs", "--method"]),
        ExampleArg::FlatShot => ("flat-shot", &["--runs", "--method"]),
        ExampleArg::PegInHole => ("peg-in-hole", &["--runs", "--generations", "--population"]),
        ExampleArg::CubeToss => ("cube-toss", &TOSSES_OPTIONS),
        // A mechanism's final faces are not forecast yet: the options before theirs.
        ExampleArg::ElbowToss => ("elbow-toss", &TOSSES_OPTIONS[..7]),
    };
    let unread: Vec<&str> = (given.iter())
        .filter(|(option, set)| *set && !reads.contains(option))
        .map(|(option, _)| *option)
        .collect();
    anyhow::ensure!(
        unread.is_empty(),
        "`hcm reproduce {name}` does not read {}: it reads {} (see `hcm reproduce --help`)",
        unread.join(", "),
        reads.join(", ")
    );
    Ok(match args.example {
        ExampleArg::BouncingBall => Preset::Paper(paper(args, Example::BouncingBall)),
        ExampleArg::FlatShot => Preset::Paper(paper(args, Example::FlatShot)),
        ExampleArg::PegInHole => Preset::PegInHole(peg(args)),
        ExampleArg::CubeToss => Preset::CubeToss(cube(args, ExampleArg::CubeToss)?),
        ExampleArg::ElbowToss => Preset::CubeToss(cube(args, ExampleArg::ElbowToss)?),
    })
}

/// The scenario the options choose for an example whose shipped one is `shipped`.
fn scenario(args: &Args, shipped: Shipped) -> ScenarioChoice {
    ScenarioChoice {
        shipped,
        file: args.scenario.clone(),
        overrides: args.overrides.clone(),
    }
}

fn paper(args: &Args, example: Example) -> ReproduceSettings {
    ReproduceSettings {
        example,
        scenario: scenario(args, example.shipped()),
        seed: args.seed,
        runs: args.runs.unwrap_or(example.runs()),
        method: match args.method.as_deref() {
            Some("lsq") => Pm2Method::Lsq,
            _ => Pm2Method::Ga,
        },
    }
}

fn peg(args: &Args) -> PegSettings {
    let shipped = PegSettings::shipped();
    let mut genetic = shipped.genetic.clone();
    genetic.generations = args.generations.unwrap_or(genetic.generations);
    genetic.population = args.population.unwrap_or(genetic.population);
    PegSettings {
        scenario: scenario(args, Shipped::PegInHole),
        seed: args.seed,
        runs: args.runs.unwrap_or(shipped.runs),
        genetic,
        ..shipped
    }
}

/// The settings of the filmed tosses' example `example` (cube-toss or elbow-toss).
fn cube(args: &Args, example: ExampleArg) -> anyhow::Result<CubeSettings> {
    let (name, folder) = match example {
        ExampleArg::ElbowToss => ("elbow-toss", "contactnets-elbow"),
        _ => ("cube-toss", "contactnets-cube"),
    };
    let data = args.data.clone().ok_or_else(|| {
        anyhow::anyhow!(
            "`hcm reproduce {name}` needs --data: the filmed tosses, e.g. \
             data/{folder}/tosses.csv of the source"
        )
    })?;
    if let Some(first) = args.first {
        anyhow::ensure!(
            first >= 6,
            "--first {first}: give at least 6 runs (3 per part)"
        );
    }
    let shipped = match example {
        ExampleArg::ElbowToss => CubeSettings::elbow(&data),
        _ => CubeSettings::shipped(&data),
    };
    Ok(CubeSettings {
        first: args.first,
        scenario: scenario(args, shipped.scenario.shipped),
        seed: args.seed,
        population: args.population.unwrap_or(shipped.population),
        generations: args.generations.unwrap_or(shipped.generations),
        polish: args.polish.unwrap_or(shipped.polish),
        diagnose: !args.no_diagnosis,
        face_members: args.face_members.map_or(shipped.face_members, usize::from),
        ..shipped
    })
}

/// Writes `reproduction` into the staged output directory, moves it into place and
/// prints the report: the same for every example.
fn finish(staged: StagedDirectory, mut reproduction: Box<dyn Reproduced>) -> anyhow::Result<()> {
    let report = write_reproduction(reproduction.as_mut(), staged.path())?;
    staged.commit()?;
    print!("{report}");
    Ok(())
}
