//! Fuzz targets over the library's readers of untrusted input: whatever the
//! bytes, each reader answers `Ok` or `Err` — it never panics and never hangs — and
//! every refusal is a real message: non-empty and at most [`MESSAGE_LIMIT`] bytes (a
//! message quotes a short excerpt of the input, never the input).
//!
//! Three targets, each starting from valid seeds (the shipped files) and mutating them
//! with a deterministic generator (ChaCha8, a fixed seed; case `i` is drawn from its
//! own generator, so the cases and the totals do not depend on the thread count):
//!
//! - [`fuzz_scenario`]: scenario TOML through [`Scenario::parse`] (or
//!   [`Scenario::load`] for text that is not UTF-8) and [`Scenario::model`] — parsing,
//!   validation and resolution into the simulator's model, what `hcm simulate` does
//!   before it simulates; `--set` assignments on a shipped scenario; and physics files
//!   (`hcm identify`'s output) through [`Physics::read`], [`Physics::apply`] and
//!   [`Scenario::model`], as `hcm simulate --physics` reads them. Seeds: `scenarios/`,
//!   `examples/rig/`, `tests/common/scenes/`, `examples/blobs/*.pm2.toml` and
//!   `benches/peers/full-run/hcm_fit.toml`.
//! - [`fuzz_dataset`]: measured-data CSV through [`Dataset::from_reader`], then, for
//!   what reads, every command's [`Dataset::require`] check and
//!   [`complete`] against the scenario the data belong to. Seeds: the
//!   first 200 lines of `data/contactnets-cube/tosses.csv` and two 1D ball files
//!   written with [`Dataset::to_writer`] (one complete, one with camera-rate motion).
//! - [`fuzz_blob`]: weights blobs through the host's [`ContactResidual::decode`] (every
//!   shipped shape, both storages), the core's [`decode`] at other shapes and depths,
//!   and [`Model::with_residual`] for what decodes; and `hcm train`'s residual JSON
//!   through [`TrainedResidual::read`] and [`export::blob`] (encode, decode in the
//!   core, round trip), as `hcm export` runs them. Seeds: `examples/blobs/*.hcm` and
//!   two networks written here.
//!
//! Mutations: byte and bit flips; insertions of interesting tokens (NaN, inf, −1, 0,
//! 1e308, numbers of many digits, NUL, non-UTF-8, a byte-order mark, brackets, quotes);
//! huge arrays, very long lines and deep nesting; deleted, duplicated (duplicated keys)
//! and swapped lines; truncation; the empty input; and structure-aware ones — TOML: a
//! value replaced by one of another type, an array resized, a key removed, renamed or
//! added, a value copied from elsewhere; CSV: a row with more or fewer cells, a header
//! renamed or duplicated, columns dropped, swapped or duplicated, non-numeric cells,
//! rows duplicated or reordered; blobs: shape, tags, version and sections edited,
//! section length prefixes changed, the CRC re-sealed or not, truncation and trailing
//! bytes; JSON: shape fields, vector lengths and values.
//!
//! `HCM_FUZZ_CASES=N` sets the number of cases per target (default [`DEFAULT_CASES`],
//! a few seconds per target in `--release` on two cores); `HCM_FUZZ_SEED=S` changes
//! the seed (default [`SEED`]). E.g. one million cases of the scenario target:
//!
//! ```text
//! HCM_FUZZ_CASES=1000000 cargo test --release --test commands fuzz::fuzz_scenario -- --nocapture
//! ```
//!
//! A case taking longer than [`HANG_LIMIT`] is reported as a hang (with its input) and
//! ends the process. On failure the first few failing inputs are shrunk and printed,
//! escaped, with the panic's location.

use hcm_core::residual::{decode, F32Weights, Int8Weights, Quantisation};
use hcm_host::dataset::{complete, BodyTrack, Dataset, Requirement, Run, Sample};
use hcm_host::export;
use hcm_host::identify::Physics;
use hcm_host::residual::ContactResidual;
use hcm_host::scenario::{Model, Scenario};
use hcm_host::train::{Activation, Network, TrainedResidual};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::cell::{Cell, RefCell};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, Once};
use std::time::{Duration, Instant};

/// Cases per target without `HCM_FUZZ_CASES`.
const DEFAULT_CASES: u64 = 20_000;
/// The seed without `HCM_FUZZ_SEED`.
const SEED: u64 = 0x4843_4d5f_4655_5a5a;
/// The longest an error message may be (bytes), whatever the input: messages quote at
/// most a short excerpt of it (`hcm_host::input`), never a whole line or name.
const MESSAGE_LIMIT: usize = 2_000;
/// A case running longer than this is a hang.
const HANG_LIMIT: Duration = Duration::from_secs(20);
/// Failing inputs shrunk and printed.
const SHOWN_FAILURES: usize = 4;
/// Failures kept (the lowest case numbers).
const KEPT_FAILURES: usize = 32;
/// Attempts the shrinker may make per input.
const SHRINK_BUDGET: usize = 4_000;

// ------------------------------------------------------------------------------------
// The harness: cases, outcomes, panics, hangs, totals.
// ------------------------------------------------------------------------------------

/// One fuzz case: which pipeline and seed (`lane`, `seed`) and the mutated bytes.
#[derive(Clone, Debug)]
struct Case {
    lane: usize,
    seed: usize,
    bytes: Vec<u8>,
}

/// What a reader answered (a panic is caught by the harness).
enum Outcome {
    /// Read, checked and resolved.
    Accepted,
    /// Refused at `stage` with `message`.
    Refused {
        stage: &'static str,
        message: String,
    },
}

/// `Refused` at `stage` with the error's message.
fn refused(stage: &'static str, error: impl std::fmt::Display) -> Outcome {
    Outcome::Refused {
        stage,
        message: error.to_string(),
    }
}

/// A fuzz target: how to draw a case and how to run it.
trait Target: Sync {
    /// The target's name in reports.
    fn name(&self) -> &'static str;
    /// The name of a case's pipeline and seed.
    fn label(&self, case: &Case) -> String;
    /// Draws a case.
    fn generate(&self, rng: &mut ChaCha8Rng) -> Case;
    /// Runs a case; `scratch` is a directory for readers that take a path.
    fn run(&self, case: &Case, scratch: &Path) -> Outcome;
    /// The case's input, for people.
    fn show(&self, case: &Case) -> String {
        escaped(&case.bytes, 1_500)
    }
}

/// How one case ended, as judged by the harness.
#[derive(Clone, Debug, PartialEq)]
enum Verdict {
    Accepted,
    Refused(&'static str),
    /// A panic: its message and location (and backtrace for the first few).
    Panicked(String),
    /// An error message that is empty or too long.
    BadMessage(String),
}

impl Verdict {
    /// Whether this is a failure, and which kind (for shrinking: the same kind).
    fn failure_kind(&self) -> Option<String> {
        match self {
            Verdict::Panicked(text) => {
                Some(format!("panic {}", text.lines().next().unwrap_or_default()))
            }
            Verdict::BadMessage(text) => {
                Some(text.split(':').next().unwrap_or_default().to_owned())
            }
            _ => None,
        }
    }
}

thread_local! {
    /// Set while a case runs: the panic hook then records instead of printing.
    static IN_CASE: Cell<bool> = const { Cell::new(false) };
    /// The last panic's message, location (and backtrace) on this thread.
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
    /// This thread's scratch file name (one per thread: the cases run in parallel).
    static SCRATCH_NAME: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Backtraces captured so far (only the first few: they are slow).
static BACKTRACES: AtomicUsize = AtomicUsize::new(0);

/// Installs (once) a panic hook that records the panics of fuzz cases quietly and
/// leaves every other panic to the previous hook.
fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !IN_CASE.with(Cell::get) {
                return previous(info);
            }
            let mut text = info.to_string();
            if BACKTRACES.fetch_add(1, Ordering::Relaxed) < 8 {
                let trace = std::backtrace::Backtrace::force_capture();
                let _ = write!(text, "\nbacktrace:\n{trace}");
            }
            LAST_PANIC.with(|last| *last.borrow_mut() = Some(text));
        }));
    });
}

