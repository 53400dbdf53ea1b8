//! Which parameters of a law are identified, and the box they are searched in.

use super::IdentifyError;
use crate::law_catalogue;
use crate::numerics::optimize::{Bound, Parameters};
use hcm_core::law::{AnyNormalLaw, LawKind};
use std::collections::BTreeMap;
use std::f64::consts::TAU;

/// The free parameters of one law with their search intervals.
#[derive(Clone, Debug, PartialEq)]
pub struct Bounds {
    /// One bound per free parameter, in catalogue order; every name is a parameter of
    /// the law.
    pub(crate) parameters: Vec<Bound>,
    /// The law they are parameters of.
    kind: LawKind,
}

/// The scenario's `[identify.bounds.<law>]` tables: parameter name → [lower, upper].
pub type BoundsOverrides = BTreeMap<String, BTreeMap<String, [f64; 2]>>;

/// Default search box of a law's free parameters: (name, lower, upper, log scale).
/// Geometric and mass parameters (radius, effective modulus, effective mass) are not
/// free: they come from the scenario.
fn defaults(law: &str) -> &'static [(&'static str, f64, f64, bool)] {
    const STIFFNESS: (&str, f64, f64, bool) = ("stiffness", 1e8, 1e11, true);
    const EXPONENT: (&str, f64, f64, bool) = ("exponent", 1.0, 2.5, false);
    match law {
        "hertz" => &[STIFFNESS, EXPONENT],
        "lankarani_nikravesh" => &[STIFFNESS, EXPONENT, ("restitution", 0.5, 1.0, false)],
        "flores" => &[STIFFNESS, EXPONENT, ("restitution", 0.3, 1.0, false)],
        "hunt_crossley" => &[STIFFNESS, EXPONENT, ("damping", 0.0, 5.0, false)],
        "variable_stiffness" => &[
            ("surface_loading", 4.0 / 3.0, TAU, false),
            ("damping", 0.0, 1e4, false),
        ],
        "impact" => &[
            STIFFNESS,
            EXPONENT,
            ("max_damping", 0.0, 1e4, false),
            ("full_damping_depth", 1e-7, 1e-3, true),
        ],
        _ => &[],
    }
}

impl Bounds {
    /// The box for `law`, with the scenario's `[identify.bounds.<law>]` entries
    /// (`name = [lower, upper]`) replacing the defaults.
    pub fn for_law(
        law: &str,
        overrides: Option<&BTreeMap<String, [f64; 2]>>,
    ) -> Result<Bounds, String> {
        let kind = law_catalogue::kind(law).map_err(|e| e.to_string())?;
        let mut parameters: Vec<Bound> = defaults(law).iter().map(Bound::of_row).collect();
        let free = parameters
            .iter()
            .map(|p| p.name.clone())
            .collect::<Vec<_>>();
        for (name, [lower, upper]) in overrides.into_iter().flatten() {
            let Some(slot) = parameters.iter_mut().find(|p| &p.name == name) else {
                let what = if kind.parameter_index(name).is_some() {
                    "is fixed by the scenario, not a free parameter"
                } else {
                    "is not a parameter"
                };
                return Err(format!(
                    "identify.bounds.{law}.{name}: `{name}` {what} of `{law}` (its free parameters: {})",
                    free.join(", ")
                ));
            };
            if !(lower < upper && lower.is_finite() && upper.is_finite())
                || (slot.log_scale && *lower <= 0.0)
            {
                return Err(format!("identify.bounds.{law}.{name}: needs finite lower < upper (and > 0 for {name}), found [{lower}, {upper}]"));
            }
            (slot.lower, slot.upper) = (*lower, *upper);
        }
        Ok(Bounds { parameters, kind })
    }

    /// Checks every `[identify.bounds.<law>]` table of a scenario, not only the one
    /// of the law being identified: a law or a parameter name it does not know is an
    /// error naming its key, never ignored.
    pub(crate) fn check_scenario(all: &BoundsOverrides) -> Result<(), String> {
        for (law, overrides) in all {
            law_catalogue::kind(law).map_err(|e| format!("identify.bounds.{law}: {e}"))?;
            Bounds::for_law(law, Some(overrides))?;
        }
        Ok(())
    }

    /// `Ok` if these are the bounds of `law`'s kind of law.
    pub fn check(&self, law: &AnyNormalLaw<f64>) -> Result<(), IdentifyError> {
        if law.kind() == self.kind {
            Ok(())
        } else {
            Err(IdentifyError::Setup(format!(
                "the search box of `{}` cannot fit law `{}`",
                self.kind,
                law.name()
            )))
        }
    }

    /// The values of the free parameters in `law`, in [`Bounds::free`] order.
    pub fn checked_values(&self, law: &AnyNormalLaw<f64>) -> Result<Vec<f64>, IdentifyError> {
        self.check(law)?;
        let value = |p: &Bound| law.get(&p.name);
        let values = self.parameters.iter().map(value).collect::<Result<_, _>>();
        values.map_err(|e| IdentifyError::Setup(e.to_string()))
    }

    /// `law` with the free parameters set to `values` (in [`Bounds::free`] order) and
    /// the others unchanged: the model a fitness or a residual evaluates.
    pub fn with(&self, law: &AnyNormalLaw<f64>, values: &[f64]) -> AnyNormalLaw<f64> {
        law.map_named(|name, v| {
            let free = self.parameters.iter().position(|p| p.name == name);
            free.map_or(v, |i| values[i])
        })
    }

