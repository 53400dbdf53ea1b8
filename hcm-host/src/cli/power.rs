//! `hcm power`: the diagnosis's power study on a scenario, whole or in shards.

use super::progress::Bars;
use hcm_host::diagnose::power::{
    line_effect, read_rows, summary_markdown, write_rows, PowerBase, PowerRow, PowerSettings,
    PowerStudy,
};
use hcm_host::diagnose::{line_candidates, Candidate, DiagnoseSettings};
use hcm_host::experiment::Shard;
use hcm_host::output::{commit, write_atomically, StagedFile};
use std::io::Write;
use std::path::{Path, PathBuf};

/// How strong must an effect be before `hcm diagnose` names it on this rig? A power study.
///
/// Example: `hcm power --scenario scenarios/bouncing_ball.toml --runs 16 --seeds 10 --out power.csv`
///
/// For each catalogued effect of the 1D diagnosis, hidden at each strength of --levels,
/// and for each of --seeds seeds: the runs `hcm generate` makes of the scenario with the
/// effect hidden, then `hcm diagnose` on them against the scenario's own law (or that law
/// fitted on the same runs, --base fitted). The same with nothing hidden gives the false
/// alarms. Writes a row per data set to OUT (CSV) and the table beside it (OUT with .md):
/// per effect and strength how often it was named exactly, the wrong names, how often a
/// named parameter's 95 % interval held the truth. The table is printed too.
///
/// Terms:
///   strength    the largest change of the force the effect makes, to first order
///               along the data with nothing hidden, as a share of the peak force:
///               0.01 = 1 % (viscous damping c = 0.01·F̂/δ̇̂, an offset 0.01·F̂, a
///               delay of about 0.01·t_c/π on a contact of duration t_c)
///   named exactly  the hidden effect named and nothing else beside it
///   wrong name  a cause named that was not hidden
///   false alarm  a cause named in data with nothing hidden
///   shard       a share of the data sets for one machine (--shard), joined by --merge
///               into the same bytes one machine writes
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Runs per data set.
    #[arg(long, default_value_t = 16)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::runs)]
    runs: usize,
    /// Data sets (seeds) per effect and strength, and with nothing hidden.
    #[arg(long, default_value_t = 10)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::seeds)]
    seeds: u64,
    /// The first data set's seed (`hcm generate --seed`): seeds SEED to SEED + SEEDS − 1.
    #[arg(long, default_value_t = 1)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::seed)]
    seed: u64,
    /// Strengths, as shares of the peak force, comma-separated (0.01 = 1 %).
    #[arg(long, value_delimiter = ',', default_value = "0.005,0.01,0.03")]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::number)]
    levels: Vec<f64>,
    /// Effects to hide, comma-separated catalogue names; default: every effect the 1D
    /// diagnosis names (viscous_damping, hysteresis_damping, stiffness_exponent,
    /// adhesion, plasticity, force_offset, sensor_delay, sensor_filter).
    #[arg(long, value_delimiter = ',', value_parser = line_effect)]
    effects: Vec<Candidate>,
    /// What each diagnosis judges the data against: the scenario's own law as given
    /// (`scenario`), or that law fitted by least squares on the same runs (`fitted`,
    /// as `hcm identify --method lsq` then `hcm diagnose` would).
    #[arg(long, value_enum, default_value = "scenario")]
    base: Base,
    /// Which contact of the scenario.
    #[arg(long, default_value_t = 0)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::contact)]
    contact: usize,
    /// Share of each data set's runs the diagnosis holds out for its gain table.
    #[arg(long, default_value_t = 0.25)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::share)]
    holdout: f64,
    /// Output file (CSV): a row per data set; the table is written beside it (power.csv
    /// → power.md). With --shard, OUT holds the shard's rows alone.
    #[arg(long)]
    out: PathBuf,
    /// Make only shard I of N (numbered from 0), the data sets [⌊T·I/N⌋, ⌊T·(I+1)/N⌋)
    /// of the T, to OUT alone; `--merge` joins the shards. On a Slurm job array the
    /// default is the array task's: SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN of
    /// SLURM_ARRAY_TASK_COUNT.
    #[arg(long, value_name = "I/N", value_parser = Shard::parse)]
    shard: Option<Shard>,
    /// Join shard files (`--shard`'s OUTs, in shard order) into OUT and its table: the
    /// same bytes as one `hcm power` with the same options. Each shard's first data
    /// set is made again and compared.
    #[arg(long, value_name = "SHARD", num_args = 1.., conflicts_with = "shard")]
    merge: Vec<PathBuf>,
}

