//! `hcm force`: one law at one contact state, in f64 and in the controller's f32.

use hcm_core::effect::ContactMemory;
use hcm_core::law::Indentation;
use hcm_core::model::ContactModel;
use hcm_host::law_catalogue;

/// Evaluate one normal law at one contact state.
///
/// Example: `hcm force --law hertz --set stiffness=3.6e9 --set exponent=1.5 --depth 1e-5`
///
/// Prints the normal force f_n (N, > 0 pushing apart) in f64 and in the f32 a controller
/// computes. `hcm laws` lists the laws and their parameters.
///
/// Terms:
///   δ     indentation: how far the two undeformed surfaces overlap (m), > 0 in contact
///   δ̇     indentation rate (m/s), > 0 while the bodies approach
///   δ̇0    approach speed at touch-down (m/s), used by some laws' damping
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    /// Law name (see `hcm laws`).
    #[arg(long)]
    law: String,
    /// A law parameter, `name=value` in SI units; repeat for each parameter.
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = super::parse_assignment)]
    parameters: Vec<(String, f64)>,
    /// Indentation δ (m), > 0 in contact.
    #[arg(long, allow_negative_numbers = true)]
    #[arg(value_parser = super::numbers::number)]
    depth: f64,
    /// Indentation rate δ̇ (m/s), > 0 while approaching.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    #[arg(value_parser = super::numbers::number)]
    rate: f64,
    /// Approach speed δ̇0 (m/s) of this impact (Lankarani–Nikravesh, Flores).
    #[arg(long, default_value_t = 1.0)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::number)]
    approach_speed: f64,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let law = law_catalogue::build(&args.law, &args.parameters)?;
    let state = Indentation {
        depth: args.depth,
        rate: args.rate,
        approach_speed: args.approach_speed,
    };
    // Through the contact model, as a controller evaluates it (one fresh contact).
    let model = ContactModel::physics(law);
    let force = model.physics_normal_force(&state, &ContactMemory::touch_down());
    let state_32 = Indentation {
        depth: state.depth as f32,
        rate: state.rate as f32,
        approach_speed: state.approach_speed as f32,
    };
    let force_32 = model
        .cast::<f32>()
        .physics_normal_force(&state_32, &ContactMemory::touch_down());
    println!(
        "{}: f_n = {force:.6e} N (f64), {force_32:.6e} N (f32)",
        law.name()
    );
    Ok(())
}
