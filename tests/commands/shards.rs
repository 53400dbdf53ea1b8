//! `--shard I/N` and `--merge` of `hcm generate` and `hcm power`: the shards' files
//! joined are the whole job's files byte for byte (generate's OUT, S1 and S2; power's
//! rows and table), whatever the shard count and thread count; a Slurm job array's
//! variables stand for `--shard`, and the example script (`examples/slurm/shards.sh`)
//! run as separate processes gives the same files; shard files that do not make the
//! job are refused by name.

use hcm_tests::cli::{hcm_exe, Hcm};
use std::path::{Path, PathBuf};
use std::process::Command;

const RUNS: &str = "30";

fn ball() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/bouncing_ball.toml")
}

/// The whole experiment in one process: OUT, S1, S2 bytes.
fn whole(hcm: &Hcm) -> [Vec<u8>; 3] {
    hcm.run("generate")
        .opt("--scenario", ball())
        .opt("--runs", RUNS)
        .opt("--out", hcm.path("whole.csv"))
        .ok();
    ["whole.csv", "whole.s1.csv", "whole.s2.csv"].map(|f| std::fs::read(hcm.path(f)).unwrap())
}

/// Shard files made with `--shard i/n` (threads as given), merged into `name`.
fn sharded(hcm: &Hcm, count: usize, threads: &str, name: &str) -> [Vec<u8>; 3] {
    let mut files = Vec::new();
    for i in 0..count {
        let file = hcm.path(&format!("{name}.shard{i}.csv"));
        hcm.run("generate")
            .opt("--scenario", ball())
            .opt("--runs", RUNS)
            .opt("--shard", format!("{i}/{count}"))
            .opt("--threads", threads)
            .opt("--out", &file)
            .ok();
        files.push(file);
    }
    let mut merge = hcm
        .run("generate")
        .opt("--scenario", ball())
        .opt("--runs", RUNS);
    merge = merge.arg("--merge");
    for file in &files {
        merge = merge.arg(file);
    }
    merge.opt("--out", hcm.path(&format!("{name}.csv"))).ok();
    [".csv", ".s1.csv", ".s2.csv"].map(|s| std::fs::read(hcm.path(&format!("{name}{s}"))).unwrap())
}

#[test]
fn shards_merged_are_the_whole_experiment_byte_for_byte() {
    let hcm = Hcm::new();
    let whole = whole(&hcm);
    assert!(whole.iter().all(|f| f.len() > 1000));
    assert_eq!(
        sharded(&hcm, 4, "1", "four"),
        whole,
        "4 shards, 1 thread each"
    );
    assert_eq!(
        sharded(&hcm, 7, "2", "seven"),
        whole,
        "7 shards, 2 threads each"
    );
    // A shard holds its runs' rows alone: no S1 or S2 beside it.
    assert!(!hcm.path("four.shard0.s1.csv").exists());
}

#[test]
fn a_slurm_array_task_is_a_shard_and_the_script_runs_without_a_cluster() {
    let hcm = Hcm::new();
    let whole = whole(&hcm);
    let ball = ball().display().to_string();
    slurm_array(&hcm, &["generate", "--scenario", &ball, "--runs", RUNS]);
    let merged =
        ["array.csv", "array.s1.csv", "array.s2.csv"].map(|f| std::fs::read(hcm.path(f)).unwrap());
    assert_eq!(merged, whole);
}

/// `examples/slurm/shards.sh` with `command` (an hcm command and its options) as a job
/// array of 3 tasks numbered from 1 (sbatch --array=1-3), run in reverse order as
/// separate processes, then its merge step: OUT `array` in `hcm`'s folder.
fn slurm_array(hcm: &Hcm, command: &[&str]) {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/slurm/shards.sh");
    let run = |vars: &[(&str, String)], merge: bool| {
        let mut call = Command::new("bash");
        call.arg(&script)
            .current_dir(hcm.dir())
            .env("HCM", hcm_exe())
            .env("OUT", "array");
        for (k, v) in vars {
            call.env(k, v);
        }
        if merge {
            call.arg("merge");
        }
        let done = call.args(command).output().unwrap();
        assert!(
            done.status.success(),
            "{}",
            String::from_utf8_lossy(&done.stderr)
        );
    };
    for task in [3, 2, 1] {
        let vars = [
            ("SLURM_ARRAY_TASK_ID", task.to_string()),
            ("SLURM_ARRAY_TASK_MIN", "1".into()),
            ("SLURM_ARRAY_TASK_COUNT", "3".into()),
        ];
        run(&vars, false);
    }
    run(&[("SHARDS", "3".into())], true);
}

