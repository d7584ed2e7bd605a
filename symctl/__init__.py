"""symctl: neural implementations of delayed optimal controllers, derived in closed form.

The public names, in the order of the paper's pipeline. They are loaded on first use
(PEP 562), so ``import symctl`` stays quick and a script pays only for what it uses.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

from symctl.errors import (
    DimensionError,
    NotStabilizableError,
    ParameterError,
    ParseError,
    SymctlError,
    SymctlTypeError,
)

__version__ = "0.1.0"

_LOCATIONS = {
    "RealizationCheck": "symctl.check",
    "check_realization": "symctl.check",
    "Circuit": "symctl.circuit",
    "CircuitSystem": "symctl.circuit",
    "Neuron": "symctl.circuit",
    "Synapse": "symctl.circuit",
    "CompatibilityResult": "symctl.compatibility",
    "ControllerCompatibility": "symctl.compatibility",
    "brute_force_compatibility": "symctl.compatibility",
    "check_compatibility": "symctl.compatibility",
    "controller_compatibility": "symctl.compatibility",
    "AugmentedSystem": "symctl.delay",
    "augment": "symctl.delay",
    "DelayAssignment": "symctl.delaygraph",
    "DelayGraph": "symctl.delaygraph",
    "DimensionError": "symctl.errors",
    "NotStabilizableError": "symctl.errors",
    "ParameterError": "symctl.errors",
    "ParseError": "symctl.errors",
    "SymctlError": "symctl.errors",
    "SymctlTypeError": "symctl.errors",
    "Factorization": "symctl.factorization",
    "factor": "symctl.factorization",
    "FiringPatterns": "symctl.firing",
    "FiringSummary": "symctl.firing",
    "circuit_firing": "symctl.firing",
    "Gains": "symctl.lqr",
    "lqr_gains": "symctl.lqr",
    "DiscretePlant": "symctl.plant",
    "Linearization": "symctl.plant",
    "MuscleModel": "symctl.plant",
    "discretize": "symctl.plant",
    "linearize": "symctl.plant",
    "Realization": "symctl.realization",
    "controllable_canonical": "symctl.realization",
    "general_realization": "symctl.realization",
    "observable_canonical": "symctl.realization",
    "random_realization": "symctl.realization",
    "BatchResponse": "symctl.simulate",
    "NonlinearCheck": "symctl.simulate",
    "Response": "symctl.simulate",
    "closed_loop_response": "symctl.simulate",
    "ifp_realization": "symctl.simulate",
    "nonlinear_check": "symctl.simulate",
    "open_loop_response": "symctl.simulate",
    "pulse": "symctl.simulate",
    "simulate_batch": "symctl.simulate",
    "simulate_realization": "symctl.simulate",
    "Block": "symctl.structure",
    "Structure": "symctl.structure",
    "ifp_structure": "symctl.structure",
    "same_structure": "symctl.structure",
    "PaperResults": "symctl.report",
    "derive_paper": "symctl.report",
    "z": "symctl.symbols",
    "DiscreteTF": "symctl.transfer",
    "controller_tf": "symctl.transfer",
    "prove_controller_tf": "symctl.transfer",
}

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
    "FiringPatterns",
    "FiringSummary",
    "Gains",
    "Linearization",
    "MuscleModel",
    "Neuron",
    "NonlinearCheck",
    "NotStabilizableError",
    "PaperResults",
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
    "circuit_firing",
    "closed_loop_response",
    "controllable_canonical",
    "controller_compatibility",
    "controller_tf",
    "derive_paper",
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


_SUBMODULES = ("latex",)  # modules reached as attributes: ``symctl.latex.export(...)``


def __getattr__(name: str):
    if name in _SUBMODULES:
        return importlib.import_module(f"symctl.{name}")
    module = _LOCATIONS.get(name)
    if module is None:
        raise AttributeError(f"module 'symctl' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__) | set(_SUBMODULES))


if TYPE_CHECKING:  # static tools see the eager imports
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
    from symctl.factorization import Factorization, factor
    from symctl.firing import FiringPatterns, FiringSummary, circuit_firing
    from symctl.lqr import Gains, lqr_gains
    from symctl.plant import DiscretePlant, Linearization, MuscleModel, discretize, linearize
    from symctl.realization import (
        Realization,
        controllable_canonical,
        general_realization,
        observable_canonical,
        random_realization,
    )
    from symctl.report import PaperResults, derive_paper
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
