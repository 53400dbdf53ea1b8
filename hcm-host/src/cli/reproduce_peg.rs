//! `hcm reproduce peg-in-hole`: the library's peg pipeline
//! ([`hcm_host::pipeline::peg`]) with progress bars, its data, report, `results.json`
//! and figures written to the output directory as one unit.

use super::progress::Bars;
use super::reproduce::{finish, Args};
use hcm_host::output::StagedDirectory;
use hcm_host::pipeline::peg::{reproduce_peg, PegSettings};

pub fn run(args: Args) -> anyhow::Result<()> {
    let shipped = PegSettings::shipped();
    let mut genetic = shipped.genetic.clone();
    genetic.generations = args.generations.unwrap_or(genetic.generations);
    genetic.population = args.population.unwrap_or(genetic.population);
    let settings = PegSettings {
        scenario: args.scenario,
        overrides: args.overrides,
        seed: args.seed,
        runs: args.runs.unwrap_or(shipped.runs),
        genetic,
        ..shipped
    };
    let staged = StagedDirectory::create(&args.out, "results.json")?;
    finish(staged, reproduce_peg(&settings, &Bars::default())?)
}
