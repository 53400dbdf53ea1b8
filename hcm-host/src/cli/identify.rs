//! `hcm identify`: fit a normal law (PM2) to measured data.

use super::progress::Bars;
use anyhow::Context;
use hcm_host::dataset::{inventory_summary, DataUse, Dataset, Evidence};
use hcm_host::identify::Fitness;
use hcm_host::identify::{identify, FitRecord, Identification, Method, Physics};
use hcm_host::numerics::optimize::GeneticSettings;
use hcm_host::progress::{Progress, Silent};
use hcm_host::scenario::{Model, Scenario};
use std::path::PathBuf;

/// Identify a physics model (PM2) from data: force samples, or filmed poses alone.
///
/// Example: `hcm identify --scenario scenarios/bouncing_ball.toml --data data.s1.csv --law lankarani_nikravesh --out pm2.toml`
///
/// Example: `hcm identify --scenario scenarios/cube_toss.toml --data data/contactnets-cube/tosses.csv --out fitted.toml --held-out held_out.csv --scenario-out fitted_scenario.toml`
///
/// What is fitted follows from the scenario and the data's channels:
///   1D scene        the law's free parameters to the force samples (least squares, or
///                   the paper's GA on simulated against measured force curves)
///   3D, with force  the law (and the friction) to the wrench at the recorded poses
///                   (least squares from several starts; `--method ga`: replayed events)
///   3D, poses only  (`--method motion` on data with force) the law's stiffness and
///                   damping, μ_s and μ_d, the table offset and the body's inertia, by
///                   replaying every toss from its window start (as `hcm predict`) and
///                   minimising the mean position error (% of the body's width) plus the
///                   mean rotation error (°): GA, then a Nelder–Mead polish. The runs are
///                   split by toss number (the digits ending a run id): even numbers
///                   train, odd ones are held out and only scored. The table offset and
///                   the inertia, which a physics file cannot carry, are kept in its
///                   `sets`; --scenario-out writes a scenario with all of them in.
/// Prints the parameters with their uncertainty (or, from poses, which ones the
/// training tosses leave loose) and writes a physics file that `hcm simulate
/// --physics`, `hcm train`, `hcm evaluate`, `hcm diagnose` and `hcm predict` read.
/// `hcm identify-motion` is this command with `--method motion`.
///
/// Terms:
///   PM2           physics model 2: a contact law with parameters identified on data
///   S1            the training set written by `hcm generate` (OUT.s1.csv)
///   physics file  TOML naming each contact's law and parameters, plus a fit record
///   GA            the paper's genetic algorithm (`--method ga`): it simulates candidate
///                 parameters and compares them with the data
///   indicators    of one contact: maximum force, impulse, energy loss and duration
///   window        a toss's frames from 3 frames before the body first comes within its
///                 circumscribed radius of a fixed body to its last frame
///   fitness       from poses: mean position error + mean rotation error per toss
///   force error   with --method both: the mean square, over the instants with a
///                 measured force, of the law's wrench at the recorded poses minus the
///                 measured one, each component over its RMS
///   frozen pose   the baseline: the body held at its recorded window-start pose
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Training data (measured-data CSV), e.g. the S1 file of `hcm generate`, or filmed
    /// tosses (position and orientation in every frame).
    #[arg(long)]
    data: PathBuf,
    /// Law to identify (see `hcm laws`); needed on force data. From poses: fitted in
    /// place of the scenario's, its parameters starting from the scenario's where they
    /// share names (default: the scenario's own law).
    #[arg(long)]
    law: Option<String>,
    /// `lsq`: least squares on the force samples (fast; 1D: separable + Levenberg–
    /// Marquardt; 3D: Levenberg–Marquardt on the wrench at the recorded poses, from
    /// several starts). `ga`: the paper's genetic algorithm on simulated vs measured
    /// data (3D: replayed contact events). `motion`: from the poses alone, by
    /// replays (what data without force get whatever this says). `both` (3D, force and
    /// poses): the fit from motion with the force at the recorded poses in the same
    /// objective: (motion fitness / its value at the scenario's parameters) + (force
    /// error / its value there), so each starts at 1.
    #[arg(long, value_parser = ["lsq", "ga", "motion", "both"], default_value = "lsq")]
    method: String,
    /// GA fitness: `curve` (force curves, default) or `indicators`.
    #[arg(long, value_parser = ["curve", "indicators"], default_value = "curve")]
    fitness: String,
    /// Which contact of the scenario (index of its `[[contact]]`). Default: the first;
    /// from poses, the moving body's first.
    #[arg(long)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::contact)]
    contact: Option<usize>,
    /// Seed of the genetic algorithm.
    #[arg(long, default_value_t = 1)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::seed)]
    seed: u64,
    /// GA population size (default 60; from poses 20).
    #[arg(long)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::population)]
    population: Option<usize>,
    /// GA generations (default 150, stopping earlier when the best has stalled for 30;
    /// from poses 10).
    #[arg(long)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::generations)]
    generations: Option<usize>,
    /// From poses: fitness evaluations of the Nelder–Mead polish after the GA (0: none).
    #[arg(long, default_value_t = 40)]
    polish: usize,
    /// From poses: use only the first N runs of --data (before the split).
    #[arg(long, value_name = "N")]
    first: Option<usize>,
    /// From poses: also write the held-out tosses (measured-data CSV), for `hcm predict
    /// --data`.
    #[arg(long, value_name = "FILE")]
    held_out: Option<PathBuf>,
    /// From poses: also write the fitted scenario (TOML): the scenario with the fitted
    /// law parameters, friction, table offset and inertia in it, for `hcm predict
    /// --scenario`.
    #[arg(long, value_name = "FILE")]
    scenario_out: Option<PathBuf>,
    /// The same as `--method both` (the name `hcm identify-motion` gave it).
    #[arg(long, hide = true)]
    with_force: bool,
    /// Rigid contacts: fix the law's exponent at this value (PM2's; default: the
    /// scenario's) and identify the rest. With `--method lsq` and without it, the
    /// exponent is fitted too.
    #[arg(long)]
    exponent: Option<f64>,
    /// Rigid contacts: how many contact events to fit, from the first (default: as
    /// many as the runs usually make).
    #[arg(long)]
    events: Option<usize>,
    /// Physics file to write (TOML), read by `simulate --physics` and `evaluate`.
    #[arg(long)]
    out: PathBuf,
}

