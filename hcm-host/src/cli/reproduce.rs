//! `hcm reproduce`: the paper's whole method for one example — generate (PM1) →
//! split → identify (PM2) → train → export → evaluate — with the report and figures.

use super::export::{blob, Weights};
use super::progress_bar;
use anyhow::Context;
use hcm_host::evaluate::{evaluate, markdown, ConditionTable};
use hcm_host::experiment::{generate, split};
use hcm_host::figure::{Band, Colour, Figure, Series};
use hcm_host::identify::evolve::Fitness;
use hcm_host::identify::genetic::GeneticSettings;
use hcm_host::identify::replay::{curve, simulate_target_with, targets, Target};
use hcm_host::identify::samples::force_samples;
use hcm_host::identify::{identify, Method, Physics};
use hcm_host::law_catalogue;
use hcm_host::output::write_bytes;
use hcm_host::residual::{ContactResidual, HIDDEN, WIDTH};
use hcm_host::scenario::Scenario;
use hcm_host::train::{quantisation_aware, residual_pairs, train, TrainSettings, TrainedResidual};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Epochs of quantisation-aware fine-tuning of the int8 twin.
const INT8_EPOCHS: usize = 20;

/// The paper's examples.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum Example {
    /// Section 5.1, Table 5.
    BouncingBall,
    /// Section 5.2, Table 10.
    FlatShot,
}

impl Example {
    fn file(self) -> &'static str {
        match self {
            Example::BouncingBall => "bouncing_ball.toml",
            Example::FlatShot => "flat_shot.toml",
        }
    }
    /// Runs per condition as in the paper (1000 ball runs; 10 speeds × 100).
    fn runs(self) -> usize {
        match self {
            Example::BouncingBall => 1000,
            Example::FlatShot => 100,
        }
    }
    /// The paper's PM2 and HCM errors (%), Tables 5 and 10.
    fn paper(self) -> ([f64; 4], [f64; 4]) {
        match self {
            Example::BouncingBall => ([1.58, 0.31, 8.05, 0.88], [0.12, 0.01, 0.01, 0.01]),
            Example::FlatShot => ([0.46, 1.02, 37.50, 0.86], [0.16, 0.02, 4.17, 0.01]),
        }
    }
}

/// Reproduce one of the paper's examples end to end: `hcm reproduce bouncing-ball --out results/ball`.
#[derive(clap::Args)]
pub struct Args {
    /// Which example.
    example: Example,
    /// Output directory (created): data, pm2.toml, residual blobs, report.md, figures.
    #[arg(long)]
    out: PathBuf,
    /// Seed of the experiment, the GA and the training.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Runs per condition (default: the paper's).
    #[arg(long)]
    runs: Option<usize>,
    /// Identification method of PM2: `ga` (the paper's, polished by LM) or `lsq`.
    #[arg(long, value_parser = ["ga", "lsq"], default_value = "ga")]
    method: String,
    /// Scenario file (default: scenarios/<example>.toml of this repository).
    #[arg(long)]
    scenario: Option<PathBuf>,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let path = args.scenario.clone().unwrap_or_else(|| {
        let local = Path::new("scenarios").join(args.example.file());
        if local.exists() {
            local
        } else {
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../scenarios")
                .join(args.example.file())
        }
    });
    let scenario = Scenario::load(&path, &[])?;
    let model = scenario.model()?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let mut timings: Vec<(&str, f64)> = Vec::new();
    let runs = args.runs.unwrap_or(args.example.runs());

    let clock = Instant::now();
    let total = (runs * scenario.experiment.conditions.len().max(1)) as u64;
    let bar = progress_bar(total, "1/5 generate");
    let data = generate(&scenario, runs, args.seed, || bar.inc(1))?;
    bar.finish_and_clear();
    let sets = split(&scenario, data, args.seed);
    for (set, name) in [(&sets.training, "s1.csv"), (&sets.validation, "s2.csv")] {
        set.write(&args.out.join(name))?;
    }
    timings.push(("generate + split + write", clock.elapsed().as_secs_f64()));

    let clock = Instant::now();
    let method = match args.method.as_str() {
        "lsq" => Method::Lsq,
        _ => Method::Ga(
            Fitness::Curve,
            GeneticSettings {
                population: 60,
                generations: 150,
                seed: args.seed,
                ..GeneticSettings::default()
            },
        ),
    };
    let bar = progress_bar(1, "2/5 identify");
    let found = identify(
        &scenario,
        &model,
        &sets.training,
        0,
        "lankarani_nikravesh",
        method,
        |g, n, _| {
            bar.set_length(n as u64);
            bar.set_position(g as u64);
        },
    )?;
    bar.finish_and_clear();
    let physics = Physics::for_contact(&model, 0, &found.law, found.fit.clone());
    physics.write(
        &args.out.join("pm2.toml"),
        &format!("PM2 of `{}` from hcm reproduce", scenario.name),
    )?;
    let pm2 = physics.apply(&scenario, &path)?.model()?;
    timings.push(("identify PM2", clock.elapsed().as_secs_f64()));

