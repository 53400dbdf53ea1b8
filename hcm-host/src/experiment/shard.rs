//! One machine's share of an experiment: `--shard I/N` makes runs
//! [⌊T·I/N⌋, ⌊T·(I+1)/N⌋) of the T runs, the same bytes those runs have in the whole
//! experiment (run i draws from its own stream (seed, i)); `--merge` joins the shards'
//! files into the whole experiment's OUT, S1 and S2, byte for byte.
//!
//! On a Slurm job array the shard defaults to the array task's: index
//! `SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN` (the minimum 0 when unset) of
//! `SLURM_ARRAY_TASK_COUNT`, so `sbatch --array=0-3` runs the same command four times.

use std::fmt;
use std::ops::Range;

/// Shard `index` (from 0) of `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which shard, 0 ≤ index < count.
    pub index: usize,
    /// How many shards.
    pub count: usize,
}

impl Shard {
    /// Parses `I/N` (0 ≤ I < N).
    pub fn parse(text: &str) -> Result<Shard, String> {
        let (index, count) = text
            .split_once('/')
            .ok_or_else(|| format!("`{text}` is not I/N (e.g. 0/4: the first of four shards)"))?;
        let number = |part: &str, what: &str| {
            part.trim()
                .parse::<usize>()
                .map_err(|_| format!("`{text}`: {what} `{part}` is not a whole number ≥ 0"))
        };
        let (index, count) = (number(index, "I")?, number(count, "N")?);
        if count == 0 || index >= count {
            return Err(format!(
                "`{text}`: shards are numbered 0 to N − 1 of N ≥ 1 (e.g. 0/4 … 3/4)"
            ));
        }
        Ok(Shard { index, count })
    }

    /// The shard a Slurm job array's task stands for, if the variables are set (and
    /// what is wrong with them, if they do not make a shard).
    pub fn from_slurm(variable: impl Fn(&str) -> Option<String>) -> Option<Result<Shard, String>> {
        let id = variable("SLURM_ARRAY_TASK_ID")?;
        let count = variable("SLURM_ARRAY_TASK_COUNT")?;
        let min = variable("SLURM_ARRAY_TASK_MIN").unwrap_or_else(|| "0".into());
        let parsed = (id.trim().parse::<usize>(), min.trim().parse::<usize>());
        Some(match parsed {
            (Ok(id), Ok(min)) if id >= min => Shard::parse(&format!("{}/{}", id - min, count.trim()))
                .map_err(|e| format!("SLURM_ARRAY_TASK_ID {id}, SLURM_ARRAY_TASK_MIN {min}, SLURM_ARRAY_TASK_COUNT {count}: {e}")),
            _ => Err(format!(
                "SLURM_ARRAY_TASK_ID `{id}` and SLURM_ARRAY_TASK_MIN `{min}` do not give a task \
                 index (whole numbers, ID ≥ MIN); give --shard I/N"
            )),
        })
    }

    /// The shard a command makes: `given` (`--shard`), else a Slurm array task's from
    /// the process's environment — unless it merges shards (`merging`), which is no
    /// shard's work. None: the whole job.
    pub fn chosen(given: Option<Shard>, merging: bool) -> Result<Option<Shard>, String> {
        match (given, merging) {
            (Some(shard), _) => Ok(Some(shard)),
            (None, false) => Shard::from_slurm(|name| std::env::var(name).ok()).transpose(),
            (None, true) => Ok(None),
        }
    }

    /// The run indices of this shard among `total` runs.
    pub fn range(self, total: usize) -> Range<usize> {
        let bound = |i: usize| ((total as u128 * i as u128) / self.count as u128) as usize;
        bound(self.index)..bound(self.index + 1)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shards_cover_every_run_once_in_order() {
        for (total, count) in [(1000, 4), (10, 3), (3, 5), (0, 2), (7, 1)] {
            let mut next = 0;
            for index in 0..count {
                let range = Shard { index, count }.range(total);
                assert_eq!(range.start, next);
                assert!(range.len() <= total / count + 1);
                next = range.end;
            }
            assert_eq!(next, total);
        }
    }

    #[test]
    fn bad_shards_are_refused_by_name() {
        assert_eq!(Shard::parse("2/4"), Ok(Shard { index: 2, count: 4 }));
        for bad in ["4/4", "1/0", "x/2", "2", "-1/3"] {
            let error = Shard::parse(bad).unwrap_err();
            assert!(error.contains(bad), "{error}");
        }
    }

    #[test]
    fn a_slurm_array_task_is_a_shard() {
        fn env<'a>(vars: &'a [(&str, &str)]) -> impl Fn(&str) -> Option<String> + 'a {
            move |name| {
                vars.iter()
                    .find(|(k, _)| *k == name)
                    .map(|(_, v)| v.to_string())
            }
        }
        assert_eq!(Shard::from_slurm(env(&[])), None);
        let task = [
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
        ];
        assert_eq!(
            Shard::from_slurm(env(&task)),
            Some(Ok(Shard { index: 2, count: 4 }))
        );
        let bad = [
            ("SLURM_ARRAY_TASK_ID", "7"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ];
        assert!(Shard::from_slurm(env(&bad))
            .unwrap()
            .unwrap_err()
            .contains("SLURM_ARRAY_TASK_ID 7"));
    }
}
