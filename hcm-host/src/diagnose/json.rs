//! A 1D diagnosis as JSON: diagnosis.json.

use super::{answer, Diagnosis};
use serde_json::json;

/// The contents of `hcm diagnose`'s diagnosis.json for a 1D diagnosis (documented in
/// docs/diagnosis.md): the causes with their intervals and shares, the answer, the
/// gains and every step's record.
pub fn diagnosis_json(d: &Diagnosis) -> serde_json::Value {
    let causes: Vec<_> = d
        .causes
        .iter()
        .map(|c| {
            json!({
                "effect": c.effect,
                "kind": c.family.kind(),
                "parameters": c.parameters.iter().map(|p| (p.name.clone(), json!(p.value))).collect::<serde_json::Map<_, _>>(),
                "ci": c.parameters.iter().map(|p| (p.name.clone(), json!([p.ci.0, p.ci.1]))).collect::<serde_json::Map<_, _>>(),
                "share": c.share,
            })
        })
        .collect();
    json!({
        "causes": causes,
        "unexplained_share": d.unexplained_share,
        "partial": d.partial,
        "answer": answer(d),
        "noise_sigma": d.noise.sigma,
        "base_structured": d.base_structured,
        "runs": d.runs,
        "base_parameters": d.base_parameters,
        "base_freedom": d.base_freedom,
        "selection": d.selection,
        "naming": d.naming,
        "data_quality": d.data_quality,
        "not_accepted": d.not_accepted,
        "ambiguous": d.ambiguous,
        "chance": d.chance,
        "sensor_gain": d.sensor_gain,
        "before": d.before,
        "after": d.after,
        "gain": d.gain,
        "in_sample": d.in_sample,
        "air_drag_fit": d.drag,
    })
}