/// Runs `case` with panics caught and judges its outcome.
fn judge<T: Target>(target: &T, case: &Case, scratch: &Path) -> Verdict {
    IN_CASE.with(|flag| flag.set(true));
    let result = catch_unwind(AssertUnwindSafe(|| target.run(case, scratch)));
    IN_CASE.with(|flag| flag.set(false));
    match result {
        Err(payload) => {
            let recorded = LAST_PANIC.with(|last| last.borrow_mut().take());
            Verdict::Panicked(recorded.unwrap_or_else(|| panic_text(payload.as_ref())))
        }
        Ok(Outcome::Accepted) => Verdict::Accepted,
        Ok(Outcome::Refused { stage, message }) => {
            if message.trim().is_empty() {
                Verdict::BadMessage(format!("empty message at {stage}: {message:?}"))
            } else if message.len() > MESSAGE_LIMIT {
                Verdict::BadMessage(format!(
                    "message of {} bytes at {stage}: {}",
                    message.len(),
                    escaped(message.as_bytes(), 400)
                ))
            } else {
                Verdict::Refused(stage)
            }
        }
    }
}

/// A panic payload's text.
fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(a panic without a message)".into())
}

/// Totals over a set of cases.
#[derive(Default)]
struct Stats {
    cases: u64,
    accepted: u64,
    refused: u64,
    panics: u64,
    bad_messages: u64,
    /// Refusals by stage, and acceptances by lane.
    tally: BTreeMap<String, u64>,
    /// (case number, verdict) of the failures with the lowest case numbers.
    failures: Vec<(u64, Verdict)>,
    /// The slowest case: (time, case number).
    slowest: (Duration, u64),
}

impl Stats {
    /// Counts case `index` of `lane`, which took `time`.
    fn add(mut self, index: u64, lane: String, verdict: Verdict, time: Duration) -> Stats {
        self.cases += 1;
        if time > self.slowest.0 {
            self.slowest = (time, index);
        }
        let key = match &verdict {
            Verdict::Accepted => {
                self.accepted += 1;
                format!("accepted, {lane}")
            }
            Verdict::Refused(stage) => {
                self.refused += 1;
                format!("refused at {stage}")
            }
            Verdict::Panicked(_) => {
                self.panics += 1;
                format!("PANIC, {lane}")
            }
            Verdict::BadMessage(_) => {
                self.bad_messages += 1;
                format!("BAD MESSAGE, {lane}")
            }
        };
        *self.tally.entry(key).or_default() += 1;
        if verdict.failure_kind().is_some() {
            self.failures.push((index, verdict));
            self.failures.sort_by_key(|(i, _)| *i);
            self.failures.truncate(KEPT_FAILURES);
        }
        self
    }

    /// Both totals together (order-independent).
    fn merge(mut self, other: Stats) -> Stats {
        self.cases += other.cases;
        self.accepted += other.accepted;
        self.refused += other.refused;
        self.panics += other.panics;
        self.bad_messages += other.bad_messages;
        for (key, count) in other.tally {
            *self.tally.entry(key).or_default() += count;
        }
        self.failures.extend(other.failures);
        self.failures.sort_by_key(|(i, _)| *i);
        self.failures.truncate(KEPT_FAILURES);
        if other.slowest.0 > self.slowest.0 {
            self.slowest = other.slowest;
        }
        self
    }
}

/// A whole number from the environment variable `name`, else `default`.
fn from_env(name: &str, default: u64) -> u64 {
    match std::env::var(name) {
        Ok(text) => text
            .replace('_', "")
            .parse()
            .unwrap_or_else(|_| panic!("{name}={text}: expected a whole number")),
        Err(_) => default,
    }
}

/// Case `index`'s own generator: the same case whichever thread draws it.
fn case_rng(seed: u64, index: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed ^ index.wrapping_mul(0x9e37_79b9_7f4a_7c15))
}

/// The cases that are running, by case number, and since when.
type Running = Mutex<BTreeMap<u64, Instant>>;

/// Draws and judges case `index`, registered in `running` meanwhile.
fn one_case<T: Target>(
    target: &T,
    seed: u64,
    index: u64,
    scratch: &Path,
    running: &Running,
) -> (String, Verdict, Duration) {
    let case = target.generate(&mut case_rng(seed, index));
    let start = Instant::now();
    running.lock().unwrap().insert(index, start);
    let verdict = judge(target, &case, scratch);
    running.lock().unwrap().remove(&index);
    (target.label(&case), verdict, start.elapsed())
}

/// Watches `running` until `done`: a case older than [`HANG_LIMIT`] is printed and
/// ends the process (a hung reader cannot be stopped from outside its thread).
fn watchdog<T: Target>(target: &T, seed: u64, running: &Running, done: &AtomicBool) {
    while !done.load(Ordering::Relaxed) {
        std::thread::sleep(Duration::from_millis(200));
        let oldest = running
            .lock()
            .unwrap()
            .iter()
            .map(|(&index, &start)| (start.elapsed(), index))
            .max();
        if let Some((elapsed, index)) = oldest.filter(|(elapsed, _)| *elapsed > HANG_LIMIT) {
            let case = target.generate(&mut case_rng(seed, index));
            eprintln!(
                "HANG in fuzz target {}: case {index} ({}) has run for {elapsed:?}; input:\n{}",
                target.name(),
                target.label(&case),
                target.show(&case)
            );
            std::process::exit(2);
        }
    }
}

/// Sets its flag when dropped.
struct Stop<'a>(&'a AtomicBool);

impl Drop for Stop<'_> {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// Runs `target` over `HCM_FUZZ_CASES` cases, prints its totals and fails on any
/// panic or bad message, or if too few cases are refused or accepted.
fn fuzz<T: Target>(target: &T) {
    install_panic_hook();
    let cases = from_env("HCM_FUZZ_CASES", DEFAULT_CASES);
    let seed = from_env("HCM_FUZZ_SEED", SEED);
    let scratch = tempfile::tempdir().expect("a scratch directory");
    let running = Running::default();
    let done = AtomicBool::new(false);
    let start = Instant::now();
    let stats = std::thread::scope(|scope| {
        scope.spawn(|| watchdog(target, seed, &running, &done));
        // Stops the watchdog however the cases end (a panic outside a case included).
        let _stop = Stop(&done);
        let stats = (0..cases)
            .into_par_iter()
            .map(|index| {
                (
                    index,
                    one_case(target, seed, index, scratch.path(), &running),
                )
            })
            .fold(Stats::default, |stats, (index, (lane, verdict, time))| {
                stats.add(index, lane, verdict, time)
            })
            .reduce(Stats::default, Stats::merge);
        stats
    });
    report(target, seed, &stats, start.elapsed());
    if !stats.failures.is_empty() {
        show_failures(target, seed, &stats, scratch.path());
    }
    assert_eq!(stats.cases, cases);
    assert_eq!((stats.panics, stats.bad_messages), (0, 0), "failures above");
    check_balance(&stats);
}

/// Prints the totals of a run.
fn report<T: Target>(target: &T, seed: u64, stats: &Stats, wall: Duration) {
    let percent = |n: u64| 100.0 * n as f64 / stats.cases.max(1) as f64;
    println!(
        "fuzz {}: {} cases (seed {seed:#x}) in {:.1} s: {} accepted ({:.1} %), {} refused \
         ({:.1} %), {} panics, {} bad messages, 0 hangs; slowest case {} ({:.1} ms)",
        target.name(),
        stats.cases,
        wall.as_secs_f64(),
        stats.accepted,
        percent(stats.accepted),
        stats.refused,
        percent(stats.refused),
        stats.panics,
        stats.bad_messages,
        stats.slowest.1,
        stats.slowest.0.as_secs_f64() * 1e3
    );
    for (key, count) in &stats.tally {
        println!("  {count:>9}  {key}");
    }
}

/// Asserts that the fuzzer exercised both sides: most cases refused, some accepted.
fn check_balance(stats: &Stats) {
    if stats.cases < 1_000 {
        return;
    }
    let share = |n: u64| n as f64 / stats.cases as f64;
    assert!(
        share(stats.refused) >= 0.3,
        "only {} of {} cases refused: the mutations hardly reach the errors",
        stats.refused,
        stats.cases
    );
    assert!(
        share(stats.accepted) >= 0.01,
        "only {} of {} cases accepted: the mutations never keep an input valid",
        stats.accepted,
        stats.cases
    );
}

/// Shrinks and prints the first failing inputs, and every kept failure's verdict.
fn show_failures<T: Target>(target: &T, seed: u64, stats: &Stats, scratch: &Path) {
    eprintln!(
        "fuzz {}: {} failing case(s); the first {} kept:",
        target.name(),
        stats.panics + stats.bad_messages,
        stats.failures.len()
    );
    for (shown, (index, verdict)) in stats.failures.iter().enumerate() {
        let case = target.generate(&mut case_rng(seed, *index));
        eprintln!("--- case {index} ({}): {verdict:?}", target.label(&case));
        if shown >= SHOWN_FAILURES {
            continue;
        }
        let small = shrink(target, &case, verdict, scratch);
        eprintln!(
            "input ({} bytes, shrunk from {}):\n{}",
            small.bytes.len(),
            case.bytes.len(),
            target.show(&small)
        );
    }
}

