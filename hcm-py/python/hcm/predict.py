"""Recorded tosses replayed and scored (``hcm predict``)."""

from __future__ import annotations

import os
from typing import Optional, Union

import numpy as np

from . import _hcm
from .dataset import Dataset
from .experiment import Progress
from .scenario import Scenario

PathLike = Union[str, "os.PathLike[str]"]


class Prediction:
    """The tosses replayed from their window start: the predicted trajectories, each
    toss's scores (position error in % of the body's width, rotation error in °) and the
    frozen pose's on the same frames."""

    def __init__(self, compiled: _hcm.Prediction) -> None:
        self._prediction = compiled

    @property
    def data(self) -> Dataset:
        """The predicted trajectories (``hcm predict --out``)."""
        return Dataset(self._prediction.dataset())

    @property
    def scores(self) -> dict[str, np.ndarray]:
        """Per toss: ``run``, ``frames``, ``position_error`` (%), ``rotation_error`` (°),
        ``frozen_position_error``, ``frozen_rotation_error``."""
        rows = self._prediction.scores()
        names = ("run", "frames", "position_error", "rotation_error", "frozen_position_error", "frozen_rotation_error")
        columns = list(zip(*rows)) if rows else [()] * len(names)
        return {
            name: np.array(values, dtype=str if name == "run" else (np.int64 if name == "frames" else np.float64))
            for name, values in zip(names, columns)
        }

    @property
    def summary(self) -> dict[str, tuple[float, float, float]]:
        """``(mean, std, median)`` over the tosses, as ``hcm predict``'s table."""
        keys = ("position_error", "rotation_error", "frozen_position_error", "frozen_rotation_error")
        return dict(zip(keys, self._prediction.summary()))

    def write_scores(self, path: PathLike) -> None:
        """Writes each toss's scores as ``hcm predict --scores`` does."""
        self._prediction.write_scores(os.fspath(path))


def predict(scenario: Scenario, data: Dataset, first: Optional[int] = None, progress: Progress = None) -> Prediction:
    """Replays the tosses of ``data`` (their first ``first``) with ``scenario``'s physics
    (``scenario.with_physics(...)`` for a fitted one): ``hcm predict``."""
    return Prediction(_hcm.predict(scenario._scenario, data._dataset, first, progress))
