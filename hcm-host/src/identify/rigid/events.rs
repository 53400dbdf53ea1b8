//! PM2 by the genetic algorithm on a rigid contact's events — the one stage `hcm
//! identify --method ga` and `hcm reproduce peg-in-hole` both run: the target read
//! from the data's first contact events, the box scaled from the force samples where
//! the data have them ([`ContactScales`]; a box the scenario gives is kept), the GA.

use super::{
    identify_rigid, ContactScales, RecordedContact, RigidIdentification, RigidIdentifyError,
    RigidParameters, WrenchTarget,
};
use crate::dataset::Dataset;
use crate::numerics::optimize::genetic::GeneticSettings;
use crate::progress::Progress;
use crate::scenario::Model;

/// What [`identify_events`] found, and what it searched.
pub struct EventFit {
    /// The fit.
    pub found: RigidIdentification,
    /// The events it replayed.
    pub target: WrenchTarget,
    /// The scales read from the force samples, if the data have them.
    pub scales: Option<ContactScales>,
    /// The parameters whose box those scales moved.
    pub scaled: Vec<String>,
}

/// Contact `c` of `start` (its exponent as it should stay) fitted by the GA with
/// `settings` to the first `events` contact events of `data` (all the runs usually make
/// without it), in the scenario's box (`start.scenario.identify.bounds`) scaled from
/// the force samples where it gives none.
pub fn identify_events(
    start: &Model,
    data: &Dataset,
    c: usize,
    events: Option<usize>,
    settings: &GeneticSettings,
    progress: &dyn Progress,
) -> Result<EventFit, RigidIdentifyError> {
    let overrides = &start.scenario.identify.bounds;
    let mut parameters = RigidParameters::new(start, c, overrides)?;
    let (scales, scaled) = match RecordedContact::from_data(start, data, c) {
        Ok(recorded) => {
            let exponent = start.contacts[c].law().get("exponent").unwrap_or(1.5);
            let scales = ContactScales::of(&recorded, exponent);
            let scaled = scales.apply(start, c, &mut parameters);
            (Some(scales), scaled)
        }
        Err(_) => (None, Vec::new()),
    };
    let target = WrenchTarget::from_data(start, data, c, events)?;
    let found = identify_rigid(start, &target, &parameters, settings, progress)?;
    Ok(EventFit {
        found,
        target,
        scales,
        scaled,
    })
}
