"""hcm from Python: hybrid contact modelling over numpy arrays.

The compiled module ``hcm._hcm`` is hcm's own Rust (hcm-host and hcm-core); this
package turns Python values into the arrays it takes and wraps what it returns, so a
figure printed here is the one the ``hcm`` command prints for the same input.

    import hcm
    law = hcm.Law("hertz", stiffness=6.86e9, exponent=1.5)
    law.force([10e-6, 20e-6], 0.0)          # N, one per indentation

Errors hcm refuses an input for are raised as :class:`HcmError`, with the message
the ``hcm`` command prints after ``error:``.
"""

import os as _os

from ._hcm import HcmError, __version__, set_threads
from .dataset import Dataset
from .diagnose import Diagnosis, diagnose
from .evaluate import evaluate
from .experiment import Experiment, generate
from .hybrid import HybridModel
from .identify import Physics, identify
from .laws import Law, LawInfo, Parameter, laws
from .objective import Objective
from .power import PowerResult, PowerStudy, power
from .predict import Prediction, predict
from .scenario import Scenario
from .simulate import simulate
from .train import Residual, train

__all__ = [
    "Dataset",
    "Diagnosis",
    "Experiment",
    "HcmError",
    "HybridModel",
    "Law",
    "LawInfo",
    "Objective",
    "Parameter",
    "Physics",
    "PowerResult",
    "PowerStudy",
    "Prediction",
    "Residual",
    "Scenario",
    "__version__",
    "diagnose",
    "evaluate",
    "generate",
    "identify",
    "laws",
    "power",
    "predict",
    "set_threads",
    "simulate",
    "train",
]

# The CLI's HCM_THREADS, read once as the package loads.
if _os.environ.get("HCM_THREADS"):
    set_threads(int(_os.environ["HCM_THREADS"]))
