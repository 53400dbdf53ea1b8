//! [`AnyNormalLaw`]'s parameters by name and as a list of values, without any
//! serialisation: what a scenario file, an identification loop or a diagnosis reads
//! and writes.

use super::{AnyNormalLaw, LawKind, ParameterValues};
use super::{Flores, Hertz, HuntCrossley, Impact, LankaraniNikravesh, VariableStiffness};
use crate::LawError;

/// `$body` with `$law` bound to the law struct inside any variant of `$any`.
macro_rules! each_law {
    ($any:expr, $law:ident => $body:expr) => {
        match $any {
            AnyNormalLaw::Hertz($law) => $body,
            AnyNormalLaw::LankaraniNikravesh($law) => $body,
            AnyNormalLaw::VariableStiffness($law) => $body,
            AnyNormalLaw::Impact($law) => $body,
            AnyNormalLaw::HuntCrossley($law) => $body,
            AnyNormalLaw::Flores($law) => $body,
        }
    };
}

impl<T> AnyNormalLaw<T> {
    /// Which law this is.
    pub fn kind(&self) -> LawKind {
        match self {
            AnyNormalLaw::Hertz(_) => LawKind::Hertz,
            AnyNormalLaw::LankaraniNikravesh(_) => LawKind::LankaraniNikravesh,
            AnyNormalLaw::VariableStiffness(_) => LawKind::VariableStiffness,
            AnyNormalLaw::Impact(_) => LawKind::Impact,
            AnyNormalLaw::HuntCrossley(_) => LawKind::HuntCrossley,
            AnyNormalLaw::Flores(_) => LawKind::Flores,
        }
    }

    /// The law's name as used in scenario files, on the command line and as its
    /// serde tag ([`LawKind::name`]).
    pub fn name(&self) -> &'static str {
        self.kind().name()
    }
}

impl<T: Copy> AnyNormalLaw<T> {
    /// Every parameter's value, in [`LawKind::parameters`] order.
    pub fn values(&self) -> ParameterValues<T> {
        each_law!(self, law => ParameterValues::from_array(law.to_array()))
    }

    /// `(name, value)` of every parameter, in [`LawKind::parameters`] order.
    pub fn named(&self) -> impl Iterator<Item = (&'static str, T)> {
        let names = self.kind().parameters().iter().map(|p| p.name);
        names.zip(self.values())
    }

    /// The value of parameter `name`; [`LawError::UnknownParameter`] if the law has
    /// none of that name.
    pub fn get(&self, name: &str) -> Result<T, LawError> {
        let kind = self.kind();
        each_law!(self, law => law.parameter(name))
            .ok_or_else(|| LawError::unknown_parameter(kind.name(), name, kind.parameters()))
    }

    /// Sets parameter `name` to `value`; [`LawError::UnknownParameter`] (and the law
    /// unchanged) if the law has none of that name.
    pub fn set(&mut self, name: &str, value: T) -> Result<(), LawError> {
        let kind = self.kind();
        let slot = each_law!(self, law => law.parameter_mut(name))
            .ok_or_else(|| LawError::unknown_parameter(kind.name(), name, kind.parameters()))?;
        *slot = value;
        Ok(())
    }

    /// The law `kind` with `values` in [`LawKind::parameters`] order;
    /// [`LawError::ParameterCount`] unless there is exactly one value per parameter.
    /// The values are not validated ([`NormalLaw::validate`](super::NormalLaw)).
    pub fn from_values(kind: LawKind, values: &[T]) -> Result<Self, LawError> {
        let count = LawError::ParameterCount {
            law: kind.name(),
            expected: kind.parameters(),
            found: values.len(),
        };
        Ok(match kind {
            LawKind::Hertz => Hertz::from_array(values.try_into().map_err(|_| count)?).into(),
            LawKind::LankaraniNikravesh => {
                LankaraniNikravesh::from_array(values.try_into().map_err(|_| count)?).into()
            }
            LawKind::VariableStiffness => {
                VariableStiffness::from_array(values.try_into().map_err(|_| count)?).into()
            }
            LawKind::Impact => Impact::from_array(values.try_into().map_err(|_| count)?).into(),
            LawKind::HuntCrossley => {
                HuntCrossley::from_array(values.try_into().map_err(|_| count)?).into()
            }
            LawKind::Flores => Flores::from_array(values.try_into().map_err(|_| count)?).into(),
        })
    }

