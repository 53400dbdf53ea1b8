//! Which parameters of a law are identified, and the box they are searched in.

use super::genetic::Bound;
use crate::law_catalogue;
use hcm_core::law::AnyNormalLaw;
use std::collections::BTreeMap;
use std::f64::consts::TAU;

/// The free parameters of one law with their search intervals.
#[derive(Clone, Debug, PartialEq)]
pub struct Bounds {
    /// (name, lower, upper, log-scaled) per free parameter, in catalogue order.
    pub parameters: Vec<(String, f64, f64, bool)>,
}

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
        let entry = law_catalogue::entry(law).map_err(|e| e.to_string())?;
        let mut parameters: Vec<(String, f64, f64, bool)> = defaults(law)
            .iter()
            .map(|&(n, lo, hi, log)| (n.to_owned(), lo, hi, log))
            .collect();
        for (name, [lower, upper]) in overrides.into_iter().flatten() {
            let Some(slot) = parameters.iter_mut().find(|p| &p.0 == name) else {
                let known: Vec<_> = entry.parameters.iter().map(|p| p.name).collect();
                return Err(format!(
                    "identify.bounds.{law}.{name}: not a free parameter of `{law}` ({})",
                    known.join(", ")
                ));
            };
            if !(lower < upper && lower.is_finite() && upper.is_finite())
                || (slot.3 && *lower <= 0.0)
            {
                return Err(format!("identify.bounds.{law}.{name}: needs finite lower < upper (and > 0 for {name}), found [{lower}, {upper}]"));
            }
            (slot.1, slot.2) = (*lower, *upper);
        }
        Ok(Bounds { parameters })
    }

    /// Names of the free parameters.
    pub fn free(&self) -> Vec<&str> {
        self.parameters.iter().map(|p| p.0.as_str()).collect()
    }

    /// Interval of parameter `name` ((−∞, ∞) if it is not free).
    pub fn range(&self, name: &str) -> (f64, f64) {
        self.parameters
            .iter()
            .find(|p| p.0 == name)
            .map_or((f64::NEG_INFINITY, f64::INFINITY), |p| (p.1, p.2))
    }

    /// `law` with each free parameter clamped into its interval.
    pub fn clamp(&self, law: &AnyNormalLaw<f64>) -> AnyNormalLaw<f64> {
        law_catalogue::map_parameters(law, |name, v| {
            let (lo, hi) = self.range(name);
            if v.is_nan() {
                0.5 * (lo + hi)
            } else {
                v.clamp(lo, hi)
            }
        })
    }

    /// The box as the genetic algorithm's bounds.
    pub fn genetic(&self) -> Vec<Bound> {
        self.parameters
            .iter()
            .map(|(name, lower, upper, log_scale)| Bound {
                name: name.clone(),
                lower: *lower,
                upper: *upper,
                log_scale: *log_scale,
            })
            .collect()
    }

    /// A point inside the box: the (geometric, where log-scaled) middle.
    pub fn middle(&self) -> Vec<(String, f64)> {
        self.parameters
            .iter()
            .map(|(n, lo, hi, log)| {
                (
                    n.clone(),
                    if *log {
                        (lo * hi).sqrt()
                    } else {
                        0.5 * (lo + hi)
                    },
                )
            })
            .collect()
    }
}
