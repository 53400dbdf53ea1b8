//! `hcm identify-motion`: a tossed body's contact law, friction and table height fitted
//! to filmed tosses (poses, no force), judged on tosses the fit never saw.

use super::progress::Bars;
use anyhow::Context;
use hcm_host::dataset::Dataset;
use hcm_host::identify::with_law;
use hcm_host::identify::ForceData;
use hcm_host::identify::{
    beside_physics, fitted_assignments, fitted_physics, fitted_scenario_text, identify_motion,
    set_options, split_tosses, MotionFit, MotionParameters, MotionTarget,
};
use hcm_host::identify::{identify_motion_and_force, MotionSearch};
use hcm_host::numerics::optimize::GeneticSettings;
use hcm_host::output::write_bytes;
use hcm_host::progress::{Fold, Stage};
use hcm_host::scenario::{Assignment, Model};
use hcm_host::toss::{evaluate_tosses, summarize, EvaluationSummary, TossSetup};
use std::path::PathBuf;

/// Fit a thrown body's contact to filmed throws (motion only) and judge it on held-out ones.
///
/// Example: `hcm identify-motion --scenario scenarios/cube_toss.toml --data data/contactnets-cube/tosses.csv --out fitted.toml`
///
/// The scenario has one moving body (a box or a sphere) and its contacts with fixed
/// bodies (planes, boxes, spheres, compounds); its first contact is fitted. Splits the
/// runs of --data by toss number (the digits ending a run id): even numbers are the
/// training part, odd numbers the held-out part, which the fit never sees. On the
/// training part, fits the contact law's stiffness and damping (or restitution), the
/// friction's μ_s and μ_d, the table offset and the body's inertia (a scale on the
/// scenario's) — in the scenario's [identify.bounds.<law>] box where it gives one, else
/// in one scaled from the scenario's own values — by
/// replaying every toss from its window start (as `hcm predict` does) and minimising
/// the mean position error (%) plus the mean rotation error (°): the genetic
/// algorithm, then a Nelder–Mead polish, each candidate's tosses simulated in
/// parallel. Writes the physics file (law and friction; the table offset and the
/// inertia, which a physics file cannot carry, are printed as the `--set`s that apply
/// them, and kept in the file's notes; --scenario-out writes a scenario with all of
/// them in), and prints the scores of the scenario's parameters, the fitted ones and
/// the frozen pose on both parts, and which parameters the training tosses leave
/// loose (moving one ×/÷ 1.25, or by 10 % of its box, costs under 1 % of the fitness).
///
/// Terms:
///   window         a toss's frames from 3 frames before the body's centre first comes
///                  within its circumscribed radius of a fixed body (or bounces off it
///                  between two frames) to its last frame
///   position error mean over the window's frames of |p_pred − p| / the body's width, %
///   rotation error mean over the window's frames of the angle of R_predᵀ·R, degrees
///   fitness        mean position error + mean rotation error over the training tosses
///   force error    with --with-force: the mean square, over the instants with a
///                  measured force, of the law's wrench at the recorded poses minus the
///                  measured one, each component over its RMS
///   table offset   the fixed partner's surface moved (m): a plane along its normal,
///                  another shape along the up direction; the tracker's table height
///   inertia scale  the factor (–) on the scenario's inertia tensor of the tossed body
///   frozen pose    the baseline: the body held at its recorded window-start pose
///   physics file   the fitted law with its parameters and friction, which
///                  `hcm predict --physics` and `hcm simulate --physics` read
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Filmed tosses (measured-data CSV): position and orientation in every frame.
    #[arg(long)]
    data: PathBuf,
    /// Where to write the physics file (TOML).
    #[arg(long)]
    out: PathBuf,
    /// Use only the first N runs of --data (before the split).
    #[arg(long, value_name = "N")]
    first: Option<usize>,
    /// Also write the held-out tosses (measured-data CSV), for `hcm predict --data`.
    #[arg(long, value_name = "FILE")]
    held_out: Option<PathBuf>,
    /// Also write the fitted scenario (TOML): the scenario with the fitted law
    /// parameters, friction and table offset in it, for `hcm predict --scenario`.
    #[arg(long, value_name = "FILE")]
    scenario_out: Option<PathBuf>,
    /// Seed of the genetic algorithm.
    #[arg(long, default_value_t = 1)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::seed)]
    seed: u64,
    /// GA population size.
    #[arg(long, default_value_t = 20)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::population)]
    population: usize,
    /// GA generations.
    #[arg(long, default_value_t = 10)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::generations)]
    generations: usize,
    /// Fitness evaluations of the Nelder–Mead polish after the GA (0: none).
    #[arg(long, default_value_t = 40)]
    polish: usize,
    /// Law to fit in place of the scenario's (see `hcm laws`); its parameters start
    /// from the scenario's where they share names.
    #[arg(long)]
    law: Option<String>,
    /// Which contact to fit (index of its `[[contact]]`; one of the moving body's).
    /// Default: its first.
    #[arg(long)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::contact)]
    contact: Option<usize>,
    /// Fit the force measured at the recorded poses too, in one objective with the
    /// motion: (motion fitness / its value at the scenario's parameters) + (force
    /// error / its value there), so each starts at 1 (`hcm identify --method both`).
    #[arg(long)]
    with_force: bool,
}