/// A smaller input failing the same way as `case` (chunks removed while it still
/// does, halving the chunk size down to one byte).
fn shrink<T: Target>(target: &T, case: &Case, verdict: &Verdict, scratch: &Path) -> Case {
    let kind = verdict.failure_kind();
    let mut best = case.clone();
    let mut budget = SHRINK_BUDGET;
    let mut chunk = (best.bytes.len() / 2).max(1);
    loop {
        let mut start = 0;
        while start < best.bytes.len() && budget > 0 {
            budget -= 1;
            let mut candidate = best.clone();
            let end = (start + chunk).min(candidate.bytes.len());
            candidate.bytes.drain(start..end);
            if judge(target, &candidate, scratch).failure_kind() == kind {
                best = candidate;
            } else {
                start += chunk;
            }
        }
        if chunk == 1 || budget == 0 {
            return best;
        }
        chunk /= 2;
    }
}

/// `bytes` as escaped text (`\n`, `\u{0}`, `\xff`), at most about `limit` characters.
fn escaped(bytes: &[u8], limit: usize) -> String {
    let mut out = String::new();
    for chunk in bytes.utf8_chunks() {
        out.extend(chunk.valid().chars().flat_map(char::escape_debug));
        for byte in chunk.invalid() {
            let _ = write!(out, "\\x{byte:02x}");
        }
        if out.len() > limit {
            break;
        }
    }
    if out.len() > limit {
        let cut = (0..=limit)
            .rev()
            .find(|&i| out.is_char_boundary(i))
            .unwrap_or(0);
        out.truncate(cut);
        let _ = write!(out, "… ({} bytes in all)", bytes.len());
    }
    out
}

/// The path of this thread's scratch file in `dir`, with `extension`.
fn scratch_file(dir: &Path, extension: &str) -> PathBuf {
    SCRATCH_NAME.with(|name| {
        let mut name = name.borrow_mut();
        if name.is_empty() {
            *name = format!("{:?}", std::thread::current().id())
                .chars()
                .filter(char::is_ascii_alphanumeric)
                .collect();
        }
        dir.join(format!("{name}.{extension}"))
    })
}

/// Writes `bytes` to this thread's scratch file and runs `read` on its path.
fn through_file<R>(dir: &Path, extension: &str, bytes: &[u8], read: impl FnOnce(&Path) -> R) -> R {
    let path = scratch_file(dir, extension);
    std::fs::write(&path, bytes).expect("the scratch file is written");
    read(&path)
}

/// A file of the repository.
fn repo_file(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

/// The text of a file of the repository.
fn repo_text(relative: &str) -> String {
    std::fs::read_to_string(repo_file(relative)).unwrap_or_else(|e| panic!("{relative}: {e}"))
}

// ------------------------------------------------------------------------------------
// Generic mutations of bytes and lines.
// ------------------------------------------------------------------------------------

/// Tokens inserted anywhere.
const TOKENS: &[&[u8]] = &[
    b"NaN",
    b"nan",
    b"inf",
    b"-inf",
    b"+inf",
    b"-1",
    b"0",
    b"-0",
    b"-0.0",
    b"1e308",
    b"-1e308",
    b"1e309",
    b"5e-324",
    b"1e-320",
    b"18446744073709551616",
    b"9223372036854775807",
    b"-9223372036854775808",
    b"0x7f",
    b"1_000",
    b"\0",
    b"\xef\xbb\xbf",
    b"\xff\xfe",
    b"\xc3",
    b"\xed\xa0\x80",
    b"\"",
    b"'",
    b"[",
    b"]",
    b"{",
    b"}",
    b"=",
    b",",
    b"\n",
    b"\r\n",
    b"\r",
    b"#",
    b"\\",
    b"\t",
    b" ",
    b"true",
    b"\"\"",
    b"[]",
    b"{}",
    b"[[body]]",
    b"[[contact]]",
    b"[simulation]",
    b"1979-05-27T07:32:00Z",
    b"\"\"\"",
    b"'''",
    b".",
    b"-",
    b"e",
    b"1e",
    b"null",
    b"\\u0000",
    b"\\uD800",
];

/// A value-like token: an interesting number or word, or a generated long one.
fn token(rng: &mut ChaCha8Rng) -> Vec<u8> {
    if rng.random_bool(0.85) {
        return TOKENS[rng.random_range(0..TOKENS.len())].to_vec();
    }
    let n = if rng.random_bool(0.9) {
        rng.random_range(1..400)
    } else {
        rng.random_range(400..60_000)
    };
    match rng.random_range(0..7) {
        0 => format!("1{}", "0".repeat(n)).into_bytes(),
        1 => format!("0.{}1", "0".repeat(n)).into_bytes(),
        2 => format!("-{}.{}e-{}", "9".repeat(n), "9".repeat(n), n).into_bytes(),
        3 => "x".repeat(n).into_bytes(),
        4 => format!("[{}]", "1.0, ".repeat(n)).into_bytes(),
        5 => format!("{}{}", "[".repeat(n.min(3_000)), "]".repeat(n.min(3_000))).into_bytes(),
        _ => {
            let mut bytes = vec![0; n.min(2_000)];
            rng.fill(&mut bytes[..]);
            bytes
        }
    }
}

/// The byte ranges of `bytes`' lines, each with its line ending.
fn lines(bytes: &[u8]) -> Vec<std::ops::Range<usize>> {
    let mut spans = Vec::new();
    let mut start = 0;
    for (i, &b) in bytes.iter().enumerate() {
        if b == b'\n' {
            spans.push(start..i + 1);
            start = i + 1;
        }
    }
    if start < bytes.len() {
        spans.push(start..bytes.len());
    }
    spans
}

/// A random position in `bytes` (0 for none).
fn position(rng: &mut ChaCha8Rng, bytes: &[u8]) -> usize {
    rng.random_range(0..=bytes.len())
}

/// One mutation of `bytes` that ignores their structure (or of their lines).
fn mutate_bytes(rng: &mut ChaCha8Rng, bytes: &mut Vec<u8>) {
    let spans = lines(bytes);
    let line = (!spans.is_empty()).then(|| spans[rng.random_range(0..spans.len())].clone());
    match rng.random_range(0..16) {
        0 | 1 if !bytes.is_empty() => {
            let at = rng.random_range(0..bytes.len());
            bytes[at] = rng.random();
        }
        2 if !bytes.is_empty() => {
            let at = rng.random_range(0..bytes.len());
            bytes[at] ^= 1 << rng.random_range(0..8);
        }
        3..=5 => {
            let at = position(rng, bytes);
            let token = token(rng);
            bytes.splice(at..at, token);
        }
        6 if !bytes.is_empty() => {
            let at = rng.random_range(0..bytes.len());
            let end = (at + rng.random_range(1..16)).min(bytes.len());
            bytes.drain(at..end);
        }
        7 | 8 if line.is_some() => {
            bytes.drain(line.unwrap_or_default());
        }
        9 if line.is_some() => {
            let line = line.unwrap_or_default();
            let copy = bytes[line.clone()].to_vec();
            let at = spans[rng.random_range(0..spans.len())].start;
            bytes.splice(at..at, copy);
        }
        10 if spans.len() >= 2 => {
            let (a, b) = (
                rng.random_range(0..spans.len()),
                rng.random_range(0..spans.len()),
            );
            let mut parts: Vec<Vec<u8>> = spans.iter().map(|s| bytes[s.clone()].to_vec()).collect();
            parts.swap(a, b);
            *bytes = parts.concat();
        }
        11 => {
            let at = position(rng, bytes);
            bytes.truncate(at);
        }
        12 if rng.random_bool(0.1) => bytes.clear(),
        13 if line.is_some() => replace_value(rng, bytes, line.unwrap_or_default()),
        14 if !bytes.is_empty() => {
            let at = rng.random_range(0..bytes.len());
            let end = (at + rng.random_range(1..64)).min(bytes.len());
            let copy = bytes[at..end].repeat(rng.random_range(2..200));
            bytes.splice(at..at, copy);
        }
        _ => {
            let at = position(rng, bytes);
            bytes.splice(at..at, b"\xff".iter().copied());
        }
    }
}

/// Replaces what follows the first `=` or a random `,` of `line` (a TOML value, a CSV
/// cell) up to the next separator with a token.
fn replace_value(rng: &mut ChaCha8Rng, bytes: &mut Vec<u8>, line: std::ops::Range<usize>) {
    let separators: Vec<usize> = (line.clone())
        .filter(|&i| matches!(bytes[i], b'=' | b','))
        .collect();
    let Some(&at) = separators.get(rng.random_range(0..separators.len().max(1))) else {
        return;
    };
    let end = (at + 1..line.end)
        .find(|&i| matches!(bytes[i], b',' | b'\n' | b'\r' | b'#'))
        .unwrap_or(line.end);
    let token = token(rng);
    bytes.splice(at + 1..end, token);
}

// ------------------------------------------------------------------------------------
// Structure-aware mutations of TOML documents.
// ------------------------------------------------------------------------------------

/// One step of a path into a TOML document.
#[derive(Clone, Debug)]
enum Step {
    Key(String),
    Index(usize),
}

/// A seed TOML file: its name, text, parsed document and the paths of its nodes.
struct TomlSeed {
    name: String,
    text: String,
    document: toml::Value,
    paths: Vec<Vec<Step>>,
}

impl TomlSeed {
    /// The repository's file `relative`.
    fn read(relative: &str) -> TomlSeed {
        let text = repo_text(relative);
        let document = toml::Value::Table(text.parse().expect("a seed parses"));
        let mut paths = Vec::new();
        collect_paths(&document, &mut Vec::new(), &mut paths);
        TomlSeed {
            name: relative.to_owned(),
            text,
            document,
            paths,
        }
    }

    /// The seed's text, mutated by one to four operations (on the document or the
    /// text).
    fn mutated(&self, rng: &mut ChaCha8Rng) -> Vec<u8> {
        if rng.random_bool(0.5) {
            let mut document = self.document.clone();
            for _ in 0..rng.random_range(1..=3) {
                mutate_tree(rng, &mut document, &self.paths);
            }
            let text = toml::to_string(&document);
            let mut bytes =
                text.map_or_else(|_| self.text.clone().into_bytes(), String::into_bytes);
            if rng.random_bool(0.25) {
                mutate_bytes(rng, &mut bytes);
            }
            return bytes;
        }
        let mut bytes = self.text.clone().into_bytes();
        for _ in 0..rng.random_range(1..=3) {
            mutate_bytes(rng, &mut bytes);
        }
        bytes
    }
}

/// Appends the path of every node under `value` (at `prefix`) to `out`.
fn collect_paths(value: &toml::Value, prefix: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    let children: Vec<(Step, &toml::Value)> = match value {
        toml::Value::Table(table) => table
            .iter()
            .map(|(k, v)| (Step::Key(k.clone()), v))
            .collect(),
        toml::Value::Array(items) => items
            .iter()
            .enumerate()
            .map(|(i, v)| (Step::Index(i), v))
            .collect(),
        _ => Vec::new(),
    };
    for (step, child) in children {
        prefix.push(step);
        out.push(prefix.clone());
        collect_paths(child, prefix, out);
        prefix.pop();
    }
}

/// The node at `path` under `root`, if it is still there.
fn node_at<'a>(root: &'a mut toml::Value, path: &[Step]) -> Option<&'a mut toml::Value> {
    path.iter().try_fold(root, |node, step| match (node, step) {
        (toml::Value::Table(table), Step::Key(key)) => table.get_mut(key),
        (toml::Value::Array(items), Step::Index(i)) => items.get_mut(*i),
        _ => None,
    })
}