    /// The same law with every parameter replaced by `f(name, value)`, called in
    /// [`LawKind::parameters`] order.
    pub fn map_named(self, f: impl FnMut(&'static str, T) -> T) -> Self {
        each_law!(self, law => law.map_named(f).into())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::{Indentation, NormalLaw};
    use serde::de::value::{Error, MapAccessDeserializer, MapDeserializer};
    use serde::Deserialize;

    /// Distinct values 1, 2, … for each parameter of `kind`.
    fn law(kind: LawKind) -> AnyNormalLaw<f64> {
        let values = [1.0, 2.0, 3.0, 4.0, 5.0];
        let n = kind.parameters().len();
        AnyNormalLaw::from_values(kind, &values[..n]).unwrap()
    }

    /// Decodes `{ tag = { name = value, … } }` through serde, from the catalogue's
    /// names: the serde tag must be the kind's name and the fields its parameters.
    fn decode(
        tag: &str,
        names: &[&'static str],
        values: &[f64],
    ) -> Result<AnyNormalLaw<f64>, Error> {
        let fields =
            MapDeserializer::<_, Error>::new(names.iter().copied().zip(values.iter().copied()));
        let outer = MapDeserializer::new(core::iter::once((tag, fields)));
        AnyNormalLaw::deserialize(MapAccessDeserializer::new(outer))
    }

    #[test]
    fn serde_tags_and_fields_are_the_catalogue_names() {
        for kind in LawKind::ALL {
            let expected = law(kind);
            let names: heapless::Vec<&str, 5> = kind.parameters().iter().map(|p| p.name).collect();
            let decoded = decode(kind.name(), &names, &expected.values());
            assert_eq!(decoded, Ok(expected), "{kind}");
            assert_eq!(expected.name(), kind.name());
            assert_eq!(expected.kind(), kind);
        }
        let names = ["stiffness", "exponent"];
        assert!(
            decode("Hertz", &names, &[1.0, 2.0]).is_err(),
            "tags are snake_case"
        );
    }

    #[test]
    fn get_and_set_by_name() {
        for kind in LawKind::ALL {
            let mut law = law(kind);
            for (i, parameter) in kind.parameters().iter().enumerate() {
                assert_eq!(law.get(parameter.name), Ok(i as f64 + 1.0));
                law.set(parameter.name, -(i as f64)).unwrap();
                assert_eq!(law.values().get(i), Some(&-(i as f64)));
            }
            let unknown = law.get("stifness").unwrap_err();
            assert_eq!(law.set("stifness", 1.0), Err(unknown));
            match unknown {
                LawError::UnknownParameter {
                    law: name,
                    parameter,
                    expected,
                } => {
                    assert_eq!((name, parameter.as_str()), (kind.name(), "stifness"));
                    assert_eq!(expected, kind.parameters());
                }
                other => panic!("{other:?}"),
            }
        }
    }

    #[test]
    fn a_failed_set_leaves_the_law_unchanged() {
        let mut hertz = law(LawKind::Hertz);
        assert!(hertz.set("restitution", 0.5).is_err());
        assert_eq!(hertz, law(LawKind::Hertz));
    }

    #[test]
    fn values_round_trip_and_a_wrong_count_is_an_error() {
        for kind in LawKind::ALL {
            let law = law(kind);
            assert_eq!(AnyNormalLaw::from_values(kind, &law.values()), Ok(law));
            let n = kind.parameters().len();
            for found in [0, n - 1, n + 1] {
                let values = [0.5; 6];
                let error = AnyNormalLaw::from_values(kind, &values[..found]).unwrap_err();
                assert_eq!(
                    error,
                    LawError::ParameterCount {
                        law: kind.name(),
                        expected: kind.parameters(),
                        found
                    }
                );
            }
        }
    }

    #[test]
    fn map_named_visits_every_parameter_in_order_with_its_name() {
        for kind in LawKind::ALL {
            let mut seen: heapless::Vec<&str, 5> = heapless::Vec::new();
            let doubled = law(kind).map_named(|name, value| {
                let _ = seen.push(name);
                2.0 * value
            });
            let names: heapless::Vec<&str, 5> = kind.parameters().iter().map(|p| p.name).collect();
            assert_eq!(seen, names);
            let expected: heapless::Vec<f64, 5> =
                law(kind).values().iter().map(|v| 2.0 * v).collect();
            assert_eq!(doubled.values(), expected);
            assert!(law(kind).named().map(|(n, _)| n).eq(names.iter().copied()));
        }
    }

    #[test]
    fn a_set_parameter_changes_the_force() {
        let contact = Indentation {
            depth: 1e-5,
            rate: 0.0,
            approach_speed: 1.0,
        };
        let mut hertz: AnyNormalLaw<f64> = Hertz {
            stiffness: 1e9,
            exponent: 1.5,
        }
        .into();
        let before = hertz.normal_force(&contact);
        hertz.set("stiffness", 2e9).unwrap();
        assert_eq!(hertz.normal_force(&contact), 2.0 * before);
    }
}
