//! `hcm train`: the data-driven error model of the HCM, trained on S1, with its
//! quantisation-aware int8 twin; `hcm export` turns the result into weights blobs.

use super::progress::Bars;
use hcm_host::dataset::{inventory_summary, DataUse, Dataset, Evidence};
use hcm_host::identify::Physics;
use hcm_host::progress::Stage;
use hcm_host::train::{explains_nothing, ResidualKind, ResidualSettings};
use std::path::PathBuf;

/// Train the residual network of the HCM on S1 (and its int8 twin).
///
/// Example: `hcm train --scenario scenarios/bouncing_ball.toml --data data.s1.csv --physics pm2.toml --out residual.json`
///
/// Its inputs are δ, δ̇ and δ̇0 of each contact sample, its output the measured force
/// minus PM2's. On a 3D (rigid) scenario it learns the wrench PM2 misses on the moving
/// body at every touching sample, from one of two kinds of input (`--inputs`):
///   contact  each touching point's δ, δ̇, slip speed, spin and rolling rate, one
///            network evaluated at every point, its force and couple added there
///            (the default);
///   state    the body's 13 state components (position, quaternion, velocity, angular
///            velocity; Eq 12), one network for the whole contact.
/// OUT (JSON) holds the network, its int8 twin and its envelope; turn it into a blob for
/// the core with `hcm export`.
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
    /// Rigid (3D) contacts: train on the samples before the contact event of this
    /// number (0-based; e.g. 2 = the first two events only). Default: every touching
    /// sample.
    #[arg(long)]
    events: Option<usize>,
    /// Rigid (3D) contacts: the residual's inputs, each touching point's contact-frame
    /// features (`contact`, the default: it acts wherever the contact feels as in
    /// training, also at another place or speed) or the moving body's state (`state`,
    /// Eq 12: switched off wherever the body is not where and as it was in training).
    #[arg(long, value_enum, default_value_t = Inputs::Contact)]
    inputs: Inputs,
    /// A mechanism (a scenario with joints) on a camera's poses: which joint's torque
    /// residual to learn (its angle and rate → the torque on its child, N·m).
    #[arg(long, default_value_t = 0)]
    joint: usize,
    /// Trained residual file to write (JSON), e.g. `residual.json`.
    #[arg(long)]
    out: PathBuf,
}

/// What the contact-frame network's training leaves to say: the outputs no sample
/// felt, and a warning when it explains nothing.
fn warn_contact(trained: &hcm_host::train::Trained) {
    let outputs = ["k_n", "r_f", "c_t", "c_n", "c_r"];
    if !trained.silenced.is_empty() {
        let silenced: Vec<&str> = (trained.silenced.iter())
            .filter_map(|&k| outputs.get(k).copied())
            .collect();
        println!(
            "fixed at 0 (the fit does not need them: each carries under 1 % of its gain): {}",
            silenced.join(", ")
        );
    }
    if explains_nothing(trained) {
        eprintln!(
            "warning: the network explains under 10 % of PM2's error in every component and \
             is no better than a zero output. PM2 may already fit the data (see `hcm \
             identify`'s residual RMS), or the error depends on what the contact's own state \
             does not show — try `--inputs state` or more runs"
        );
    }
}

/// What a rigid contact's residual reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum Inputs {
    /// The moving body's 13 state components (Eq 12).
    State,
    /// Each touching point's δ, δ̇, slip speed, spin and rolling rate.
    Contact,
}