#[test]
fn shard_files_that_do_not_make_the_experiment_are_refused() {
    let hcm = Hcm::new();
    let shard = |i: usize, seed: &str| {
        let file = hcm.path(&format!("s{i}-{seed}.csv"));
        hcm.run("generate")
            .opt("--scenario", ball())
            .opt("--runs", RUNS)
            .opt("--seed", seed)
            .opt("--shard", format!("{i}/3"))
            .opt("--out", &file)
            .ok();
        file
    };
    let (a, b, c) = (shard(0, "1"), shard(1, "1"), shard(2, "1"));
    let merge = |files: &[&PathBuf]| {
        let mut call = hcm
            .run("generate")
            .opt("--scenario", ball())
            .opt("--runs", RUNS)
            .arg("--merge");
        for f in files {
            call = call.arg(f);
        }
        call.opt("--out", hcm.path("merged.csv")).fails()
    };
    let missing = merge(&[&a, &b]);
    assert!(
        missing.contains("hold 20 of the experiment's 30 runs"),
        "{missing}"
    );
    let order = merge(&[&b, &a, &c]);
    assert!(
        order.contains("where run `00` (run 0 of 30) was expected"),
        "{order}"
    );
    let other_seed = shard(1, "2");
    let seed = merge(&[&a, &other_seed, &c]);
    assert!(
        seed.contains("is not the one this scenario and --seed make"),
        "{seed}"
    );
    assert!(!hcm.path("merged.csv").exists() && !hcm.path("merged.s1.csv").exists());
    let bad = hcm
        .run("generate")
        .opt("--scenario", ball())
        .opt("--runs", RUNS)
        .opt("--shard", "3/3")
        .opt("--out", hcm.path("x.csv"))
        .fails();
    assert!(bad.contains("shards are numbered 0 to N − 1"), "{bad}");
}

/// A small power study of the ball: two effects (a law term, a measurement) at one
/// strength, two seeds, and
/// nothing hidden (6 data sets of 4 runs), from seed `seed`.
fn power(hcm: &Hcm, seed: &str) -> hcm_tests::cli::Call {
    hcm.run("power")
        .opt("--scenario", ball())
        .opt("--runs", "4")
        .opt("--seeds", "2")
        .opt("--seed", seed)
        .opt("--levels", "0.03")
        .opt("--effects", "viscous_damping,force_offset")
}

/// `hcm power`'s rows and table for OUT `name`.
fn power_files(hcm: &Hcm, name: &str) -> [Vec<u8>; 2] {
    [".csv", ".md"].map(|s| std::fs::read(hcm.path(&format!("{name}{s}"))).unwrap())
}

