//! `hcm reproduce cube-toss`: the library's cube pipeline
//! ([`hcm_host::pipeline::cube`]) with progress bars, its physics file, data, report,
//! `results.json` and figures written to the output directory as one unit.

use super::progress::Bars;
use super::reproduce::{finish, Args};
use hcm_host::output::StagedDirectory;
use hcm_host::pipeline::cube::{reproduce_cube, CubeSettings};

pub fn run(args: Args) -> anyhow::Result<()> {
    let data = args.data.ok_or_else(|| {
        anyhow::anyhow!(
            "`hcm reproduce cube-toss` needs --data: the filmed tosses, e.g. \
             data/contactnets-cube/tosses.csv of the source"
        )
    })?;
    if let Some(first) = args.first {
        anyhow::ensure!(
            first >= 6,
            "--first {first}: give at least 6 runs (3 per part)"
        );
    }
    let shipped = CubeSettings::shipped(&data);
    let settings = CubeSettings {
        first: args.first,
        scenario: args.scenario,
        overrides: args.overrides,
        seed: args.seed,
        population: args.population.unwrap_or(shipped.population),
        generations: args.generations.unwrap_or(shipped.generations),
        polish: args.polish.unwrap_or(shipped.polish),
        diagnose: !args.no_diagnosis,
        ..shipped
    };
    let staged = StagedDirectory::create(&args.out, "results.json")?;
    finish(staged, reproduce_cube(&settings, &Bars::default())?)
}
