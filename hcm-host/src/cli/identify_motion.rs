//! `hcm identify` from poses (the data hold no force, or `--method motion`/`both`): a
//! tossed body's contact law, friction, table height and inertia fitted to filmed tosses
//! by replaying them, judged on tosses the fit never saw.

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
use hcm_host::replay::{evaluate_tosses, summarize, EvaluationSummary, TossSetup};
use hcm_host::scenario::{Assignment, Model, Scenario};
use std::path::PathBuf;

/// What the fit from poses reads of `hcm identify`'s options (the GA's size and the
/// polish already at their defaults for poses).
pub struct Args {
    pub scenario: super::ScenarioArgs,
    pub data: PathBuf,
    pub out: PathBuf,
    pub first: Option<usize>,
    pub held_out: Option<PathBuf>,
    pub scenario_out: Option<PathBuf>,
    pub seed: u64,
    pub population: usize,
    pub generations: usize,
    pub polish: usize,
    pub law: Option<String>,
    pub contact: Option<usize>,
    pub with_force: bool,
}

/// Fits `scenario`'s contact to `data` (both as `hcm identify` read them).
pub fn run(args: Args, scenario: &Scenario, data: Dataset) -> anyhow::Result<()> {
    let mut model = scenario.model()?;
    let setup = TossSetup::new(&model)?;
    let mut parameters = MotionParameters::for_contact(&model, &setup, args.contact)?;
    if let Some(law) = &args.law {
        // Every contact fitted as one takes the law (else they would no longer be alike).
        for c in parameters.contacts() {
            model = with_law(&model, c, law, None)?;
        }
        parameters = MotionParameters::for_contact(&model, &setup, args.contact)?;
    }
    let (training, held_out) = read_split(&args, data, &model, &setup)?;
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
             hcm identify from poses to the even-numbered tosses of {}: {}",
            scenario.name,
            args.scenario.scenario.display(),
            args.data.display(),
            (assignments.iter().map(Assignment::to_string))
                .collect::<Vec<_>>()
                .join(" ")
        );
        let text = fitted_scenario_text(scenario, &assignments, &header)?;
        write_bytes(path, text.as_bytes())?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Takes --data's first N runs (with --first), checks the poses and splits them into
/// (training, held out); writes the held-out part with --held-out.
fn read_split(
    args: &Args,
    mut data: Dataset,
    model: &Model,
    setup: &TossSetup,
) -> anyhow::Result<(Dataset, Dataset)> {
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
    fitted_physics(fit, &parameters.contacts(), sets, method, &data, runs)
        .write(
            &args.out,
            &format!("contact of scenario `{name}` fitted to tosses by hcm identify from poses"),
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