#[test]
fn power_study_shards_merged_are_the_whole_study_byte_for_byte() {
    let hcm = Hcm::new();
    power(&hcm, "1").opt("--out", hcm.path("whole.csv")).ok();
    let whole = power_files(&hcm, "whole");
    let rows = String::from_utf8(whole[0].clone()).unwrap();
    // The key line, the header and the 6 data sets, each diagnosed.
    assert_eq!(rows.lines().count(), 8, "{rows}");
    assert!(rows
        .lines()
        .nth(2)
        .unwrap()
        .starts_with("0,viscous_damping,0.03,1,"));
    assert!(rows.lines().nth(7).unwrap().starts_with("5,none,0.0,2,"));
    // At 3 % of the peak force each effect is named alone, the truth inside its 95 %
    // interval (an offset along the wrong direction would be named negative); nothing
    // is named where nothing is hidden.
    for line in rows.lines().skip(2) {
        let f: Vec<&str> = line.split(',').collect();
        let (effect, truth, named, exact) = (f[1], f[5], f[7], f[8]);
        assert_eq!(exact, "true", "{line}");
        if effect == "none" {
            assert_eq!(named, "", "{line}");
            continue;
        }
        let number = |k: usize| f[k].parse::<f64>().unwrap();
        assert_eq!(named, effect, "{line}");
        assert!(number(11) <= number(5) && number(5) <= number(12), "{line}");
        assert!(truth.parse::<f64>().unwrap() > 0.0, "{line}");
    }
    // 4 shards on 1 thread and 7 (one of them empty) on 2.
    for (count, threads) in [(4, "1"), (7, "2")] {
        let mut files = Vec::new();
        for i in 0..count {
            let file = hcm.path(&format!("p{count}.shard{i}.csv"));
            power(&hcm, "1")
                .opt("--shard", format!("{i}/{count}"))
                .opt("--threads", threads)
                .opt("--out", &file)
                .ok();
            assert!(!hcm.path(&format!("p{count}.shard{i}.md")).exists());
            files.push(file);
        }
        let mut merge = power(&hcm, "1").arg("--merge");
        for file in &files {
            merge = merge.arg(file);
        }
        merge.opt("--out", hcm.path(&format!("p{count}.csv"))).ok();
        assert_eq!(
            power_files(&hcm, &format!("p{count}")),
            whole,
            "{count} shards, {threads} thread(s) each"
        );
    }
    let ball = ball().display().to_string();
    slurm_array(
        &hcm,
        &[
            "power",
            "--scenario",
            &ball,
            "--runs",
            "4",
            "--seeds",
            "2",
            "--levels",
            "0.03",
            "--effects",
            "viscous_damping,force_offset",
        ],
    );
    assert_eq!(
        power_files(&hcm, "array"),
        whole,
        "the Slurm script's job array"
    );
}

#[test]
fn power_shards_that_do_not_make_the_study_are_refused() {
    let hcm = Hcm::new();
    let shard = |i: usize, seed: &str| {
        let file = hcm.path(&format!("s{i}-{seed}.csv"));
        power(&hcm, seed)
            .opt("--shard", format!("{i}/3"))
            .opt("--out", &file)
            .ok();
        file
    };
    let (a, b, c) = (shard(0, "1"), shard(1, "1"), shard(2, "1"));
    let merge = |files: &[&PathBuf]| {
        let mut call = power(&hcm, "1").arg("--merge");
        for f in files {
            call = call.arg(f);
        }
        call.opt("--out", hcm.path("merged.csv")).fails()
    };
    let missing = merge(&[&a, &c]);
    assert!(
        missing.contains("data set 4 where 2 comes next"),
        "{missing}"
    );
    let short = merge(&[&a, &b]);
    assert!(short.contains("hold data sets 0..4 of 6"), "{short}");
    let other_seed = shard(1, "2");
    let seed = merge(&[&a, &other_seed, &c]);
    assert!(
        seed.contains("line 1: it is not a shard of this study") && seed.contains("seeds 2+2"),
        "{seed}"
    );
    // A row edited by hand: its data set made again reads differently.
    let text = std::fs::read_to_string(&b).unwrap();
    let edited = hcm.path("edited.csv");
    std::fs::write(&edited, text.replacen(",true,", ",false,", 1)).unwrap();
    let tampered = merge(&[&a, &edited, &c]);
    assert!(
        tampered.contains("reads differently when made again"),
        "{tampered}"
    );
    assert!(!hcm.path("merged.csv").exists() && !hcm.path("merged.md").exists());
    // A study that cannot be made is refused before any work, by what is wrong.
    let refused = |option: &str, value: &str| {
        hcm.run("power")
            .opt("--scenario", ball())
            .opt(option, value)
            .opt("--out", hcm.path("bad.csv"))
            .fails()
    };
    let level = refused("--levels", "0.01,2");
    assert!(
        level.contains("2 is not a share of the peak force in (0, 1]"),
        "{level}"
    );
    let effect = refused("--effects", "coulomb_friction");
    assert!(effect.contains("not an effect the 1D diagnosis names; one of: viscous_damping"));
    let rigid = hcm
        .run("power")
        .opt("--scenario", ball().with_file_name("cube_drop.toml"))
        .opt("--out", hcm.path("bad.csv"))
        .fails();
    assert!(rigid.contains("is a rigid (3D) scene"), "{rigid}");
    assert!(!hcm.path("bad.csv").exists());
}