/// Interesting floats.
const FLOATS: &[f64] = &[
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    -1.0,
    1.0,
    0.5,
    2.0,
    1e308,
    -1e308,
    5e-324,
    1e-300,
    1e9,
    -1e-9,
    f64::MAX,
    f64::MIN_POSITIVE,
    0.1,
];
/// Interesting integers.
const INTEGERS: &[i64] = &[
    0,
    1,
    -1,
    2,
    3,
    4,
    7,
    1_000_000,
    i64::MAX,
    i64::MIN,
    4_294_967_296,
];
/// Interesting strings (names the scenarios use, and others).
const WORDS: &[&str] = &[
    "",
    "ball",
    "ground",
    "cube",
    "table",
    "peg",
    "hole",
    "hertz",
    "impact",
    "variable_stiffness",
    "lankarani_nikravesh",
    "hunt_crossley",
    "sphere",
    "nan",
    "steel",
    "ü",
    "\u{0}",
    "body.ball.mass=1",
];

/// A random TOML value of any type (`depth` bounds the nesting).
fn random_value(rng: &mut ChaCha8Rng, depth: u32) -> toml::Value {
    let kinds = if depth == 0 { 5 } else { 8 };
    match rng.random_range(0..kinds) {
        0 => toml::Value::Float(FLOATS[rng.random_range(0..FLOATS.len())]),
        1 => toml::Value::Integer(INTEGERS[rng.random_range(0..INTEGERS.len())]),
        2 if rng.random_bool(0.1) => toml::Value::String("y".repeat(rng.random_range(0..5_000))),
        2 => toml::Value::String(WORDS[rng.random_range(0..WORDS.len())].into()),
        3 => toml::Value::Boolean(rng.random()),
        4 => toml::Value::Datetime("1979-05-27T07:32:00Z".parse().expect("a datetime")),
        5 => {
            let count = [0, 1, 2, 3, 4, 6][rng.random_range(0..6)];
            toml::Value::Array((0..count).map(|_| random_value(rng, depth - 1)).collect())
        }
        6 => toml::Value::Array(vec![toml::Value::Float(rng.random_range(-2.0..2.0)); 3]),
        _ => {
            let mut table = toml::Table::new();
            for _ in 0..rng.random_range(0..3) {
                let key = ["sphere", "radius", "plane", "normal", "coefficient", "zz"]
                    [rng.random_range(0..6)];
                table.insert(key.into(), random_value(rng, depth - 1));
            }
            toml::Value::Table(table)
        }
    }
}

/// One structure-aware mutation of `root` at one of `paths` (if still there).
fn mutate_tree(rng: &mut ChaCha8Rng, root: &mut toml::Value, paths: &[Vec<Step>]) {
    if paths.is_empty() {
        return;
    }
    let path = &paths[rng.random_range(0..paths.len())];
    let donor = node_at(root, &paths[rng.random_range(0..paths.len())]).map(|v| v.clone());
    let (parent_path, last) = path.split_at(path.len() - 1);
    let op = rng.random_range(0..7);
    if op >= 5 {
        // Remove or rename: act on the parent.
        let Some(parent) = node_at(root, parent_path) else {
            return;
        };
        match (parent, &last[0]) {
            (toml::Value::Table(table), Step::Key(key)) => {
                if let Some(value) = table.remove(key) {
                    if op == 6 {
                        let renamed = [format!("{key}_x"), key.to_uppercase(), String::new()]
                            [rng.random_range(0..3)]
                        .clone();
                        table.insert(renamed, value);
                    }
                }
            }
            (toml::Value::Array(items), Step::Index(i)) if *i < items.len() => {
                items.remove(*i);
            }
            _ => {}
        }
        return;
    }
    let Some(node) = node_at(root, path) else {
        return;
    };
    match op {
        0 => *node = random_value(rng, 2),
        1 => *node = same_type(rng, node),
        2 => resize(rng, node),
        3 => *node = donor.unwrap_or_else(|| random_value(rng, 1)),
        _ => match node {
            toml::Value::Table(table) => {
                table.insert("unknown_key".into(), random_value(rng, 1));
            }
            other => *other = toml::Value::Integer(INTEGERS[rng.random_range(0..INTEGERS.len())]),
        },
    }
}

/// Another value of `node`'s type (an element changed, for an array): what passes the
/// parser and reaches the checks.
fn same_type(rng: &mut ChaCha8Rng, node: &toml::Value) -> toml::Value {
    match node {
        toml::Value::Float(_) => toml::Value::Float(FLOATS[rng.random_range(0..FLOATS.len())]),
        toml::Value::Integer(_) => {
            toml::Value::Integer(INTEGERS[rng.random_range(0..INTEGERS.len())])
        }
        toml::Value::String(_) => {
            toml::Value::String(WORDS[rng.random_range(0..WORDS.len())].into())
        }
        toml::Value::Boolean(b) => toml::Value::Boolean(!b),
        toml::Value::Array(items) if !items.is_empty() => {
            let mut items = items.clone();
            let at = rng.random_range(0..items.len());
            items[at] = same_type(rng, &items[at]);
            toml::Value::Array(items)
        }
        _ => random_value(rng, 1),
    }
}

