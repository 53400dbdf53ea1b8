"""PM2: a law fitted to force data (``hcm identify``), and physics files."""

from __future__ import annotations

import json
import os
from typing import Optional, Union

from . import _hcm
from .dataset import Dataset
from .experiment import Progress
from .scenario import Scenario

PathLike = Union[str, "os.PathLike[str]"]


class Physics:
    """A physics file: each contact's law and parameters (SI units), the standard
    errors of a least-squares fit, how the fit went, and the file's text."""

    def __init__(self, compiled: _hcm.Physics) -> None:
        self._physics = compiled
        self._contents = json.loads(compiled.to_json())

    @classmethod
    def read(cls, path: PathLike) -> "Physics":
        """Reads a physics file (``hcm identify --out``, a diagnosis's extended.toml)."""
        return cls(_hcm.Physics.read(os.fspath(path)))

    @property
    def law(self) -> str:
        """The first contact's law."""
        return self._contents["contact"][0]["law"]

    @property
    def parameters(self) -> dict[str, float]:
        """The first contact's parameters by name (SI units)."""
        return dict(self._contents["contact"][0]["parameters"])

    @property
    def standard_errors(self) -> dict[str, float]:
        """One-σ standard errors of the fitted parameters (least squares; else empty)."""
        return dict(self._physics.standard_errors)

    @property
    def fit(self) -> dict:
        """How the fit went: method, data, runs, events, samples, force_rms (N),
        curve_rms (N), seconds, notes."""
        return dict(self._contents.get("fit", {}))

    @property
    def contents(self) -> dict:
        """The whole file: ``contact`` (list), ``body``, ``sets``, ``fit``."""
        return self._contents

    def to_toml(self, comment: str = "physics from hcm") -> str:
        """The file's text, ``comment`` on its first line."""
        return self._physics.to_toml(comment)

    def write(self, path: PathLike, comment: str = "physics from hcm") -> None:
        """Writes the file (atomically)."""
        self._physics.write(os.fspath(path), comment)

    def __repr__(self) -> str:
        values = ", ".join(f"{k}={v:.6e}" for k, v in self.parameters.items())
        return f"Physics({self.law!r}, {values})"


def identify(
    scenario: Scenario,
    data: Dataset,
    law: Optional[str] = None,
    method: str = "lsq",
    fitness: str = "curve",
    seed: int = 1,
    population: int = 60,
    generations: int = 150,
    contact: int = 0,
    progress: Progress = None,
) -> Physics:
    """Fits ``law`` to the force samples of ``contact`` in ``data`` (1D data), by least
    squares (``"lsq"``) or the genetic algorithm (``"ga"``, with its ``fitness``):
    ``hcm identify --law LAW --method METHOD`` with the same defaults."""
    return Physics(
        _hcm.identify(
            scenario._scenario, data._dataset, law, method, fitness, seed,
            population, generations, contact, progress,
        )
    )