impl Args {
    /// `hcm identify` on a camera's poses: this fit with its own defaults (GA 20 × 10,
    /// polish 40), the given seed and law.
    pub fn from_identify(
        scenario: super::ScenarioArgs,
        data: PathBuf,
        out: PathBuf,
        seed: u64,
        law: String,
        contact: usize,
        with_force: bool,
    ) -> Args {
        Args {
            scenario,
            data,
            out,
            first: None,
            held_out: None,
            scenario_out: None,
            seed,
            population: 20,
            generations: 10,
            polish: 40,
            law: Some(law),
            contact: Some(contact),
            with_force,
        }
    }
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = args.scenario.load()?;
    let mut model = scenario.model()?;
    let setup = TossSetup::new(&model)?;
    let mut parameters = MotionParameters::for_contact(&model, &setup, args.contact)?;
    if let Some(law) = &args.law {
        model = with_law(&model, parameters.contact, law, None)?;
        parameters = MotionParameters::for_contact(&model, &setup, args.contact)?;
    }
    let (training, held_out) = read_split(&args, &model, &setup)?;
    let target = MotionTarget::new(&model, &training)?;
    let settings = GeneticSettings {
        seed: args.seed,
        population: args.population,
        generations: args.generations,
        ..GeneticSettings::default()
    };
    let force = force_term(&args, &model, &training, parameters.contact)?;
    let fit = run_fit(
        &model,
        &target,
        &parameters,
        &settings,
        args.polish,
        force.as_ref(),
    )?;
    println!(
        "fitted on {} training tosses in {:.1} s ({} replays of them): fitness {:.3} with \
         the scenario's parameters, {:.3} after the GA, {:.3} after the polish",
        training.runs.len(),
        fit.seconds,
        fit.evaluations,
        fit.start_fitness,
        fit.genetic_fitness,
        fit.fitness
    );
    print_parameters(&fit);
    let assignments = fitted_assignments(&model, &parameters, &fit.parameters);
    let sets = beside_physics(&model, &parameters, &fit.parameters);
    println!(
        "{}: kept in the physics file's `sets` (`hcm predict --physics` applies them): {}",
        body_genes(&fit.parameters),
        set_options(&sets)
    );
    print!("{}", score_table(&model, &fit.model, &training, &held_out)?);
    write_physics(
        &args,
        &scenario.name,
        &fit,
        &parameters,
        &sets,
        training.runs.len(),
    )?;
    if let Some(path) = &args.scenario_out {
        let header = format!(
            "Scenario `{}` ({}) with the contact, table height and inertia fitted by\n\
             hcm identify-motion to the even-numbered tosses of {}: {}",
            scenario.name,
            args.scenario.scenario.display(),
            args.data.display(),
            (assignments.iter().map(Assignment::to_string))
                .collect::<Vec<_>>()
                .join(" ")
        );
        let text = fitted_scenario_text(&scenario, &assignments, &header)?;
        write_bytes(path, text.as_bytes())?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Reads --data (its first N runs with --first), checks the poses and splits it into
/// (training, held out); writes the held-out part with --held-out.
fn read_split(args: &Args, model: &Model, setup: &TossSetup) -> anyhow::Result<(Dataset, Dataset)> {
    let mut data = Dataset::read(&args.data)?;
    if let Some(first) = args.first {
        anyhow::ensure!(first > 1, "--first {first}: give at least 2 runs to split");
        data.runs.truncate(first);
    }
    setup.check_data(&args.data.display().to_string(), model, &data)?;
    let (training, held_out) = split_tosses(&data);
    anyhow::ensure!(
        !training.runs.is_empty() && !held_out.runs.is_empty(),
        "{}: the split by toss number left {} training and {} held-out runs; both parts \
         need runs (even and odd numbers)",
        args.data.display(),
        training.runs.len(),
        held_out.runs.len()
    );
    if let Some(path) = &args.held_out {
        held_out
            .write(path)
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok((training, held_out))
}

/// Writes the physics file: the fitted law and friction, the `--set`s of the table
/// offset and the inertia in the notes.
fn write_physics(
    args: &Args,
    name: &str,
    fit: &MotionFit,
    parameters: &MotionParameters,
    sets: &[Assignment],
    runs: usize,
) -> anyhow::Result<()> {
    let method = "ga + Nelder–Mead on toss replays (motion only)";
    let data = args.data.display().to_string();
    fitted_physics(fit, parameters.contact, sets, method, &data, runs)
        .write(
            &args.out,
            &format!("contact of scenario `{name}` fitted to tosses by hcm identify-motion"),
        )
        .with_context(|| format!("writing {}", args.out.display()))?;
    println!("wrote {}", args.out.display());
    Ok(())
}

/// The fit, with a progress bar per stage.
fn run_fit(
    model: &Model,
    target: &MotionTarget<'_>,
    parameters: &MotionParameters,
    settings: &GeneticSettings,
    polish: usize,
    force: Option<&ForceData<'_>>,
) -> anyhow::Result<MotionFit> {
    let bars = Bars::with_status(|stage| match stage {
        Stage::MotionPolish(_) => "polish",
        _ => "GA generations",
    });
    let fold = Fold::First;
    let fit = match force {
        Some(force) => {
            let search = MotionSearch {
                settings,
                polish_budget: polish,
                fold,
            };
            identify_motion_and_force(model, (target, force), parameters, &search, &bars)?
        }
        None => identify_motion(model, target, parameters, settings, polish, fold, &bars)?,
    };
    Ok(fit)
}

/// The scores of the scenario's parameters, the fitted ones and the frozen pose on the
/// training and held-out tosses, as a markdown table.
fn score_table(
    start: &Model,
    fitted: &Model,
    training: &Dataset,
    held_out: &Dataset,
) -> anyhow::Result<String> {
    let summary = |model: &Model, data: &Dataset| -> anyhow::Result<EvaluationSummary> {
        Ok(summarize(&evaluate_tosses(model, data, || {})?))
    };
    let mut out = String::from(
        "\n| tosses | model | position error (%): mean ± std | median | rotation error (°): mean ± std | median |\n|---|---|---|---|---|---|\n",
    );
    for (label, data) in [("training", training), ("held out", held_out)] {
        let before = summary(start, data)?;
        let after = summary(fitted, data)?;
        let rows = [
            ("scenario's parameters", before.position, before.rotation),
            ("fitted", after.position, after.rotation),
            (
                "frozen pose",
                after.baseline_position,
                after.baseline_rotation,
            ),
        ];
        for (model, p, r) in rows {
            out.push_str(&format!(
                "| {label} ({}) | {model} | {:.2} ± {:.2} | {:.2} | {:.2} ± {:.2} | {:.2} |\n",
                p.count, p.mean, p.std, p.median, r.mean, r.std, r.median
            ));
        }
    }
    Ok(out)
}

/// The fitted parameters, each said at its bound or not fixed by the data where so,
/// and a warning naming those.
fn print_parameters(fit: &MotionFit) {
    for (name, value) in &fit.parameters {
        let probe = fit.sensitivity.iter().find(|s| &s.name == name);
        let note = match probe {
            Some(s) if s.at_bound => "  at the bound of its box: the data may want it beyond",
            Some(s) if s.loose => "  not fixed by the data (moving it costs < 1 % of the fitness)",
            _ => "",
        };
        println!("  {name:<14} {value:.6e}{note}");
    }
    let loose: Vec<&str> = (fit.sensitivity.iter())
        .filter(|s| s.loose)
        .map(|s| s.name.as_str())
        .collect();
    let bounded: Vec<&str> = (fit.sensitivity.iter())
        .filter(|s| s.at_bound)
        .map(|s| s.name.as_str())
        .collect();
    if !bounded.is_empty() {
        println!(
            "warning: {} ended at the bound of the search box: widen it with \
             [identify.bounds.<law>] in the scenario for a law parameter, or look for an \
             effect the model lacks (`hcm diagnose`)",
            bounded.join(", ")
        );
    }
    if !loose.is_empty() {
        println!(
            "warning: the training tosses do not fix {}: their value is one of many that \
             replay the tosses as well; tosses that exercise them (sliding for friction, \
             bouncing for the damping) would",
            loose.join(", ")
        );
    }
}

/// With `--with-force`, the force term of the objective on the `training` runs'
/// contact `contact` (an error where they hold no force), said.
fn force_term<'a>(
    args: &Args,
    model: &Model,
    training: &'a Dataset,
    contact: usize,
) -> anyhow::Result<Option<ForceData<'a>>> {
    if !args.with_force {
        return Ok(None);
    }
    let force = ForceData {
        data: training,
        contact,
    };
    anyhow::ensure!(
        force.cost(model).is_finite(),
        "{}: --with-force (--method both) needs the contact's force at the recorded poses, \
         and the training runs give none (fx, fy, fz of either body)",
        args.data.display()
    );
    println!(
        "objective: motion fitness / its value at the scenario's parameters + force residual \
         at the recorded poses / its value there (each 1 at the start)"
    );
    Ok(Some(force))
}

/// The fitted values a physics file keeps as `--set`s, named: the table offset (where
/// fitted), the inertia and the rounding (where fitted).
fn body_genes(parameters: &[(String, f64)]) -> String {
    let fitted = |name: &str| parameters.iter().any(|p| p.0 == name);
    let names: Vec<&str> = [
        ("table_offset", "table offset"),
        ("inertia_scale", "inertia"),
        ("rounding", "rounding"),
    ]
    .into_iter()
    .filter(|(gene, _)| fitted(gene))
    .map(|(_, name)| name)
    .collect();
    match names.as_slice() {
        [] => "nothing".to_owned(),
        [one] => (*one).to_owned(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}
