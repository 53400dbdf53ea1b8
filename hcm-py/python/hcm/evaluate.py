"""The paper's table (``hcm evaluate``): PM2 and the HCM against held-out runs."""

from __future__ import annotations

import json
from typing import Optional

from . import _hcm
from .dataset import Dataset
from .experiment import Progress
from .identify import Physics
from .scenario import Scenario


def evaluate(
    scenario: Scenario,
    physics: Physics,
    data: Dataset,
    residual: Optional[bytes] = None,
    contact: int = 0,
    progress: Progress = None,
) -> list[dict]:
    """PM2 (``physics``), and the HCM when ``residual`` (a blob) is given, on ``data``
    (S2): per condition, the four indicators' S2 means, each model's values and Eq 20
    errors — ``hcm evaluate --json``'s tables."""
    text = _hcm.evaluate(
        scenario._scenario, physics._physics, data._dataset,
        None if residual is None else bytes(residual), contact, progress,
    )
    return json.loads(text)
