//! `hcm diagnose`: what the simulation gets wrong, the cause named, the model extended
//! with it, and the gain measured on held-out runs.

use super::progress_bar;
use hcm_host::dataset::{inventory_summary, DataUse, Dataset, Evidence};
use hcm_host::diagnose::BaseFreedom;
use hcm_host::diagnose::MotionBase;
use hcm_host::diagnose::{diagnose, DiagnoseSettings};
use hcm_host::diagnose::{write_diagnosis, DiagnosisOf};
use hcm_host::identify::Physics;
use hcm_host::output::StagedDirectory;
use hcm_host::scenario::{Model, Scenario};
use std::path::PathBuf;

/// Diagnose a physics model against data: what is wrong, why, and the model extended.
///
/// Example: `hcm diagnose --scenario scenarios/flat_shot.toml --data measured.csv --physics base.toml --out diag/`
///
/// Compares the base model's force with the data against the noise floor, names the
/// catalogued effects that explain the difference (with parameters, 95 % intervals and
/// shares), writes the extended model (OUT/extended.toml) and measures its gain on
/// held-out runs (and a held-out condition) beside the base model and the HCM. Writes
/// OUT/report.md, OUT/diagnosis.json and figures.
///
/// On a 3D (rigid) scenario: the 3D catalogue (friction, resistance, normal and sensor
/// effects, and every other law in the base's place) fitted with the base's own
/// parameters on the wrench at the recorded poses, judged on held-out runs (even
/// against odd); OUT/report.md, diagnosis.json, extended.toml (`--seed` and `--holdout`
/// are not used there).
///
/// From poses (a rigid scenario and data without force, or `--from-poses`; `hcm
/// diagnose-motion` is this command with `--from-poses`): the runs are split by toss
/// number (even numbers train, odd ones are held out) and every candidate change of the
/// model — the friction's coefficient, Coulomb's law, viscous friction, torsional and
/// rolling resistance, a restitution falling with speed, the table's height and tilt,
/// the tracker's length scale, the body's inertia, a box's edge rounding — is fitted on
/// the training tosses by replaying them (as `hcm predict`) and judged on the held-out
/// ones, toss by toss, by how much it lowers their score. A candidate helps when its
/// mean held-out gain is at least 3 standard errors above zero and at least 1 % of the
/// model's held-out score; the best is named only if it beats every other helping
/// candidate by 2 standard errors on the same tosses, else the answer is "ambiguous".
/// A named cause is added and the search repeats once. Writes the diagnosis as JSON.
///
/// Terms:
///   base model      the physics file given with `--physics` (e.g. from `hcm identify`);
///                   from poses without it, the scenario's own model
///   score           per toss: mean position error (% of the body's width) + mean
///                   rotation error (°) over its window's frames, as `hcm predict`
///   held-out gain   the model's score minus the candidate's, per held-out toss
///   extended model  the base model plus the effects found
///   noise floor     the data's own force noise σ, from its second differences
///   held-out runs   runs never fitted, on which the gain is measured
///   HCM             hybrid contact model: the base model plus a residual network
///                   trained on the same runs, for comparison
///   residual        measured − model force (N); the network learns it
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Measured data (measured-data CSV).
    #[arg(long)]
    data: PathBuf,
    /// Physics file of the base model (as written by `hcm identify`); needed on force
    /// data. From poses, without it: the scenario's own model, as given.
    #[arg(long)]
    physics: Option<PathBuf>,
    /// Output directory (created): report.md, diagnosis.json, extended.toml, figures.
    /// From poses: report.md, diagnosis.json, and where a chance is named its forecast's
    /// figures and (chances alone) extended.toml; or the diagnosis alone in OUT itself
    /// when it ends in `.json`.
    #[arg(long, value_hint = clap::ValueHint::DirPath)]
    out: PathBuf,
    /// Use only the first N runs of --data.
    #[arg(long, value_name = "N")]
    first: Option<usize>,
    /// Diagnose by replaying the recorded poses alone, whatever else the data hold
    /// (what data without force get anyway): the tosses split by toss number, every
    /// candidate fitted on the even ones and judged on the odd ones.
    #[arg(long)]
    from_poses: bool,
    /// After the deterministic effects, also try chance, judged by proper scores of
    /// ensemble forecasts on the held-out runs. From poses: the contact's scatter, the
    /// start state's uncertainty, the fixed body's height and tilt from run to run
    /// (energy score). On force (1D): each free law parameter's scatter and the sensor's
    /// noise level (CRPS of the peak force, impulse and energy taken); a named scatter
    /// goes into extended.toml's `noise`. Asked for: on runs without true run-to-run
    /// variation, a spread can still cover what a fit left.
    #[arg(long)]
    chance: bool,
    /// Which contact of the scenario.
    #[arg(long, default_value_t = 0)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::contact)]
    contact: usize,
    /// Seed of the hold-out draw and of the HCM's training (1D scenarios; a 3D
    /// diagnosis holds out the even and the odd runs in turn).
    #[arg(long, default_value_t = 1)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::seed)]
    seed: u64,
    /// 1D scenarios: share of the runs (inside the fitted range) held out for the gain table. The
    /// condition held out whole is the scenario's first `experiment.holdout_conditions`
    /// entry (else the last condition), e.g. `--set 'experiment.holdout_conditions=["v1.0"]'`.
    #[arg(long, default_value_t = 0.25)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::share)]
    holdout: f64,
}

impl Args {
    /// The diagnosis from poses, whatever else the data hold (`hcm diagnose-motion`).
    pub fn fitting_poses(mut self) -> Self {
        self.from_poses = true;
        self
    }
}

