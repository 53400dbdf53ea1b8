"""The diagnosis's power study (``hcm power``): how strong an effect must be before
``hcm diagnose`` names it on a scenario, and how often it names one with nothing hidden.

Every data set is independent, so a study maps over workers: ``study.rows(start, stop)``
for each of ``study.chunks(n)`` on Ray, Dask or a process pool, then
``study.join(parts)`` gives the rows and table one call (and ``hcm power``) gives, byte for
byte. A study pickles as its options, and is rebuilt where it lands.
"""

from __future__ import annotations

import csv
import io
import os
from typing import Dict, List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from . import _hcm
from .experiment import Progress
from .scenario import Scenario

#: The default strengths, as shares of the peak force (``hcm power --levels``).
LEVELS = (0.005, 0.01, 0.03)


class PowerResult(NamedTuple):
    """A study's rows (the CSV ``hcm power`` writes to OUT) and table (OUT.md)."""

    csv: str
    table: str

    @property
    def columns(self) -> Dict[str, object]:
        """The rows by column: numbers as float arrays, flags as bool arrays, names as
        lists of strings."""
        lines = self.csv.splitlines()[1:]
        rows = list(csv.DictReader(io.StringIO("\n".join(lines))))
        out: Dict[str, object] = {}
        for name in rows[0].keys() if rows else []:
            values = [r[name] for r in rows]
            if name in ("exact", "wrong"):
                out[name] = np.array([v == "true" for v in values])
            elif name in ("effect", "parameter", "answer", "named"):
                out[name] = values
            else:
                out[name] = np.array([float(v) for v in values])
        return out

    def write(self, path: "os.PathLike[str] | str") -> None:
        """Writes the rows to ``path`` and the table beside it (``power.csv`` →
        ``power.md``), as ``hcm power --out path`` does."""
        path = os.fspath(path)
        table = os.path.splitext(path)[0] + ".md"
        for target, text in ((path, self.csv), (table, self.table)):
            temporary = f"{target}.tmp-{os.getpid()}"
            with open(temporary, "w", encoding="utf-8", newline="") as f:
                f.write(text)
            os.replace(temporary, target)


class PowerStudy:
    """A power study of ``scenario`` with ``hcm power``'s options (``effects=None``: every
    effect the 1D diagnosis names; ``base``: ``"scenario"`` or ``"fitted"``). Building it
    generates the first seed's data with nothing hidden, to scale the strengths."""

    def __init__(
        self,
        scenario: Scenario,
        runs: int = 16,
        seeds: int = 10,
        seed: int = 1,
        levels: Sequence[float] = LEVELS,
        effects: Optional[Sequence[str]] = None,
        base: str = "scenario",
        contact: int = 0,
        holdout: float = 0.25,
    ) -> None:
        self._options = (scenario, runs, seeds, seed, tuple(levels),
                         tuple(effects or ()), base, contact, holdout)
        self._study = _hcm.PowerStudy(scenario._scenario, runs, seeds, seed, list(levels),
                                      list(effects or ()), base, contact, holdout)

    def __reduce__(self):
        return (PowerStudy, self._options)

    def __len__(self) -> int:
        return len(self._study)

    @property
    def key(self) -> str:
        """The line that names the study in its files (a shard of another study is
        refused by it)."""
        return self._study.key

    def chunks(self, count: int) -> List[Tuple[int, int]]:
        """``count`` contiguous ranges of data sets, ``hcm power --shard I/N``'s."""
        total = len(self)
        return [(total * i // count, total * (i + 1) // count) for i in range(count)]

    def rows(self, start: int = 0, stop: Optional[int] = None,
             progress: Progress = None) -> str:
        """Data sets ``start`` to ``stop`` made and diagnosed: the file ``hcm power
        --shard`` writes for them."""
        return self._study.rows(start, len(self) if stop is None else stop, progress)

    def join(self, parts: Sequence[str]) -> PowerResult:
        """The rows of ``parts`` (in order, every data set once) and the table."""
        return PowerResult(*self._study.join(list(parts)))


def power(scenario: Scenario, runs: int = 16, seeds: int = 10, seed: int = 1,
          levels: Sequence[float] = LEVELS, effects: Optional[Sequence[str]] = None,
          base: str = "scenario", contact: int = 0, holdout: float = 0.25,
          progress: Progress = None) -> PowerResult:
    """The whole study in one call (its data sets in parallel): what ``hcm power`` writes
    with the same options."""
    study = PowerStudy(scenario, runs, seeds, seed, levels, effects, base, contact, holdout)
    return study.join([study.rows(progress=progress)])
