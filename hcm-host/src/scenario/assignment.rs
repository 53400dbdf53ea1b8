//! One change of a scenario document: a TOML value at a dotted key path. The command
//! line's `--set key=value` is parsed into one; the library builds them typed — the
//! key as path segments, the value as a TOML value — so no text is formatted only to
//! be parsed back.

use super::ScenarioError;
use std::fmt;

/// A value to put at a key path of a scenario document (see [`super::overrides`] for
/// how the path walks arrays of tables by position or by name).
#[derive(Clone, Debug, PartialEq)]
pub struct Assignment {
    /// The key path, e.g. `contact`, `0`, `parameters`, `stiffness`.
    pub(crate) key: Vec<String>,
    /// The value put there.
    pub(crate) value: toml::Value,
}

impl Assignment {
    /// `value` at the key path `key`.
    pub fn new<K: ToString>(
        key: impl IntoIterator<Item = K>,
        value: impl Into<toml::Value>,
    ) -> Self {
        Assignment {
            key: key.into_iter().map(|k| k.to_string()).collect(),
            value: value.into(),
        }
    }

    /// `value` at `contact.<index>.<rest…>`.
    pub fn contact(index: usize, rest: &[&str], value: impl Into<toml::Value>) -> Self {
        let key = std::iter::once(index.to_string()).chain(rest.iter().map(|k| k.to_string()));
        Assignment::new(std::iter::once("contact".to_owned()).chain(key), value)
    }

    /// `value` at `body.<name>.<rest…>`.
    pub fn body(name: &str, rest: &[&str], value: impl Into<toml::Value>) -> Self {
        let key = ["body", name].into_iter().chain(rest.iter().copied());
        Assignment::new(key, value)
    }

    /// Parses `key=value` (the value in TOML syntax; a bare word is a string).
    pub fn parse(text: &str) -> Result<Assignment, ScenarioError> {
        let fail = |message: String| ScenarioError::Override {
            assignment: text.to_owned(),
            message,
        };
        let (path, value) = text
            .split_once('=')
            .ok_or_else(|| fail("expected key=value, e.g. body.ball.velocity=[0,0,-1.4]".into()))?;
        let value = parse_value(value.trim()).map_err(&fail)?;
        let key: Vec<String> = path
            .trim()
            .split('.')
            .map(|k| k.trim().to_owned())
            .collect();
        if key.last().is_none_or(|k| k.is_empty()) {
            return Err(fail("empty key".into()));
        }
        Ok(Assignment { key, value })
    }
}

/// `key.path=value`, floats in scientific notation (`1.25e3`), read back by
/// [`Assignment::parse`] to the same bits: the form printed for a user to pass as
/// `--set`.
impl fmt::Display for Assignment {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}=", self.key.join("."))?;
        write_value(f, &self.value)
    }
}

/// A TOML value with its floats as `{:e}` (shortest round-trip form) and arrays
/// without spaces.
fn write_value(f: &mut fmt::Formatter<'_>, value: &toml::Value) -> fmt::Result {
    match value {
        toml::Value::Float(x) => write!(f, "{x:e}"),
        toml::Value::Array(items) => {
            f.write_str("[")?;
            for (i, item) in items.iter().enumerate() {
                if i > 0 {
                    f.write_str(",")?;
                }
                write_value(f, item)?;
            }
            f.write_str("]")
        }
        other => write!(f, "{other}"),
    }
}

/// What can be applied to a scenario as an [`Assignment`]: the typed value itself, or
/// the `key=value` text a user gave.
pub trait IntoAssignment: fmt::Display {
    /// The assignment, or an error naming the text that does not parse.
    fn assignment(&self) -> Result<Assignment, ScenarioError>;
}

/// Written as its `key.path=value` text ([`fmt::Display`]), as a physics file's `sets`
/// hold it.
impl serde::Serialize for Assignment {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

/// Read from its `key.path=value` text ([`Assignment::parse`]): a malformed one is an
/// error where the file is read, naming it.
impl<'de> serde::Deserialize<'de> for Assignment {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let text = String::deserialize(deserializer)?;
        Assignment::parse(&text).map_err(serde::de::Error::custom)
    }
}

impl IntoAssignment for Assignment {
    fn assignment(&self) -> Result<Assignment, ScenarioError> {
        Ok(self.clone())
    }
}

impl IntoAssignment for String {
    fn assignment(&self) -> Result<Assignment, ScenarioError> {
        Assignment::parse(self)
    }
}

impl IntoAssignment for &str {
    fn assignment(&self) -> Result<Assignment, ScenarioError> {
        Assignment::parse(self)
    }
}

/// Parses a TOML value; a bare word that is not TOML is taken as a string.
fn parse_value(text: &str) -> Result<toml::Value, String> {
    match format!("value = {text}").parse::<toml::Table>() {
        Ok(mut table) => table.remove("value").ok_or_else(|| "no value".to_owned()),
        Err(_) if !text.is_empty() && text.chars().all(|c| c.is_alphanumeric() || c == '_') => {
            Ok(toml::Value::String(text.to_owned()))
        }
        Err(_) => Err(format!(
            "`{text}` is not a TOML value (number, [array], \"string\")"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn printed_assignments_parse_back_to_the_same_bits() {
        let values: [f64; 5] = [0.1, -3.0e-7, 1.0 / 3.0, 2.5e10, -0.0];
        for x in values {
            let printed = Assignment::contact(0, &["parameters", "stiffness"], x).to_string();
            let back = Assignment::parse(&printed).unwrap();
            assert_eq!(
                back.value.as_float().map(f64::to_bits),
                Some(x.to_bits()),
                "{printed}"
            );
            assert_eq!(back.key, ["contact", "0", "parameters", "stiffness"]);
        }
        let inertia = toml::Value::Array(vec![1e-3.into(), 2e-3.into(), 3e-3.into()]);
        let printed = Assignment::body("cube", &["inertia"], inertia.clone()).to_string();
        assert_eq!(printed, "body.cube.inertia=[1e-3,2e-3,3e-3]");
        assert_eq!(Assignment::parse(&printed).unwrap().value, inertia);
    }

    #[test]
    fn text_that_is_no_assignment_is_refused_with_what_was_expected() {
        let e = Assignment::parse("gravity").unwrap_err().to_string();
        assert!(e.contains("key=value"), "{e}");
        let e = Assignment::parse("a.=1").unwrap_err().to_string();
        assert!(e.contains("empty key"), "{e}");
        let e = Assignment::parse("a=[1,").unwrap_err().to_string();
        assert!(e.contains("not a TOML value"), "{e}");
        assert_eq!(
            Assignment::parse("contact.0.law=flores")
                .unwrap()
                .value
                .as_str(),
            Some("flores")
        );
    }
}
