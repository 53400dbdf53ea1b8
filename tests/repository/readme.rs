//! Every command the documentation shows runs. Each `hcm …` and `cargo run … -p hcm-host
//! -- …` line of the `sh` blocks of `README.md` and of every Markdown page under `docs/`
//! runs through the `hcm` fixture, block by block, each block in a fresh directory holding
//! a copy of `scenarios/` and `examples/rig/` (as a clone's root does), so that relative
//! paths resolve as they would for a reader who runs them from the repository's root, and
//! outputs land in the temporary directory. A failing command fails the test, naming its
//! file and line.
//!
//! As the README says, some lines are too long for CI and run smaller: a `--runs`
//! above [`MOST_RUNS`] runs with `--runs` [`MOST_RUNS`], `reproduce` (the paper's
//! 1000 runs by default) with `--runs` [`MOST_RUNS`], and `power` (10 seeds by default)
//! with `--seeds` [`MOST_SEEDS`]. Commands too long even so (minutes)
//! are shown in `bash`, `console` or `text` blocks, which this test does not run.

use hcm_tests::cli::Hcm;
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// The most runs a README command is given here (README: "too long for CI").
const MOST_RUNS: usize = 20;

/// The most seeds an `hcm power` line is given here: its default study (250 data sets of
/// 16 runs) took half a minute of this test's both cores in the dev profile.
const MOST_SEEDS: usize = 1;

/// Lines of `sh` blocks that CI runs itself (`.ci/run`) or that measure this machine:
/// not run here.
const NOT_RUN: [&str; 5] = [
    "cargo test",
    "cargo bench",
    "cargo clippy",
    "cargo fmt",
    "cargo build",
];

/// A command line of a page: its line number (1-based) and text, continuation
/// lines joined.
struct Line {
    number: usize,
    text: String,
}

/// The logical lines of every ```sh block, one list per block.
fn sh_blocks(readme: &str) -> Vec<Vec<Line>> {
    let mut blocks = Vec::new();
    let mut current: Option<Vec<Line>> = None;
    let mut continued = false;
    for (index, raw) in readme.lines().enumerate() {
        let trimmed = raw.trim_end();
        match current.as_mut() {
            None if trimmed.trim_start() == "```sh" => current = Some(Vec::new()),
            None => {}
            Some(_) if trimmed.trim_start().starts_with("```") => {
                blocks.extend(current.take());
                continued = false;
            }
            Some(lines) => {
                let (body, continues) = match trimmed.strip_suffix('\\') {
                    Some(body) => (body, true),
                    None => (trimmed, false),
                };
                match lines.last_mut() {
                    Some(last) if continued => {
                        last.text.push(' ');
                        last.text.push_str(body.trim());
                    }
                    _ if body.trim().is_empty() => {}
                    _ => lines.push(Line {
                        number: index + 1,
                        text: body.trim().to_owned(),
                    }),
                }
                continued = continues;
            }
        }
    }
    blocks
}

/// The words of a shell command line: whitespace separates, '…' and "…" quote, a
/// backslash escapes the next character, and `#` at the start of a word begins a
/// comment.
fn words(line: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word: Option<String> = None;
    let mut chars = line.chars();
    while let Some(c) = chars.next() {
        match c {
            c if c.is_whitespace() => words.extend(word.take()),
            '#' if word.is_none() => break,
            '\'' => word
                .get_or_insert_with(String::new)
                .extend(chars.by_ref().take_while(|&q| q != '\'')),
            '"' => {
                let word = word.get_or_insert_with(String::new);
                while let Some(q) = chars.next() {
                    match q {
                        '"' => break,
                        '\\' => word.extend(chars.next()),
                        q => word.push(q),
                    }
                }
            }
            '\\' => word.get_or_insert_with(String::new).extend(chars.next()),
            c => word.get_or_insert_with(String::new).push(c),
        }
    }
    words.extend(word);
    words
}