/// The training settings the options give, and the bars that show it.
fn settings_and_bars(args: &Args) -> (ResidualSettings, Bars) {
    let settings = ResidualSettings {
        epochs: args.epochs,
        int8_epochs: args.int8_epochs,
        seed: args.seed,
    };
    let bars = Bars::with_status(|stage| match stage {
        Stage::Int8Twin => "int8 fine-tuning",
        _ => "training epochs",
    });
    (settings, bars)
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = args.scenario.load()?;
    let pm2 = Physics::read(&args.physics)?
        .apply(&scenario, &args.physics)?
        .model()?;
    super::check_contact(args.contact, &pm2)?;
    let data = Dataset::read(&args.data)?;
    let evidence = Evidence::of(&pm2, &data, args.contact);
    if evidence != Evidence::LineForce {
        println!("{}", inventory_summary(&data, &pm2, args.contact));
    }
    let file = args.data.display().to_string();
    data.require_for(&file, &pm2, args.contact, evidence, DataUse::Train)?;
    let kind = ResidualKind::of(
        evidence,
        args.inputs == Inputs::State,
        !pm2.joints.is_empty(),
    );
    if kind == ResidualKind::Joint {
        return run_joint(&args, &pm2, &data);
    }
    if kind != ResidualKind::Force {
        return run_rigid(&args, kind, &pm2, &data);
    }
    let (settings, bars) = settings_and_bars(&args);
    let trained = kind.train((&pm2, &data, args.contact), usize::MAX, &settings, &bars)?;
    let (report, tuned) = (&trained.report, &trained.int8);
    println!(
        "trained on {} samples from {} runs: {} epochs (best {}), train RMS {:.3} N, validation RMS {:.3} N, {:.2} s",
        trained.rows,
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
    written(&trained, &args.out)
}

/// The mechanism's path: joint `--joint`'s torque residual from the recorded poses, the
/// share of the missed joint angle it explains, and a warning when it explains nothing.
fn run_joint(args: &Args, pm2: &hcm_host::scenario::Model, data: &Dataset) -> anyhow::Result<()> {
    let Some(joint) = pm2.joints.get(args.joint) else {
        anyhow::bail!(
            "--joint {}: scenario `{}` has {} joint(s), numbered from 0",
            args.joint,
            pm2.scenario.name,
            pm2.joints.len()
        );
    };
    let (settings, bars) = settings_and_bars(args);
    let kind = ResidualKind::Joint;
    let trained = kind.train((pm2, data, args.joint), usize::MAX, &settings, &bars)?;
    let report = &trained.report;
    println!(
        "trained {} of joint `{}` on {} frames in flight of {} runs: {} epochs (best {}), \
         train RMS {:.3e} rad, validation RMS {:.3e} rad, {:.2} s",
        kind.describe(),
        joint.name,
        trained.rows,
        data.runs.len(),
        report.epochs,
        report.best_epoch,
        report.train_loss.sqrt(),
        report.validation_loss.sqrt(),
        report.seconds
    );
    let explained = trained.explained.first().copied().unwrap_or(0.0);
    println!("share of the missed joint angle explained (R², training rows): {explained:.2}");
    if !trained.silenced.is_empty() {
        eprintln!(
            "warning: the network is no better than a zero torque and is fixed at 0 (the \
             HCM is PM2): the recorded joint angles show no torque the joint's law misses \
             that its angle and rate would tell, or too few frames in flight"
        );
    }
    written(&trained, &args.out)
}

/// The rigid path: the wrench residual of Eq 12 on every touching sample (or those
/// before `--events`), its outputs' R², and a warning when it explains nothing.
fn run_rigid(
    args: &Args,
    kind: ResidualKind,
    pm2: &hcm_host::scenario::Model,
    data: &Dataset,
) -> anyhow::Result<()> {
    let (settings, bars) = settings_and_bars(args);
    let events = args.events.unwrap_or(usize::MAX);
    let trained = kind.train((pm2, data, args.contact), events, &settings, &bars)?;
    let what = kind.describe();
    let report = &trained.report;
    println!(
        "trained {what} on {} touching samples of {} runs: {} epochs (best {}), train MSE \
         {:.3e}, validation MSE {:.3e}, {:.2} s",
        trained.rows,
        data.runs.len(),
        report.epochs,
        report.best_epoch,
        report.train_loss,
        report.validation_loss,
        report.seconds
    );
    let names = ["fx", "fy", "fz", "tx", "ty", "tz"];
    let explained: Vec<String> = (names.iter().zip(&trained.explained))
        .map(|(n, r2)| format!("{n} {r2:.2}"))
        .collect();
    println!(
        "share of PM2's error explained (R², training rows): {}",
        explained.join(", ")
    );
    if args.inputs == Inputs::Contact {
        warn_contact(&trained);
    } else if trained.silenced.len() == names.len() {
        eprintln!(
            "warning: the network explains under 10 % of PM2's error in every output and is \
             no better than a zero output: every output is fixed at 0 (the HCM is PM2). \
             PM2 may already fit the data (see `hcm identify`'s residual RMS), or the error \
             depends on what the 13 state inputs do not show — try `--inputs contact` or \
             more runs"
        );
    } else if !trained.silenced.is_empty() {
        let silenced: Vec<&str> = trained.silenced.iter().map(|&k| names[k]).collect();
        println!(
            "fixed at 0 (R² under 0.1: noise to the network): {}",
            silenced.join(", ")
        );
    }
    written(&trained, &args.out)
}

/// Writes the trained file and says how to export it.
fn written(trained: &hcm_host::train::Trained, out: &std::path::Path) -> anyhow::Result<()> {
    trained.residual.write(out)?;
    println!(
        "→ {} (export with `hcm export --residual {0} --out residual.bin`)",
        out.display()
    );
    Ok(())
}
