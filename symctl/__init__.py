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

_PUBLIC_BY_MODULE = (
    # errors
    (
        "symctl.errors",
        "DimensionError LatexError MissingDependencyError ModelFileError NotRealizableError "
        "NotStabilizableError ParameterError ParseError SymctlError SymctlTypeError",
    ),
    # symbols
    ("symctl.symbols", "z"),
    # verdicts: every check's result
    ("symctl.proof", "Proof"),
    # 1-2. design: plant, delays, LQR, G(z)
    ("symctl.design.augment", "AugmentedSystem augment"),
    ("symctl.design.controller", "controller_tf prove_controller_tf"),
    ("symctl.design.lqr", "Gains lqr_gains"),
    ("symctl.design.kalman", "KalmanGains kalman_gains lqg_tf prove_lqg_tf"),
    ("symctl.design.plant", "DiscretePlant Linearization MuscleModel discretize linearize"),
    ("symctl.design.ode", "ODEModel"),
    ("symctl.design.tf", "DiscreteTF"),
    # 3. realization: G = G3 G2 G1, realizations of G2, the exact checker
    ("symctl.realization.check", "RealizationCheck check_realization"),
    ("symctl.realization.factorization", "Factorization factor"),
    (
        "symctl.realization.realization",
        "Realization controllable_canonical controller_realization first_order_realization "
        "observable_canonical",
    ),
    ("symctl.realization.minimal", "minimal_realization"),
    (
        "symctl.realization.realizers",
        "Realizer RealizerResult general_realization get_realizer ifp_realization "
        "random_realization",
    ),
    # 4. compatibility: structures, delay graphs, assignments
    ("symctl.compatibility.assignment", "DelayAssignment"),
    (
        "symctl.compatibility.check",
        "CompatibilityResult brute_force_compatibility check_compatibility",
    ),
    ("symctl.compatibility.construction", "PathPart markov_split"),
    ("symctl.compatibility.controller", "ControllerCompatibility controller_compatibility"),
    ("symctl.compatibility.delaygraph", "DelayGraph"),
    ("symctl.compatibility.statespace", "structure_realization"),
    ("symctl.compatibility.structure", "Block Structure ifp_structure same_structure"),
    # 5. neural: circuits, simulation, firing
    ("symctl.neural.batch", "BatchResponse simulate_batch"),
    ("symctl.neural.circuit", "Circuit CircuitSystem"),
    ("symctl.neural.compensator", "lqg_realization"),
    ("symctl.neural.firing", "FiringPatterns FiringSummary circuit_firing structure_firing"),
    ("symctl.neural.neuron", "Neuron Synapse"),
    ("symctl.neural.nonlinear", "NonlinearCheck nonlinear_check DelaySearch longest_delay"),
    ("symctl.neural.noise", "Noise"),
    ("symctl.neural.montecarlo", "MonteCarlo monte_carlo"),
    (
        "symctl.neural.simulate",
        "Response closed_loop_response open_loop_response pulse simulate_realization",
    ),
    ("symctl.neural.stability", "LoopStability loop_stability"),
    # circuits in other simulators: a neutral connection list (nengo and NEST: Circuit methods)
    ("symctl.spiking.connections", "export_circuit"),
    ("symctl.spiking.loop", "SpikingResponse spiking_response"),
    ("symctl.spiking.cost", "SpikingCost spiking_cost"),
    # the circuit atlas
    ("symctl.circuitatlas.atlas", "Atlas atlas"),
    ("symctl.circuitatlas.candidates", "CandidateCircuit circuits_for"),
    ("symctl.circuitatlas.circuitclass", "CircuitClass"),
    ("symctl.circuitatlas.universality", "Evidence"),
    ("symctl.circuitatlas.pattern", "Pattern"),
    # Dale's law: excitatory and inhibitory neurons
    ("symctl.dalelaw.dale", "DaleResult dale"),
    ("symctl.dalelaw.interneurons", "EICircuit ei_circuit"),
    ("symctl.dalelaw.dale_atlas", "DaleTable dale_atlas"),
    # fitting: a circuit fitted to recorded firing rates
    ("symctl.fitting.fit", "FitResult fit"),
    ("symctl.fitting.identify", "Identifiability identifiability"),
    ("symctl.fitting.traces", "Traces read_traces synthetic_traces"),
    # your own system: model files
    ("symctl.model.model", "Model"),
    ("symctl.model.modelfile", "load_model"),
    # 6. the derivation: the whole pipeline on a model
    ("symctl.derivation.derivation", "Derivation PaperResults"),
    ("symctl.derivation.pipeline", "derive_paper derive"),
    ("symctl.derivation.load", "SavedDerivation load_results"),
)
_PUBLIC = {name: module for module, names in _PUBLIC_BY_MODULE for name in names.split()}
"""The public names: one table, ``{name: module}``, from which ``__all__`` is built."""

__getattr__, __dir__, __all__ = attach(__name__, _PUBLIC, submodules=("latex",))
