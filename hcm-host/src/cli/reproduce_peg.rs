//! `hcm reproduce peg-in-hole`: the library's peg pipeline
//! ([`hcm_host::pipeline::peg`]) with progress bars, its data, report, `results.json`
//! and figures written to the output directory as one unit.

use super::reproduce::{write_figures, Bars};
use hcm_host::output::{write_bytes, StagedDirectory};
use hcm_host::pipeline::peg::{reproduce_peg, PegSettings};
use hcm_host::pipeline::StageTiming;
use std::path::PathBuf;
use std::time::Instant;

/// The options `hcm reproduce` passes on for the peg-in-hole.
pub struct PegArgs {
    pub out: PathBuf,
    pub seed: u64,
    pub runs: Option<usize>,
    pub scenario: Option<PathBuf>,
    pub overrides: Vec<String>,
    pub generations: Option<usize>,
    pub population: Option<usize>,
}

pub fn run(args: PegArgs) -> anyhow::Result<()> {
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
    let out = staged.path();
    let mut reproduction = reproduce_peg(&settings, &Bars::default())?;
    let clock = Instant::now();
    reproduction.sets.training.write(&out.join("s1.csv"))?;
    reproduction.sets.validation.write(&out.join("s2.csv"))?;
    let comment = format!("PM2 of `{}` from hcm reproduce", reproduction.scenario.name);
    let fit = hcm_host::identify::FitRecord {
        method: "ga (contact events)".into(),
        data: "s1.csv".into(),
        seconds: reproduction.pm2.seconds,
        ..Default::default()
    };
    let pm2 = &reproduction.pm2.model;
    hcm_host::identify::Physics::for_contact(pm2, 0, pm2.contacts[0].law(), fit)
        .write(&out.join("pm2.toml"), &comment)?;
    reproduction
        .trained
        .residual
        .write(&out.join("residual.json"))?;
    write_bytes(&out.join("residual.bin"), &reproduction.blobs.f32.bytes)?;
    write_bytes(
        &out.join("residual.int8.bin"),
        &reproduction.blobs.int8.bytes,
    )?;
    write_figures(&reproduction.evaluation.figures, out)?;
    reproduction.timings.push(StageTiming {
        stage: "write files".into(),
        seconds: clock.elapsed().as_secs_f64(),
    });
    let json = reproduction.json(settings.seed, settings.runs)?;
    write_bytes(&out.join("results.json"), json.as_bytes())?;
    let report = reproduction.markdown();
    write_bytes(&out.join("report.md"), report.as_bytes())?;
    staged.commit()?;
    print!("{report}");
    Ok(())
}