impl Args {
    /// The fit from poses, whatever else the data hold (`hcm identify-motion`); its
    /// `--with-force` still asks for `--method both`.
    pub fn fitting_poses(mut self) -> Self {
        if self.method != "both" {
            self.method = "motion".into();
        }
        self
    }

    /// The law named by --law: required on force data.
    fn law(&self) -> anyhow::Result<String> {
        self.law.clone().ok_or_else(|| {
            anyhow::anyhow!(
                "{}: name the law to fit with --law (see `hcm laws`), e.g. --law hertz; \
                 only a fit from poses defaults to the scenario's own law",
                self.data.display()
            )
        })
    }

    /// What the rigid path needs.
    fn into_rigid(self, law: String, contact: usize) -> super::identify_rigid::RigidArgs {
        super::identify_rigid::RigidArgs {
            data: self.data,
            law,
            method: self.method,
            contact,
            exponent: self.exponent,
            events: self.events,
            out: self.out,
        }
    }

    /// What the fit from poses needs: its own GA size (20 × 10) unless given.
    fn into_motion(self, with_force: bool) -> super::identify_motion::Args {
        super::identify_motion::Args {
            scenario: self.scenario,
            data: self.data,
            out: self.out,
            first: self.first,
            held_out: self.held_out,
            scenario_out: self.scenario_out,
            seed: self.seed,
            population: self.population.unwrap_or(20),
            generations: self.generations.unwrap_or(10),
            polish: self.polish,
            law: self.law,
            contact: self.contact,
            with_force,
        }
    }
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = args.scenario.load()?;
    let model = scenario.model()?;
    let contact = args.contact.unwrap_or(0);
    super::check_contact(contact, &model)?;
    let data = Dataset::read(&args.data)?;
    let evidence = Evidence::of(&model, &data, contact);
    if evidence != Evidence::LineForce {
        println!("{}", inventory_summary(&data, &model, contact));
    }
    let with_force = args.with_force || args.method == "both";
    anyhow::ensure!(
        !(evidence == Evidence::Poses && with_force),
        "{}: --method both fits the force with the motion, and the data hold no force \
         (fx, fy, fz); drop --method to fit from the poses alone",
        args.data.display()
    );
    let from_poses = evidence == Evidence::Poses
        || (evidence == Evidence::Wrench && (with_force || args.method == "motion"));
    if from_poses {
        println!(
            "fitting from the poses{} (GA {} × {}, polish {})",
            if with_force {
                " and the force at them"
            } else {
                ""
            },
            args.population.unwrap_or(20),
            args.generations.unwrap_or(10),
            args.polish
        );
        return super::identify_motion::run(args.into_motion(with_force), &scenario, data);
    }
    anyhow::ensure!(
        matches!(args.method.as_str(), "lsq" | "ga"),
        "--method {}: fits a rigid (3D) contact from its poses; scenario `{}` is 1D, fit \
         it with --method lsq or ga",
        args.method,
        scenario.name
    );
    let law = args.law()?;
    let what = if args.method == "ga" {
        DataUse::IdentifyEvents
    } else {
        DataUse::Identify
    };
    let file = args.data.display().to_string();
    data.require_for(&file, &model, contact, evidence, what)?;
    let settings = GeneticSettings {
        seed: args.seed,
        population: args.population.unwrap_or(60),
        generations: args.generations.unwrap_or(150),
        ..GeneticSettings::default()
    };
    if evidence == Evidence::Wrench {
        let rigid = args.into_rigid(law, contact);
        return super::identify_rigid::run(&rigid, &scenario, &model, &data, settings);
    }
    anyhow::ensure!(
        args.exponent.is_none() && args.events.is_none(),
        "--exponent and --events are for rigid (3D) contacts; scenario `{}` is 1D: bound the \
         exponent with [identify.bounds.<law>] exponent = [lo, hi] instead",
        scenario.name
    );
    identify_one_dimensional(&args, &law, contact, &scenario, &model, &data, settings)
}