    let clock = Instant::now();
    let (samples, _) = force_samples(&pm2, &sets.training, 0)?;
    let (inputs, outputs) = residual_pairs(&samples, &pm2.contacts[0].model);
    let settings = TrainSettings {
        hidden_layers: HIDDEN,
        width: WIDTH,
        seed: args.seed,
        ..TrainSettings::default()
    };
    let bar = progress_bar(settings.max_epochs as u64, "3/5 train");
    let (network, report) = train(&inputs, &outputs, &settings, |epoch, _, _| {
        bar.set_position(epoch as u64)
    })?;
    bar.finish_and_clear();
    let bar = progress_bar(INT8_EPOCHS as u64, "3/5 int8 twin");
    let (int8, tuned) = quantisation_aware(&network, &inputs, INT8_EPOCHS, args.seed, |e, _| {
        bar.set_position(e as u64)
    })?;
    bar.finish_and_clear();
    let trained = TrainedResidual::new(0, network, int8);
    trained.write(&args.out.join("residual.json"))?;
    timings.push(("train (+ int8 twin)", clock.elapsed().as_secs_f64()));

    let clock = Instant::now();
    let mut blobs = Vec::new();
    for (weights, name) in [
        (Weights::F32, "residual.bin"),
        (Weights::Int8, "residual.int8.bin"),
    ] {
        let (bytes, round_trip) = blob(&trained, weights)?;
        write_bytes(&args.out.join(name), &bytes)?;
        blobs.push((
            weights,
            bytes.len(),
            round_trip,
            ContactResidual::decode(&bytes).map_err(|e| anyhow::anyhow!("{e}"))?,
        ));
    }
    timings.push(("export", clock.elapsed().as_secs_f64()));

    let clock = Instant::now();
    let bar = progress_bar(1, "5/5 evaluate");
    let mut models = vec![("PM2".to_owned(), pm2.clone())];
    for (weights, _, _, residual) in &blobs {
        let mut hcm = pm2.clone();
        hcm.contacts[0].model.residual = Some(residual.clone());
        models.push((
            if *weights == Weights::F32 {
                "HCM".into()
            } else {
                "HCM int8".into()
            },
            hcm,
        ));
    }
    let columns: Vec<(&str, &hcm_host::scenario::Model)> =
        models.iter().map(|(l, m)| (l.as_str(), m)).collect();
    let tables = evaluate(&columns, &sets.validation, 0)?;
    let table = tables
        .first()
        .context("the validation data hold no condition")?;
    let figures = figures(&pm2, &models[1].1, &sets.validation, &args.out)?;
    bar.finish_and_clear();
    timings.push(("evaluate + figures", clock.elapsed().as_secs_f64()));

    let mut md = String::new();
    let _ = writeln!(
        md,
        "# hcm reproduce {:?} (seed {}, {runs} runs per condition)\n",
        args.example, args.seed
    );
    let _ = writeln!(md, "Scenario `{}` (a reconstruction of the paper's lost parameters). PM2 = Lankarani–Nikravesh by {}: {}.\n", path.display(), found.fit.method,
        law_catalogue::parameters(&found.law).iter().map(|(n, v)| format!("{n} = {v:.6e}")).collect::<Vec<_>>().join(", "));
    let _ = writeln!(
        md,
        "## Table (S2 = {} runs{})\n",
        table.runs,
        if table.condition.is_empty() {
            String::new()
        } else {
            format!(", condition {}", table.condition)
        }
    );
    md.push_str(&markdown(table));
    md.push_str(&paper_comparison(args.example, table));
    let _ = writeln!(md, "\nResidual: {} training samples, {} epochs (best {}), validation RMS {:.2} N. int8 twin: RMS to the f32 network {:.3} N after plain rounding, {:.3} N after {} epochs of quantisation-aware fine-tuning. Blobs (core vs host, worst relative error over the envelope): {}.\n", inputs.len(), report.epochs, report.best_epoch, report.validation_loss.sqrt(),
        tuned.rounded_rms, tuned.tuned_rms, tuned.epochs,
        blobs.iter().map(|(w, n, e, _)| format!("{w:?} {n} bytes ({e:.1e})")).collect::<Vec<_>>().join(", "));
    let _ = writeln!(md, "## Stage timings (s)\n\n| stage | s |\n|---|---|");
    for (stage, seconds) in &timings {
        let _ = writeln!(md, "| {stage} | {seconds:.2} |");
    }
    let _ = writeln!(md, "\nFigures: {}", figures.join(", "));
    write_bytes(&args.out.join("report.md"), md.as_bytes())?;
    print!("{md}");
    Ok(())
}

