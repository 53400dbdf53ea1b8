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

from ._hcm import HcmError, __version__
from .dataset import Dataset
from .hybrid import HybridModel
from .laws import Law, LawInfo, Parameter, laws
from .scenario import Scenario
from .simulate import simulate

__all__ = [
    "Dataset",
    "HcmError",
    "HybridModel",
    "Law",
    "LawInfo",
    "Parameter",
    "Scenario",
    "__version__",
    "laws",
    "simulate",
]
