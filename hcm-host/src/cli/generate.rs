//! `hcm generate`: the noise-added experiment (PM1) and its S1/S2 split.

use super::progress::Bars;
use hcm_host::experiment::{write_shard, ExperimentWriter, Shard};
use hcm_host::output::bytes;
use std::path::{Path, PathBuf};

/// Generate a noise-added experiment (PM1) and split it into S1 and S2.
///
/// Example: `hcm generate --scenario scenarios/bouncing_ball.toml --runs 1000 --seed 1 --out data.csv`
///
/// Writes three files: OUT with every run, and beside it the split: S1 in OUT.s1.csv
/// and S2 in OUT.s2.csv (the extension of OUT replaced: data.csv → data.s1.csv,
/// data.s2.csv). Noise levels, conditions and the split rule come from the scenario's
/// `[experiment]` and `[[contact]] noise` (README, "Scenario keys for experiments").
///
/// Terms:
///   PM1   the scenario's contact simulated with noise, standing in for measurements:
///         each run scatters the law's (and friction's) parameters (the paper's Eq 18)
///         and adds random noise to every recorded force (and torque) sample (Eq 19)
///   S1    the training set: the runs `hcm identify` and `hcm train` learn from
///   S2    the validation set, used only to judge models (`hcm evaluate`): a random
///         share of the runs, or the runs of the scenario's holdout conditions
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
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
    /// Output file (CSV, measured-data format) for every run; S1 and S2 are written
    /// beside it as OUT.s1.csv and OUT.s2.csv (data.csv → data.s1.csv, data.s2.csv).
    /// With --shard, OUT holds the shard's runs alone (no S1, S2).
    #[arg(long)]
    out: PathBuf,
    /// Make only shard I of N (numbered from 0: 0/4 … 3/4), the runs
    /// [⌊T·I/N⌋, ⌊T·(I+1)/N⌋) of the T runs, to OUT alone — the rows they have in the
    /// whole experiment; `--merge` joins the shards' files. On a Slurm job array the
    /// default is the array task's: SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN of
    /// SLURM_ARRAY_TASK_COUNT.
    #[arg(long, value_name = "I/N", value_parser = hcm_host::experiment::Shard::parse)]
    shard: Option<hcm_host::experiment::Shard>,
    /// Join shard files (`--shard`'s OUTs, in shard order) into OUT, S1 and S2: the same
    /// bytes as one `hcm generate` with the same --scenario, --set, --runs and --seed.
    #[arg(long, value_name = "SHARD", num_args = 1.., conflicts_with = "shard")]
    merge: Vec<PathBuf>,
}

/// OUT with `suffix` before the extension: data.csv → data.s1.csv.
pub fn sibling(out: &Path, suffix: &str) -> PathBuf {
    let stem = out
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    out.with_file_name(format!("{stem}.{suffix}.csv"))
}

/// Outputs above this size are announced before the work starts (bytes).
const LARGE_OUTPUT: u64 = 1_000_000_000;

pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = args.scenario.load()?;
    let shard = Shard::chosen(args.shard, !args.merge.is_empty()).map_err(anyhow::Error::msg)?;
    if let Some(shard) = shard {
        let progress = Bars::named(|_| "simulating runs");
        let written = write_shard(
            &scenario,
            (args.runs, args.seed),
            shard,
            &args.out,
            &progress,
        )?;
        println!(
            "{}: shard {shard}: {written} runs → {} (join the shards with --merge)",
            scenario.name,
            args.out.display()
        );
        return Ok(());
    }
    let (s1, s2) = (sibling(&args.out, "s1"), sibling(&args.out, "s2"));
    // Every refusal (too few runs, a special file at an output, too little disk space)
    // comes here, before the simulations and before anything appears at the outputs.
    let writer = ExperimentWriter::new(&scenario, args.runs, args.seed, [&args.out, &s1, &s2])?;
    let estimate = writer.estimated_bytes();
    if estimate > LARGE_OUTPUT {
        eprintln!(
            "note: OUT, S1 and S2 will take about {} together",
            bytes(estimate)
        );
    }
    let conditions = writer.generation().conditions();
    let written = if args.merge.is_empty() {
        writer.write(&Bars::named(|_| "simulating runs"))?
    } else {
        writer.merge(&args.merge)?
    };
    println!(
        "{}: {} runs ({} condition{}) → {}; S1 {} runs → {}; S2 {} runs → {}",
        scenario.name,
        written.runs,
        conditions,
        if conditions == 1 { "" } else { "s" },
        args.out.display(),
        written.training,
        s1.display(),
        written.validation,
        s2.display()
    );
    Ok(())
}
