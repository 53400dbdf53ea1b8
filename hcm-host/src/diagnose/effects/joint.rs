//! What a mechanism's joints may lack: their own friction (viscous, Coulomb), a
//! stiffness, or their point on the link elsewhere than the model has it. Each acts on
//! every joint of the scene with one value (one hinge: the hinge); their boxes come
//! from the (first) joint's [`crate::scenario::JointScales`], in [`Scales::joint`].

use super::{first, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::{JointTerm, Model};

/// A term of the joints' law (`hcm_core::joint`): c ∈ [0, 4·I·ω̂] N·m·s/rad, τ_c ∈
/// [0, 2·τ̂] N·m, k ∈ [0, 4·τ̂] N·m/rad ([`JointTerm::upper`]); a spring about its rest
/// angle (0, the aligned frames, where the joint has none).
#[derive(Debug)]
pub struct JointLawTerm {
    term: JointTerm,
}

/// Viscous friction in the joints, −c·θ̇.
pub static VISCOUS: JointLawTerm = JointLawTerm {
    term: JointTerm::Viscous,
};
/// Coulomb friction in the joints, STEP-smoothed.
pub static COULOMB: JointLawTerm = JointLawTerm {
    term: JointTerm::Coulomb,
};
/// A torsional stiffness in the joints, −k·(θ − θ₀).
pub static STIFFNESS: JointLawTerm = JointLawTerm {
    term: JointTerm::Stiffness,
};

/// The box's upper end of the joints' scales, or 0 where there are none.
fn upper(term: JointTerm, s: &Scales) -> f64 {
    (s.joint.map(|j| term.upper(&j)))
        .filter(|u| u.is_finite())
        .unwrap_or(0.0)
}

impl Effect for JointLawTerm {
    fn name(&self) -> &'static str {
        match self.term {
            JointTerm::Viscous => "joint_viscous_friction",
            JointTerm::Coulomb => "joint_coulomb_friction",
            JointTerm::Stiffness => "joint_stiffness",
        }
    }
    fn family(&self) -> Family {
        Family::Joint
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::Poses
    }
    fn applies(&self, model: &Model, _site: Site) -> bool {
        !model.joints.is_empty()
    }
    /// The fit from motion frees a term every joint declares.
    fn within_base_fit(&self, model: &Model, _site: Site) -> bool {
        !model.joints.is_empty() && (model.joints.iter()).all(|j| self.term.get(&j.law).is_some())
    }
    fn bounds(&self, _evidence: Evidence, s: &Scales) -> Vec<Bound> {
        let [_, coefficient] = self.term.key();
        vec![Bound::linear(coefficient, 0.0, upper(self.term, s))]
    }
    /// The first joint's coefficient (0 where it has no such term).
    fn neutral(&self, model: &Model, _site: Site) -> Vec<f64> {
        let first = model.joints.first().and_then(|j| self.term.get(&j.law));
        vec![first.unwrap_or(0.0)]
    }
    fn per_contact(&self) -> bool {
        false
    }
    fn apply(&self, model: &mut Model, _site: Site, values: &[f64]) {
        for j in 0..model.joints.len() {
            let scales = model.joints[j].scales(model);
            self.term
                .set(&mut model.joints[j].law, first(values), &scales);
        }
    }
}

/// The joint's point on its child moved by d (m) along the child's lever — from its
/// centre of mass towards the joint, off the axis — d ∈ [−L/5, L/5], L the body's
/// largest half extent: the hinge elsewhere on the link than the model has it.
#[derive(Debug)]
pub struct JointOffset;