/// Changes an array's length (emptied, shortened, grown, or grown huge); another
/// node becomes an array holding it.
fn resize(rng: &mut ChaCha8Rng, node: &mut toml::Value) {
    let toml::Value::Array(items) = node else {
        *node = toml::Value::Array(vec![node.clone(); rng.random_range(0..4)]);
        return;
    };
    match rng.random_range(0..5) {
        0 => items.clear(),
        1 => {
            items.pop();
        }
        2 | 3 => {
            let copy = items.last().cloned().unwrap_or(toml::Value::Float(1.0));
            items.push(copy);
        }
        _ => {
            let copy = items.last().cloned().unwrap_or(toml::Value::Float(1.0));
            let count = if rng.random_bool(0.9) { 100 } else { 20_000 };
            items.extend(std::iter::repeat_n(copy, count));
        }
    }
}

// ------------------------------------------------------------------------------------
// Target 1: scenarios, `--set` assignments and physics files.
// ------------------------------------------------------------------------------------

/// The scenario target's pipelines.
const SCENARIO_TEXT: usize = 0;
const SCENARIO_SETS: usize = 1;
const SCENARIO_PHYSICS: usize = 2;

/// Scenario seeds, physics seeds (with the scenario each applies to), parsed.
struct ScenarioTarget {
    scenarios: Vec<TomlSeed>,
    parsed: Vec<Scenario>,
    physics: Vec<(TomlSeed, usize)>,
}

impl ScenarioTarget {
    fn new() -> ScenarioTarget {
        let scenario_files = [
            "scenarios/bouncing_ball.toml",
            "scenarios/cube_drop.toml",
            "scenarios/cube_toss.toml",
            "scenarios/flat_shot.toml",
            "scenarios/peg_in_hole.toml",
            "examples/rig/ball_on_plate.toml",
            "examples/rig/rig.toml",
            "tests/common/scenes/ball_on_plate.toml",
            "tests/common/scenes/ball_hits_block.toml",
            "tests/common/scenes/block_on_block.toml",
        ];
        let scenarios: Vec<TomlSeed> = scenario_files.iter().map(|f| TomlSeed::read(f)).collect();
        let parsed: Vec<Scenario> = scenarios
            .iter()
            .map(|seed| {
                let scenario = Scenario::parse(Path::new(&seed.name), &seed.text, &[]);
                let scenario = scenario.unwrap_or_else(|e| panic!("seed {}: {e}", seed.name));
                scenario
                    .model()
                    .unwrap_or_else(|e| panic!("seed {}: {e}", seed.name));
                scenario
            })
            .collect();
        let physics = [
            (
                "examples/blobs/bouncing_ball.pm2.toml",
                "scenarios/bouncing_ball.toml",
            ),
            (
                "examples/blobs/peg_in_hole.pm2.toml",
                "scenarios/peg_in_hole.toml",
            ),
            (
                "benches/peers/full-run/hcm_fit.toml",
                "scenarios/cube_toss.toml",
            ),
        ]
        .iter()
        .map(|(physics, scenario)| {
            let index = scenario_files
                .iter()
                .position(|f| f == scenario)
                .expect("a seed");
            let path = repo_file(physics);
            let read = Physics::read(&path).and_then(|p| p.apply(&parsed[index], &path));
            read.and_then(|s| Ok(s.model()?))
                .unwrap_or_else(|e| panic!("seed {physics}: {e}"));
            (TomlSeed::read(physics), index)
        })
        .collect();
        ScenarioTarget {
            scenarios,
            parsed,
            physics,
        }
    }

    /// One to three `key=value` assignments on `seed`'s keys (one a line), mutated.
    fn assignments(&self, rng: &mut ChaCha8Rng, seed: &TomlSeed) -> Vec<u8> {
        let mut text = String::new();
        for _ in 0..rng.random_range(1..=3) {
            let path = &seed.paths[rng.random_range(0..seed.paths.len())];
            let mut document = seed.document.clone();
            let key: Vec<String> = path
                .iter()
                .enumerate()
                .map(|(i, step)| match step {
                    Step::Key(key) => key.clone(),
                    Step::Index(index) => node_at(&mut document, &path[..=i])
                        .and_then(|node| node.get("name")?.as_str().map(str::to_owned))
                        .filter(|_| rng.random_bool(0.5))
                        .unwrap_or_else(|| index.to_string()),
                })
                .collect();
            let value = match rng.random_range(0..3) {
                0 => node_at(&mut document, path).map_or_else(String::new, |v| v.to_string()),
                1 => random_value(rng, 2).to_string(),
                _ => String::from_utf8_lossy(&token(rng)).into_owned(),
            };
            let _ = writeln!(text, "{}={value}", key.join("."));
        }
        let mut bytes = text.into_bytes();
        if rng.random_bool(0.3) {
            mutate_bytes(rng, &mut bytes);
        }
        bytes
    }
}

/// Reads scenario text (through a file when it is not UTF-8, as `hcm` would) and
/// resolves it.
fn read_scenario(bytes: &[u8], scratch: &Path, sets: &[String]) -> Outcome {
    let parsed = match std::str::from_utf8(bytes) {
        Ok(text) => Scenario::parse(Path::new("fuzz.toml"), text, sets),
        Err(_) => through_file(scratch, "toml", bytes, |path| Scenario::load(path, sets)),
    };
    match parsed {
        Err(error) => refused("scenario parse", error),
        Ok(scenario) => match scenario.model() {
            Err(error) => refused("scenario resolve", error),
            Ok(_) => Outcome::Accepted,
        },
    }
}

impl Target for ScenarioTarget {
    fn name(&self) -> &'static str {
        "scenario"
    }

    fn label(&self, case: &Case) -> String {
        match case.lane {
            SCENARIO_TEXT => format!("scenario text of {}", self.scenarios[case.seed].name),
            SCENARIO_SETS => format!("--set on {}", self.scenarios[case.seed].name),
            _ => format!("physics {}", self.physics[case.seed].0.name),
        }
    }

    fn generate(&self, rng: &mut ChaCha8Rng) -> Case {
        let lane = [
            SCENARIO_TEXT,
            SCENARIO_TEXT,
            SCENARIO_SETS,
            SCENARIO_PHYSICS,
            SCENARIO_PHYSICS,
        ][rng.random_range(0..5)];
        let (seed, bytes) = match lane {
            SCENARIO_TEXT => {
                let seed = rng.random_range(0..self.scenarios.len());
                (seed, self.scenarios[seed].mutated(rng))
            }
            SCENARIO_SETS => {
                let seed = rng.random_range(0..self.scenarios.len());
                (seed, self.assignments(rng, &self.scenarios[seed]))
            }
            _ => {
                let seed = rng.random_range(0..self.physics.len());
                (seed, self.physics[seed].0.mutated(rng))
            }
        };
        Case { lane, seed, bytes }
    }

    fn run(&self, case: &Case, scratch: &Path) -> Outcome {
        match case.lane {
            SCENARIO_TEXT => read_scenario(&case.bytes, scratch, &[]),
            SCENARIO_SETS => {
                let sets: Vec<String> = String::from_utf8_lossy(&case.bytes)
                    .lines()
                    .map(str::to_owned)
                    .collect();
                read_scenario(self.scenarios[case.seed].text.as_bytes(), scratch, &sets)
            }
            _ => through_file(scratch, "toml", &case.bytes, |path| {
                let scenario = &self.parsed[self.physics[case.seed].1];
                let physics = match Physics::read(path) {
                    Ok(physics) => physics,
                    Err(error) => return refused("physics read", error),
                };
                match physics.apply(scenario, path) {
                    Err(error) => refused("physics apply", error),
                    Ok(applied) => match applied.model() {
                        Err(error) => refused("physics resolve", error),
                        Ok(_) => Outcome::Accepted,
                    },
                }
            }),
        }
    }
}

/// Scenario TOML, `--set` assignments and physics files never panic, and every
/// refusal is a short message.
#[test]
fn fuzz_scenario() {
    fuzz(&ScenarioTarget::new());
}

// ------------------------------------------------------------------------------------
// Target 2: the measured-data CSV reader.
// ------------------------------------------------------------------------------------

/// Every command's data requirement, checked on what reads.
const REQUIREMENTS: [&Requirement; 9] = [
    &Requirement::IDENTIFY,
    &Requirement::IDENTIFY_RIGID,
    &Requirement::IDENTIFY_RIGID_SAMPLES,
    &Requirement::TRAIN_RIGID,
    &Requirement::TRAIN,
    &Requirement::DIAGNOSE,
    &Requirement::EVALUATE,
    &Requirement::INDICATORS,
    &Requirement::INDICATORS_RIGID,
];

/// A seed data file and the model of the scenario it belongs to.
struct CsvSeed {
    name: &'static str,
    text: String,
    model: Model,
}

