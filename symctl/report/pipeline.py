"""The main job: run the paper's derivation and collect its results.

:func:`derive_paper` runs the pipeline (plant -> delays -> LQR -> G(z)) for
given parameters and returns a :class:`PaperResults`; :meth:`PaperResults.to_json`
gives the ``results.json`` document (schema in the README). ``symctl paper``
is a thin command around these.

>>> res = derive_paper()
>>> round(res.to_json()["plant"]["f_bar"], 4)
43.8635
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import sympy as sp

from symctl._util.display import descending_str
from symctl.compatibility.check import CompatibilityResult, check_compatibility
from symctl.compatibility.delaygraph import DelayGraph
from symctl.compatibility.structure import Structure, ifp_structure
from symctl.design.augment import AugmentedSystem, augment
from symctl.design.controller import controller_tf, prove_controller_tf
from symctl.design.lqr import Gains, lqr_gains
from symctl.design.plant import DiscretePlant, MuscleModel
from symctl.design.tf import DiscreteTF
from symctl.errors import ParameterError
from symctl.neural.circuit import Circuit
from symctl.neural.firing import FiringPatterns, circuit_firing
from symctl.neural.nonlinear import NonlinearCheck, nonlinear_check
from symctl.neural.simulate import Response, closed_loop_response, open_loop_response
from symctl.realization.check import RealizationCheck, check_realization
from symctl.realization.factorization import Factorization, factor
from symctl.realization.realization import Realization
from symctl.realization.realizers import REALIZERS

__all__ = ["CIRCUITS", "CircuitRecord", "PaperResults", "RealizationRecord", "derive_paper"]

SCHEMA_VERSION = 1
SYMBOLIC_P_MAX_ORDER = 3  # the general realization keeps a fully symbolic P up to this order
DEFAULT_REALIZATIONS = 4  # simulated realizations per circuit (the IFP controller has one)
CIRCUITS = ("ifp", "general", "controllable", "observable")
"""The circuits of the report: the IFP controller, and G3 G2 G1 with each realization of G2."""


@dataclass(frozen=True, eq=False)
class PaperResults:
    """Everything the derivation produced, symbolic and numeric."""

    model: MuscleModel
    plant_symbolic: DiscretePlant
    plant: DiscretePlant
    system: AugmentedSystem
    gains: Gains
    G_symbolic: DiscreteTF
    G: DiscreteTF
    proved: bool
    seed: int
    factors: Factorization
    realizations: dict
    graph: DelayGraph
    circuits: dict
    open_loop: Response
    closed_loop: Response
    nonlinear: NonlinearCheck

    def parameters(self) -> dict:
        """The inputs of the derivation (the ``parameters`` entry of :meth:`to_json`)."""
        s = self.system
        return {
            **self.model.as_dict(),
            "sensor_delay": s.sensor_delay,
            "actuator_delay": s.actuator_delay,
            "Q": _matrix(s.Q_plant),
            "R": _matrix(s.R),
            "seed": self.seed,
        }

    def to_json(self) -> dict:
        """A JSON-ready dictionary (plain lists and floats)."""
        s = self.system
        G = self.G
        rows, cols = G.shape
        numerator = [[_floats(G.num_coeffs(i, j)) for j in range(cols)] for i in range(rows)]
        return {
            "schema_version": SCHEMA_VERSION,
            "parameters": self.parameters(),
            "plant": {
                "f_bar": self.model.f_bar,
                "r_bar": self.model.r_bar,
                "A": _matrix(self.plant.A),
                "B": _matrix(self.plant.B),
                "Ts": self.model.Ts,
                "symbolic": {
                    "A": sp.sstr(self.plant_symbolic.A[0, 0]),
                    "B": sp.sstr(self.plant_symbolic.B[0, 0]),
                    "f_bar": sp.sstr(self.model.f_bar_symbolic),
                },
            },
            "augmented": {
                "T": s.T,
                "state": list(s.state_names),
                "A": _matrix(s.A),
                "B": _matrix(s.B),
                "Q": _matrix(s.Q),
            },
            "gains": {
                "K": self.gains.K.tolist(),
                "names": [str(k) for k in self.G_symbolic.free_symbols_sorted()],
            },
            "controller": {
                "numerator": numerator[0][0] if G.is_siso else numerator,
                "denominator": _floats(G.den_coeffs()),
                "relative_degree": G.relative_degree,
                "dt": self.model.Ts,
                "symbolic": {
                    "numerator": _poly_text(self.G_symbolic.num),
                    "denominator": descending_str(self.G_symbolic.den),
                    "latex": self.G_symbolic.latex(),
                },
                "proved": self.proved,
            },
            "factorization": self._factorization_json(),
            "closed_loop": {
                "poles": [[float(p.real), float(p.imag)] for p in self.gains.poles],
                "spectral_radius": self.gains.spectral_radius,
            },
            "delay_graph": {
                "E": _delays(self.graph.E),
                "vertices": self.graph.n,
                "chain_delays": list(self.graph.chain_delays or ()),
            },
            "circuits": {name: rec.to_json() for name, rec in self.circuits.items()},
            "simulation": self._simulation_json(),
        }

    def _simulation_json(self) -> dict:
        ol, cl, nl = self.open_loop, self.closed_loop, self.nonlinear
        return {
            "t": _floats(cl.t),
            "open_loop": {
                "pulse": _floats(ol.delta_r[:, 0]),
                "delta_f": _floats(ol.delta_f[:, 0]),
            },
            "closed_loop": {
                "disturbance": _floats(cl.w[:, 0]),
                "delta_f": _floats(cl.delta_f[:, 0]),
                "delta_r": _floats(cl.delta_r[:, 0]),
            },
            "nonlinear": {
                "amplitudes": _floats(nl.amplitudes),
                "max_deviation": _floats(nl.max_deviation),
                "relative_deviation": _floats(nl.relative_deviation),
            },
        }

    def _factorization_json(self) -> dict:
        f = self.factors
        reals = {}
        for name, rec in self.realizations.items():
            reals[name] = {
                "symbolic": {k: _text_matrix(getattr(rec.symbolic, k)) for k in "FHMN"},
                "numeric": {k: _matrix(getattr(rec.numeric, k)) for k in "FHMN"},
                "values": {k: float(v) for k, v in rec.values.items()},
                "P": _matrix(rec.numeric.params["P"]) if "P" in rec.numeric.params else None,
                "check": {
                    "symbolic": {"ok": rec.check_symbolic.ok, "method": rec.check_symbolic.method},
                    "numeric": {"ok": rec.check_numeric.ok, "method": rec.check_numeric.method},
                },
            }
        return {
            "G1": str(f.G1),
            "G2": str(f.G2),
            "G3": str(f.G3),
            "N": sp.sstr(f.N),
            "remainder_coeffs": [sp.sstr(c) for c in f.remainder_coeffs],
            "verified": f.verify(),
            "realizations": reals,
        }

    def write(
        self,
        out: Path,
        *,
        figures: bool = True,
        pdf: bool = True,
        jobs: int | None = None,
        progress: Callable[[str], None] | None = None,
    ) -> list[Path]:
        """Write the outputs into folder ``out``; returns the paths written.

        ``results.json``, ``derivation.tex`` and ``report.md``; with ``figures``
        the figures as PNG and SVG (:func:`symctl.report.figures.paper_figures`); with
        ``pdf`` also ``derivation.pdf`` when ``pdflatex`` is on the PATH. ``jobs``
        is the number of processes drawing figures
        (:func:`symctl.report.figures.write_figures`).
        """
        from symctl.report import document as derivation
        from symctl.report import figures as figs

        step = progress or (lambda _name: None)
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        written = []
        path = out / "results.json"
        path.write_text(json.dumps(self.to_json(), indent=2, allow_nan=False) + "\n")
        written.append(path)
        names: list[str] = []
        if figures:
            step("figures")
            paths = figs.write_figures(self, out, jobs=jobs)
            names = [p.stem for p in paths if p.suffix == ".png"]
            written += paths
        step("documents")
        story = derivation.story(self, figures=names)
        written.append(derivation.write_tex(story, out / "derivation.tex"))
        written.append(derivation.write_markdown(story, out / "report.md"))
        if pdf:
            step("pdflatex")
            compiled = derivation.compile_pdf(out / "derivation.tex")
            if compiled is not None:
                written.append(compiled)
        return written


def _section_C(params: dict) -> list[str]:
    """The C of each section drawn (all 1 in :func:`~symctl.neural.firing.circuit_firing`)."""
    return [str(k).replace("epsilon", "C", 1) for k in params if str(k).startswith("epsilon")]


def _poly_text(value) -> str | list:
    if isinstance(value, sp.MatrixBase):
        return [[descending_str(e) for e in row] for row in value.tolist()]
    return descending_str(value)


def _text_matrix(mat: sp.MatrixBase) -> list[list[str]]:
    return [[sp.sstr(e) for e in row] for row in mat.tolist()]


def _floats(values) -> list[float]:
    return [float(v) for v in values]


def _matrix(mat: sp.MatrixBase) -> list[list[float]]:
    return np.array(mat.evalf(), dtype=float).tolist()


def _delays(E: np.ndarray) -> list[list[int | None]]:
    """A delay matrix for JSON: integers, ``None`` for infinity (no path)."""
    return [[None if np.isinf(v) else int(v) for v in row] for row in np.asarray(E)]


def _value(v):
    """An exact or numeric parameter value for JSON (a float, or nested lists for a matrix)."""
    if isinstance(v, sp.MatrixBase | np.ndarray):
        return _matrix(sp.Matrix(v))
    return float(v)


def derive_paper(
    tau: float = 0.02,
    f_max: float = 60.0,
    r_bar: float = 1.0,
    Ts: float = 0.01,
    sensor_delay: int = 1,
    actuator_delay: int = 1,
    Q=None,
    R=None,
    seed: int = 0,
    realizations: int = DEFAULT_REALIZATIONS,
    progress: Callable[[str], None] | None = None,
) -> PaperResults:
    """Run the derivation on the paper's muscle; every argument defaults to the paper's value.

    ``realizations`` is the number of random realizations simulated per circuit
    (the IFP controller has one). ``progress`` is called with the name of each
    step before it runs.
    """
    step = progress or (lambda _name: None)
    if sensor_delay == 0 and actuator_delay == 0:  # other bad values: augment names them
        raise ParameterError(
            "sensor_delay, actuator_delay: the derivation needs a net delay "
            "T = sensor_delay + actuator_delay >= 1 (the delay graph and the IFP controller "
            "have T steps), got 0"
        )
    step("plant")
    model = MuscleModel(tau=tau, f_max=f_max, r_bar=r_bar, Ts=Ts)
    plant_symbolic = model.discrete_symbolic()
    plant = model.plant()
    step("delays")
    system = augment(plant, sensor_delay, actuator_delay, Q=Q, R=R)
    step("LQR")
    gains = lqr_gains(system)
    step("G(z)")
    G_symbolic = controller_tf(system)
    proved = prove_controller_tf(system, G_symbolic)
    G = G_symbolic.subs(gains.substitutions())
    step("factorization")
    factors = factor(G_symbolic, sensor_delay, actuator_delay)
    step("simulation")
    firing = {
        k: circuit_firing(k, gains, count=1 if k == "ifp" else realizations, seed=seed)
        for k in CIRCUITS
    }
    step("realizations")
    records = _realizations(factors, gains, {k: firing[k].params[0] for k in CIRCUITS[1:]})
    step("compatibility")
    graph = DelayGraph.chain([1] * system.T)
    structures = {"ifp": ifp_structure(system.T)}
    structures.update(
        {k: Structure.from_factorization(factors, records[k].symbolic) for k in CIRCUITS[1:]}
    )
    verdicts = {k: check_compatibility(S, graph) for k, S in structures.items()}
    circuits = {
        k: CircuitRecord(
            k,
            structures[k],
            verdicts[k],
            Circuit.from_structure(structures[k], verdicts[k] if verdicts[k].ok else None),
            firing[k],
        )
        for k in CIRCUITS
    }
    return PaperResults(
        model,
        plant_symbolic,
        plant,
        system,
        gains,
        G_symbolic,
        G,
        proved,
        seed,
        factors,
        records,
        graph,
        circuits,
        open_loop_response(plant),
        closed_loop_response(gains),
        nonlinear_check(model, gains),
    )


@dataclass(frozen=True, eq=False)
class CircuitRecord:
    """One circuit of the report: its structure, compatibility, neurons and simulations.

    ``structure`` and ``circuit`` are symbolic (for ``"general"`` with the
    symbolic or seeded ``P`` of :class:`RealizationRecord`); ``firing`` holds
    the closed-loop simulations of the random realizations
    (:func:`~symctl.neural.firing.circuit_firing`).
    """

    name: str
    structure: Structure
    compatibility: CompatibilityResult
    circuit: Circuit
    firing: FiringPatterns

    @property
    def g2_neurons(self) -> int | None:
        """The neurons of the G2 part (None for the IFP controller, which has no G2)."""
        if self.name == "ifp":
            return None
        return sum(1 for n in self.circuit.neurons if n.part == "G2")

    def to_json(self) -> dict:
        c, fp, verdict = self.circuit, self.firing, self.compatibility
        peak = fp.summary().peak
        return {
            "neurons": {
                "count": c.n_neurons,
                "G2": self.g2_neurons,
                "names": [n.name for n in c.neurons],
                "vertices": {n.name: n.vertex for n in c.neurons},
                "branches": {n.name: n.branches for n in c.neurons},
            },
            "synapses": len(c.synapses),
            "signals": len(self.structure.signals),
            "compatible": verdict.ok,
            "compatibility": {
                "method": verdict.method,
                "reason": verdict.reason,
                "E_tilde": _delays(verdict.E_tilde) if verdict.ok else None,
            },
            "max_closed_loop_deviation": fp.max_deviation,
            "realizations": [
                {str(k): _value(v) for k, v in params.items()}
                | {c: 1.0 for c in _section_C(params)}
                for params in fp.params
            ],
            "peak_firing": {
                name: [None if np.isnan(v) else float(v) for v in peak[:, i]]
                for i, name in enumerate(fp.neurons)
            },
        }


@dataclass(frozen=True, eq=False)
class RealizationRecord:
    """One realization of G2 for the report: symbolic, numeric, and the checks of both."""

    name: str
    symbolic: Realization
    numeric: Realization
    values: dict
    check_symbolic: RealizationCheck
    check_numeric: RealizationCheck


def _realizations(
    factors: Factorization, gains: Gains, drawn: dict[str, dict]
) -> dict[str, RealizationRecord]:
    """The paper's three realizations of G2: controllable and observable canonical, general.

    Symbolic forms keep K, eps and C (and, up to order
    :data:`SYMBOLIC_P_MAX_ORDER`, a fully symbolic ``P`` for the general one;
    above it the seeded random ``P``); numeric ones use the optimal gains (as
    the exact rationals of their binary floats, so that the checks stay exact),
    C = 1 on every section and ``drawn[name]``, the epsilons (and for the
    general one ``P``) of the first simulated realization of that circuit.
    """
    unit_C = {c: 1 for c in (*factors.sensor_C, *factors.actuator_C)}
    exact_gains = {k: sp.Rational(v) for k, v in gains.substitutions().items()}
    G2_gains = factors.G2.subs(exact_gains).subs(unit_C)
    out = {}
    for name in ("controllable", "observable", "general"):
        eps = {k: v for k, v in drawn[name].items() if isinstance(k, sp.Symbol)}
        G2_num = G2_gains.subs(eps)
        realizer = REALIZERS[name]
        symbolic_options, numeric_options = {}, {}
        if realizer.takes_transform:
            P_num = drawn[name]["P"]
            n = P_num.shape[0]
            if n <= SYMBOLIC_P_MAX_ORDER:
                P = sp.Matrix(n, n, sp.symbols(f"p_1:{n + 1}(1:{n + 1})"))
            else:  # a fully symbolic P costs minutes beyond order 3: use the drawn one
                P = P_num
            symbolic_options, numeric_options = {"P": P}, {"P": P_num}
        symbolic = realizer(factors.G2, **symbolic_options).realization
        numeric = realizer(G2_num, **numeric_options).realization
        out[name] = RealizationRecord(
            name,
            symbolic,
            numeric,
            {**{str(k): v for k, v in eps.items()}, **{str(k): 1 for k in unit_C}},
            check_realization(symbolic, factors.G2),
            check_realization(numeric, G2_num),
        )
    return out