/// The 1D path: fits `law` to contact `contact`'s force samples by the method asked for, prints the
/// result and writes the physics file.
fn identify_one_dimensional(
    args: &Args,
    law: &str,
    contact: usize,
    scenario: &Scenario,
    model: &Model,
    data: &Dataset,
    settings: GeneticSettings,
) -> anyhow::Result<()> {
    let method = match (args.method.as_str(), args.fitness.as_str()) {
        ("lsq", _) => Method::Lsq,
        (_, "indicators") => Method::Ga(Fitness::Indicators, settings),
        _ => Method::Ga(Fitness::Curve, settings),
    };
    // Least squares takes a moment: no bar.
    let bars = Bars::with_status(|_| "GA generations");
    let progress: &dyn Progress = match method {
        Method::Lsq => &Silent,
        Method::Ga(..) => &bars,
    };
    let result = identify(scenario, model, data, contact, law, method, progress)?;
    let mut fit = result.fit.clone();
    fit.data = args.data.display().to_string();
    print_identification(law, &result, &fit);
    let physics = Physics::for_contact(model, contact, &result.law, fit);
    write_physics(&physics, &scenario.name, &args.out)
}

/// Prints the fit of `law`: runs, events and samples used, time (s), each parameter
/// with its standard error, the force RMS errors (N) and the notes.
fn print_identification(law: &str, result: &Identification, fit: &FitRecord) {
    println!(
        "{} by {} on {} runs ({} events, {} force samples) in {:.3} s",
        law, fit.method, fit.runs, fit.events, fit.samples, fit.seconds
    );
    for (name, value) in result.law.named() {
        let error = result
            .standard_errors
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, e)| format!("  ± {e:.3e} (1σ)"))
            .unwrap_or_default();
        println!("  {name:<20} {value:.6e}{error}");
    }
    println!(
        "  force residual RMS   {:.4} N over the force samples",
        fit.force_rms
    );
    println!(
        "  force curve RMS      {:.4} N between replayed and mean measured curves",
        fit.curve_rms
    );
    for note in &fit.notes {
        println!("  note: {note}");
    }
}

/// Writes `physics` (PM2 of scenario `name`) to `out` and says so.
pub(super) fn write_physics(
    physics: &Physics,
    name: &str,
    out: &std::path::Path,
) -> anyhow::Result<()> {
    physics
        .write(
            out,
            &format!("PM2 of scenario `{name}` identified by hcm identify"),
        )
        .with_context(|| format!("writing {}", out.display()))?;
    println!("wrote {}", out.display());
    Ok(())
}
