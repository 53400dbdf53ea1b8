//! Where a rigid identification starts: the scenario's model with the contact's law
//! replaced by the one asked for (PM2 may be another law than the data's: the HCM's
//! point) and its exponent fixed where asked.

use super::RigidIdentifyError;
use crate::identify::bounds::Bounds;
use crate::law_catalogue;
use crate::scenario::Model;

/// `model` with contact `c`'s normal law replaced by `law` when it names another one —
/// the parameters it shares with the scenario's law kept, the others at the middle of
/// their default search box — and its exponent set to `exponent` if given.
pub fn with_law(
    model: &Model,
    c: usize,
    law: &str,
    exponent: Option<f64>,
) -> Result<Model, RigidIdentifyError> {
    let mut start = model.clone();
    let base = &mut (start.contacts.get_mut(c))
        .ok_or(RigidIdentifyError::NoSuchContact(c))?
        .model
        .normal
        .base;
    let setup = |e: &dyn std::fmt::Display| RigidIdentifyError::Setup(format!("--law {law}: {e}"));
    if law != base.name() {
        let entry = law_catalogue::entry(law).map_err(|e| setup(&e))?;
        let middle = Bounds::for_law(law, None).map_err(|e| setup(&e))?.middle();
        let values: Vec<(String, f64)> = (entry.parameters.iter())
            .map(|p| {
                let kept = base
                    .get(p.name)
                    .ok()
                    .or_else(|| middle.iter().find(|(n, _)| n == p.name).map(|(_, v)| *v));
                (p.name.to_owned(), kept.unwrap_or(1.5))
            })
            .collect();
        *base = law_catalogue::build(law, &values).map_err(|e| setup(&e))?;
    }
    if let Some(exponent) = exponent {
        base.set("exponent", exponent)
            .map_err(|e| RigidIdentifyError::Setup(format!("--exponent {exponent}: {e}")))?;
    }
    Ok(start)
}
