//! What `hcm --help` and each command's help tell a new user: every command listed
//! in the description, every term a help uses defined in it, the files `generate`
//! says it writes written, and `reproduce` running outside the repository.

use hcm_tests::cli::Hcm;

/// Terms a help may use only with a definition in its `Terms:` block. Acronyms match
/// case-sensitively, words in any case.
const TERMS: [&str; 11] = [
    "PM1",
    "PM2",
    "S1",
    "S2",
    "HCM",
    "int8",
    "residual",
    "envelope",
    "blob",
    "indicators",
    "noise floor",
];

/// The subcommands clap lists under `Commands:` (without `help`).
fn commands(help: &str) -> Vec<String> {
    help.lines()
        .skip_while(|l| l.trim() != "Commands:")
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        // A command's line starts two spaces in; its summary's continuation further.
        .filter(|l| l.starts_with("  ") && !l.starts_with("   "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|name| *name != "help")
        .map(str::to_owned)
        .collect()
}

#[test]
fn the_description_lists_every_command_clap_knows() {
    let hcm = Hcm::new();
    let help = hcm.run("--help").ok();
    let listed = commands(&help);
    assert!(listed.len() >= 11, "clap lists {listed:?}:\n{help}");
    let description = help.split("Usage:").next().unwrap_or_default();
    for name in &listed {
        assert!(
            description.contains(&format!("  hcm {name} ")),
            "`hcm {name}` is not in the description:\n{description}"
        );
    }
    // And the description names nothing clap does not know.
    for line in description.lines().filter(|l| l.starts_with("  hcm ")) {
        let name = line.split_whitespace().nth(1).unwrap_or_default();
        assert!(
            listed.iter().any(|n| n == name),
            "`hcm {name}` is no command"
        );
    }
}

/// Whether `text` uses `term` as a word of its own.
fn uses(text: &str, term: &str) -> bool {
    let acronym = term.chars().any(|c| c.is_ascii_digit() || c.is_uppercase());
    let (text, term) = if acronym {
        (text.to_owned(), term.to_owned())
    } else {
        (text.to_lowercase(), term.to_lowercase())
    };
    text.match_indices(&term).any(|(at, _)| {
        let before = text[..at].chars().next_back();
        let after = text[at + term.len()..].chars().next();
        let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
        // `data.s1.csv` and `OUT.s1.csv` name files, not the set.
        !word(before) && !word(after) && before != Some('.')
    })
}

#[test]
fn every_term_a_command_uses_is_defined_in_its_help() {
    let hcm = Hcm::new();
    let top = hcm.run("--help").ok();
    let mut undefined = Vec::new();
    for name in commands(&top) {
        let help = hcm.run(&name).arg("--help").ok();
        let terms: Vec<&str> = help
            .split("Terms:")
            .nth(1)
            .unwrap_or_default()
            .split("Usage:")
            .next()
            .unwrap_or_default()
            .lines()
            .filter(|l| l.starts_with("  ") && !l.starts_with("    "))
            .map(str::trim)
            .collect();
        for term in TERMS.into_iter().filter(|t| uses(&help, t)) {
            let defined = (terms.iter())
                .any(|line| line.starts_with(term) || line.contains(&format!(", {term} ")));
            if !defined {
                undefined.push(format!("`hcm {name} --help` uses {term}"));
            }
        }
    }
    assert!(
        undefined.is_empty(),
        "terms used without a definition under `Terms:`:\n{}",
        undefined.join("\n")
    );
}

#[test]
fn generate_writes_the_files_its_help_names() {
    let hcm = Hcm::new();
    let help = hcm.run("generate").arg("--help").ok();
    assert!(
        help.contains("OUT.s1.csv") && help.contains("OUT.s2.csv"),
        "{help}"
    );
    let scenario = hcm_tests::scenario("bouncing_ball.toml");
    hcm.run("generate")
        .opt("--scenario", &scenario)
        .opt("--runs", "4")
        .opt("--out", "data.csv")
        .ok();
    for file in ["data.csv", "data.s1.csv", "data.s2.csv"] {
        assert!(hcm.path(file).is_file(), "{file} was not written");
    }
}

#[test]
fn evaluate_says_where_its_residual_blob_comes_from() {
    let help = Hcm::new().run("evaluate").arg("--help").ok();
    let residual = help
        .split("--residual <RESIDUAL>")
        .nth(1)
        .and_then(|rest| rest.split("--contact").next())
        .unwrap_or_default();
    assert!(residual.contains("hcm export"), "{help}");
}

#[test]
fn reproduce_runs_outside_the_repository() {
    // The fixture's working directory is a fresh temporary one: no `scenarios/` there.
    let hcm = Hcm::new();
    assert!(!hcm.path("scenarios").exists());
    hcm.run("reproduce")
        .arg("bouncing-ball")
        .opt("--runs", "12")
        .opt("--method", "lsq")
        .opt("--out", "ball")
        .ok();
    let report = std::fs::read_to_string(hcm.path("ball/report.md")).unwrap();
    assert!(
        report.contains("scenario `scenarios/bouncing_ball.toml (built in)`"),
        "{report}"
    );
    let json = std::fs::read_to_string(hcm.path("ball/results.json")).unwrap();
    let results: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(results["runs_per_condition"], 12);
    // `--scenario` still runs a file, and an edit to it shows.
    let edited = hcm.path("ball.toml");
    let text = std::fs::read_to_string(hcm_tests::scenario("bouncing_ball.toml")).unwrap();
    std::fs::write(&edited, text.replace("0.1127", "0.0627")).unwrap();
    hcm.run("reproduce")
        .arg("bouncing-ball")
        .opt("--runs", "12")
        .opt("--method", "lsq")
        .opt("--scenario", &edited)
        .opt("--out", "edited")
        .ok();
    let report = std::fs::read_to_string(hcm.path("edited/report.md")).unwrap();
    assert!(
        report.contains("starts at rest 50 mm above `ground`"),
        "{report}"
    );
}