/// The arguments to `hcm` of a command line: after `hcm`, or after the `--` of a
/// `cargo run` of the `hcm-host` package. None for anything else.
fn hcm_arguments(words: &[String]) -> Option<Vec<String>> {
    match words {
        [first, rest @ ..] if first == "hcm" => Some(rest.to_vec()),
        [cargo, run, rest @ ..] if cargo == "cargo" && run == "run" => {
            let split = rest.iter().position(|w| w == "--")?;
            let (options, arguments) = (&rest[..split], &rest[split + 1..]);
            let package = options
                .windows(2)
                .any(|w| w[0] == "-p" && w[1] == "hcm-host")
                || options.iter().any(|w| w == "--package=hcm-host");
            package.then(|| arguments.to_vec())
        }
        _ => None,
    }
}

/// `arguments` as CI runs them: at most [`MOST_RUNS`] runs, and `reproduce` with that
/// many when it names none.
fn shortened(mut arguments: Vec<String>) -> Vec<String> {
    let runs = arguments.iter().position(|a| a == "--runs");
    match runs {
        Some(i) if i + 1 < arguments.len() => {
            let asked: usize = arguments[i + 1].parse().expect("--runs takes a count");
            arguments[i + 1] = asked.min(MOST_RUNS).to_string();
        }
        None if arguments.first().is_some_and(|a| a == "reproduce") => {
            arguments.extend(["--runs".to_owned(), MOST_RUNS.to_string()]);
        }
        _ => {}
    }
    if arguments.first().is_some_and(|a| a == "power") {
        match arguments.iter().position(|a| a == "--seeds") {
            Some(i) if i + 1 < arguments.len() => {
                let asked: usize = arguments[i + 1].parse().expect("--seeds takes a count");
                arguments[i + 1] = asked.min(MOST_SEEDS).to_string();
            }
            _ => arguments.extend(["--seeds".to_owned(), MOST_SEEDS.to_string()]),
        }
    }
    arguments
}

/// Copies the files of directory `from` into `to` (created).
fn copy_files(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        if path.is_file() {
            std::fs::copy(&path, to.join(path.file_name().unwrap())).unwrap();
        }
    }
}

/// Runs the hcm commands of one `sh` block of `page` in a fresh directory; how many ran.
fn run_block(root: &Path, page: &Path, block: &[Line]) -> usize {
    let hcm = Hcm::new();
    copy_files(&root.join("scenarios"), &hcm.path("scenarios"));
    copy_files(&root.join("examples/rig"), &hcm.path("examples/rig"));
    let mut ran = 0;
    for line in block {
        let words = words(&line.text);
        let Some(arguments) = hcm_arguments(&words) else {
            assert!(
                NOT_RUN.iter().any(|p| line.text.starts_with(p)),
                "{} line {}: `{}` is neither an hcm command nor one CI runs itself",
                page.display(),
                line.number,
                line.text
            );
            continue;
        };
        let arguments = shortened(arguments);
        // Shown with the fixture's message if the command fails.
        eprintln!(
            "{} line {}: hcm {}",
            page.display(),
            line.number,
            arguments.join(" ")
        );
        let (subcommand, rest) = arguments.split_first().expect("a subcommand");
        rest.iter()
            .fold(hcm.run(subcommand), |call, argument| call.arg(argument))
            .ok();
        ran += 1;
    }
    for report in markdown_files(&hcm.path("")) {
        let text = std::fs::read_to_string(&report).unwrap();
        if let Some(header) = table_without_rows(&text) {
            panic!(
                "{} (written by {} line {}'s block): a table without rows under `{header}`",
                report.display(),
                page.display(),
                block.first().map_or(0, |l| l.number)
            );
        }
    }
    ran
}

/// Every `.md` file under `directory`, at any depth.
fn markdown_files(directory: &Path) -> Vec<std::path::PathBuf> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(directory).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            found.extend(markdown_files(&path));
        } else if path.extension().is_some_and(|e| e == "md") {
            found.push(path);
        }
    }
    found
}

