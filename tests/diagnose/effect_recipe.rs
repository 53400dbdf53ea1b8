//! docs/architecture.md's recipe "Adding an effect", followed in this one file: an
//! effect the built-in catalogue lacks — the normal law's exponent shifted —
//! written against the public `Effect` trait and added with one line
//! (`Catalogue::default().with(&EXPONENT_SHIFT)`). The force diagnosis names it on
//! data whose exponent differs from the model's, and names nothing where it does not.
//! (A stiffness scale would not do: at given poses it is one model with the built-in
//! `force_gain`, and the diagnosis says so.)

use hcm_host::dataset::Evidence;
use hcm_host::diagnose::{
    diagnose_rigid, Catalogue, Effect, Family, RigidDiagnoseSettings, RigidDiagnosis, Scales, Site,
};
use hcm_host::experiment::generate;
use hcm_host::numerics::optimize::Bound;
use hcm_host::progress::Silent;
use hcm_host::scenario::{Model, Scenario};
use rayon::prelude::*;

/// The law's elastic exponent n → n + Δ (–), Δ ∈ [−0.3, 0.3]; judged from a wrench.
#[derive(Debug)]
struct ExponentShift;

static EXPONENT_SHIFT: ExponentShift = ExponentShift;

impl Effect for ExponentShift {
    fn name(&self) -> &'static str {
        "exponent_shift"
    }
    fn family(&self) -> Family {
        Family::Normal
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::Wrench
    }
    fn bounds(&self, _evidence: Evidence, _scales: &Scales) -> Vec<Bound> {
        vec![Bound::linear("change", -0.3, 0.3)]
    }
    fn neutral(&self, _model: &Model, _site: Site) -> Vec<f64> {
        vec![0.0]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        let law = &mut model.contacts[site.contact].model.normal.base;
        if let (Ok(n), Some(change)) = (law.get("exponent"), values.first()) {
            let _ = law.set("exponent", n + change);
        }
    }
}

/// The ball-on-plate scene with the contact law's exponent `exponent` (–).
fn ball(exponent: f64) -> Scenario {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/common/scenes/ball_on_plate.toml");
    let set = format!("contact.0.parameters.exponent={exponent}");
    Scenario::load(&path, &[set]).expect("the scene reads")
}

/// The scene's own model (exponent 1.5) diagnosed, as given, on 12 runs generated with
/// `exponent`, the test's effect in the catalogue.
fn diagnosed(exponent: f64) -> RigidDiagnosis {
    let data = generate(&ball(exponent), 12, 5, &Silent).unwrap();
    let model = ball(1.5).model().unwrap();
    let settings = RigidDiagnoseSettings {
        contact: 0,
        fitted_base: false,
        overrides: Default::default(),
        catalogue: Catalogue::default().with(&EXPONENT_SHIFT),
    };
    diagnose_rigid(&model, &data, &settings, &Silent).unwrap()
}

#[test]
fn an_effect_written_in_a_test_file_is_named_where_it_is_hidden_and_only_there() {
    let runs: Vec<RigidDiagnosis> = [1.53, 1.5].par_iter().map(|&k| diagnosed(k)).collect();
    println!(
        "exponent 1.53: {}\nas modelled: {}",
        runs[0].answer, runs[1].answer
    );
    assert_eq!(runs[0].named, ["exponent_shift"], "{}", runs[0].answer);
    let first = &runs[0].rounds[0];
    let scored = first.candidates.iter().find(|c| c.name == "exponent_shift");
    assert!(scored.is_some_and(|c| c.helps), "{:?}", first.candidates);
    // Its parameter, fitted with the extended model on every run: the hidden 0.03.
    let change = (runs[0].fit.parameters.iter())
        .find(|(name, _)| name == "exponent_shift.change")
        .map(|(_, v)| *v);
    assert!(
        change.is_some_and(|v| (v - 0.03).abs() < 0.01),
        "{change:?}"
    );
    assert!(runs[1].named.is_empty(), "{}", runs[1].answer);
    assert!(
        !runs[1].ambiguous.contains(&"exponent_shift"),
        "{}",
        runs[1].answer
    );
}
