//! hcm-host is layered: each top-level module uses only the modules of the layers below
//! it (the map in `hcm-host/src/lib.rs`). These tests read the sources and fail on an
//! import that goes up or sideways into a cycle, naming the file that makes it.

use hcm_tests::sources::rust_sources;
use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The layers, bottom first; a module may use any module of a lower layer and none of
/// its own or a higher one. Kept in step with the map in `hcm-host/src/lib.rs`.
const LAYERS: &[&[&str]] = &[
    &["numerics", "output", "law_catalogue", "progress"],
    &["input"],
    &["residual"],
    &["scenario"],
    &["dataset"],
    &["indicators"],
    &["simulate"],
    &["experiment", "replay", "figure"],
    &["identify"],
    &["train", "evaluate"],
    &["export"],
    &["diagnose"],
    &["pipeline"],
];

fn host_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("hcm-host/src")
}

/// The library's top-level modules (the CLI, `src/cli/`, belongs to the binary).
fn top_level_modules() -> BTreeSet<String> {
    let mut modules = BTreeSet::new();
    for entry in fs::read_dir(host_src()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let is_module = path.is_dir() || path.extension().is_some_and(|e| e == "rs");
        if is_module && !["lib", "main", "cli"].contains(&name.as_str()) {
            modules.insert(name);
        }
    }
    modules
}

/// `source` without comments and without `#[cfg(test)]` items (a unit-test module
/// may use anything).
fn code_of(source: &str) -> String {
    let mut code = String::new();
    for line in source.lines() {
        let line = line.split("//").next().unwrap_or("");
        code.push_str(line);
        code.push('\n');
    }
    while let Some(at) = code.find("#[cfg(test)]") {
        let rest = &code[at..];
        let end = match (rest.find('{'), rest.find(';')) {
            (Some(brace), semicolon) if semicolon.is_none_or(|s| brace < s) => {
                let mut depth = 0;
                let mut end = rest.len();
                for (i, c) in rest[brace..].char_indices() {
                    depth += match c {
                        '{' => 1,
                        '}' => -1,
                        _ => 0,
                    };
                    if depth == 0 {
                        end = brace + i + 1;
                        break;
                    }
                }
                end
            }
            (_, Some(semicolon)) => semicolon + 1,
            _ => rest.len(),
        };
        code.replace_range(at..at + end, "");
    }
    code
}

/// The module path of `file` below `src` (`identify/motion/fit.rs` → identify, motion,
/// fit; a `mod.rs` is its folder's module).
fn module_path(src: &Path, file: &Path) -> Vec<String> {
    let relative = file.strip_prefix(src).unwrap().with_extension("");
    let mut path: Vec<String> = relative
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if path.last().is_some_and(|l| l == "mod") {
        path.pop();
    }
    path
}

/// The names at the top level of a `{ a, b::c, d::{e, f} }` group's inside.
fn group_heads(group: &str) -> Vec<String> {
    let mut heads = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (i, c) in group.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                heads.push(group[start..i].to_owned());
                start = i + 1;
            }
            _ => {}
        }
    }
    heads.push(group[start..].to_owned());
    heads
        .iter()
        .filter_map(|h| leading_ident(h.trim()))
        .collect()
}

/// The identifier `text` starts with.
fn leading_ident(text: &str) -> Option<String> {
    let end = text
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(text.len());
    (end > 0).then(|| text[..end].to_owned())
}

/// The brace group starting at `text[0] == '{'`, without its braces.
fn brace_group(text: &str) -> &str {
    let mut depth = 0;
    for (i, c) in text.char_indices() {
        depth += match c {
            '{' => 1,
            '}' => -1,
            _ => 0,
        };
        if depth == 0 {
            return &text[1..i];
        }
    }
    &text[1..]
}

