//! `hcm train`: the data-driven error model of the HCM, trained on S1, with its
//! quantisation-aware int8 twin; `hcm export` turns the result into weights blobs.

use super::progress::Bars;
use hcm_host::dataset::{needs, Dataset};
use hcm_host::identify::Physics;
use hcm_host::progress::Stage;
use hcm_host::train::{train_force_residual, ResidualSettings};
use std::path::PathBuf;

/// Train the residual network of the HCM on S1 (and its int8 twin).
///
/// Example: `hcm train --scenario scenarios/bouncing_ball.toml --data data.s1.csv --physics pm2.toml --out residual.json`
///
/// Its inputs are δ, δ̇ and δ̇0 of each contact sample, its output the measured force
/// minus PM2's. OUT (JSON) holds the network, its int8 twin and its envelope; turn it
/// into a blob for the core with `hcm export`.
///
/// Terms:
///   residual  the network's output: the force PM2 gets wrong (measured − PM2, N)
///   HCM       hybrid contact model: PM2 plus the residual network
///   PM2       the physics law identified by `hcm identify` (`--physics`)
///   S1        the training set written by `hcm generate` (OUT.s1.csv)
///   int8      the network with 8-bit integer weights (less memory on a controller),
///             fine-tuned to match the f32 network
///   envelope  the range of inputs seen in training; outside it the HCM is PM2 alone
///   blob      the network in the core's binary format, written by `hcm export`
///   δ, δ̇, δ̇0  indentation (m), its rate (m/s), the approach speed at touch-down (m/s)
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Training data (e.g. the S1 file of `hcm generate`).
    #[arg(long)]
    data: PathBuf,
    /// Physics file of the PM2 (from `hcm identify`).
    #[arg(long)]
    physics: PathBuf,
    /// Which contact of the scenario.
    #[arg(long, default_value_t = 0)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::contact)]
    contact: usize,
    /// Seed of the initialisation, split and shuffles.
    #[arg(long, default_value_t = 1)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::seed)]
    seed: u64,
    /// Most training epochs (early stopping usually ends sooner).
    #[arg(long, default_value_t = 200)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::epochs)]
    epochs: usize,
    /// Epochs of quantisation-aware fine-tuning of the int8 twin (0: plain rounding).
    #[arg(long, default_value_t = 20)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::fine_tuning_epochs)]
    int8_epochs: usize,
    /// Trained residual file to write (JSON), e.g. `residual.json`.
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = args.scenario.load()?;
    let pm2 = Physics::read(&args.physics)?
        .apply(&scenario, &args.physics)?
        .model()?;
    super::require_one_dimensional(&pm2, "train")?;
    super::check_contact(args.contact, &pm2)?;
    let data = Dataset::read(&args.data)?;
    data.require(
        &args.data.display().to_string(),
        &pm2,
        &[args.contact],
        &needs::TRAIN,
    )?;
    let settings = ResidualSettings {
        epochs: args.epochs,
        int8_epochs: args.int8_epochs,
        seed: args.seed,
    };
    let bars = Bars::with_status(|stage| match stage {
        Stage::Int8Twin => "int8 fine-tuning",
        _ => "training epochs",
    });
    let trained = train_force_residual(&pm2, &data, args.contact, &settings, &bars)?;
    let (report, tuned) = (&trained.report, &trained.int8);
    println!(
        "trained on {} samples from {} runs: {} epochs (best {}), train RMS {:.3} N, validation RMS {:.3} N, {:.2} s",
        trained.samples,
        data.runs.len(),
        report.epochs,
        report.best_epoch,
        report.train_loss.sqrt(),
        report.validation_loss.sqrt(),
        report.seconds
    );
    println!(
        "int8 twin: RMS against the f32 network {:.3} N rounded → {:.3} N after {} epochs (worst {:.3} N), {:.2} s",
        tuned.rounded_rms, tuned.tuned_rms, tuned.epochs, tuned.tuned_max, tuned.seconds
    );
    trained.residual.write(&args.out)?;
    println!(
        "→ {} (export with `hcm export --residual {0} --out residual.bin`)",
        args.out.display()
    );
    Ok(())
}
