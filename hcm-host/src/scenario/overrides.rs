//! `--set key=value`: change one value of a scenario document before it is read.
//!
//! The key is a dotted path. Arrays of tables (`[[body]]`, `[[contact]]`) take a
//! selector after their name: a position (`contact.0.law`) or, for tables with a
//! `name`, that name (`body.ball.velocity`). The value is TOML: `0.95`,
//! `[0.0, 0.95, 0.0]`, `"hertz"` (a bare word is taken as a string). Every list on
//! the path must exist; a table or the last key may be new (`variation.start_state`
//! on a scenario without `[variation]`): typos are caught when the scenario is read,
//! since unknown keys are rejected there.

use super::assignment::{Assignment, IntoAssignment};
use super::ScenarioError;

/// Applies one assignment to `document`.
pub fn apply(document: &mut toml::Table, assignment: &Assignment) -> Result<(), ScenarioError> {
    let fail = |message: String| ScenarioError::Override {
        assignment: assignment.to_string(),
        message,
    };
    let (last, parents) = assignment
        .key
        .split_last()
        .ok_or_else(|| fail("empty key".into()))?;
    let mut table = document;
    let mut i = 0;
    while i < parents.len() {
        let key = parents[i].as_str();
        let at = if i == 0 {
            "at the top level".to_owned()
        } else {
            format!("in `{}`", parents[..i].join("."))
        };
        if !table.contains_key(key) {
            table.insert(key.to_owned(), toml::Table::new().into());
        }
        table = match table.get_mut(key) {
            Some(toml::Value::Table(child)) => child,
            Some(toml::Value::Array(items)) => {
                let selector = parents.get(i + 1).ok_or_else(|| {
                    fail(format!(
                        "`{key}` is a list: write `{key}.<index or name>.{last}`"
                    ))
                })?;
                i += 1;
                select(items, selector).map_err(|m| fail(format!("{m} in `{key}`")))?
            }
            _ => return Err(fail(format!("`{key}` {at} is a value, not a table"))),
        };
        i += 1;
    }
    table.insert(last.to_string(), assignment.value.clone());
    Ok(())
}

/// The first of `assignments` that, applied alone to `base`, makes `check` fail: an
/// error naming its key and what the key expects. `None` when `base` itself fails or
/// no assignment fails alone (then only their combination is wrong).
///
/// Deserialising the document after the overrides loses the keys (serde reports
/// "invalid type: string "abc", expected f64" with no path); this finds the culprit.
pub(crate) fn blame<A: IntoAssignment>(
    base: &toml::Table,
    assignments: &[A],
    check: impl Fn(&toml::Table) -> Result<(), String>,
) -> Option<ScenarioError> {
    check(base).ok()?;
    assignments.iter().find_map(|given| {
        let assignment = given.assignment().ok()?;
        let mut document = base.clone();
        apply(&mut document, &assignment).ok()?;
        let message = check(&document).err()?;
        Some(ScenarioError::Override {
            assignment: given.to_string(),
            message: format!("`{}` {}", assignment.key.join("."), in_words(&message)),
        })
    })
}

/// serde's "invalid type: string "abc", expected f64" as "expects a number, found
/// string "abc"", and its other common messages likewise; others as they are, after
/// "is refused:" (they say what was expected themselves: "unknown field `colour`,
/// expected one of `name`, `mass`, …").
fn in_words(message: &str) -> String {
    let message = message.trim();
    let typed = ["invalid type: ", "invalid value: "]
        .iter()
        .find_map(|prefix| message.strip_prefix(prefix));
    if let Some(rest) = typed {
        if let Some((found, expected)) = rest.split_once(", expected ") {
            let found = if found == "sequence" {
                "an array"
            } else {
                found
            };
            return format!("expects {}, found {found}", type_in_words(expected));
        }
    }
    if let Some(rest) = message.strip_prefix("invalid length ") {
        if let Some((found, expected)) = rest.split_once(", expected ") {
            return format!("expects {expected}, found {found} values");
        }
    }
    format!("is refused: {message}")
}

/// A Rust type name as serde gives it, in words.
fn type_in_words(expected: &str) -> &str {
    match expected {
        "f64" | "f32" => "a number",
        "u8" | "u16" | "u32" | "u64" | "usize" => "a whole number ≥ 0",
        "i8" | "i16" | "i32" | "i64" | "isize" => "a whole number",
        "a sequence" => "an array [...]",
        other => other,
    }
}