/// The CSV seeds.
struct CsvTarget {
    seeds: Vec<CsvSeed>,
    columns: Vec<String>,
}

/// The model of the shipped scenario `file`.
fn shipped_model(file: &str) -> Model {
    let path = repo_file(&format!("scenarios/{file}"));
    Scenario::load(&path, &[])
        .and_then(|s| s.model())
        .expect("a shipped scenario resolves")
}

/// The first 200 rows of the cube tosses (and the header).
fn tosses_head() -> String {
    let text = repo_text("data/contactnets-cube/tosses.csv");
    text.lines()
        .take(201)
        .flat_map(|line| [line, "\n"])
        .collect()
}

/// A 1D ball bouncing on the ground, written by the library: complete rows, or
/// (`camera`) the motion only on every fifth row and the force on all.
fn ball_csv(camera: bool) -> String {
    let radius = 0.0127;
    let runs = (0..2)
        .map(|run| {
            let samples = (0..60)
                .map(|i| {
                    let t = i as f64 * 2e-4;
                    let mut sample = Sample::at_rest(t);
                    let depth = 1e-5 * (t * 1e4 - 30.0).abs().min(30.0) - 1e-4;
                    sample.position = [0.0, 0.0, radius + depth];
                    sample.velocity = [0.0, 0.0, -0.5 + t * 3e2];
                    sample.force = [0.0, 0.0, if depth < 0.0 { -depth * 1e7 } else { 0.0 }];
                    if camera && i % 5 != 0 {
                        sample.position = [f64::NAN; 3];
                        sample.velocity = [f64::NAN; 3];
                        sample.orientation = [f64::NAN; 4];
                        sample.angular_velocity = [f64::NAN; 3];
                    }
                    sample.torque = [f64::NAN; 3];
                    sample
                })
                .collect();
            Run {
                id: format!("{run}"),
                bodies: vec![BodyTrack {
                    body: "ball".into(),
                    samples,
                }],
            }
        })
        .collect();
    let mut out = Vec::new();
    Dataset { runs }
        .to_writer(&mut out)
        .expect("the ball data are written");
    String::from_utf8(out).expect("UTF-8")
}

impl CsvTarget {
    fn new() -> CsvTarget {
        let ball = shipped_model("bouncing_ball.toml");
        let seeds = vec![
            CsvSeed {
                name: "tosses.csv (first 200 rows)",
                text: tosses_head(),
                model: shipped_model("cube_toss.toml"),
            },
            CsvSeed {
                name: "ball.csv",
                text: ball_csv(false),
                model: ball.clone(),
            },
            CsvSeed {
                name: "ball camera.csv",
                text: ball_csv(true),
                model: ball,
            },
        ];
        for seed in &seeds {
            Dataset::from_reader(seed.name, seed.text.as_bytes()).expect("a seed reads");
        }
        let columns = hcm_host::dataset::csv_header()
            .split(',')
            .map(str::to_owned)
            .collect();
        CsvTarget { seeds, columns }
    }

    /// The seed's text with one or two structure-aware and up to two byte mutations.
    fn mutated(&self, rng: &mut ChaCha8Rng, text: &str) -> Vec<u8> {
        let mut bytes = if rng.random_bool(0.75) {
            let mut rows: Vec<Vec<String>> = text
                .lines()
                .map(|l| l.split(',').map(str::to_owned).collect())
                .collect();
            for _ in 0..rng.random_range(1..=2) {
                self.mutate_rows(rng, &mut rows);
            }
            let end = if rng.random_bool(0.1) { "\r\n" } else { "\n" };
            let mut out: String = rows.iter().map(|r| r.join(",") + end).collect();
            if rng.random_bool(0.05) {
                out.insert(0, '\u{feff}');
            }
            out.into_bytes()
        } else {
            let mut bytes = text.as_bytes().to_vec();
            mutate_bytes(rng, &mut bytes);
            bytes
        };
        for _ in 0..rng.random_range(0..=2) {
            mutate_bytes(rng, &mut bytes);
        }
        bytes
    }

    /// One structure-aware mutation of the rows (the header is row 0).
    fn mutate_rows(&self, rng: &mut ChaCha8Rng, rows: &mut [Vec<String>]) {
        let row = rng.random_range(0..rows.len());
        let data_row = rng.random_range(1..rows.len().max(2)).min(rows.len() - 1);
        let width = rows[0].len().max(1);
        let column = rng.random_range(0..width);
        match rng.random_range(0..12) {
            0 | 1 => {
                let numbers = [
                    "0", "1", "-5", "0.5", "1e3", "1e-300", "1e300", "-0.25", "100",
                ];
                let cell = match rng.random() {
                    true => numbers[rng.random_range(0..numbers.len())].to_owned(),
                    false => csv_cell(rng),
                };
                if let Some(slot) = rows[data_row].get_mut(column) {
                    *slot = cell;
                }
            }
            2 if rng.random() => rows[row].push(csv_cell(rng)),
            2 => {
                rows[row].pop();
            }
            3 => {
                let name = match rng.random_range(0..4) {
                    0 => self.columns[rng.random_range(0..self.columns.len())].clone(),
                    1 => rows[0]
                        .get(column)
                        .map_or_else(String::new, |c| c.to_uppercase()),
                    2 => "extra".into(),
                    _ => String::new(),
                };
                if let Some(slot) = rows[0].get_mut(column) {
                    *slot = name;
                }
            }
            4..=6 => {
                let other = rng.random_range(0..width);
                let op = rng.random_range(4..=6);
                for cells in rows
                    .iter_mut()
                    .filter(|r| column < r.len() && other < r.len())
                {
                    match op {
                        4 => drop(cells.remove(column)),
                        5 => cells.swap(column, other),
                        _ => cells.insert(other, cells[column].clone()),
                    }
                }
            }
            7 => {
                rows[data_row] =
                    rows[rng.random_range(1..rows.len().max(2)).min(rows.len() - 1)].clone()
            }
            8 => rows[1..].reverse(),
            9 => rows[data_row].clear(),
            10 => {
                let names = ["toss_001", "0", "ball", "cube", "table", "", "ghost", "ü"];
                let name = names[rng.random_range(0..names.len())];
                if let Some(slot) = rows[data_row].get_mut(rng.random_range(0..2)) {
                    *slot = name.into();
                }
            }
            _ => {
                let time = ["0", "-1", "0.0", "1e300", "-0", "NaN"][rng.random_range(0..6)];
                if let Some(slot) = rows[data_row].get_mut(2) {
                    *slot = time.into();
                }
            }
        }
    }
}

/// A CSV cell: a number or not, empty, quoted, or a generated token.
fn csv_cell(rng: &mut ChaCha8Rng) -> String {
    const CELLS: &[&str] = &[
        "",
        "abc",
        "NaN",
        "nan",
        "inf",
        "-inf",
        "1e400",
        "-1e400",
        "1e-400",
        "-0",
        " 1.0",
        "1.0 ",
        "\"1.0\"",
        "\"unterminated",
        "1,0",
        "0x10",
        "ü",
        "\0",
        "1e",
        ".",
        "+1",
        "1_000",
        "true",
        "\"a\"\"b\"",
    ];
    if rng.random_bool(0.9) {
        CELLS[rng.random_range(0..CELLS.len())].into()
    } else {
        String::from_utf8_lossy(&token(rng)).into_owned()
    }
}

impl Target for CsvTarget {
    fn name(&self) -> &'static str {
        "dataset"
    }

    fn label(&self, case: &Case) -> String {
        format!("CSV from {}", self.seeds[case.seed].name)
    }

    fn generate(&self, rng: &mut ChaCha8Rng) -> Case {
        let seed = rng.random_range(0..self.seeds.len());
        let bytes = self.mutated(rng, &self.seeds[seed].text);
        Case {
            lane: 0,
            seed,
            bytes,
        }
    }

    fn run(&self, case: &Case, _: &Path) -> Outcome {
        let data = match Dataset::from_reader("fuzz.csv", case.bytes.as_slice()) {
            Ok(data) => data,
            Err(error) => return refused("csv read", error),
        };
        let model = &self.seeds[case.seed].model;
        // Each command's check: its refusals must be messages too (not counted).
        for requirement in REQUIREMENTS {
            if let Err(error) = data.require("fuzz.csv", model, &[0], requirement) {
                let message = error.to_string();
                if message.trim().is_empty() || message.len() > MESSAGE_LIMIT {
                    return refused("csv require", message);
                }
            }
        }
        match complete(model, &data) {
            Ok(_) => Outcome::Accepted,
            Err(error) => refused("csv reconstruct", error),
        }
    }
}

