//! Arrays read with their length checked. serde's fixed-size arrays keep the first N
//! numbers of a longer TOML array and drop the rest without a word (a gravity written
//! with 4 components would lose its last), so every vector, quaternion, tensor and
//! interval a scenario writes is read here: as a list, then refused unless it has
//! exactly the length its key needs, the error naming that length. The TOML reader
//! adds the file, line and key to the message.

use serde::de::{Deserializer, Error};
use serde::Deserialize;
use std::collections::BTreeMap;

/// What a key of `N` numbers expects, in words (for serde's `invalid_length`).
struct Numbers(usize);

impl std::fmt::Display for Numbers {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "an array of {} numbers", self.0)
    }
}

impl serde::de::Expected for Numbers {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        std::fmt::Display::fmt(self, f)
    }
}

/// `values` as an array of exactly `N`, or what was expected and found.
pub(crate) fn exactly<const N: usize>(values: &[f64]) -> Result<[f64; N], String> {
    <[f64; N]>::try_from(values).map_err(|_| {
        format!(
            "expected {}, found {} number{}",
            Numbers(N),
            values.len(),
            if values.len() == 1 { "" } else { "s" }
        )
    })
}

/// An array of exactly `N` numbers (serde's `deserialize_with`).
pub(crate) fn array<'de, D: Deserializer<'de>, const N: usize>(
    deserializer: D,
) -> Result<[f64; N], D::Error> {
    let values = Vec::<f64>::deserialize(deserializer)?;
    <[f64; N]>::try_from(values.as_slice())
        .map_err(|_| D::Error::invalid_length(values.len(), &Numbers(N)))
}

/// Per law, per parameter, an interval `[lower, upper]`.
pub(crate) type Intervals = BTreeMap<String, BTreeMap<String, [f64; 2]>>;

/// `[identify.bounds.<law>]` tables whose every entry is `[lower, upper]`.
pub(crate) fn intervals<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Intervals, D::Error> {
    let tables = BTreeMap::<String, BTreeMap<String, Vec<f64>>>::deserialize(deserializer)?;
    let mut checked = BTreeMap::new();
    for (law, table) in tables {
        let mut entries = BTreeMap::new();
        for (name, values) in table {
            let interval = exactly::<2>(&values)
                .map_err(|e| D::Error::custom(format!("{law}.{name}: [lower, upper] {e}")))?;
            entries.insert(name, interval);
        }
        checked.insert(law, entries);
    }
    Ok(checked)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Deserialize)]
    struct Holder {
        #[serde(deserialize_with = "array")]
        v: [f64; 3],
    }

    #[test]
    fn a_longer_or_shorter_array_is_refused_and_an_exact_one_read() {
        let ok: Holder = toml::from_str("v = [1, 2.5, 3]").unwrap();
        assert_eq!(ok.v, [1.0, 2.5, 3.0]);
        for text in ["v = [1, 2, 3, 4]", "v = [1, 2]", "v = []"] {
            let err = toml::from_str::<Holder>(text).unwrap_err().to_string();
            assert!(err.contains("expected an array of 3 numbers"), "{err}");
        }
        assert_eq!(exactly::<4>(&[1.0; 4]), Ok([1.0; 4]));
        let err = exactly::<4>(&[1.0; 5]).unwrap_err();
        assert_eq!(err, "expected an array of 4 numbers, found 5 numbers");
    }
}
