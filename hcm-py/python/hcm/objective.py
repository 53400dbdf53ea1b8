"""A fit's objective for optimisers outside hcm (DEAP, nevergrad, Ray, Dask)."""

from __future__ import annotations

import numpy as np

from . import _hcm
from .dataset import Dataset
from .scenario import Scenario


class Objective:
    """What ``hcm identify --law LAW --method ga --fitness FITNESS`` minimises, over the
    law's free parameters: ``fitness(params)`` takes candidates as rows ``[m, p]`` (the
    columns in ``parameters`` order, SI units) and returns their ``m`` values, computed in
    parallel in one call. The values do not depend on how a batch is split, so a
    cluster can map it in any chunks.

    >>> objective = Objective(ball, s1, "lankarani_nikravesh")
    >>> objective.fitness(np.array([[6.9e9, 1.49, 0.93]]))   # N (curve RMS)
    """

    def __init__(self, scenario: Scenario, data: Dataset, law: str, fitness: str = "curve", contact: int = 0) -> None:
        self._objective = _hcm.Objective(scenario._scenario, data._dataset, law, fitness, contact)

    @property
    def parameters(self) -> list[str]:
        """The free parameters' names: a candidate's columns."""
        return self._objective.parameters

    @property
    def bounds(self) -> np.ndarray:
        """``[p, 2]``: each free parameter's interval (the scenario's identify bounds)."""
        return np.array(self._objective.bounds, dtype=np.float64).reshape(-1, 2)

    def fitness(self, params) -> np.ndarray:
        """The fitness of each candidate: ``params`` ``[m, p]`` (or one candidate ``[p]``)
        → ``[m]`` (curve: RMS N; indicators: summed squared relative errors; +inf where a
        replay fails)."""
        array = np.asarray(params, dtype=np.float64)
        single = array.ndim == 1
        values = self._objective.values(np.ascontiguousarray(array.reshape(1, -1) if single else array))
        return values[0] if single else values

    __call__ = fitness
