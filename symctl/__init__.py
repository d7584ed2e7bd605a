"""symctl: neural implementations of delayed optimal controllers, derived in closed form.

The public names are those of the table below (``symctl.__all__``), in the order of the
paper's pipeline, loaded on first use so that ``import symctl`` stays quick.

>>> import symctl
>>> symctl.controller_tf(2)
DiscreteTF((K_0)/(z**2 - K_1*z - K_2), dt=None)
"""

from __future__ import annotations

from symctl._util.lazy import attach
from symctl._util.pickling import register as _register_pickling

_register_pickling()  # read-only mappings pickle, so every value object does

__version__ = "0.1.0"

# the public names by module (below ``symctl.``); an indented line continues the one above
_TABLE = """
errors: DimensionError LatexError MissingDependencyError ModelFileError NotRealizableError
    NotStabilizableError ParameterError ParseError SymctlError SymctlTypeError
symbols: z
proof: Proof
design.augment: AugmentedSystem augment
design.controller: controller_tf prove_controller_tf
design.lqr: Gains lqr_gains
design.kalman: KalmanGains kalman_gains lqg_tf prove_lqg_tf
design.plant: DiscretePlant Linearization MuscleModel discretize linearize
design.ode: ODEModel
design.tf: DiscreteTF
realization.check: RealizationCheck check_realization
realization.factorization: Factorization factor
realization.realization: Realization controllable_canonical controller_realization
    first_order_realization observable_canonical
realization.minimal: minimal_realization
realization.realizers: Realizer RealizerResult general_realization get_realizer
    ifp_realization random_realization
compatibility.assignment: DelayAssignment
compatibility.check: CompatibilityResult brute_force_compatibility check_compatibility
compatibility.construction: PathPart markov_split
compatibility.controller: ControllerCompatibility controller_compatibility
compatibility.delaygraph: DelayGraph
compatibility.statespace: structure_realization
compatibility.structure: Block Structure ifp_structure same_structure
neural.batch: BatchResponse simulate_batch
neural.circuit: Circuit CircuitSystem
neural.compensator: lqg_realization
neural.firing: FiringPatterns FiringSummary circuit_firing structure_firing
neural.neuron: Neuron Synapse
neural.nonlinear: NonlinearCheck nonlinear_check DelaySearch longest_delay
neural.noise: Noise
neural.montecarlo: MonteCarlo monte_carlo
neural.simulate: Response closed_loop_response open_loop_response pulse simulate_realization
neural.stability: LoopStability loop_stability
spiking.connections: export_circuit
spiking.loop: SpikingResponse spiking_response
spiking.cost: SpikingCost spiking_cost
circuitatlas.atlas: Atlas atlas
circuitatlas.candidates: CandidateCircuit circuits_for
circuitatlas.circuitclass: CircuitClass
circuitatlas.universality: Evidence
circuitatlas.pattern: Pattern
dalelaw.dale: DaleResult dale
dalelaw.interneurons: EICircuit ei_circuit
dalelaw.dale_atlas: DaleTable dale_atlas
fitting.fit: FitResult fit
fitting.identify: Identifiability identifiability
fitting.traces: Traces read_traces synthetic_traces
model.model: Model
model.modelfile: load_model
derivation.derivation: Derivation PaperResults
derivation.pipeline: derive_paper derive
derivation.load: SavedDerivation load_results
"""

_PUBLIC = {
    name: f"symctl.{module}"
    for module, _, names in (
        line.partition(":") for line in _TABLE.replace("\n    ", " ").strip().splitlines()
    )
    for name in names.split()
}  # {name: module}, from which __all__ is built

__getattr__, __dir__, __all__ = attach(__name__, _PUBLIC, submodules=("latex",))
