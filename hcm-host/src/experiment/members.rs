//! A scenario's members: runs drawn from its variation as a forecast draws them
//! (`Draw::Member`: each contact's `noise` and the fixed bodies' `[variation]`), each
//! from its own random stream, so that member m is the same run whatever the thread
//! count, the member count or the order they run in.

use crate::scenario::{drawn_run, Draw, Model};
use crate::simulate::{simulate, Simulation, SimulationError};
use hcm_core::LawError;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// Member `m` of `model`: its variation drawn from stream `m` of `seed` as a forecast
/// draws it (`Draw::Member`); the contact whose drawn law is refused, with why.
pub fn member_model(model: &Model, seed: u64, m: usize) -> Result<Model, (usize, LawError)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(m as u64);
    drawn_run(model, &mut rng, Draw::Member)
}

/// `members` runs of `model`, member m ([`member_model`]) simulated, in member order. The first error (in member order) is returned: a member the model
/// cannot simulate is a model to mend, not a member to skip.
pub fn simulate_members(
    model: &Model,
    members: usize,
    seed: u64,
) -> Result<Vec<Simulation>, SimulationError> {
    (0..members)
        .into_par_iter()
        .map(|m| {
            let drawn = member_model(model, seed, m)
                .map_err(|(contact, source)| SimulationError::Noise { contact, source })?;
            simulate(&drawn)
        })
        .collect::<Vec<_>>()
        .into_iter()
        .collect()
}