/// Measured-data CSV never panics the reader, the requirement checks or the
/// reconstruction, and every refusal is a short message.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn fuzz_dataset() {
    fuzz(&CsvTarget::new());
}

// ------------------------------------------------------------------------------------
// Target 3: weights blobs and the trained-residual JSON.
// ------------------------------------------------------------------------------------

/// The blob target's pipelines.
const BLOB_RAW: usize = 0;
const BLOB_SEALED: usize = 1;
const BLOB_EDITED: usize = 2;
const BLOB_JSON: usize = 3;

/// A blob's fields, owned: what the structure-aware mutations edit.
#[derive(Clone)]
struct BlobParts {
    magic: [u8; 4],
    version: u16,
    shape: hcm_core::residual::blob::Shape,
    activation: u8,
    quantisation: u8,
    sections: [Vec<u8>; 3],
}

impl BlobParts {
    /// The fields of a valid blob.
    fn of(blob: &[u8]) -> BlobParts {
        let body = &blob[..blob.len() - 4];
        let (c, _) = postcard::take_from_bytes::<hcm_core::residual::blob::BlobContents<'_>>(body)
            .expect("a seed blob");
        BlobParts {
            magic: c.magic,
            version: c.version,
            shape: c.shape,
            activation: c.activation,
            quantisation: c.quantisation,
            sections: [
                c.normalisation.to_vec(),
                c.envelope.to_vec(),
                c.layers.to_vec(),
            ],
        }
    }

    /// The blob, as the encoder lays it out (header, then each section's varint length
    /// and bytes), with section `prefix.0`'s length written as `prefix.1` if given,
    /// sealed with its CRC-32.
    fn sealed(&self, prefix: Option<(usize, Vec<u8>)>) -> Vec<u8> {
        let header = (
            self.magic,
            self.version,
            self.shape,
            self.activation,
            self.quantisation,
        );
        let mut body = postcard::to_allocvec(&header).expect("a header");
        for (i, section) in self.sections.iter().enumerate() {
            match &prefix {
                Some((at, bytes)) if *at == i => body.extend_from_slice(bytes),
                _ => body.extend(varint(section.len() as u64)),
            }
            body.extend_from_slice(section);
        }
        let crc = hcm_core::residual::crc32(&body);
        body.extend_from_slice(&crc.to_le_bytes());
        body
    }

    /// One structure-aware edit.
    fn edit(&mut self, rng: &mut ChaCha8Rng) {
        const SIZES: &[u32] = &[0, 1, 2, 3, 4, 5, 6, 8, 13, 16, 32, 48, 1 << 31, u32::MAX];
        let size = SIZES[rng.random_range(0..SIZES.len())];
        let section = rng.random_range(0..3);
        match rng.random_range(0..10) {
            0 => self.shape.inputs = size,
            1 => self.shape.width = size,
            2 => self.shape.outputs = size,
            3 => self.shape.hidden_layers = size,
            4 if rng.random() => self.activation = [0, 1, 2, 255][rng.random_range(0..4)],
            4 => self.quantisation = [0, 1, 2, 255][rng.random_range(0..4)],
            5 if rng.random() => self.version = [0, 1, 2, 4, u16::MAX][rng.random_range(0..5)],
            5 => self.magic[rng.random_range(0..4)] ^= 0x20,
            6 if rng.random() => {
                let keep = self.sections[section]
                    .len()
                    .saturating_sub(rng.random_range(1..9));
                self.sections[section].truncate(keep);
            }
            6 => self.sections[section]
                .extend((0..rng.random_range(1..9)).map(|_| rng.random::<u8>())),
            7 | 8 => put_f32(rng, &mut self.sections[section]),
            _ if rng.random() => self.sections.swap(section, (section + 1) % 3),
            _ => {
                let layers = &mut self.sections[2];
                if !layers.is_empty() {
                    let at = rng.random_range(0..layers.len());
                    layers[at] = 0x80;
                }
            }
        }
    }
}

/// `value` as a postcard varint (LEB128).
fn varint(mut value: u64) -> Vec<u8> {
    let mut out = Vec::new();
    loop {
        let byte = (value & 0x7f) as u8;
        value >>= 7;
        if value == 0 {
            out.push(byte);
            return out;
        }
        out.push(byte | 0x80);
    }
}

/// Overwrites 4 aligned bytes of `bytes` with an interesting `f32`.
fn put_f32(rng: &mut ChaCha8Rng, bytes: &mut [u8]) {
    const VALUES: &[f32] = &[
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        0.0,
        -0.0,
        -1.0,
        f32::MAX,
        f32::MIN,
        1e-45,
        1e30,
        -1e30,
    ];
    if bytes.len() >= 4 {
        let at = rng.random_range(0..bytes.len() / 4) * 4;
        let value = VALUES[rng.random_range(0..VALUES.len())];
        bytes[at..at + 4].copy_from_slice(&value.to_le_bytes());
    }
}

/// One byte-level mutation of a binary blob.
fn mutate_blob_bytes(rng: &mut ChaCha8Rng, bytes: &mut Vec<u8>) {
    match rng.random_range(0..6) {
        0 => mutate_bytes(rng, bytes),
        1 => put_f32(rng, bytes),
        2 => {
            let extra: Vec<u8> = (0..rng.random_range(1..64)).map(|_| rng.random()).collect();
            bytes.extend(extra);
        }
        3 if !bytes.is_empty() => {
            let at = rng.random_range(0..bytes.len());
            bytes[at] ^= 1 << rng.random_range(0..8);
        }
        4 if !bytes.is_empty() => {
            let at = rng.random_range(0..bytes.len());
            bytes[at] = [0x00, 0x7f, 0x80, 0xff][rng.random_range(0..4)];
        }
        _ => {
            let at = position(rng, bytes);
            bytes.truncate(at);
        }
    }
}

/// A 3-`width`-…-`outputs` network with small deterministic weights.
fn network(inputs: usize, width: usize, outputs: usize, hidden: usize) -> Network {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut sizes = vec![inputs];
    sizes.extend(std::iter::repeat_n(width, hidden));
    sizes.push(outputs);
    let mut values =
        |n: usize| -> Vec<f64> { (0..n).map(|_| rng.random_range(-0.5..0.5)).collect() };
    let layers = sizes
        .windows(2)
        .map(|p| (values(p[0] * p[1]), values(p[1])))
        .collect();
    Network {
        inputs,
        width,
        outputs,
        hidden_layers: hidden,
        activation: Activation::Tanh,
        layers,
        input_mean: vec![0.0; inputs],
        input_scale: vec![1.0; inputs],
        output_mean: vec![0.0; outputs],
        output_scale: vec![2.0; outputs],
        envelope_min: vec![-1.0; inputs],
        envelope_max: vec![1.0; inputs],
        envelope_tolerance: vec![0.1; inputs],
    }
}

/// Seed blobs (and their fields), seed JSON files, and the models blobs attach to.
struct BlobTarget {
    blobs: Vec<(String, Vec<u8>, BlobParts)>,
    json: Vec<(String, serde_json::Value)>,
    models: Vec<Model>,
}

impl BlobTarget {
    fn new() -> BlobTarget {
        let blobs = [
            "bouncing_ball.f32.hcm",
            "bouncing_ball.int8.hcm",
            "peg_in_hole.f32.hcm",
            "peg_in_hole.int8.hcm",
        ]
        .iter()
        .map(|name| {
            let bytes =
                std::fs::read(repo_file(&format!("examples/blobs/{name}"))).expect("a blob");
            ContactResidual::decode(&bytes).expect("a seed blob decodes");
            let parts = BlobParts::of(&bytes);
            assert_eq!(
                parts.sealed(None),
                bytes,
                "{name}: the fields re-encode exactly"
            );
            (name.to_string(), bytes, parts)
        })
        .collect();
        let json = [("force 3-16-16-1", 3, 16, 1, 2), ("tiny 2-3-1", 2, 3, 1, 1)]
            .iter()
            .map(|&(name, inputs, width, outputs, hidden)| {
                let net = network(inputs, width, outputs, hidden);
                let trained = TrainedResidual::new(0, net.clone(), net);
                (
                    name.to_string(),
                    serde_json::to_value(&trained).expect("JSON"),
                )
            })
            .collect();
        let models = vec![
            shipped_model("bouncing_ball.toml"),
            shipped_model("peg_in_hole.toml"),
        ];
        BlobTarget {
            blobs,
            json,
            models,
        }
    }

