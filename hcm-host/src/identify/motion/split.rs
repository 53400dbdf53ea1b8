//! The documented, deterministic split of tosses into a training part (what the fit
//! sees) and a held-out part (what it is judged on): by toss number, the digits that end
//! a run id (`toss_042` is 42). Even numbers train, odd numbers are held out — half and
//! half, spread evenly over the session the tosses were recorded in, and the same split
//! whatever the file's order. A run id without a number counts by its position in the
//! file instead.

use crate::dataset::Dataset;

/// Which part a toss belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// Fitted on.
    Training,
    /// Judged on, never fitted.
    HeldOut,
}

/// The number of a toss: the digits that end its run id, or `position` without any.
pub(crate) fn toss_number(id: &str, position: usize) -> u64 {
    let digits = id.len() - id.trim_end_matches(|c: char| c.is_ascii_digit()).len();
    id[id.len() - digits..].parse().unwrap_or(position as u64)
}

/// The part of the toss with run id `id` at `position` in its file.
pub fn part_of(id: &str, position: usize) -> Part {
    if toss_number(id, position).is_multiple_of(2) {
        Part::Training
    } else {
        Part::HeldOut
    }
}

/// `data` split into (training, held-out), each in the file's order.
pub fn split_tosses(data: &Dataset) -> (Dataset, Dataset) {
    let mut training = Dataset::default();
    let mut held_out = Dataset::default();
    for (position, run) in data.runs.iter().enumerate() {
        match part_of(&run.id, position) {
            Part::Training => training.runs.push(run.clone()),
            Part::HeldOut => held_out.runs.push(run.clone()),
        }
    }
    (training, held_out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tosses_split_by_the_number_that_ends_their_id() {
        assert_eq!(toss_number("toss_042", 7), 42);
        assert_eq!(toss_number("toss_000", 7), 0);
        assert_eq!(toss_number("run", 7), 7);
        assert_eq!(part_of("toss_042", 1), Part::Training);
        assert_eq!(part_of("toss_043", 0), Part::HeldOut);
        assert_eq!(part_of("first", 0), Part::Training);
    }
}
