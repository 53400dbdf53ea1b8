//! What hcm leaves at its outputs when something is wrong or it is interrupted: a clear
//! refusal before any work and nothing at the destination, or the complete outputs.
//! The interrupts are real signals sent to a real `hcm generate`, so these tests are
//! Unix's (as are FIFOs, sockets and /dev/null).
#![cfg(unix)]

use hcm_tests::cli::{hcm_exe, Hcm};
use hcm_tests::scenario;
use std::fs;
use std::os::unix::fs::FileTypeExt;
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

/// The names in `dir`, sorted.
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Runs of a `generate` that is interrupted long before its end: tens of seconds of work,
/// yet an output (≈ 300 MB) that fits on a small test disk.
const LONG: &str = "3000";

/// `hcm generate` of the ball, `runs` runs, seed 2, into `out`, started in `dir`.
fn spawn_generate(dir: &Path, runs: &str, out: &str, threads: Option<&str>) -> Child {
    let mut command = Command::new(hcm_exe());
    command
        .current_dir(dir)
        .args(["generate", "--runs", runs, "--seed", "2", "--out", out])
        .arg("--scenario")
        .arg(scenario("bouncing_ball.toml"))
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    if let Some(threads) = threads {
        command.env("RAYON_NUM_THREADS", threads);
    }
    command.spawn().expect("hcm starts")
}

/// Sends `signal` (`TERM`, `INT`, `KILL`) to `child` with the `kill` command.
fn send(child: &Child, signal: &str) {
    let status = Command::new("kill")
        .arg(format!("-{signal}"))
        .arg(child.id().to_string())
        .status()
        .expect("kill runs");
    assert!(status.success(), "kill -{signal} failed");
}