/// The base model read for a diagnosis: the scenario with `--physics` applied (if given),
/// whether that file holds a fit, and the data (their first `--first` runs).
struct Inputs {
    scenario: Scenario,
    base: Model,
    has_physics: bool,
    fitted: bool,
    data: Dataset,
}

impl Inputs {
    fn read(args: &Args) -> anyhow::Result<Inputs> {
        let scenario = args.scenario.load()?;
        let physics = args.physics.as_deref().map(Physics::read).transpose()?;
        let base = match (&physics, &args.physics) {
            (Some(physics), Some(path)) => physics.apply(&scenario, path)?.model()?,
            _ => scenario.model()?,
        };
        super::check_contact(args.contact, &base)?;
        let mut data = Dataset::read(&args.data)?;
        if let Some(first) = args.first {
            anyhow::ensure!(first > 0, "--first 0: give at least one run");
            data.runs.truncate(first);
        }
        Ok(Inputs {
            scenario,
            base,
            has_physics: physics.is_some(),
            fitted: physics.as_ref().is_some_and(Physics::fitted),
            data,
        })
    }

    /// The evidence the diagnosis works from: the data's, or poses with `--from-poses`.
    fn evidence(&self, args: &Args) -> anyhow::Result<Evidence> {
        Ok(match Evidence::of(&self.base, &self.data, args.contact) {
            Evidence::LineForce if args.from_poses => anyhow::bail!(
                "--from-poses replays a rigid (3D) body's poses; scenario `{}` is 1D: drop \
                 --from-poses to diagnose its force",
                self.scenario.name
            ),
            _ if args.from_poses => Evidence::Poses,
            evidence => evidence,
        })
    }
}

pub fn run(args: Args) -> anyhow::Result<()> {
    if !(args.holdout > 0.0 && args.holdout < 1.0) {
        anyhow::bail!(
            "--holdout must lie strictly between 0 and 1, found {}",
            args.holdout
        );
    }
    let inputs = Inputs::read(&args)?;
    let evidence = inputs.evidence(&args)?;
    let (base, data) = (&inputs.base, &inputs.data);
    if evidence != Evidence::LineForce && (args.seed != 1 || args.holdout != 0.25) {
        eprintln!(
            "note: --seed and --holdout shape the 1D diagnosis's hold-out draw; a 3D \
             diagnosis fits every candidate on the even runs and scores it on the odd \
             ones and back (both halves held out in turn), whatever they say"
        );
    }
    if evidence != Evidence::LineForce {
        println!("{}", inventory_summary(data, base, args.contact));
    }
    if evidence == Evidence::Poses {
        // A camera's poses: the diagnosis from motion, written to OUT.
        let freedom = if inputs.fitted {
            MotionBase::Fitted
        } else {
            MotionBase::Given
        };
        let mut catalogue = hcm_host::diagnose::Catalogue::default();
        if args.chance {
            catalogue = catalogue.with_chance();
        }
        let base_with = (freedom, &catalogue);
        let physics = args.physics.as_deref().map(Physics::read).transpose()?;
        let poses = super::diagnose_motion::PosesInputs {
            model: base,
            physics,
            scenario: &inputs.scenario.name,
            contact: args.contact,
            data: (data, &args.data),
            out: &args.out,
        };
        return super::diagnose_motion::diagnose_into(poses, base_with);
    }
    anyhow::ensure!(
        inputs.has_physics,
        "{}: diagnosing the force needs the base model: give --physics (a physics file \
         from `hcm identify`)",
        args.data.display()
    );
    let file = args.data.display().to_string();
    data.require_for(&file, base, args.contact, evidence, DataUse::Diagnose)?;
    if evidence == Evidence::Wrench {
        let rigid = super::diagnose_rigid::RigidArgs {
            data: &args.data,
            out: &args.out,
            contact: args.contact,
            fitted: inputs.fitted,
        };
        return super::diagnose_rigid::run(&rigid, &inputs.scenario, base, data);
    }
    diagnose_line_force(&args, &inputs)
}

/// The 1D diagnosis, written whole to `--out` (report.md, diagnosis.json,
/// extended.toml and the figures) and its report printed.
fn diagnose_line_force(args: &Args, inputs: &Inputs) -> anyhow::Result<()> {
    // Built as a hidden directory beside --out and renamed into place when complete:
    // a failure (too few runs, a failed fit) leaves no --out behind.
    let staged = StagedDirectory::create(&args.out, "diagnosis.json")?;
    let out = staged.path().to_owned();
    let bar = progress_bar(
        1,
        match args.chance {
            true => "diagnosing (noise, selection, re-fit, HCM, gain, chance)",
            false => "diagnosing (noise, selection, re-fit, HCM, gain)",
        },
    );
    let settings = DiagnoseSettings {
        contact: args.contact,
        seed: args.seed,
        holdout_fraction: args.holdout,
        base_freedom: if inputs.fitted {
            BaseFreedom::Fitted
        } else {
            BaseFreedom::Given
        },
        chance: args.chance,
        ..DiagnoseSettings::default()
    };
    let diagnosis = diagnose(&inputs.base, &inputs.data, &settings)?;
    bar.finish_and_clear();

    let written = DiagnosisOf {
        base: &inputs.base,
        contact: args.contact,
        data: &args.data.display().to_string(),
        scenario: &inputs.scenario.name,
    };
    let report = write_diagnosis(&out, &written, &diagnosis)?;
    staged.commit()?;
    print!("{report}");
    Ok(())
}
