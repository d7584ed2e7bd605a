"""symctl: neural implementations of delayed optimal controllers, derived in closed form.

The public names, in the order of the paper's pipeline.
"""

from symctl.check import RealizationCheck, check_realization
from symctl.circuit import Circuit, CircuitSystem, Neuron, Synapse
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
from symctl.simulate import (
    BatchResponse,
    NonlinearCheck,
    Response,
    closed_loop_response,
    ifp_realization,
    nonlinear_check,
    open_loop_response,
    pulse,
    simulate_batch,
    simulate_realization,
)
from symctl.structure import Block, Structure, ifp_structure, same_structure
from symctl.symbols import z
from symctl.transfer import DiscreteTF, controller_tf, prove_controller_tf

__version__ = "0.1.0"

__all__ = [
    "AugmentedSystem",
    "BatchResponse",
    "Block",
    "Circuit",
    "CircuitSystem",
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
    "Neuron",
    "NonlinearCheck",
    "NotStabilizableError",
    "ParameterError",
    "ParseError",
    "Realization",
    "RealizationCheck",
    "Response",
    "Structure",
    "SymctlError",
    "SymctlTypeError",
    "Synapse",
    "augment",
    "brute_force_compatibility",
    "check_compatibility",
    "check_realization",
    "closed_loop_response",
    "controllable_canonical",
    "controller_compatibility",
    "controller_tf",
    "discretize",
    "factor",
    "general_realization",
    "ifp_realization",
    "ifp_structure",
    "linearize",
    "lqr_gains",
    "nonlinear_check",
    "observable_canonical",
    "open_loop_response",
    "prove_controller_tf",
    "pulse",
    "random_realization",
    "same_structure",
    "simulate_batch",
    "simulate_realization",
    "z",
]
