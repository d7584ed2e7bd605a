"""symctl: neural implementations of delayed optimal controllers, derived in closed form.

The public names, in the order of the paper's pipeline, are in ONE table below:
a name is public if and only if it is listed there (``symctl.__all__``); every
other name, in any module, is internal and may change. Names are loaded on first
use (PEP 562, :func:`symctl._util.lazy.attach`), so ``import symctl`` stays quick
and a script pays only for what it uses. ``symctl.latex`` is reached as an
attribute too.

Examples
--------
>>> import symctl
>>> symctl.controller_tf(2)
DiscreteTF((K_0)/(z**2 - K_1*z - K_2), dt=None)
>>> symctl.controller_tf(2) == symctl.controller_tf(2)
True
"""

from __future__ import annotations

from symctl._util.lazy import attach
from symctl._util.pickling import register as _register_pickling

_register_pickling()  # read-only mappings pickle, so every value object does

__version__ = "0.1.0"

_PUBLIC = {
    # errors
    "DimensionError": "symctl.errors",
    "LatexError": "symctl.errors",
    "ModelFileError": "symctl.errors",
    "NotRealizableError": "symctl.errors",
    "NotStabilizableError": "symctl.errors",
    "ParameterError": "symctl.errors",
    "ParseError": "symctl.errors",
    "SymctlError": "symctl.errors",
    "SymctlTypeError": "symctl.errors",
    # symbols
    "z": "symctl.symbols",
    # verdicts: every check's result
    "Proof": "symctl.proof",
    # 1-2. design: plant, delays, LQR, G(z)
    "AugmentedSystem": "symctl.design.augment",
    "augment": "symctl.design.augment",
    "controller_tf": "symctl.design.controller",
    "prove_controller_tf": "symctl.design.controller",
    "Gains": "symctl.design.lqr",
    "lqr_gains": "symctl.design.lqr",
    "DiscretePlant": "symctl.design.plant",
    "Linearization": "symctl.design.plant",
    "MuscleModel": "symctl.design.plant",
    "discretize": "symctl.design.plant",
    "linearize": "symctl.design.plant",
    "ODEModel": "symctl.design.ode",
    "DiscreteTF": "symctl.design.tf",
    # 3. realization: G = G3 G2 G1, realizations of G2, the exact checker
    "RealizationCheck": "symctl.realization.check",
    "check_realization": "symctl.realization.check",
    "Factorization": "symctl.realization.factorization",
    "factor": "symctl.realization.factorization",
    "Realization": "symctl.realization.realization",
    "controllable_canonical": "symctl.realization.realization",
    "controller_realization": "symctl.realization.realization",
    "first_order_realization": "symctl.realization.realization",
    "observable_canonical": "symctl.realization.realization",
    "minimal_realization": "symctl.realization.minimal",
    "Realizer": "symctl.realization.realizers",
    "RealizerResult": "symctl.realization.realizers",
    "general_realization": "symctl.realization.realizers",
    "get_realizer": "symctl.realization.realizers",
    "ifp_realization": "symctl.realization.realizers",
    "random_realization": "symctl.realization.realizers",
    # 4. compatibility: structures, delay graphs, assignments
    "DelayAssignment": "symctl.compatibility.assignment",
    "CompatibilityResult": "symctl.compatibility.check",
    "brute_force_compatibility": "symctl.compatibility.check",
    "check_compatibility": "symctl.compatibility.check",
    "PathPart": "symctl.compatibility.construction",
    "markov_split": "symctl.compatibility.construction",
    "ControllerCompatibility": "symctl.compatibility.controller",
    "controller_compatibility": "symctl.compatibility.controller",
    "DelayGraph": "symctl.compatibility.delaygraph",
    "structure_realization": "symctl.compatibility.statespace",
    "Block": "symctl.compatibility.structure",
    "Structure": "symctl.compatibility.structure",
    "ifp_structure": "symctl.compatibility.structure",
    "same_structure": "symctl.compatibility.structure",
    # 5. neural: circuits, simulation, firing
    "BatchResponse": "symctl.neural.batch",
    "simulate_batch": "symctl.neural.batch",
    "Circuit": "symctl.neural.circuit",
    "CircuitSystem": "symctl.neural.circuit",
    "FiringPatterns": "symctl.neural.firing",
    "FiringSummary": "symctl.neural.firing",
    "circuit_firing": "symctl.neural.firing",
    "structure_firing": "symctl.neural.firing",
    "Neuron": "symctl.neural.neuron",
    "Synapse": "symctl.neural.neuron",
    "NonlinearCheck": "symctl.neural.nonlinear",
    "nonlinear_check": "symctl.neural.nonlinear",
    "DelaySearch": "symctl.neural.nonlinear",
    "longest_delay": "symctl.neural.nonlinear",
    "Response": "symctl.neural.simulate",
    "closed_loop_response": "symctl.neural.simulate",
    "open_loop_response": "symctl.neural.simulate",
    "pulse": "symctl.neural.simulate",
    "simulate_realization": "symctl.neural.simulate",
    "LoopStability": "symctl.neural.stability",
    "loop_stability": "symctl.neural.stability",
    # the circuit atlas
    "Atlas": "symctl.circuitatlas.atlas",
    "atlas": "symctl.circuitatlas.atlas",
    "CandidateCircuit": "symctl.circuitatlas.candidates",
    "circuits_for": "symctl.circuitatlas.candidates",
    "CircuitClass": "symctl.circuitatlas.circuitclass",
    "Evidence": "symctl.circuitatlas.universality",
    "Pattern": "symctl.circuitatlas.pattern",
    # Dale's law: excitatory and inhibitory neurons
    "DaleResult": "symctl.dalelaw.dale",
    "dale": "symctl.dalelaw.dale",
    "EICircuit": "symctl.dalelaw.interneurons",
    "ei_circuit": "symctl.dalelaw.interneurons",
    "DaleTable": "symctl.dalelaw.dale_atlas",
    "dale_atlas": "symctl.dalelaw.dale_atlas",
    # fitting: a circuit fitted to recorded firing rates
    "FitResult": "symctl.fitting.fit",
    "Identifiability": "symctl.fitting.identify",
    "fit": "symctl.fitting.fit",
    "identifiability": "symctl.fitting.identify",
    "Traces": "symctl.fitting.traces",
    "read_traces": "symctl.fitting.traces",
    "synthetic_traces": "symctl.fitting.traces",
    # your own system: model files
    "Model": "symctl.model.model",
    "load_model": "symctl.model.modelfile",
    # 6. the derivation: the whole pipeline on a model
    "Derivation": "symctl.derivation.derivation",
    "PaperResults": "symctl.derivation.derivation",
    "derive_paper": "symctl.derivation.pipeline",
    "derive": "symctl.derivation.pipeline",
    "SavedDerivation": "symctl.derivation.load",
    "load_results": "symctl.derivation.load",
}

__getattr__, __dir__, __all__ = attach(__name__, _PUBLIC, submodules=("latex",))
