//! No function of hcm-host is longer than [`MAX_LINES`] lines of code: a longer one is
//! split into named steps. Counted from the sources: the lines of a `fn` item from its
//! signature to its closing brace, blank lines and comment lines excluded; unit-test
//! modules (`#[cfg(test)]`, `tests.rs`) are not counted.

use hcm_tests::sources::rust_sources;
use std::fs;
use std::path::Path;

/// The longest a function may be (lines of code).
const MAX_LINES: usize = 80;

/// Whether `line` opens a function item: `fn name`, after any visibility and
/// qualifiers, at the start of the line.
fn opens_function(line: &str) -> bool {
    let mut rest = line.trim_start();
    for prefix in [
        "pub(crate) ",
        "pub(super) ",
        "pub ",
        "const ",
        "async ",
        "unsafe ",
    ] {
        rest = rest.strip_prefix(prefix).unwrap_or(rest);
    }
    rest.starts_with("fn ")
}

/// (name, first line, lines of code) of each function in `source`, test modules
/// excluded.
fn functions(source: &str) -> Vec<(String, usize, usize)> {
    let lines: Vec<&str> = source.lines().collect();
    let mut found = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        if line.trim_start().starts_with("#[cfg(test)]")
            && lines
                .get(i + 1)
                .is_some_and(|l| l.trim_start().contains("mod "))
        {
            break;
        }
        if !opens_function(line) {
            i += 1;
            continue;
        }
        let indent = line.len() - line.trim_start().len();
        // A declaration without a body (a trait's) ends with `;` before any `{`.
        let Some(open) =
            (i..lines.len()).find(|&j| lines[j].contains('{') || lines[j].ends_with(';'))
        else {
            break;
        };
        if !lines[open].contains('{') {
            i = open + 1;
            continue;
        }
        let close = (open..lines.len())
            .find(|&j| {
                let l = lines[j];
                l.len() - l.trim_start().len() == indent && l.trim_start().starts_with('}')
            })
            .unwrap_or(open);
        let code = lines[i..=close]
            .iter()
            .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with("//"))
            .count();
        let name = line.trim_start().split("fn ").nth(1).unwrap_or("");
        let name = name.split(['(', '<']).next().unwrap_or(name).to_owned();
        found.push((name, i + 1, code));
        i = close + 1;
    }
    found
}

#[test]
fn no_function_of_hcm_host_is_longer_than_the_limit() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("hcm-host/src");
    let files = rust_sources(&src);
    let mut long = Vec::new();
    for file in &files {
        for (name, line, code) in functions(&fs::read_to_string(file).unwrap()) {
            if code > MAX_LINES {
                let file = file.strip_prefix(&src).unwrap().display();
                long.push(format!("{file}:{line} {name}: {code} lines"));
            }
        }
    }
    assert!(
        long.is_empty(),
        "functions over {MAX_LINES} lines of code (split them into named steps):\n{}",
        long.join("\n")
    );
}

#[test]
fn the_counter_counts_code_lines_of_each_function() {
    let source = "pub fn a(x: u8) -> u8 {\n    // a comment\n\n    x + 1\n}\ntrait T {\n    fn b(&self);\n}\nimpl S {\n    pub(crate) fn c(&self) {\n        let y = 2;\n        drop(y);\n    }\n}\n#[cfg(test)]\nmod tests {\n    fn d() {}\n}\n";
    let found = functions(source);
    let expected = vec![("a".to_owned(), 1, 3), ("c".to_owned(), 10, 4)];
    assert_eq!(found, expected);
}