/// `--base`.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
enum Base {
    /// The scenario's own law, as given.
    Scenario,
    /// The scenario's law fitted by least squares on each data set's runs.
    Fitted,
}

/// OUT with the extension .md: power.csv → power.md.
fn table_path(out: &Path) -> PathBuf {
    out.with_extension("md")
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = args.scenario.load()?;
    let shard = Shard::chosen(args.shard, !args.merge.is_empty()).map_err(anyhow::Error::msg)?;
    let settings = PowerSettings {
        runs: args.runs,
        seeds: args.seeds,
        first_seed: args.seed,
        levels: args.levels.clone(),
        effects: match args.effects.is_empty() {
            true => line_candidates().collect(),
            false => args.effects.clone(),
        },
        base: match args.base {
            Base::Scenario => PowerBase::Scenario,
            Base::Fitted => PowerBase::Fitted,
        },
        diagnose: DiagnoseSettings {
            contact: args.contact,
            holdout_fraction: args.holdout,
            ..DiagnoseSettings::default()
        },
    };
    let study = PowerStudy::new(&scenario, settings)?;
    let progress = Bars::named(|_| "diagnosing data sets");
    if let Some(shard) = shard {
        let range = shard.range(study.len());
        let (from, to) = (range.start, range.end);
        let rows = study.rows(range, &progress)?;
        write_atomically(&args.out, |w: &mut dyn Write| -> anyhow::Result<()> {
            Ok(write_rows(w, study.key(), &rows)?)
        })?;
        println!(
            "{}: shard {shard}: data sets {from}..{to} of {} → {} (join the shards with --merge)",
            scenario.name,
            study.len(),
            args.out.display()
        );
        return Ok(());
    }
    let rows = match args.merge.is_empty() {
        true => study.rows(0..study.len(), &progress)?,
        false => merged(&study, &args.merge)?,
    };
    let table = summary_markdown(&study, &rows);
    let md = table_path(&args.out);
    let mut csv = StagedFile::create(&args.out)?;
    write_rows(&mut csv, study.key(), &rows)?;
    let mut text = StagedFile::create(&md)?;
    text.write_all(table.as_bytes())?;
    commit(vec![csv.finish()?, text.finish()?])?;
    print!("{table}");
    println!(
        "\n{} data sets → {}; the table → {}",
        rows.len(),
        args.out.display(),
        md.display()
    );
    Ok(())
}

/// The rows of `shards` (files of `--shard`, in order), checked to be this study's and
/// to follow one another from data set 0 to the last; each shard's first data set is
/// made again and must read the same.
fn merged(study: &PowerStudy, shards: &[PathBuf]) -> anyhow::Result<Vec<PowerRow>> {
    let mut parts = Vec::with_capacity(shards.len());
    for path in shards {
        let name = path.display().to_string();
        let bytes = std::fs::read(path)
            .map_err(|e| anyhow::anyhow!("--merge: {name}: cannot read it: {e}"))?;
        let part = read_rows(&name, &bytes, study.key())?;
        if let Some(first) = part.first() {
            let again = study.row(first.data_set)?;
            if line(study, &again)? != line(study, first)? {
                anyhow::bail!(
                    "--merge: {name}: its first data set ({}) reads differently when made \
                     again here: a shard of another hcm build or machine's arithmetic",
                    first.data_set
                );
            }
        }
        parts.push((name, part));
    }
    study
        .join(parts)
        .map_err(|e| anyhow::anyhow!("--merge: {e}"))
}

/// `row` as its file writes it.
fn line(study: &PowerStudy, row: &PowerRow) -> anyhow::Result<Vec<u8>> {
    let mut text = Vec::new();
    write_rows(&mut text, study.key(), std::slice::from_ref(row))?;
    Ok(text)
}
