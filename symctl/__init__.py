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
    "RealizationCheck": "symctl.realization.check",
    "check_realization": "symctl.realization.check",
    "Circuit": "symctl.neural.circuit",
    "CircuitSystem": "symctl.neural.circuit",
    "Neuron": "symctl.neural.circuit",
    "Synapse": "symctl.neural.circuit",
    "CompatibilityResult": "symctl.compatibility.check",
    "ControllerCompatibility": "symctl.compatibility.check",
    "brute_force_compatibility": "symctl.compatibility.check",
    "check_compatibility": "symctl.compatibility.check",
    "controller_compatibility": "symctl.compatibility.check",
    "AugmentedSystem": "symctl.design.augment",
    "augment": "symctl.design.augment",
    "DelayAssignment": "symctl.compatibility.delaygraph",
    "DelayGraph": "symctl.compatibility.delaygraph",
    "DimensionError": "symctl.errors",
    "LatexError": "symctl.errors",
    "NotStabilizableError": "symctl.errors",
    "ParameterError": "symctl.errors",
    "ParseError": "symctl.errors",
    "SymctlError": "symctl.errors",
    "SymctlTypeError": "symctl.errors",
    "Factorization": "symctl.realization.factorization",
    "factor": "symctl.realization.factorization",
    "FiringPatterns": "symctl.neural.firing",
    "FiringSummary": "symctl.neural.firing",
    "circuit_firing": "symctl.neural.firing",
    "Gains": "symctl.design.lqr",
    "lqr_gains": "symctl.design.lqr",
    "DiscretePlant": "symctl.design.plant",
    "Linearization": "symctl.design.plant",
    "MuscleModel": "symctl.design.plant",
    "discretize": "symctl.design.plant",
    "linearize": "symctl.design.plant",
    "Realization": "symctl.realization.realization",
    "controllable_canonical": "symctl.realization.realization",
    "general_realization": "symctl.realization.realization",
    "observable_canonical": "symctl.realization.realization",
    "random_realization": "symctl.realization.realization",
    "BatchResponse": "symctl.neural.simulate",
    "NonlinearCheck": "symctl.neural.simulate",
    "Response": "symctl.neural.simulate",
    "closed_loop_response": "symctl.neural.simulate",
    "ifp_realization": "symctl.neural.simulate",
    "nonlinear_check": "symctl.neural.simulate",
    "open_loop_response": "symctl.neural.simulate",
    "pulse": "symctl.neural.simulate",
    "simulate_batch": "symctl.neural.simulate",
    "simulate_realization": "symctl.neural.simulate",
    "Block": "symctl.compatibility.structure",
    "Structure": "symctl.compatibility.structure",
    "ifp_structure": "symctl.compatibility.structure",
    "same_structure": "symctl.compatibility.structure",
    "PaperResults": "symctl.report.results",
    "derive_paper": "symctl.report.pipeline",
    "z": "symctl.symbols",
    "DiscreteTF": "symctl.design.tf",
    "controller_tf": "symctl.design.tf",
    "prove_controller_tf": "symctl.design.tf",
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
    "LatexError",
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
    from symctl.compatibility.check import (
        CompatibilityResult,
        ControllerCompatibility,
        brute_force_compatibility,
        check_compatibility,
        controller_compatibility,
    )
    from symctl.compatibility.delaygraph import DelayAssignment, DelayGraph
    from symctl.compatibility.structure import Block, Structure, ifp_structure, same_structure
    from symctl.design.augment import AugmentedSystem, augment
    from symctl.design.lqr import Gains, lqr_gains
    from symctl.design.plant import DiscretePlant, Linearization, MuscleModel, discretize, linearize
    from symctl.design.tf import DiscreteTF, controller_tf, prove_controller_tf
    from symctl.errors import (
        DimensionError,
        NotStabilizableError,
        ParameterError,
        ParseError,
        SymctlError,
        SymctlTypeError,
    )
    from symctl.neural.circuit import Circuit, CircuitSystem, Neuron, Synapse
    from symctl.neural.firing import FiringPatterns, FiringSummary, circuit_firing
    from symctl.neural.simulate import (
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
    from symctl.realization.check import RealizationCheck, check_realization
    from symctl.realization.factorization import Factorization, factor
    from symctl.realization.realization import (
        Realization,
        controllable_canonical,
        general_realization,
        observable_canonical,
        random_realization,
    )
    from symctl.report.pipeline import derive_paper
    from symctl.report.results import PaperResults
    from symctl.symbols import z
