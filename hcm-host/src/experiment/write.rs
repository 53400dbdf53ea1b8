//! `hcm generate`'s outputs: every run to OUT and each to S1 or S2 beside it, streamed as
//! the runs are made, the three files appearing together at the end or not at all.

use super::{check_split, ExperimentError, Generation, Holdout, Shard};
use crate::dataset::{Dataset, Run, RunWriter};
use crate::output::{commit, ensure_space, StagedFile};
use crate::scenario::Scenario;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// How many runs went where.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Written {
    /// All runs (OUT).
    pub runs: usize,
    /// Runs in S1.
    pub training: usize,
    /// Runs in S2.
    pub validation: usize,
}

/// An experiment checked and about to be written: its three outputs staged (hidden
/// temporaries beside them, headers written), nothing at the destinations yet.
pub struct ExperimentWriter<'a> {
    scenario: &'a Scenario,
    generation: Generation,
    seed: u64,
    /// OUT, S1, S2.
    writers: [RunWriter<StagedFile>; 3],
    estimated_bytes: u64,
}

impl<'a> ExperimentWriter<'a> {
    /// Prepares `runs_per_condition` runs of every condition of `scenario`, seeded with
    /// `seed`, for OUT, S1 and S2 at `paths`. Refuses before any long work: a split that
    /// leaves S1 or S2 empty, a directory or special file at a destination, an output
    /// larger than the free space at OUT (estimated from the first run of each
    /// condition).
    pub fn new(
        scenario: &'a Scenario,
        runs_per_condition: usize,
        seed: u64,
        paths: [&Path; 3],
    ) -> Result<Self, ExperimentError> {
        let generation = Generation::new(scenario, runs_per_condition, seed)?;
        check_split(scenario, runs_per_condition)?;
        let mut writers = Vec::with_capacity(3);
        for path in paths {
            let file = StagedFile::create(path)?;
            writers.push(RunWriter::new(file, &path.display().to_string())?);
        }
        let writers: [RunWriter<StagedFile>; 3] = writers
            .try_into()
            .unwrap_or_else(|_| unreachable!("three paths, three writers"));
        let per_run = bytes_per_run(&generation)?;
        let runs = generation.total_runs() as u64;
        // OUT holds every run, and S1 and S2 together hold every run again.
        let estimated_bytes = per_run.saturating_mul(runs).saturating_mul(2);
        ensure_space(paths[0], estimated_bytes).map_err(|space| ExperimentError::TooLarge {
            runs,
            per_run,
            space,
        })?;
        Ok(ExperimentWriter {
            scenario,
            generation,
            seed,
            writers,
            estimated_bytes,
        })
    }

    /// The runs to be made.
    pub fn generation(&self) -> &Generation {
        &self.generation
    }

    /// About how many bytes the three files will take together.
    pub fn estimated_bytes(&self) -> u64 {
        self.estimated_bytes
    }

    /// Makes every run and writes it to OUT and to S1 or S2, then moves the three files
    /// into place together, reporting [`crate::progress::Stage::Generate`] to `progress`
    /// (a step per simulated run).
    pub fn write(
        self,
        progress: &dyn crate::progress::Progress,
    ) -> Result<Written, ExperimentError> {
        let (generation, mut router) = self.router();
        generation.for_each(progress, |_, run| router.route(&run))?;
        router.commit()
    }

    /// Writes the runs of shard files (`--shard`'s outputs, in shard order) as this
    /// experiment's OUT, S1 and S2: the bytes [`Self::write`] writes, without simulating
    /// the runs again. Each file must hold the next runs of the experiment in order
    /// (their ids), and each file's first run must be the one this scenario and seed
    /// make (simulated again to check); together, every run.
    pub fn merge(self, shards: &[PathBuf]) -> Result<Written, ExperimentError> {
        let (generation, mut router) = self.router();
        let total = generation.total_runs();
        let mut next = 0;
        for path in shards {
            let data = Dataset::read(path)?;
            let shown = path.display();
            for (k, run) in data.runs.iter().enumerate() {
                let expected = (next < total).then(|| generation.run_id(next));
                if expected.as_deref() != Some(run.id.as_str()) {
                    return Err(merge_error(format!(
                        "{shown}: holds run `{}` where {} was expected; give every shard \
                         of `hcm generate --shard I/N` once, in shard order (0/N first)",
                        run.id,
                        match expected {
                            Some(id) => format!("run `{id}` (run {next} of {total})"),
                            None => format!("no more runs (the experiment has {total})"),
                        }
                    )));
                }
                if k == 0 && !same_run(run, &generation.run(next)?)? {
                    return Err(merge_error(format!(
                        "{shown}: run `{}` is not the one this scenario and --seed make \
                         (simulated again): make the shards and merge them with the same \
                         --scenario, --set, --runs and --seed",
                        run.id
                    )));
                }
                router.route(run)?;
                next += 1;
            }
        }
        if next < total {
            return Err(merge_error(format!(
                "the shards hold {next} of the experiment's {total} runs: run `{}` and \
                 those after it are missing (a shard not given?)",
                generation.run_id(next)
            )));
        }
        router.commit()
    }

