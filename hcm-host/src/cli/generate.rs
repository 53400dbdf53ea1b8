//! `hcm generate`: the noise-added experiment (PM1) and its S1/S2 split.

use super::progress_bar;
use anyhow::Context;
use hcm_host::experiment::{generate, split};
use std::path::{Path, PathBuf};

/// Generate noisy runs of a scenario: `hcm generate --scenario scenarios/bouncing_ball.toml --runs 1000 --seed 1 --out data.csv`.
///
/// Writes all runs to OUT and the split next to it: OUT.s1.csv (training, S1) and
/// OUT.s2.csv (validation, S2). Noise levels, conditions and the split rule come from
/// the scenario's `[experiment]` and `[[contact]] noise` (see the README).
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Runs per experimental condition (the flat shot has ten conditions).
    #[arg(long)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::runs)]
    runs: usize,
    /// Random seed: the same seed gives bit-identical files.
    #[arg(long, default_value_t = 1)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::seed)]
    seed: u64,
    /// Output file (CSV, measured-data format).
    #[arg(long)]
    out: PathBuf,
}

/// OUT with `suffix` before the extension: data.csv → data.s1.csv.
pub fn sibling(out: &Path, suffix: &str) -> PathBuf {
    let stem = out
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    out.with_file_name(format!("{stem}.{suffix}.csv"))
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = args.scenario.load()?;
    let conditions = scenario.experiment.conditions.len().max(1);
    let bar = progress_bar((conditions * args.runs) as u64, "simulating runs");
    let data = generate(&scenario, args.runs, args.seed, || bar.inc(1))?;
    bar.finish_and_clear();
    let sets = split(&scenario, data.clone(), args.seed);
    let (s1, s2) = (sibling(&args.out, "s1"), sibling(&args.out, "s2"));
    for (set, path) in [
        (&data, &args.out),
        (&sets.training, &s1),
        (&sets.validation, &s2),
    ] {
        set.write(path)
            .with_context(|| format!("writing {}", path.display()))?;
    }
    println!(
        "{}: {} runs ({} condition{}) → {}; S1 {} runs → {}; S2 {} runs → {}",
        scenario.name,
        data.runs.len(),
        conditions,
        if conditions == 1 { "" } else { "s" },
        args.out.display(),
        sets.training.runs.len(),
        s1.display(),
        sets.validation.runs.len(),
        s2.display()
    );
    Ok(())
}
