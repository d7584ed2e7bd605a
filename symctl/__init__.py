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
from symctl.lqr import Gains, lqr_gains
from symctl.plant import DiscretePlant, Linearization, MuscleModel, discretize, linearize
from symctl.symbols import z
from symctl.transfer import DiscreteTF, controller_tf, prove_controller_tf

__version__ = "0.1.0"

__all__ = [
    "AugmentedSystem",
    "DimensionError",
    "DiscretePlant",
    "DiscreteTF",
    "Gains",
    "Linearization",
    "MuscleModel",
    "NotStabilizableError",
    "ParameterError",
    "ParseError",
    "SymctlError",
    "SymctlTypeError",
    "augment",
    "controller_tf",
    "discretize",
    "linearize",
    "lqr_gains",
    "prove_controller_tf",
    "z",
]
