//! `hcm laws`: the catalogue of normal laws.

use hcm_host::law_catalogue::LAWS;

/// List the normal contact laws.
#[derive(clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> anyhow::Result<()> {
    for law in LAWS {
        println!("{}  ({})", law.name, law.source);
        println!("    f_n = {}", law.formula);
        for parameter in law.parameters {
            println!(
                "    {:<20} {:<7} {}",
                parameter.name, parameter.unit, parameter.meaning
            );
        }
    }
    Ok(())
}
