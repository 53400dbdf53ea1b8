//! `hcm simulate --members N --seed S`: N runs drawn from the scenario's variation as a
//! forecast draws them, written with the column `member`; member m the same run on one
//! thread or two and among 2 members or 4; a model without variation gives N copies of
//! one run, and says so.

use hcm_tests::cli::Hcm;
use std::collections::BTreeMap;
use std::path::Path;

/// Each member's rows (the `member` column dropped), by member.
fn members(path: &Path) -> BTreeMap<String, Vec<String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert!(lines.next().unwrap().ends_with(",member"));
    let mut out: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for line in lines {
        let (row, member) = line.rsplit_once(',').unwrap();
        out.entry(member.to_owned())
            .or_default()
            .push(row.to_owned());
    }
    out
}

fn simulate(hcm: &Hcm, out: &str, count: &str, sets: &[&str], threads: &str) -> String {
    let mut call = hcm
        .run("simulate")
        .opt("--scenario", hcm_tests::scenario("bouncing_ball.toml"))
        .opt("--members", count)
        .opt("--seed", "5")
        .opt("--out", hcm.path(out))
        .env("RAYON_NUM_THREADS", threads);
    for set in sets {
        call = call.opt("--set", set);
    }
    call.ok()
}

#[test]
fn members_differ_as_the_scatter_draws_and_are_the_same_bits_on_any_thread_count() {
    let hcm = Hcm::new();
    simulate(&hcm, "four.csv", "4", &[], "2");
    simulate(&hcm, "four_1.csv", "4", &[], "1");
    simulate(&hcm, "two.csv", "2", &[], "2");
    let four = std::fs::read(hcm.path("four.csv")).unwrap();
    assert_eq!(four, std::fs::read(hcm.path("four_1.csv")).unwrap());
    let (four, two) = (
        members(&hcm.path("four.csv")),
        members(&hcm.path("two.csv")),
    );
    assert_eq!(four.keys().collect::<Vec<_>>(), ["0", "1", "2", "3"]);
    // Member m is member m whatever the count.
    assert_eq!(four["0"], two["0"]);
    assert_eq!(four["1"], two["1"]);
    // The ball's contact scatters (c and λ 2 %): each member's rows differ.
    let distinct: std::collections::BTreeSet<&Vec<String>> = four.values().collect();
    assert_eq!(distinct.len(), 4);
}

#[test]
fn without_variation_every_member_is_the_one_run_and_bad_combinations_are_refused() {
    let hcm = Hcm::new();
    let printed = hcm
        .run("simulate")
        .opt("--scenario", hcm_tests::scenario("bouncing_ball.toml"))
        .opt("--set", "contact.0.noise={}")
        .opt("--members", "3")
        .opt("--out", hcm.path("same.csv"))
        .ok();
    let same = members(&hcm.path("same.csv"));
    assert_eq!(same["0"], same["1"]);
    assert_eq!(same["0"], same["2"]);
    assert!(printed.contains("3 members"), "{printed}");
    let refused = hcm
        .run("simulate")
        .opt("--scenario", hcm_tests::scenario("cube_drop.toml"))
        .opt("--members", "2")
        .opt("--figures", hcm.path("figures"))
        .opt("--out", hcm.path("x.csv"))
        .fails();
    assert!(
        refused.contains("--figures") && refused.contains("--members"),
        "{refused}"
    );
    let refused = hcm
        .run("simulate")
        .opt("--scenario", hcm_tests::scenario("bouncing_ball.toml"))
        .opt("--members", "0")
        .opt("--out", hcm.path("x.csv"))
        .fails();
    assert!(refused.contains("--members"), "{refused}");
}
