//! The `hcm` command line: one module per subcommand, each with its `Args` and `run`.

mod diagnose;
mod diagnose_motion;
mod diagnose_rigid;
mod evaluate;
mod export;
mod faces;
mod force;
mod forecast;
mod generate;
mod identify;
mod identify_motion;
mod identify_rigid;
mod indicators;
mod laws;
use hcm_host::input::numbers;
mod paths;
mod power;
mod predict;
mod progress;
mod report;
mod reproduce;
mod simulate;
mod tosses;
mod train;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// hcm: hybrid contact modelling — a physics contact law plus a small neural network
/// that learns the law's error from measured data.
///
/// The method (the paper's): many repeated contacts are measured — here simulated with
/// noise (PM1), standing in for a rig — and split into a training set S1 and a
/// validation set S2. A physics law fitted to S1 is PM2. A residual network trained on S1
/// to predict the force PM2 gets wrong, added to PM2, is the HCM (hybrid contact model).
/// Both are judged on S2 by four indicators of each contact (maximum force, impulse,
/// energy loss, duration) and their error |measured − model| / measured (the paper's
/// Eq 20).
///
/// The commands:
///   hcm laws        list the contact laws with their equations and parameters
///   hcm force       evaluate one law at one indentation
///   hcm simulate    simulate a scenario (bodies, materials, contact laws) to a trajectory
///   hcm indicators  the four indicators of every contact in a data file
///   hcm generate    make PM1's noisy runs and split them into S1 and S2
///   hcm identify    fit a physics law (PM2) to data: force samples, or filmed poses alone
///   hcm train       train the residual network on S1 (the force PM2 gets wrong)
///   hcm export      write the trained network as a blob for the core (f32 or int8)
///   hcm evaluate    the paper's table: PM2 (and the HCM) against S2
///   hcm reproduce   all of the above for one of the paper's examples (or, cube-toss, the
///                   real cube tosses), with a report
///   hcm diagnose    name what a physics law misses in data, and extend it
///   hcm predict     replay measured tosses from their window start and score them
///   hcm power       how strong an effect must be before `hcm diagnose` names it: effects
///                   hidden in a scenario's generated data, seed after seed (shardable)
///   hcm identify-motion  `hcm identify --method motion`: from the poses, whatever else
///                   the data hold
///   hcm diagnose-motion  `hcm diagnose --from-poses`: what a tossed body's simulation
///                   misses, from motion alone
///
/// `hcm COMMAND --help` defines each command's terms; the README has the details.
#[derive(Parser)]
#[command(name = "hcm", version, verbatim_doc_comment)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Worker threads for the parallel work (runs, fits, replays); default: one per
    /// core. The outputs are the same bytes on any count.
    #[arg(long, global = true, value_name = "N", env = "HCM_THREADS")]
    #[arg(allow_negative_numbers = true, value_parser = numbers::threads)]
    threads: Option<usize>,
}

/// The subcommands; each one's help is its `Args` struct's doc comment.
#[derive(Subcommand)]
enum Command {
    Laws(laws::Args),
    Force(force::Args),
    Simulate(simulate::Args),
    Indicators(indicators::Args),
    Generate(generate::Args),
    Identify(identify::Args),
    // `hcm identify --method motion`, with identify's help (which says so).
    IdentifyMotion(identify::Args),
    Evaluate(evaluate::Args),
    Train(train::Args),
    Export(export::Args),
    Reproduce(reproduce::Args),
    Diagnose(diagnose::Args),
    Predict(predict::Args),
    Power(power::Args),
    // `hcm diagnose --from-poses`, with diagnose's help (which says so).
    DiagnoseMotion(diagnose::Args),
}

/// Parses the command line, runs the subcommand, and reports errors in plain words.
pub fn main() -> ExitCode {
    let command = <Cli as clap::CommandFactory>::command();
    let matches = command.clone().get_matches();
    let cli = <Cli as clap::FromArgMatches>::from_arg_matches(&matches)
        .unwrap_or_else(|error| error.exit());
    if let Err(error) = paths::check(&command, &matches) {
        eprintln!("error: {error:#}");
        return ExitCode::FAILURE;
    }
    if let Some(threads) = cli.threads {
        // The first use of rayon's pool: nothing has built it yet.
        if let Err(error) = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global()
        {
            eprintln!("error: --threads {threads}: {error}");
            return ExitCode::FAILURE;
        }
    }
    let result = match cli.command {
        Command::Laws(args) => laws::run(args),
        Command::Force(args) => force::run(args),
        Command::Simulate(args) => simulate::run(args),
        Command::Indicators(args) => indicators::run(args),
        Command::Generate(args) => generate::run(args),
        Command::Identify(args) => identify::run(args),
        Command::IdentifyMotion(args) => identify::run(args.fitting_poses()),
        Command::Evaluate(args) => evaluate::run(args),
        Command::Train(args) => train::run(args),
        Command::Export(args) => export::run(args),
        Command::Reproduce(args) => reproduce::run(args),
        Command::Diagnose(args) => diagnose::run(args),
        Command::Predict(args) => predict::run(args),
        Command::Power(args) => power::run(args),
        Command::DiagnoseMotion(args) => diagnose::run(args.fitting_poses()),
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
    model.check_contact(contact).map_err(anyhow::Error::msg)
}

#[cfg(test)]
mod tests {
    use super::Cli;
    use clap::CommandFactory;

    /// Every subcommand clap knows is named in the top-level description, and each has
    /// a one-line summary of its own.
    #[test]
    fn the_description_lists_every_command() {
        let cli = Cli::command();
        let description = cli
            .get_long_about()
            .map(ToString::to_string)
            .unwrap_or_default();
        for command in cli.get_subcommands() {
            let name = command.get_name();
            assert!(
                description.contains(&format!("  hcm {name} ")),
                "`hcm {name}` is missing from the description:\n{description}"
            );
            assert!(command.get_about().is_some(), "`hcm {name}` has no summary");
        }
    }
}
