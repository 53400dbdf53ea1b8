//! `hcm generate --shard I/N` and `--merge`: the shards' files joined are the whole
//! experiment's OUT, S1 and S2 byte for byte, whatever the shard count and thread
//! count; a Slurm job array's variables stand for `--shard`, and the example script
//! (`examples/slurm/generate.sh`) run as separate processes gives the same files; shard
//! files that do not make the experiment are refused by name.

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
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/slurm/generate.sh");
    let run = |vars: &[(&str, String)], merge: bool| {
        let mut command = Command::new("bash");
        command
            .arg(&script)
            .current_dir(hcm.dir())
            .env("HCM", hcm_exe())
            .env("SCENARIO", ball())
            .env("RUNS", RUNS)
            .env("OUT", "array");
        for (k, v) in vars {
            command.env(k, v);
        }
        if merge {
            command.arg("merge");
        }
        let done = command.output().unwrap();
        assert!(
            done.status.success(),
            "{}",
            String::from_utf8_lossy(&done.stderr)
        );
    };
    // Tasks numbered from 1 (sbatch --array=1-3), in reverse order.
    for task in [3, 2, 1] {
        let vars = [
            ("SLURM_ARRAY_TASK_ID", task.to_string()),
            ("SLURM_ARRAY_TASK_MIN", "1".into()),
            ("SLURM_ARRAY_TASK_COUNT", "3".into()),
        ];
        run(&vars, false);
    }
    run(&[("SHARDS", "3".into())], true);
    let merged =
        ["array.csv", "array.s1.csv", "array.s2.csv"].map(|f| std::fs::read(hcm.path(f)).unwrap());
    assert_eq!(merged, whole);
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
