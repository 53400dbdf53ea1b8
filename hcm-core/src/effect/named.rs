//! [`ContactEffect`]'s parameters by name and as a list of values, without any
//! serialisation: what a diagnosis reports and re-fits.

use super::ContactEffect;
use crate::law::{ParameterInfo, ParameterValues};
use crate::{LawError, Real};

/// `$body` with `$effect` bound to the effect struct inside any variant of `$any`.
macro_rules! each_effect {
    ($any:expr, $effect:ident => $body:expr) => {
        match $any {
            ContactEffect::ViscousDamping($effect) => $body,
            ContactEffect::HysteresisDamping($effect) => $body,
            ContactEffect::StiffnessExponent($effect) => $body,
            ContactEffect::Adhesion($effect) => $body,
            ContactEffect::Plasticity($effect) => $body,
        }
    };
}

impl<T: Real> ContactEffect<T> {
    /// The effect's parameters in field order: name, unit and meaning.
    pub fn parameters(&self) -> &'static [ParameterInfo] {
        match self {
            ContactEffect::ViscousDamping(_) => super::ViscousDamping::<T>::PARAMETERS,
            ContactEffect::HysteresisDamping(_) => super::HysteresisDamping::<T>::PARAMETERS,
            ContactEffect::StiffnessExponent(_) => super::StiffnessExponent::<T>::PARAMETERS,
            ContactEffect::Adhesion(_) => super::Adhesion::<T>::PARAMETERS,
            ContactEffect::Plasticity(_) => super::Plasticity::<T>::PARAMETERS,
        }
    }

    /// Every parameter's value, in [`ContactEffect::parameters`] order.
    pub fn values(&self) -> ParameterValues<T> {
        each_effect!(self, effect => ParameterValues::from_array(effect.to_array()))
    }

    /// `(name, value)` of every parameter, in [`ContactEffect::parameters`] order.
    pub fn named(&self) -> impl Iterator<Item = (&'static str, T)> {
        let names = self.parameters().iter().map(|p| p.name);
        names.zip(self.values())
    }

    /// The value of parameter `name`; [`LawError::UnknownParameter`] if the effect
    /// has none of that name.
    pub fn get(&self, name: &str) -> Result<T, LawError> {
        each_effect!(self, effect => effect.parameter(name))
            .ok_or_else(|| LawError::unknown_parameter(self.name(), name, self.parameters()))
    }

    /// Sets parameter `name` to `value`; [`LawError::UnknownParameter`] (and the
    /// effect unchanged) if the effect has none of that name.
    pub fn set(&mut self, name: &str, value: T) -> Result<(), LawError> {
        let (effect_name, parameters) = (self.name(), self.parameters());
        let slot = each_effect!(self, effect => effect.parameter_mut(name))
            .ok_or_else(|| LawError::unknown_parameter(effect_name, name, parameters))?;
        *slot = value;
        Ok(())
    }

    /// The same effect with every parameter replaced by `f(name, value)`, called in
    /// [`ContactEffect::parameters`] order.
    pub fn map_named(self, f: impl FnMut(&'static str, T) -> T) -> Self {
        each_effect!(self, effect => effect.map_named(f).into())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::*;
    use crate::effect::{
        Adhesion, HysteresisDamping, Plasticity, StiffnessExponent, ViscousDamping,
    };
    use serde::de::value::{Error, MapAccessDeserializer, MapDeserializer};
    use serde::Deserialize;
    use std::format;

    fn every_effect() -> [ContactEffect<f64>; 5] {
        [
            ViscousDamping { coefficient: 1.0 }.into(),
            HysteresisDamping {
                coefficient: 1.0,
                exponent: 2.0,
            }
            .into(),
            StiffnessExponent {
                exponent_change: 1.0,
                reference_depth: 2.0,
            }
            .into(),
            Adhesion {
                pull_off_force: 1.0,
            }
            .into(),
            Plasticity {
                permanent_ratio: 1.0,
            }
            .into(),
        ]
    }

    #[test]
    fn serde_tags_and_fields_are_the_catalogue_names() {
        for effect in every_effect() {
            let names = effect.parameters().iter().map(|p| p.name);
            let fields = MapDeserializer::<_, Error>::new(names.zip(effect.values()));
            let outer = MapDeserializer::new(core::iter::once((effect.name(), fields)));
            let decoded = ContactEffect::deserialize(MapAccessDeserializer::new(outer));
            assert_eq!(decoded, Ok(effect), "{}", effect.name());
        }
    }

    #[test]
    fn get_set_and_map_by_name() {
        for mut effect in every_effect() {
            let names: heapless::Vec<&str, 5> =
                effect.parameters().iter().map(|p| p.name).collect();
            assert!(effect.named().map(|(n, _)| n).eq(names.iter().copied()));
            for (i, name) in names.iter().enumerate() {
                assert_eq!(
                    effect.get(name),
                    Ok(i as f64 + 1.0),
                    "{}.{name}",
                    effect.name()
                );
                effect.set(name, 10.0 + i as f64).unwrap();
            }
            let expected: heapless::Vec<f64, 5> =
                (0..names.len()).map(|i| 10.0 + i as f64).collect();
            assert_eq!(effect.values(), expected);
            let mut seen: heapless::Vec<&str, 5> = heapless::Vec::new();
            let halved = effect.map_named(|name, value| {
                let _ = seen.push(name);
                0.5 * value
            });
            assert_eq!(seen, names);
            assert!(halved
                .values()
                .iter()
                .zip(&expected)
                .all(|(h, e)| *h == 0.5 * e));
        }
    }

    #[test]
    fn an_unknown_name_is_an_error_naming_the_effect() {
        let mut effect = every_effect()[3];
        let error = effect.set("pull_off", 2.0).unwrap_err();
        assert_eq!(effect, every_effect()[3]);
        assert_eq!(effect.get("pull_off"), Err(error));
        let text = format!("{error}");
        assert_eq!(
            text,
            "`adhesion` has no parameter `pull_off`; its parameters are: pull_off_force"
        );
    }
}