/// Our errors beside the paper's (Tables 5 and 10).
fn paper_comparison(example: Example, table: &ConditionTable) -> String {
    let (pm2, hcm) = example.paper();
    let names = [
        "maximum contact force",
        "contact impulse",
        "contact energy loss",
        "contact duration",
    ];
    let mut out = String::from("\n| indicator | PM2 error (hcm) | PM2 error (paper) | HCM error (hcm) | HCM error (paper) |\n|---|---|---|---|---|\n");
    let error = |i: usize, k: usize| {
        table
            .models
            .get(k)
            .and_then(|m| m.errors)
            .map_or("–".to_owned(), |e| format!("{:.2} %", 100.0 * e[i]))
    };
    for (i, name) in names.iter().enumerate() {
        let _ = writeln!(
            out,
            "| {name} | {} | {:.2} % | {} | {:.2} % |",
            error(i, 0),
            pm2[i],
            error(i, 1),
            hcm[i]
        );
    }
    out
}

/// The standard error of `target`'s mean force at each sample, s/√n over the runs of its
/// condition in `data` (N): the noise within which a model's difference from the mean
/// cannot be told from chance. NaN with fewer than two runs, where it is undefined.
fn mean_standard_error(
    model: &hcm_host::scenario::Model,
    data: &hcm_host::dataset::Dataset,
    target: &Target,
) -> anyhow::Result<Vec<f64>> {
    let mut curves = Vec::new();
    for run in &data.runs {
        if hcm_host::experiment::condition_of(&run.id) == target.condition {
            let len = target.curve.len();
            curves.extend(curve(model, run, 0, target.period, len)?.map(|c| c.0));
        }
    }
    let n = curves.len() as f64;
    let at = |j: usize| {
        let squares: f64 = curves
            .iter()
            .map(|c| (c[j] - target.curve[j]).powi(2))
            .sum();
        (squares / (n - 1.0)).sqrt() / n.sqrt()
    };
    Ok((0..target.curve.len())
        .map(|j| if n < 2.0 { f64::NAN } else { at(j) })
        .collect())
}

/// Fig 9/12 (contact force of S2 mean, PM2, HCM, with a zoom on the peak) and Fig 10/13
/// (force error over the contact, with the zero line and ±2 standard errors of the S2
/// mean), each as SVG and PNG; returns the file names.
fn figures(
    pm2: &hcm_host::scenario::Model,
    hcm: &hcm_host::scenario::Model,
    s2: &hcm_host::dataset::Dataset,
    out: &Path,
) -> anyhow::Result<Vec<String>> {
    let target = targets(pm2, s2, 0)?
        .into_iter()
        .next()
        .context("no validation condition")?;
    let time = |j: usize| 1e6 * j as f64 * target.period;
    let pm2_curve = simulate_target_with(&target, 0, &pm2.contacts[0])
        .map(|c| c.0)
        .unwrap_or_default();
    let hcm_curve = simulate_target_with(&target, 0, &hcm.contacts[0])
        .map(|c| c.0)
        .unwrap_or_default();
    let points = |v: &[f64]| {
        v.iter()
            .enumerate()
            .map(|(j, f)| (time(j), *f))
            .collect::<Vec<_>>()
    };
    let errors = |v: &[f64]| {
        target
            .curve
            .iter()
            .zip(v)
            .enumerate()
            .map(|(j, (m, s))| (time(j), m - s))
            .collect::<Vec<_>>()
    };
    let force = Figure::new(
        "Contact force over the contact (S2)",
        "time since touch-down (µs)",
        "normal force (N)",
        vec![
            Series {
                label: "S2 mean",
                colour: Colour::hex(0x333333),
                points: points(&target.curve),
            },
            Series {
                label: "PM2",
                colour: Colour::hex(0xd62728),
                points: points(&pm2_curve),
            },
            Series {
                label: "HCM",
                colour: Colour::hex(0x1f77b4),
                points: points(&hcm_curve),
            },
        ],
    )
    .with_peak_inset();
    let noise = mean_standard_error(pm2, s2, &target)?;
    let band = Band {
        label: "±2 standard errors of the S2 mean",
        colour: Colour::hex(0xd9d9d9),
        points: noise
            .iter()
            .enumerate()
            .map(|(j, e)| (time(j), -2.0 * e, 2.0 * e))
            .collect(),
    };
    let error = Figure::new(
        "Force error: S2 mean − model",
        "time since touch-down (µs)",
        "force error (N)",
        vec![
            Series {
                label: "PM2",
                colour: Colour::hex(0xd62728),
                points: errors(&pm2_curve),
            },
            Series {
                label: "HCM",
                colour: Colour::hex(0x1f77b4),
                points: errors(&hcm_curve),
            },
        ],
    )
    .with_band(band)
    .with_zero_line();
    let mut names = Vec::new();
    for (stem, figure) in [("contact_force", &force), ("force_error", &error)] {
        let (svg, png) = (format!("{stem}.svg"), format!("{stem}.png"));
        write_bytes(&out.join(&svg), figure.svg().as_bytes())?;
        let bytes = figure.png().with_context(|| format!("drawing {png}"))?;
        write_bytes(&out.join(&png), &bytes)?;
        names.extend([svg, png]);
    }
    Ok(names)
}