    /// A blob case of `lane` from seed `seed`.
    fn blob_case(&self, rng: &mut ChaCha8Rng, lane: usize, seed: usize) -> Vec<u8> {
        let (_, bytes, parts) = &self.blobs[seed];
        match lane {
            BLOB_RAW => {
                let mut bytes = bytes.clone();
                for _ in 0..rng.random_range(1..=3) {
                    mutate_blob_bytes(rng, &mut bytes);
                }
                bytes
            }
            BLOB_SEALED => {
                let mut body = bytes[..bytes.len() - 4].to_vec();
                for _ in 0..rng.random_range(1..=2) {
                    mutate_blob_bytes(rng, &mut body);
                }
                let crc = hcm_core::residual::crc32(&body);
                body.extend_from_slice(&crc.to_le_bytes());
                body
            }
            _ => {
                let mut parts = parts.clone();
                let prefix = rng.random_bool(0.15).then(|| {
                    let section = rng.random_range(0..3);
                    let length = parts.sections[section].len() as u64;
                    let changed = [
                        0,
                        1,
                        length.saturating_sub(1),
                        length + 1,
                        length + 4,
                        u64::MAX,
                    ][rng.random_range(0..6)];
                    (section, varint(changed))
                });
                for _ in 0..rng.random_range(usize::from(prefix.is_none())..=2) {
                    parts.edit(rng);
                }
                let mut blob = parts.sealed(prefix);
                if rng.random_bool(0.1) {
                    mutate_blob_bytes(rng, &mut blob);
                }
                blob
            }
        }
    }

    /// A JSON case from seed `seed`: structure-aware or byte mutations.
    fn json_case(&self, rng: &mut ChaCha8Rng, seed: usize) -> Vec<u8> {
        let mut value = self.json[seed].1.clone();
        let structured = rng.random_bool(0.6);
        if structured {
            for _ in 0..rng.random_range(1..=2) {
                mutate_json(rng, &mut value);
            }
        }
        let mut bytes = if rng.random() {
            serde_json::to_vec_pretty(&value)
        } else {
            serde_json::to_vec(&value)
        }
        .expect("JSON");
        for _ in 0..rng.random_range(usize::from(!structured)..=2) {
            mutate_bytes(rng, &mut bytes);
        }
        bytes
    }

    /// Decodes a blob in the host and the core, evaluates and attaches what decodes.
    fn decode(&self, bytes: &[u8]) -> Outcome {
        let core = [
            decode::<2, 3, 1, 1, F32Weights>(bytes).err(),
            decode::<3, 16, 1, 3, Int8Weights>(bytes).err(),
            decode::<13, 32, 6, 1, F32Weights>(bytes).err(),
            decode::<5, 16, 5, 2, Int8Weights>(bytes).err(),
        ];
        if let Some(error) = core.iter().flatten().find(|e| !short(&e.to_string())) {
            return refused("blob core decode", error);
        }
        let residual = match ContactResidual::decode(bytes) {
            Ok(residual) => residual,
            Err(error) => return refused("blob decode", error),
        };
        let _ = residual.correction(1e-4, -0.1, -0.5);
        let _ = residual.wrench(&[0.0; 13]);
        let mut errors = Vec::new();
        for model in &self.models {
            if let Err(message) = model.with_residual(0, residual.clone(), "fuzz.hcm") {
                errors.push(message);
            }
        }
        match errors
            .into_iter()
            .find(|m| !short(m) || self.models.len() == 1)
        {
            Some(message) => refused("blob attach", message),
            None => Outcome::Accepted,
        }
    }
}

/// Whether `message` is non-empty and at most [`MESSAGE_LIMIT`] bytes.
fn short(message: &str) -> bool {
    !message.trim().is_empty() && message.len() <= MESSAGE_LIMIT
}

/// One structure-aware mutation of a trained-residual JSON document.
fn mutate_json(rng: &mut ChaCha8Rng, root: &mut serde_json::Value) {
    use serde_json::{json, Value};
    const VECTORS: &[&str] = &[
        "input_mean",
        "input_scale",
        "output_mean",
        "output_scale",
        "envelope_min",
        "envelope_max",
        "envelope_tolerance",
        "layers",
    ];
    const SIZES: &[&str] = &["inputs", "width", "outputs", "hidden_layers"];
    let numbers = [
        json!(0),
        json!(1),
        json!(3),
        json!(4),
        json!(16),
        json!(-1),
        json!(1e20),
        json!(u64::MAX),
        json!("3"),
        Value::Null,
        json!(0.5),
    ];
    let interesting = [
        json!(0.0),
        json!(-1.0),
        json!(1e38),
        json!(1e39),
        json!(-1e39),
        json!(1e308),
        json!(5e-324),
        json!(-0.0),
        json!("x"),
        Value::Null,
    ];
    let net = ["network", "int8_network"][rng.random_range(0..2)];
    let pick =
        |rng: &mut ChaCha8Rng, values: &[Value]| values[rng.random_range(0..values.len())].clone();
    match rng.random_range(0..7) {
        0 => root[net][SIZES[rng.random_range(0..4)]] = pick(rng, &numbers),
        1 => root[["contact", "version"][rng.random_range(0..2)]] = pick(rng, &numbers),
        2 | 3 => {
            let key = VECTORS[rng.random_range(0..VECTORS.len())];
            let (layer, part) = (rng.random_range(0..3), rng.random_range(0..2));
            let vector = match &mut root[net][key] {
                layers if key == "layers" => layers.get_mut(layer).and_then(|l| l.get_mut(part)),
                vector => Some(vector),
            };
            let Some(vector) = vector else {
                return;
            };
            if let Value::Array(items) = vector {
                match rng.random_range(0..5) {
                    0 => items.clear(),
                    1 => drop(items.pop()),
                    2 => items.push(json!(0.25)),
                    3 if !items.is_empty() => {
                        let at = rng.random_range(0..items.len());
                        items[at] = pick(rng, &interesting);
                    }
                    _ => *vector = pick(rng, &interesting),
                }
            }
        }
        4 => {
            let key = VECTORS[rng.random_range(0..VECTORS.len())];
            root[net].as_object_mut().map(|o| o.remove(key));
        }
        5 => {
            root[net]["activation"] =
                json!(["relu", "tanh", "sigmoid", "Tanh", ""][rng.random_range(0..5)])
        }
        _ => root["format"] = json!(["hcm-residual", "other", ""][rng.random_range(0..3)]),
    }
}

impl Target for BlobTarget {
    fn name(&self) -> &'static str {
        "blob"
    }

    fn label(&self, case: &Case) -> String {
        match case.lane {
            BLOB_RAW => format!("raw bytes of {}", self.blobs[case.seed].0),
            BLOB_SEALED => format!("bytes of {}, CRC re-sealed", self.blobs[case.seed].0),
            BLOB_EDITED => format!("fields of {} edited", self.blobs[case.seed].0),
            _ => format!("residual JSON of {}", self.json[case.seed].0),
        }
    }

    fn generate(&self, rng: &mut ChaCha8Rng) -> Case {
        let lane = rng.random_range(BLOB_RAW..=BLOB_JSON);
        let (seed, bytes) = if lane == BLOB_JSON {
            let seed = rng.random_range(0..self.json.len());
            (seed, self.json_case(rng, seed))
        } else {
            let seed = rng.random_range(0..self.blobs.len());
            (seed, self.blob_case(rng, lane, seed))
        };
        Case { lane, seed, bytes }
    }

    fn run(&self, case: &Case, scratch: &Path) -> Outcome {
        if case.lane != BLOB_JSON {
            return self.decode(&case.bytes);
        }
        through_file(scratch, "json", &case.bytes, |path| {
            let trained = match TrainedResidual::read(path) {
                Ok(trained) => trained,
                Err(error) => return refused("json read", error),
            };
            for quantisation in [Quantisation::F32, Quantisation::Int8] {
                if let Err(error) = export::blob(&trained, quantisation) {
                    return refused("json export", error);
                }
            }
            Outcome::Accepted
        })
    }

    fn show(&self, case: &Case) -> String {
        if case.lane == BLOB_JSON {
            return escaped(&case.bytes, 1_500);
        }
        let hex: String = case
            .bytes
            .iter()
            .take(600)
            .map(|b| format!("{b:02x}"))
            .collect();
        format!(
            "{} bytes, hex: {hex}{}",
            case.bytes.len(),
            if case.bytes.len() > 600 { "…" } else { "" }
        )
    }
}

/// Weights blobs and trained-residual JSON never panic the decoders or the exporter,
/// and every refusal is a short message.
#[test]
fn fuzz_blob() {
    fuzz(&BlobTarget::new());
}
