"""What the physics gets wrong, and why (``hcm diagnose`` on force data)."""

from __future__ import annotations

import json
import os
from typing import Optional, Union

from . import _hcm
from .dataset import Dataset
from .experiment import Progress
from .identify import Physics
from .scenario import Scenario

PathLike = Union[str, "os.PathLike[str]"]


class Diagnosis:
    """A diagnosis: its answer, the named causes with their intervals and shares, the
    held-out gain, the extended model and the report."""

    def __init__(self, compiled: _hcm.Diagnosis) -> None:
        self._diagnosis = compiled
        self.contents: dict = json.loads(compiled.json)

    @property
    def answer(self) -> str:
        """The answer as diagnosis.json gives it (e.g. ``unexplained (100 %)``)."""
        return self.contents["answer"]

    @property
    def summary(self) -> str:
        """The report's answer in a sentence (its ``**Answer: …**`` line)."""
        line = next(l for l in self.report.splitlines() if l.startswith("**Answer:"))
        return line.strip("*").strip()

    @property
    def causes(self) -> list[dict]:
        """The named causes: effect, kind, parameters, 95 % intervals (``ci``), share."""
        return self.contents["causes"]

    @property
    def gain(self):
        """The extended model against the base on held-out runs."""
        return self.contents["gain"]

    @property
    def report(self) -> str:
        """The report (Markdown) ``hcm diagnose`` prints."""
        return self._diagnosis.report

    @property
    def extended(self) -> Physics:
        """The extended model (extended.toml): the base law re-fitted with the effects."""
        return Physics(self._diagnosis.extended())


def diagnose(
    scenario: Scenario,
    physics: Physics,
    data: Dataset,
    contact: int = 0,
    seed: int = 1,
    holdout: float = 0.25,
    chance: bool = False,
    first: Optional[int] = None,
    out: Optional[PathLike] = None,
    progress: Progress = None,
) -> Diagnosis:
    """Diagnoses ``contact`` under ``physics`` (the base model) on ``data``: ``hcm
    diagnose --physics`` with the same defaults. With ``out``, also writes the
    command's directory (report.md, diagnosis.json, extended.toml, figures)."""
    return Diagnosis(
        _hcm.diagnose(
            scenario._scenario, physics._physics, data._dataset, contact, seed, holdout,
            chance, first, None if out is None else os.fspath(out), progress,
        )
    )
