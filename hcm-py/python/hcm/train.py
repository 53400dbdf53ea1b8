"""The residual network: trained (``hcm train``) and exported (``hcm export``)."""

from __future__ import annotations

import json
import os
from typing import Union

from . import _hcm
from .dataset import Dataset
from .experiment import Progress
from .identify import Physics
from .scenario import Scenario

PathLike = Union[str, "os.PathLike[str]"]


class Residual:
    """A trained residual: the f32 network, its int8 twin and how training went."""

    def __init__(self, compiled: _hcm.Residual) -> None:
        self._residual = compiled

    def blob(self, weights: str = "f32") -> bytes:
        """The blob ``hcm export --weights WEIGHTS`` writes (``"f32"`` or ``"int8"``)."""
        return self._residual.blob(weights)

    @property
    def report(self) -> dict[str, float]:
        """rows, epochs, best_epoch, train_rms and validation_rms (N), seconds, and the
        int8 twin's RMS against the f32 network rounded and tuned (N)."""
        return dict(self._residual.report())

    def to_json(self) -> dict:
        """The contents of ``hcm train``'s residual.json."""
        return json.loads(self._residual.to_json())

    def write(self, path: PathLike) -> None:
        """Writes residual.json (atomically)."""
        self._residual.write(os.fspath(path))


def train(
    scenario: Scenario,
    physics: Physics,
    data: Dataset,
    contact: int = 0,
    epochs: int = 200,
    int8_epochs: int = 20,
    seed: int = 1,
    progress: Progress = None,
) -> Residual:
    """Trains the residual of ``contact`` on ``data`` (S1) against ``physics`` (PM2):
    ``hcm train`` with the same defaults, on force data."""
    return Residual(
        _hcm.train(
            scenario._scenario, physics._physics, data._dataset, contact, epochs,
            int8_epochs, seed, progress,
        )
    )