impl Effect for JointOffset {
    fn name(&self) -> &'static str {
        "joint_offset"
    }
    fn family(&self) -> Family {
        Family::Joint
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::Poses
    }
    fn applies(&self, model: &Model, _site: Site) -> bool {
        !model.joints.is_empty()
    }
    fn bounds(&self, _evidence: Evidence, s: &Scales) -> Vec<Bound> {
        vec![Bound::linear("offset", -0.2 * s.arm, 0.2 * s.arm)]
    }
    fn per_contact(&self) -> bool {
        false
    }
    fn apply(&self, model: &mut Model, _site: Site, values: &[f64]) {
        let d = first(values);
        for joint in &mut model.joints {
            let a = joint.axis.into_inner();
            let r = joint.anchors[1];
            let lever = r - a * r.dot(&a);
            let direction = match lever.try_normalize(1e-12) {
                Some(unit) => unit,
                None => joint.normals[0],
            };
            joint.anchors[1] += direction * d;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{apply_at, CATALOGUE};
    use super::*;
    use crate::scenario::{Scenario, Shape};
    use std::path::Path;

    const ELBOW: &str = include_str!("../../../scenarios/elbow_toss.toml");

    fn elbow() -> Model {
        let scenario = Scenario::parse(Path::new("elbow_toss.toml"), ELBOW, &[]).unwrap();
        scenario.model().unwrap()
    }

    fn effect(name: &str) -> &'static dyn Effect {
        *CATALOGUE.iter().find(|e| e.name() == name).unwrap()
    }

    /// On the elbow a contact's effect changes both links' contacts (alike), the
    /// table's move is made once, and a joint's term goes on the hinge.
    #[test]
    fn a_mechanism_s_effects_land_where_they_act() {
        let model = elbow();
        let site = Site::of(&model, 0);
        let mut scaled = model.clone();
        apply_at(effect("friction_coefficient"), &mut scaled, site, &[2.0]);
        for c in 0..2 {
            let (before, after) = (
                model.contacts[c].model.friction,
                scaled.contacts[c].model.friction,
            );
            let ratio = after.unwrap().static_coefficient / before.unwrap().static_coefficient;
            assert!((ratio - 2.0).abs() < 1e-12, "contact {c}: {ratio}");
        }
        let mut moved = model.clone();
        apply_at(effect("table_offset"), &mut moved, site, &[1e-3]);
        match moved.bodies[2].shape {
            Shape::Plane { offset, .. } => assert!((offset - 1e-3).abs() < 1e-15, "{offset}"),
            _ => panic!("the table is a plane"),
        }
        let mut damped = model.clone();
        let bounds = VISCOUS.bounds(
            Evidence::Poses,
            &Scales {
                joint: Some(model.joints[0].scales(&model)),
                ..Scales::of_body(0.37, 0.05)
            },
        );
        assert!(bounds[0].upper > 0.0 && bounds[0].upper.is_finite());
        apply_at(&VISCOUS, &mut damped, site, &[0.01]);
        assert_eq!(damped.joints[0].law.viscous.map(|v| v.damping), Some(0.01));
        assert!(VISCOUS.within_base_fit(&damped, site) && !VISCOUS.within_base_fit(&model, site));
        let mut offset = model.clone();
        apply_at(&JointOffset, &mut offset, site, &[0.005]);
        let lever = offset.joints[0].anchors[1] - model.joints[0].anchors[1];
        assert!(
            (lever.norm() - 0.005).abs() < 1e-15 && lever.y == 0.0,
            "{lever}"
        );
    }

    /// The elbow's hinge scales: the link's inertia about the hinge, 3.8542e-4 +
    /// 0.37·0.035² kg·m², its weight's torque 0.37·9.81·0.035 N·m.
    #[test]
    fn the_hinge_s_scales_are_the_link_s() {
        let model = elbow();
        let s = model.joints[0].scales(&model);
        assert!(
            (s.inertia - (3.8542e-4 + 0.37 * 0.035 * 0.035)).abs() < 1e-12,
            "{s:?}"
        );
        assert!((s.torque - 0.37 * 9.81 * 0.035).abs() < 1e-12, "{s:?}");
        assert!((s.rate - (s.torque / s.inertia).sqrt()).abs() < 1e-12);
    }
}