/// Waits until a temporary file in `dir` holds more than `bytes`: the run is writing.
fn wait_for_writing(dir: &Path, bytes: u64) {
    let start = Instant::now();
    loop {
        let writing = fs::read_dir(dir).unwrap().flatten().any(|e| {
            e.file_name().to_string_lossy().starts_with(".hcm-tmp-")
                && e.metadata().is_ok_and(|m| m.len() > bytes)
        });
        if writing {
            return;
        }
        assert!(
            start.elapsed() < Duration::from_secs(300),
            "no output of {bytes} bytes"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// The peak resident memory of process `pid` so far (bytes), from /proc.
fn peak_memory(pid: u32) -> u64 {
    let status = fs::read_to_string(format!("/proc/{pid}/status")).unwrap();
    let line = status.lines().find(|l| l.starts_with("VmHWM:")).unwrap();
    let kilobytes: u64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    kilobytes * 1024
}

#[test]
fn generate_holds_a_chunk_of_runs_in_memory_not_the_experiment() {
    // 3000 runs would be ≈ 300 MB in memory. The files grow while the runs are made,
    // and the peak memory after ≈ 400 runs written stays the peak after ≈ 1200.
    let hcm = Hcm::new();
    let mut child = spawn_generate(hcm.dir(), LONG, "data.csv", None);
    wait_for_writing(hcm.dir(), 20_000_000);
    let early = peak_memory(child.id());
    wait_for_writing(hcm.dir(), 60_000_000);
    let late = peak_memory(child.id());
    send(&child, "TERM");
    child.wait().unwrap();
    println!("peak memory {early} B after 20 MB written, {late} B after 60 MB");
    assert!(late < 200_000_000, "{late} B");
    assert!(late < early + 20_000_000, "{early} B → {late} B");
    assert!(entries(hcm.dir()).is_empty());
}

#[test]
fn generate_writes_the_same_bytes_on_one_and_two_threads() {
    let hcm = Hcm::new();
    let mut files = Vec::new();
    for threads in ["1", "2"] {
        let mut child = spawn_generate(hcm.dir(), "30", &format!("t{threads}.csv"), Some(threads));
        assert!(child.wait().unwrap().success());
        let read = |suffix: &str| fs::read(hcm.path(&format!("t{threads}{suffix}"))).unwrap();
        files.push([read(".csv"), read(".s1.csv"), read(".s2.csv")]);
    }
    assert_eq!(files[0], files[1]);
    let rows = String::from_utf8_lossy(&files[0][0]).lines().count();
    assert!(
        rows > 30 * 100,
        "30 runs of a few hundred samples: {rows} rows"
    );
}

#[test]
fn generate_refuses_an_experiment_larger_than_the_free_disk_space() {
    let hcm = Hcm::new();
    let start = Instant::now();
    let stderr = hcm
        .run("generate")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--runs", "1000000000")
        .opt("--out", hcm.path("data.csv"))
        .fails();
    // Before any simulation but the estimate's one: a second, not the minutes of a
    // billion runs, and without growing memory.
    assert!(start.elapsed() < Duration::from_secs(30));
    for needle in [
        "data.csv",
        "not enough disk space",
        "free",
        "1000000000 runs",
        "--runs",
    ] {
        assert!(stderr.contains(needle), "{needle}: {stderr}");
    }
    assert!(entries(hcm.dir()).is_empty(), "{:?}", entries(hcm.dir()));
}

#[test]
fn too_few_runs_for_the_split_are_refused_before_anything_is_written() {
    let hcm = Hcm::new();
    let stderr = hcm
        .run("generate")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--runs", "1")
        .opt("--out", hcm.path("data.csv"))
        .fails();
    for needle in ["--runs 1", "S1", "S2", "--runs 2 or more"] {
        assert!(stderr.contains(needle), "{needle}: {stderr}");
    }
    let stderr = hcm
        .run("reproduce")
        .arg("bouncing-ball")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--runs", "1")
        .opt("--out", hcm.path("ball"))
        .fails();
    assert!(stderr.contains("--runs 2 or more"), "{stderr}");
    assert!(entries(hcm.dir()).is_empty(), "{:?}", entries(hcm.dir()));
}

#[test]
fn one_run_in_s2_has_no_standard_error() {
    // 5 runs, 10 % held out: S2 is one run, whose spread is unknown, not 0.
    let hcm = Hcm::new();
    let out = hcm.path("ball");
    hcm.run("reproduce")
        .arg("bouncing-ball")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--runs", "5")
        .opt("--method", "lsq")
        .opt("--out", &out)
        .ok();
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    assert_eq!(json["validation"]["runs"], 1);
    assert!(json["validation"]["standard_error"].is_null(), "{json}");
    let report = fs::read_to_string(out.join("report.md")).unwrap();
    assert_eq!(report.matches("n/a (1 run)").count(), 4, "{report}");
    assert!(!report.contains("| 0.00 % |"), "{report}");
    assert_eq!(entries(hcm.dir()), ["ball"], "no temporaries left");
}

#[test]
fn reproduce_leaves_a_directory_that_is_no_previous_output_alone() {
    let hcm = Hcm::new();
    let out = hcm.path("thesis");
    fs::create_dir(&out).unwrap();
    fs::write(out.join("chapter1.tex"), "mine").unwrap();
    let stderr = hcm
        .run("reproduce")
        .arg("bouncing-ball")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--runs", "5")
        .opt("--out", &out)
        .fails();
    for needle in ["thesis", "results.json", "choose another --out"] {
        assert!(stderr.contains(needle), "{needle}: {stderr}");
    }
    assert_eq!(entries(&out), ["chapter1.tex"]);
    assert_eq!(entries(hcm.dir()), ["thesis"]);
}

/// `generate --out OUT` fails naming `shown` and `kind`; afterwards `hcm.dir()` holds
/// exactly `left`.
fn refused(hcm: &Hcm, out: &Path, shown: &str, kind: &str, left: &[&str]) {
    let stderr = hcm
        .run("generate")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--runs", "3")
        .opt("--out", out)
        .fails();
    assert!(stderr.contains(shown) && stderr.contains(kind), "{stderr}");
    assert_eq!(entries(hcm.dir()), left);
}

#[test]
fn special_files_at_out_are_refused_and_kept() {
    let hcm = Hcm::new();
    let fifo = hcm.path("fifo.csv");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    refused(
        &hcm,
        &fifo,
        "fifo.csv",
        "a FIFO (named pipe), not a regular file",
        &["fifo.csv"],
    );
    assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());

    let socket = hcm.path("socket.csv");
    let _listener = std::os::unix::net::UnixListener::bind(&socket).unwrap();
    let left = ["fifo.csv", "socket.csv"];
    refused(
        &hcm,
        &socket,
        "socket.csv",
        "a socket, not a regular file",
        &left,
    );

    let null = hcm.path("null.csv");
    std::os::unix::fs::symlink("/dev/null", &null).unwrap();
    let left = ["fifo.csv", "null.csv", "socket.csv"];
    refused(
        &hcm,
        &null,
        "links to `/dev/null`",
        "a character device",
        &left,
    );
    assert!(fs::symlink_metadata(&null).unwrap().is_symlink());
    assert!(fs::metadata("/dev/null")
        .unwrap()
        .file_type()
        .is_char_device());

    let directory = hcm.path("dir.csv");
    fs::create_dir(&directory).unwrap();
    let left = ["dir.csv", "fifo.csv", "null.csv", "socket.csv"];
    refused(&hcm, &directory, "dir.csv", "is a directory", &left);
    assert!(entries(&directory).is_empty());

    // Every writer goes through the same check: `simulate` too.
    let stderr = hcm
        .run("simulate")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--out", &fifo)
        .fails();
    assert!(
        stderr.contains("fifo.csv") && stderr.contains("FIFO"),
        "{stderr}"
    );
    assert_eq!(entries(hcm.dir()), left);
}

#[test]
fn a_link_at_out_is_followed_and_kept() {
    let hcm = Hcm::new();
    fs::create_dir(hcm.path("store")).unwrap();
    let link = hcm.path("data.csv");
    std::os::unix::fs::symlink("store/real.csv", &link).unwrap();
    let mut child = spawn_generate(hcm.dir(), "3", "data.csv", None);
    assert!(child.wait().unwrap().success());
    assert!(fs::symlink_metadata(&link).unwrap().is_symlink());
    let real = fs::read_to_string(hcm.path("store/real.csv")).unwrap();
    assert!(real.starts_with("run,body,time"));
    assert_eq!(entries(&hcm.path("store")), ["real.csv"]);
    assert_eq!(
        entries(hcm.dir()),
        ["data.csv", "data.s1.csv", "data.s2.csv", "store"]
    );
}

/// How `status` ended: by `signal` with hcm's exit code (128 + signal), or by the signal
/// itself (it came before hcm's handler was installed).
fn ended_by(status: ExitStatus, signal: i32) -> bool {
    status.code() == Some(128 + signal) || status.signal() == Some(signal)
}

#[test]
fn sigterm_and_sigint_remove_the_temporaries_and_leave_no_output() {
    for (signal, number) in [("TERM", 15), ("INT", 2)] {
        let hcm = Hcm::new();
        let mut child = spawn_generate(hcm.dir(), LONG, "data.csv", None);
        wait_for_writing(hcm.dir(), 10_000);
        send(&child, signal);
        let status = child.wait().unwrap();
        assert_eq!(status.code(), Some(128 + number), "SIG{signal}: {status}");
        assert!(entries(hcm.dir()).is_empty(), "{:?}", entries(hcm.dir()));
    }
}

#[test]
fn an_interrupt_at_any_moment_leaves_all_three_outputs_or_none() {
    // How long a whole run takes here, then interrupts spread over it and past it.
    let hcm = Hcm::new();
    let start = Instant::now();
    assert!(spawn_generate(hcm.dir(), "40", "data.csv", None)
        .wait()
        .unwrap()
        .success());
    let whole = start.elapsed();
    let mut outcomes = [0, 0];
    for step in 0..12 {
        let hcm = Hcm::new();
        let mut child = spawn_generate(hcm.dir(), "40", "data.csv", None);
        std::thread::sleep(whole * step / 10);
        let finished = child.try_wait().unwrap().is_some();
        if !finished {
            send(&child, "TERM");
        }
        let status = child.wait().unwrap();
        let left = entries(hcm.dir());
        let all = ["data.csv", "data.s1.csv", "data.s2.csv"];
        if status.success() {
            assert_eq!(left, all);
            outcomes[1] += 1;
        } else {
            assert!(ended_by(status, 15), "step {step}: {status}");
            // The signal came before the outputs were renamed into place (none left) or
            // after the last rename, on the way out (all three, complete): with other
            // tests on the cores a run can outlast the whole run's time measured here.
            assert!(left.is_empty() || left == all, "step {step}: {left:?}");
            if left.is_empty() {
                outcomes[0] += 1;
            } else {
                outcomes[1] += 1;
            }
        }
    }
    println!("interrupted {}, finished {}", outcomes[0], outcomes[1]);
    assert!(outcomes[0] > 0, "no interrupt landed: {outcomes:?}");
}

#[test]
fn leftovers_of_a_killed_run_are_removed_by_the_next_run_in_the_same_place() {
    let hcm = Hcm::new();
    let mut child = spawn_generate(hcm.dir(), LONG, "data.csv", None);
    wait_for_writing(hcm.dir(), 10_000);
    // SIGKILL cannot be caught: its temporaries stay, recognisably named.
    send(&child, "KILL");
    assert_eq!(child.wait().unwrap().signal(), Some(9));
    let left: Vec<PathBuf> = entries(hcm.dir()).iter().map(|n| hcm.path(n)).collect();
    assert_eq!(left.len(), 3, "{left:?}");
    let pid = child.id().to_string();
    for path in &left {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        assert!(name.starts_with(&format!(".hcm-tmp-{pid}-")), "{name}");
    }
    let mut next = spawn_generate(hcm.dir(), "3", "other.csv", None);
    assert!(next.wait().unwrap().success());
    assert_eq!(
        entries(hcm.dir()),
        ["other.csv", "other.s1.csv", "other.s2.csv"]
    );
}
