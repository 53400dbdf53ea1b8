"""The normal contact laws by name, evaluated element-wise over arrays."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Tuple, Union

import numpy as np

from . import _hcm

ArrayLike = Union[float, "np.typing.ArrayLike"]


@dataclass(frozen=True)
class Parameter:
    """One parameter of a law: its name, SI unit and meaning."""

    name: str
    unit: str
    meaning: str


@dataclass(frozen=True)
class LawInfo:
    """One law of the catalogue (``hcm laws``)."""

    name: str
    source: str
    formula: str
    parameters: Tuple[Parameter, ...]


def laws() -> list[LawInfo]:
    """Every normal law hcm has, in the core's order, with its parameters."""
    return [
        LawInfo(name, source, formula, tuple(Parameter(*p) for p in parameters))
        for name, source, formula, parameters in _hcm.law_catalogue()
    ]


def broadcast(dtype, *values) -> tuple[tuple[int, ...], list[np.ndarray]]:
    """The common shape of ``values`` and each of them broadcast to it, flattened,
    contiguous, of ``dtype``."""
    arrays = np.broadcast_arrays(*(np.asarray(v, dtype=dtype) for v in values))
    shape = arrays[0].shape
    return shape, [np.ascontiguousarray(a.reshape(-1), dtype=dtype) for a in arrays]


class Law:
    """A normal law with its parameters (SI units), checked as hcm checks a file's.

    >>> law = Law("hertz", stiffness=6.86e9, exponent=1.5)
    >>> float(law.force(10e-6, 0.0))  # N
    """

    def __init__(self, name: str, **parameters: float) -> None:
        self._law = _hcm.Law(name, [(k, float(v)) for k, v in parameters.items()])

    @property
    def name(self) -> str:
        """The law's name (``hcm laws``)."""
        return self._law.name

    @property
    def parameters(self) -> dict[str, float]:
        """The parameters by name, in field order (SI units)."""
        return dict(self._law.parameters)

    def force(
        self,
        delta: ArrayLike,
        delta_dot: ArrayLike = 0.0,
        approach_speed: ArrayLike = 1.0,
        dtype=np.float64,
    ) -> np.ndarray:
        """Normal force f_n (N) at indentation δ (m), rate δ̇ (m/s) and approach speed
        δ̇0 (m/s), broadcast together; 0 out of contact (δ ≤ 0). ``dtype=np.float32``
        evaluates in the controller's f32 (the result is still returned as float64)."""
        shape, (d, r, a) = broadcast(np.float64, delta, delta_dot, approach_speed)
        f32 = np.dtype(dtype) == np.float32
        return self._law.force(d, r, a, f32).reshape(shape)

    def __repr__(self) -> str:
        values = ", ".join(f"{k}={v!r}" for k, v in self.parameters.items())
        return f"Law({self.name!r}, {values})"
