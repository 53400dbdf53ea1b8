//! `hcm laws`: the catalogue of normal laws.

use hcm_host::law_catalogue::LAWS;

/// List the normal contact laws with their equations and parameters.
///
/// A normal law gives the force f_n (N) that pushes two touching bodies apart, from the
/// indentation δ and its rate δ̇. Equation numbers are those of the paper (see the README).
///
/// Terms:
///   δ     indentation: how far the two undeformed surfaces overlap (m), > 0 in contact
///   δ̇     indentation rate (m/s), > 0 while the bodies approach
///   δ̇0    approach speed at touch-down (m/s), used by some laws' damping
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
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
