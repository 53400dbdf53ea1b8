"""PM1: a scenario's noisy runs and their S1/S2 split (``hcm generate``)."""

from __future__ import annotations

from typing import Callable, NamedTuple, Optional

from . import _hcm
from .dataset import Dataset
from .scenario import Scenario

#: ``progress(stage, done, total)``: called as long work advances (from a worker
#: thread, with Python's lock held); raising in it stops the work.
Progress = Optional[Callable[[str, int, int], None]]


class Experiment(NamedTuple):
    """PM1's runs: all of them, the training set S1 and the validation set S2."""

    runs: Dataset
    s1: Dataset
    s2: Dataset


def generate(scenario: Scenario, runs: int, seed: int = 1, progress: Progress = None) -> Experiment:
    """``runs`` noisy runs of every condition of ``scenario`` (the paper's Eq 18–19),
    drawn with ``seed``, split into S1 and S2: the three files ``hcm generate --runs RUNS
    --seed SEED`` writes, byte for byte (``Dataset.to_csv``)."""
    all_runs, s1, s2 = _hcm.generate(scenario._scenario, runs, seed, progress)
    return Experiment(Dataset(all_runs), Dataset(s1), Dataset(s2))