    /// The generation and where its runs go.
    fn router(self) -> (Generation, Router<'a>) {
        let ExperimentWriter {
            scenario,
            generation,
            seed,
            writers,
            ..
        } = self;
        let holdout = Holdout::new(scenario, generation.total_runs(), seed);
        let written = Written {
            runs: 0,
            training: 0,
            validation: 0,
        };
        (
            generation,
            Router {
                writers,
                holdout,
                written,
            },
        )
    }
}

/// OUT, S1 and S2 being written, and which of S1 and S2 each run goes to.
struct Router<'a> {
    writers: [RunWriter<StagedFile>; 3],
    holdout: Holdout<'a>,
    written: Written,
}

impl Router<'_> {
    /// Writes the next run of the experiment to OUT and to S1 or S2.
    fn route(&mut self, run: &Run) -> Result<(), ExperimentError> {
        let [all, training, validation] = &mut self.writers;
        all.write_run(run)?;
        self.written.runs += 1;
        if self.holdout.takes(&run.id) {
            self.written.validation += 1;
            validation.write_run(run)?;
        } else {
            self.written.training += 1;
            training.write_run(run)?;
        }
        Ok(())
    }

    /// Moves the three files into place together.
    fn commit(self) -> Result<Written, ExperimentError> {
        let mut finished = Vec::with_capacity(3);
        for writer in self.writers {
            finished.push(writer.finish()?.finish()?);
        }
        commit(finished)?;
        Ok(self.written)
    }
}

/// Makes the runs of `shard` of the experiment of `scenario` (`runs_per_condition` runs
/// of each condition, `seed`) and writes them to `out`, atomically, in the
/// measured-data format: the rows these runs have in the whole experiment's OUT.
/// Refuses what the whole experiment would (too few runs for the split) before any
/// run is made. Returns the runs written.
pub fn write_shard(
    scenario: &Scenario,
    (runs_per_condition, seed): (usize, u64),
    shard: Shard,
    out: &Path,
    progress: &dyn crate::progress::Progress,
) -> Result<usize, ExperimentError> {
    let generation = Generation::new(scenario, runs_per_condition, seed)?;
    check_split(scenario, runs_per_condition)?;
    let mut writer = RunWriter::new(StagedFile::create(out)?, &out.display().to_string())?;
    let mut written = 0;
    let runs = shard.range(generation.total_runs());
    generation.for_each_in(runs, progress, |_, run| -> Result<(), ExperimentError> {
        writer.write_run(&run)?;
        written += 1;
        Ok(())
    })?;
    commit(vec![writer.finish()?.finish()?])?;
    Ok(written)
}

/// Whether two runs write the same rows.
fn same_run(a: &Run, b: &Run) -> Result<bool, ExperimentError> {
    let text = |run: &Run| -> Result<Vec<u8>, ExperimentError> {
        let mut writer = RunWriter::new(Vec::new(), "(comparison)")?;
        writer.write_run(run)?;
        Ok(writer.finish()?)
    };
    Ok(text(a)? == text(b)?)
}

fn merge_error(message: String) -> ExperimentError {
    ExperimentError::Merge(message)
}

/// Bytes of CSV per run, averaged over the conditions: the first run of each, simulated
/// and written to nowhere.
fn bytes_per_run(generation: &Generation) -> Result<u64, ExperimentError> {
    let mut total = 0;
    for condition in 0..generation.conditions() {
        let run = generation.run(condition * generation.runs_per_condition())?;
        let mut counter = RunWriter::new(Counter(0), "(estimate)")?;
        counter.write_run(&run)?;
        total += counter.finish()?.0;
    }
    Ok(total / generation.conditions() as u64)
}

/// A writer that only counts bytes.
struct Counter(u64);

impl Write for Counter {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        self.0 += bytes.len() as u64;
        Ok(bytes.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::{generate, split};

    #[test]
    fn streamed_files_equal_the_dataset_written_whole() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/bouncing_ball.toml");
        let ball = Scenario::load(&path, &[]).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let paths = ["all.csv", "s1.csv", "s2.csv"].map(|n| dir.path().join(n));
        let writer =
            ExperimentWriter::new(&ball, 12, 5, paths.each_ref().map(|p| p.as_path())).unwrap();
        let estimate = writer.estimated_bytes();
        let written = writer.write(&crate::progress::Silent).unwrap();
        assert_eq!(
            (written.runs, written.training, written.validation),
            (12, 11, 1)
        );

        let data = generate(&ball, 12, 5, &crate::progress::Silent).unwrap();
        let sets = split(&ball, data.clone(), 5);
        for (set, path) in [&data, &sets.training, &sets.validation].iter().zip(&paths) {
            let mut whole = Vec::new();
            set.to_writer(&mut whole).unwrap();
            assert_eq!(std::fs::read(path).unwrap(), whole, "{}", path.display());
        }
        let actual: u64 = paths.iter().map(|p| p.metadata().unwrap().len()).sum();
        let ratio = estimate as f64 / actual as f64;
        assert!(
            (0.95..1.05).contains(&ratio),
            "estimate {estimate}, wrote {actual}"
        );
    }
}