/// The element of an array of tables chosen by position or by its `name`.
fn select<'a>(items: &'a mut [toml::Value], selector: &str) -> Result<&'a mut toml::Table, String> {
    let name_of = |item: &toml::Value| item.get("name").and_then(|n| n.as_str()).map(str::to_owned);
    let names: Vec<String> = items.iter().filter_map(name_of).collect();
    let count = items.len();
    let position = selector.parse::<usize>().ok().or_else(|| {
        items
            .iter()
            .position(|item| name_of(item).as_deref() == Some(selector))
    });
    match position.and_then(|i| items.get_mut(i)) {
        Some(toml::Value::Table(item)) => Ok(item),
        Some(_) => Err(format!("entry `{selector}` is not a table")),
        None if names.is_empty() => Err(format!("no entry `{selector}` among {count}")),
        None => Err(format!(
            "no entry `{selector}` (names: {})",
            names.join(", ")
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn document() -> toml::Table {
        r#"
        gravity = [0.0, 0.0, -9.81]
        [[body]]
        name = "ball"
        velocity = [0.0, 0.0, 0.0]
        [[contact]]
        law = "hertz"
        [contact.parameters]
        exponent = 1.5
        "#
        .parse()
        .unwrap()
    }

    #[test]
    fn selects_tables_by_name_and_by_index() {
        let mut doc = document();
        apply(
            &mut doc,
            &Assignment::parse("body.ball.velocity=[0, 0, -1.4]").unwrap(),
        )
        .unwrap();
        apply(
            &mut doc,
            &Assignment::parse("contact.0.parameters.exponent=1.6").unwrap(),
        )
        .unwrap();
        apply(
            &mut doc,
            &Assignment::parse("contact.0.law=flores").unwrap(),
        )
        .unwrap();
        let body = &doc["body"][0];
        assert_eq!(body["velocity"][2].as_float(), Some(-1.4));
        assert_eq!(
            doc["contact"][0]["parameters"]["exponent"].as_float(),
            Some(1.6)
        );
        assert_eq!(doc["contact"][0]["law"].as_str(), Some("flores"));
    }

    #[test]
    fn errors_name_the_missing_step() {
        let mut doc = document();
        let e = apply(&mut doc, &Assignment::parse("body.plate.mass=1").unwrap())
            .unwrap_err()
            .to_string();
        assert!(e.contains("plate") && e.contains("ball"), "{e}");
        // A missing table is created (the scenario's reader refuses a misspelt one).
        apply(
            &mut doc,
            &Assignment::parse("simulation.end_time=1").unwrap(),
        )
        .unwrap();
        assert_eq!(doc["simulation"]["end_time"].as_integer(), Some(1));
        let e = apply(
            &mut doc,
            &Assignment::parse("simulation.end_time.x=1").unwrap(),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("end_time") && e.contains("not a table"), "{e}");
        let e = Assignment::parse("gravity").unwrap_err().to_string();
        assert!(e.contains("key=value"), "{e}");
    }

    /// `check` for [`blame`]: the body's velocity must be 3 numbers.
    fn three_numbers(document: &toml::Table) -> Result<(), String> {
        let velocity = &document["body"][0]["velocity"];
        let numbers: Vec<f64> = velocity
            .clone()
            .try_into()
            .map_err(|e: toml::de::Error| e.message().to_owned())?;
        match numbers.len() {
            3 => Ok(()),
            n => Err(format!("invalid length {n}, expected an array of length 3")),
        }
    }

    #[test]
    fn blame_names_the_assignment_that_breaks_the_document_alone() {
        let assignments = [
            "contact.0.law=flores".to_owned(),
            "body.ball.velocity=[0, 0]".to_owned(),
            "body.ball.velocity=[0, 0, abc]".to_owned(),
        ];
        let e = blame(&document(), &assignments, three_numbers)
            .unwrap()
            .to_string();
        assert_eq!(
            e,
            "--set body.ball.velocity=[0, 0]: `body.ball.velocity` expects an array of length 3, found 2 values"
        );
        let typed = ["body.ball.velocity=\"fast\"".to_owned()];
        let e = blame(&document(), &typed, three_numbers)
            .unwrap()
            .to_string();
        assert!(e.contains("`body.ball.velocity` expects "), "{e}");
        assert!(e.contains("found string \"fast\""), "{e}");
        // Fine alone: nothing to blame.
        assert!(blame(&document(), &assignments[..1], three_numbers).is_none());
    }
}
