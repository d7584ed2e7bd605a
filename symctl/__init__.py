"""symctl: neural implementations of delayed optimal controllers, derived in closed form.

The public names, in the order of the paper's pipeline.
"""

from symctl.delay import AugmentedSystem, augment
from symctl.errors import (
    DimensionError,
    NotStabilizableError,
    ParameterError,
    ParseError,
    SymctlError,
    SymctlTypeError,
)
from symctl.factor import Factorization, factor
from symctl.lqr import Gains, lqr_gains
from symctl.plant import DiscretePlant, Linearization, MuscleModel, discretize, linearize
from symctl.realization import (
    Realization,
    controllable_canonical,
    general_realization,
    observable_canonical,
    random_realization,
)
from symctl.symbols import z
from symctl.transfer import DiscreteTF, controller_tf, prove_controller_tf

__version__ = "0.1.0"

__all__ = [
    "AugmentedSystem",
    "DimensionError",
    "DiscretePlant",
    "DiscreteTF",
    "Factorization",
    "Gains",
    "Linearization",
    "MuscleModel",
    "NotStabilizableError",
    "ParameterError",
    "ParseError",
    "Realization",
    "SymctlError",
    "SymctlTypeError",
    "augment",
    "controllable_canonical",
    "controller_tf",
    "discretize",
    "factor",
    "general_realization",
    "linearize",
    "lqr_gains",
    "observable_canonical",
    "prove_controller_tf",
    "random_realization",
    "z",
]
