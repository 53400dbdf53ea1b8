"""The simulator, as ``hcm simulate`` runs it."""

from __future__ import annotations

from . import _hcm
from .dataset import Dataset
from .scenario import Scenario


def simulate(scenario: Scenario) -> Dataset:
    """Simulates ``scenario`` once; its trajectory (run ``0``) with the contact force on
    each body at every sample, the data ``hcm simulate --out`` writes."""
    return Dataset(_hcm.simulate(scenario._scenario))