/// The header of the first Markdown table in `text` with no row under its `|---|`
/// line (a report saying "listed below" over an empty table), if any.
fn table_without_rows(text: &str) -> Option<&str> {
    // A blank line after the last, so that a table ending the file is seen too.
    let lines: Vec<&str> = text.lines().chain([""]).collect();
    lines.windows(3).find_map(|w| {
        let separator = w[1].starts_with("|---") || w[1].starts_with("| ---");
        (w[0].starts_with('|') && separator && !w[2].starts_with('|')).then_some(w[0])
    })
}

#[test]
fn a_table_without_rows_is_found() {
    assert_eq!(
        table_without_rows("text\n\n| a | b |\n|---|---|\n\nmore"),
        Some("| a | b |")
    );
    assert_eq!(
        table_without_rows("| a | b |\n|---|---|\n| 1 | 2 |\n"),
        None
    );
    // At the very end of a file too.
    assert_eq!(table_without_rows("| a |\n|---|\n"), Some("| a |"));
}

#[test]
fn every_command_of_the_readme_and_the_docs_runs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut pages_blocks = Vec::new();
    for page in hcm_tests::sources::markdown_pages(root) {
        let text = std::fs::read_to_string(root.join(&page)).unwrap();
        pages_blocks.extend(
            sh_blocks(&text)
                .into_iter()
                .map(|block| (page.clone(), block)),
        );
    }
    // Each block runs in a directory of its own: two at once keep both cores busy while
    // one block's command runs on one.
    let blocks = pages_blocks.len();
    let ran: usize = pages_blocks
        .par_iter()
        .map(|(page, block)| run_block(root, page, block))
        .sum();
    // The blocks: the first two commands, the worked examples, the simulations, the
    // hertz example, PM1/PM2, the HCM step by step, the peg and the rigid fits.
    assert!(blocks >= 6 && ran >= 17, "{blocks} blocks, {ran} commands");
}

#[test]
fn the_pages_are_the_readme_and_the_docs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let pages = hcm_tests::sources::markdown_pages(root);
    assert_eq!(pages[0], Path::new("README.md"));
    assert!(
        pages.contains(&PathBuf::from("docs/README.md")),
        "{pages:?}"
    );
    assert!(
        pages[1..].iter().all(|p| p.starts_with("docs")),
        "{pages:?}"
    );
}

#[test]
fn command_lines_parse_as_a_shell_would() {
    let readme = "text\n```sh\nhcm a --x 'b c' \\\n    --y \"d\\\"e\"   # comment\n\ncargo run --release -p hcm-host -- reproduce x\ncargo test --workspace\n```\n```csv\nhcm no\n```\n";
    let blocks = sh_blocks(readme);
    assert_eq!(blocks.len(), 1);
    let lines: Vec<(usize, Vec<String>)> = blocks[0]
        .iter()
        .map(|l| (l.number, words(&l.text)))
        .collect();
    assert_eq!(
        lines[0],
        (
            3,
            vec!["hcm", "a", "--x", "b c", "--y", "d\"e"]
                .into_iter()
                .map(String::from)
                .collect()
        )
    );
    let reproduce = hcm_arguments(&lines[1].1).unwrap();
    let most = MOST_RUNS.to_string();
    assert_eq!(shortened(reproduce), ["reproduce", "x", "--runs", &most]);
    assert_eq!(hcm_arguments(&lines[2].1), None);
    let generate = ["generate", "--runs", "1000", "--out", "x.csv"]
        .map(String::from)
        .to_vec();
    assert_eq!(shortened(generate)[2], most);
    let few = ["generate", "--runs", "10"].map(String::from).to_vec();
    assert_eq!(shortened(few)[2], "10");
    let power = ["power", "--out", "p.csv"].map(String::from).to_vec();
    assert_eq!(shortened(power)[3..], ["--seeds", "1"]);
    let seeds = ["power", "--seeds", "20"].map(String::from).to_vec();
    assert_eq!(shortened(seeds)[2], "1");
}
