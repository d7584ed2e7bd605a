"""symctl: neural implementations of delayed optimal controllers, derived in closed form.

The public names, in the order of the paper's pipeline.
"""

from symctl.check import RealizationCheck, check_realization
from symctl.compatibility import (
    CompatibilityResult,
    ControllerCompatibility,
    brute_force_compatibility,
    check_compatibility,
    controller_compatibility,
)
from symctl.delay import AugmentedSystem, augment
from symctl.delaygraph import DelayAssignment, DelayGraph
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
from symctl.structure import Block, Structure, ifp_structure, same_structure
from symctl.symbols import z
from symctl.transfer import DiscreteTF, controller_tf, prove_controller_tf

__version__ = "0.1.0"

__all__ = [
    "AugmentedSystem",
    "Block",
    "CompatibilityResult",
    "ControllerCompatibility",
    "DelayAssignment",
    "DelayGraph",
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
    "RealizationCheck",
    "Structure",
    "SymctlError",
    "SymctlTypeError",
    "augment",
    "brute_force_compatibility",
    "check_compatibility",
    "check_realization",
    "controllable_canonical",
    "controller_compatibility",
    "controller_tf",
    "discretize",
    "factor",
    "general_realization",
    "ifp_structure",
    "linearize",
    "lqr_gains",
    "observable_canonical",
    "prove_controller_tf",
    "random_realization",
    "same_structure",
    "z",
]
