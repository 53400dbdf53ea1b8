//! `hcm train`: the data-driven error model of the HCM, trained on S1 and exported
//! as the core's weights blob.

use super::progress_bar;
use anyhow::Context;
use hcm_core::residual::Quantisation;
use hcm_host::dataset::Dataset;
use hcm_host::export::encode;
use hcm_host::identify::samples::force_samples;
use hcm_host::identify::Physics;
use hcm_host::output::write_atomically;
use hcm_host::residual::{export_model, ContactResidual, HIDDEN, WIDTH};
use hcm_host::train::{residual_pairs, train, TrainSettings};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Train the residual network (inputs δ, δ̇, δ̇0; output measured − PM2 force) and
/// export it: OUT gets the f32 blob, OUT with `.int8` before the extension the int8 one.
#[derive(clap::Args)]
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
    contact: usize,
    /// Seed of the initialisation, split and shuffles.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Most training epochs (early stopping usually ends sooner).
    #[arg(long, default_value_t = 200)]
    epochs: usize,
    /// Weights blob to write (f32); the int8 blob goes beside it.
    #[arg(long)]
    out: PathBuf,
}

fn write_blob(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    write_atomically(path, |w: &mut dyn Write| -> anyhow::Result<()> {
        Ok(w.write_all(bytes)?)
    })
    .with_context(|| format!("writing {}", path.display()))
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = args.scenario.load()?;
    let pm2 = Physics::read(&args.physics)?
        .apply(&scenario, &args.physics)?
        .model()?;
    super::check_contact(args.contact, &pm2)?;
    let data = Dataset::read(&args.data)?;
    let (samples, _) = force_samples(&pm2, &data, args.contact)?;
    let (inputs, targets) = residual_pairs(&samples, &pm2.contacts[args.contact].law);
    let settings = TrainSettings {
        hidden_layers: HIDDEN,
        width: WIDTH,
        max_epochs: args.epochs,
        seed: args.seed,
        ..TrainSettings::default()
    };
    let bar = progress_bar(settings.max_epochs as u64, "training epochs");
    let (network, report) = train(&inputs, &targets, &settings, |epoch, _, validation| {
        bar.set_position(epoch as u64);
        bar.set_message(format!("val RMS {:.2} N", validation.sqrt()));
    })?;
    bar.finish_and_clear();
    let export = export_model(&network);
    let int8_path = super::generate::sibling(&args.out, "int8").with_extension("bin");
    let mut sizes = Vec::new();
    for (quantisation, path) in [
        (Quantisation::F32, &args.out),
        (Quantisation::Int8, &int8_path),
    ] {
        let bytes = encode(&export, quantisation)?;
        // Round trip: the blob decodes in the core and reproduces the host network.
        let decoded = ContactResidual::decode(&bytes)
            .map_err(|e| anyhow::anyhow!("the exported blob does not decode: {e}"))?;
        let worst = inputs
            .iter()
            .step_by((inputs.len() / 2000).max(1))
            .filter_map(|x| {
                decoded
                    .correction(x[0], x[1], x[2])
                    .map(|y| (y - network.evaluate(x)[0]).abs())
            })
            .fold(0.0_f64, f64::max);
        write_blob(path, &bytes)?;
        sizes.push(format!(
            "{quantisation} {} bytes → {} (worst |core − host| {worst:.3e} N)",
            bytes.len(),
            path.display()
        ));
    }
    println!(
        "trained on {} samples from {} runs: {} epochs (best {}), train RMS {:.3} N, validation RMS {:.3} N, {:.2} s",
        inputs.len(),
        data.runs.len(),
        report.epochs,
        report.best_epoch,
        report.train_loss.sqrt(),
        report.validation_loss.sqrt(),
        report.seconds
    );
    for line in sizes {
        println!("  {line}");
    }
    Ok(())
}