/// The crate-root names `code` (of the module at `path`) refers to: after `crate::`,
/// or after as many `super::` as climb to the root.
fn root_references(code: &str, path: &[String]) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    let bytes = code.as_bytes();
    let mut i = 0;
    while i < code.len() {
        let boundary = i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
        let rest = &code[i..];
        let mut climbed = None;
        if boundary && rest.starts_with("crate::") {
            climbed = Some(("crate::".len(), true));
        } else if boundary && rest.starts_with("super::") {
            let mut at = 0;
            let mut supers = 0;
            while rest[at..].starts_with("super::") {
                at += "super::".len();
                supers += 1;
            }
            climbed = Some((at, supers >= path.len()));
        }
        match climbed {
            Some((at, true)) => {
                let after = rest[at..].trim_start();
                if after.starts_with('{') {
                    names.extend(group_heads(brace_group(after)));
                } else if let Some(name) = leading_ident(after) {
                    names.insert(name);
                }
                i += at;
            }
            Some((at, false)) => i += at,
            None => i += rest.chars().next().map_or(1, char::len_utf8),
        }
    }
    names
}

/// For each top-level module, the other top-level modules it uses and, for each, the
/// first file that does.
fn imports() -> BTreeMap<String, BTreeMap<String, PathBuf>> {
    let src = host_src();
    let modules = top_level_modules();
    let files = rust_sources(&src);
    let mut graph: BTreeMap<String, BTreeMap<String, PathBuf>> = BTreeMap::new();
    for file in files {
        let path = module_path(&src, &file);
        let Some(top) = path.first().filter(|t| modules.contains(*t)) else {
            continue;
        };
        let code = code_of(&fs::read_to_string(&file).unwrap());
        for used in root_references(&code, &path) {
            if &used != top && modules.contains(&used) {
                let edges = graph.entry(top.clone()).or_default();
                edges.entry(used).or_insert_with(|| file.clone());
            }
        }
    }
    graph
}

#[test]
fn every_top_level_module_is_in_one_layer() {
    let modules = top_level_modules();
    let layered: Vec<&str> = LAYERS.iter().flat_map(|l| l.iter().copied()).collect();
    for module in &modules {
        let count = layered.iter().filter(|l| **l == module).count();
        assert_eq!(
            count, 1,
            "module `{module}` must be in exactly one layer of LAYERS"
        );
    }
    for module in layered {
        assert!(
            modules.contains(module),
            "LAYERS names `{module}`, which is gone"
        );
    }
}

#[test]
fn each_module_uses_only_the_layers_below_it() {
    let layer_of = |m: &str| LAYERS.iter().position(|l| l.contains(&m));
    let mut wrong = Vec::new();
    for (module, used) in imports() {
        for (target, file) in used {
            if layer_of(&target) >= layer_of(&module) {
                wrong.push(format!("{module} → {target} ({})", file.display()));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports against the layers:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn no_import_cycle_among_top_level_modules() {
    let graph = imports();
    // Depth-first search; a back edge closes a cycle, printed with its files.
    fn visit(
        module: &str,
        graph: &BTreeMap<String, BTreeMap<String, PathBuf>>,
        stack: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(at) = stack.iter().position(|m| m == module) {
            let mut cycle = stack[at..].to_vec();
            cycle.push(module.to_owned());
            return Some(cycle);
        }
        if !done.insert(module.to_owned()) {
            return None;
        }
        stack.push(module.to_owned());
        for next in graph.get(module).into_iter().flat_map(|e| e.keys()) {
            if let Some(cycle) = visit(next, graph, stack, done) {
                return Some(cycle);
            }
        }
        stack.pop();
        None
    }
    let mut done = BTreeSet::new();
    for module in graph.keys() {
        if let Some(cycle) = visit(module, &graph, &mut Vec::new(), &mut done) {
            let steps: Vec<String> = cycle
                .windows(2)
                .map(|w| format!("{} → {} ({})", w[0], w[1], graph[&w[0]][&w[1]].display()))
                .collect();
            panic!("import cycle:\n{}", steps.join("\n"));
        }
    }
}

#[test]
fn the_reader_sees_every_form_of_import() {
    let code =
        "use crate::{a::X, b::{c, d}};\nuse super::super::e::Y;\nfn f() { crate::g::h(); }\n";
    let path = ["top".to_owned(), "inner".to_owned()];
    let found = root_references(&code_of(code), &path);
    let expected: BTreeSet<String> = ["a", "b", "e", "g"].map(String::from).into();
    assert_eq!(found, expected);
    let tests = "#[cfg(test)]\nmod tests { use crate::z::W; }\n// crate::comment\n";
    assert!(root_references(&code_of(tests), &path).is_empty());
}
