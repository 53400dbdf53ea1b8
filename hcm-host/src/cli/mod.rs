//! The `hcm` command line: one module per subcommand, each with its `Args` and `run`.

mod diagnose;
mod evaluate;
mod export;
mod force;
mod generate;
mod identify;
mod indicators;
mod laws;
mod numbers;
mod report;
mod reproduce;
mod simulate;
mod train;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Hybrid contact modeling: contact laws, simulation, identification and diagnosis.
#[derive(Parser)]
#[command(name = "hcm", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List the normal contact laws with their equations and parameters.
    Laws(laws::Args),
    /// Evaluate one normal law at one contact state.
    Force(force::Args),
    /// Simulate a scenario and write its trajectory (measured-data CSV).
    Simulate(simulate::Args),
    /// Contact indicators (max force, impulse, energy loss, duration) from a data file.
    Indicators(indicators::Args),
    /// Generate a noise-added experiment (PM1) and split it into S1 and S2.
    Generate(generate::Args),
    /// Identify a physics model (PM2) from data: least squares or genetic algorithm.
    Identify(identify::Args),
    /// The paper's table for a physics model on validation data (S2).
    Evaluate(evaluate::Args),
    /// Train the residual network of the HCM on S1 (and its int8 twin).
    Train(train::Args),
    /// Export a trained residual network as the core's weights blob (f32 or int8).
    Export(export::Args),
    /// Reproduce one of the paper's examples end to end, with report and figures.
    Reproduce(reproduce::Args),
    /// Diagnose a physics model against measured data: what is wrong, the cause named,
    /// the extended model and its gain.
    Diagnose(diagnose::Args),
}

/// Parses the command line, runs the subcommand, and reports errors in plain words.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Laws(args) => laws::run(args),
        Command::Force(args) => force::run(args),
        Command::Simulate(args) => simulate::run(args),
        Command::Indicators(args) => indicators::run(args),
        Command::Generate(args) => generate::run(args),
        Command::Identify(args) => identify::run(args),
        Command::Evaluate(args) => evaluate::run(args),
        Command::Train(args) => train::run(args),
        Command::Export(args) => export::run(args),
        Command::Reproduce(args) => reproduce::run(args),
        Command::Diagnose(args) => diagnose::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}

/// Parses `key=value` with a floating-point value (for `--set`).
pub fn parse_assignment(text: &str) -> Result<(String, f64), String> {
    let (key, value) = text
        .split_once('=')
        .ok_or_else(|| format!("`{text}` is not key=value (e.g. stiffness=6.86e9)"))?;
    let value: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("`{value}` in `{text}` is not a number"))?;
    Ok((key.trim().to_owned(), value))
}

/// A progress bar on standard error for `total` steps of long work; hidden when
/// standard error is not a terminal (CI logs, pipes).
pub fn progress_bar(total: u64, message: &'static str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(total);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg:>16} [{bar:40}] {pos}/{len} ({eta})")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.set_message(message);
    bar
}

/// The scenario options every subcommand that reads a scenario shares.
#[derive(clap::Args)]
pub struct ScenarioArgs {
    /// Scenario file (TOML); see the README's "Scenario files".
    #[arg(long)]
    pub scenario: std::path::PathBuf,
    /// Override a scenario value, e.g. `--set body.ball.velocity=[0,0,-1]`,
    /// `--set contact.0.parameters.damping=500`. Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
}

impl ScenarioArgs {
    /// Reads the scenario with the overrides applied.
    pub fn load(&self) -> Result<hcm_host::scenario::Scenario, hcm_host::scenario::ScenarioError> {
        hcm_host::scenario::Scenario::load(&self.scenario, &self.overrides)
    }
}

/// Checks that `contact` indexes one of `model`'s contacts.
pub fn check_contact(contact: usize, model: &hcm_host::scenario::Model) -> anyhow::Result<usize> {
    anyhow::ensure!(
        contact < model.contacts.len(),
        "--contact {contact}: the scenario has {} contact(s), numbered from 0",
        model.contacts.len()
    );
    Ok(contact)
}
