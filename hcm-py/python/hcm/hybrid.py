"""The hybrid contact model, physics plus the exported residual, through the core."""

from __future__ import annotations

import os
from typing import NamedTuple, Union

import numpy as np

from . import _hcm
from .laws import ArrayLike, broadcast
from .scenario import Scenario


class HybridForce(NamedTuple):
    """One batch's result: the hybrid force and the physics alone (N, float32), and
    whether the residual took part (in contact, inside its envelope)."""

    force: np.ndarray
    physics: np.ndarray
    residual_used: np.ndarray


class HybridModel:
    """A scenario's contact (its law and effects) plus an exported residual blob,
    evaluated in f32 by the core's own code: the arithmetic a controller runs."""

    def __init__(self, scenario: Scenario, blob: Union[bytes, str, "os.PathLike[str]"], contact: int = 0) -> None:
        if not isinstance(blob, (bytes, bytearray)):
            with open(blob, "rb") as file:
                blob = file.read()
        self._model = _hcm.HybridModel(scenario._scenario, bytes(blob), contact)

    @property
    def int8(self) -> bool:
        """Whether the residual's weights are int8 (else f32)."""
        return self._model.int8

    def force(self, delta: ArrayLike, delta_dot: ArrayLike, approach_speed: ArrayLike) -> HybridForce:
        """The normal force at indentation δ (m), rate δ̇ (m/s) and approach speed
        δ̇0 (m/s), broadcast together, each a fresh contact. One call evaluates every
        state in Rust: far faster than a Python loop of single states."""
        shape, (d, r, a) = broadcast(np.float32, delta, delta_dot, approach_speed)
        force, physics, used = self._model.force(d, r, a)
        return HybridForce(force.reshape(shape), physics.reshape(shape), used.reshape(shape))
