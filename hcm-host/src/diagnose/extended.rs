//! The extended model a 1D diagnosis ends with, as the physics file every command reads
//! (`hcm diagnose`'s extended.toml).

use super::Diagnosis;
use crate::identify::{FitRecord, Physics, PhysicsBody};
use crate::scenario::Model;

/// The extended model in the physics-file format every command reads: the re-fitted
/// law with its effects on contact `contact`, the named chance as its scatter, and the
/// air drag if one was fitted; `data` names the data file in its fit record.
pub fn extended_physics(
    base: &Model,
    contact: usize,
    data: &str,
    diagnosis: &Diagnosis,
) -> Physics {
    let mut extended = Physics::for_contact(
        base,
        contact,
        &diagnosis.extended.base,
        FitRecord {
            method: "diagnose".into(),
            data: data.to_owned(),
            runs: diagnosis.runs.training,
            ..FitRecord::default()
        },
    );
    extended.contacts[0].effects = diagnosis.extended.effects.iter().copied().collect();
    if let Some(chance) = &diagnosis.chance {
        extended.contacts[0].noise = chance.noise().into_iter().collect();
    }
    if let Some(air_drag) = diagnosis.drag.as_ref().and_then(|d| d.air_drag()) {
        extended.bodies.push(PhysicsBody {
            name: diagnosis.drag_body.clone(),
            air_drag,
        });
    }
    extended
}