    /// Names of the free parameters.
    pub fn free(&self) -> Vec<&str> {
        self.parameters.iter().map(|p| p.name.as_str()).collect()
    }

    /// Interval of parameter `name` ((−∞, ∞) if it is not free).
    pub fn range(&self, name: &str) -> (f64, f64) {
        self.parameters
            .iter()
            .find(|p| p.name == name)
            .map_or((f64::NEG_INFINITY, f64::INFINITY), Bound::range)
    }

    /// `law` with each free parameter clamped into its interval.
    pub fn clamp(&self, law: &AnyNormalLaw<f64>) -> AnyNormalLaw<f64> {
        law.map_named(|name, v| {
            let (lo, hi) = self.range(name);
            if v.is_nan() {
                0.5 * (lo + hi)
            } else {
                v.clamp(lo, hi)
            }
        })
    }

    /// A point inside the box: the (geometric, where log-scaled) middle.
    pub fn middle(&self) -> Vec<(String, f64)> {
        self.parameters
            .iter()
            .map(|b| {
                (
                    b.name.clone(),
                    if b.log_scale {
                        (b.lower * b.upper).sqrt()
                    } else {
                        0.5 * (b.lower + b.upper)
                    },
                )
            })
            .collect()
    }
}

/// A law's free parameters as one searchable vector: the genetic algorithm's box,
/// Levenberg–Marquardt's projection box.
impl Parameters for Bounds {
    type Target = AnyNormalLaw<f64>;

    fn bounds(&self) -> Vec<Bound> {
        self.parameters.clone()
    }

    /// NaN for a parameter `law` lacks (a law of another kind: see [`Bounds::check`]).
    fn values(&self, law: &AnyNormalLaw<f64>) -> Vec<f64> {
        let value = |p: &Bound| law.get(&p.name).unwrap_or(f64::NAN);
        self.parameters.iter().map(value).collect()
    }

    fn apply(&self, law: &AnyNormalLaw<f64>, values: &[f64]) -> AnyNormalLaw<f64> {
        self.with(law, values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_free_parameter_is_a_parameter_of_its_law() {
        for kind in LawKind::ALL {
            let bounds = Bounds::for_law(kind.name(), None).unwrap();
            assert!(!bounds.free().is_empty(), "{kind}");
            for name in bounds.free() {
                assert!(kind.parameter_index(name).is_some(), "{kind}.{name}");
            }
        }
    }

    #[test]
    fn with_sets_the_free_parameters_and_keeps_the_others() {
        let law = law_catalogue::build(
            "variable_stiffness",
            &[
                ("surface_loading".into(), 2.0),
                ("effective_modulus".into(), 1e10),
                ("radius".into(), 0.01),
                ("damping".into(), 100.0),
                ("effective_mass".into(), 0.06),
            ],
        )
        .unwrap();
        let bounds = Bounds::for_law("variable_stiffness", None).unwrap();
        assert_eq!(bounds.checked_values(&law).unwrap(), [2.0, 100.0]);
        let moved = bounds.with(&law, &[3.0, 50.0]);
        let values: Vec<f64> = moved.values().to_vec();
        assert_eq!(values, [3.0, 1e10, 0.01, 50.0, 0.06]);
        let hertz = law_catalogue::build(
            "hertz",
            &[("stiffness".into(), 1e9), ("exponent".into(), 1.5)],
        );
        assert!(bounds.checked_values(&hertz.unwrap()).is_err());
    }

    #[test]
    fn a_bound_on_a_parameter_the_law_does_not_have_is_an_error_naming_its_key() {
        let overrides = BTreeMap::from([("stifness".to_owned(), [1e9, 1e10])]);
        let err = Bounds::for_law("hertz", Some(&overrides)).unwrap_err();
        assert!(err.starts_with("identify.bounds.hertz.stifness: "), "{err}");
        assert!(
            err.contains("not a parameter") && err.contains("stiffness, exponent"),
            "{err}"
        );
        let fixed = BTreeMap::from([("radius".to_owned(), [0.01, 0.02])]);
        let err = Bounds::for_law("variable_stiffness", Some(&fixed)).unwrap_err();
        assert!(err.contains("fixed by the scenario"), "{err}");
    }

    #[test]
    fn every_law_table_of_a_scenario_is_checked() {
        let table = BTreeMap::from([("exponent".to_owned(), [1.2, 1.8])]);
        let good = BoundsOverrides::from([("flores".to_owned(), table.clone())]);
        assert_eq!(Bounds::check_scenario(&good), Ok(()));
        let typo = BoundsOverrides::from([("lankarani".to_owned(), table)]);
        let err = Bounds::check_scenario(&typo).unwrap_err();
        assert!(
            err.starts_with("identify.bounds.lankarani: unknown law"),
            "{err}"
        );
        let wrong = BTreeMap::from([("restitution".to_owned(), [0.5, 1.0])]);
        let err = Bounds::check_scenario(&BoundsOverrides::from([("hertz".to_owned(), wrong)]));
        assert!(err
            .unwrap_err()
            .starts_with("identify.bounds.hertz.restitution: "));
    }
}
