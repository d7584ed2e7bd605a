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

from symctl.check import RealizationCheck, check_realization
from symctl.delay import AugmentedSystem, augment
from symctl.factorization import Factorization, factor
from symctl.lqr import Gains, lqr_gains
from symctl.plant import DiscretePlant, MuscleModel
from symctl.realization import (
    Realization,
    controllable_canonical,
    general_realization,
    observable_canonical,
    random_realization,
)
from symctl.transfer import DiscreteTF, controller_tf, descending_str, prove_controller_tf

__all__ = ["PaperResults", "derive_paper"]

SCHEMA_VERSION = 1
SYMBOLIC_P_MAX_ORDER = 3  # the general realization keeps a fully symbolic P up to this order


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

    def to_json(self) -> dict:
        """A JSON-ready dictionary (plain lists and floats)."""
        s = self.system
        G = self.G
        rows, cols = G.shape
        numerator = [[_floats(G.num_coeffs(i, j)) for j in range(cols)] for i in range(rows)]
        return {
            "schema_version": SCHEMA_VERSION,
            "parameters": {
                **self.model.as_dict(),
                "sensor_delay": s.sensor_delay,
                "actuator_delay": s.actuator_delay,
                "Q": _matrix(s.Q_plant),
                "R": _matrix(s.R),
                "seed": self.seed,
            },
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

    def write(self, out: Path) -> list[Path]:
        """Write the outputs into folder ``out``; returns the paths written."""
        out.mkdir(parents=True, exist_ok=True)
        path = out / "results.json"
        path.write_text(json.dumps(self.to_json(), indent=2) + "\n")
        return [path]


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
    progress: Callable[[str], None] | None = None,
) -> PaperResults:
    """Run the derivation on the paper's muscle; every argument defaults to the paper's value.

    ``progress`` is called with the name of each step before it runs.
    """
    step = progress or (lambda _name: None)
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
    realizations = _realizations(factors, gains, seed)
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
        realizations,
    )


@dataclass(frozen=True, eq=False)
class RealizationRecord:
    """One realization of G2 for the report: symbolic, numeric, and the checks of both."""

    name: str
    symbolic: Realization
    numeric: Realization
    values: dict
    check_symbolic: RealizationCheck
    check_numeric: RealizationCheck


def _realizations(factors: Factorization, gains: Gains, seed: int) -> dict[str, RealizationRecord]:
    """The paper's three realizations of G2: controllable and observable canonical, general.

    Symbolic forms keep K, eps and C (and, up to order
    :data:`SYMBOLIC_P_MAX_ORDER`, a fully symbolic ``P`` for the general one;
    above it the seeded random ``P``); numeric ones use the optimal gains (as
    the exact rationals of their binary floats, so that the checks stay exact),
    C = 1 on every section, and (general) random eps and a random full-rank P
    drawn from ``seed`` as the paper describes.
    """
    rng = np.random.default_rng(seed)
    unit_C = {c: 1 for c in (*factors.sensor_C, *factors.actuator_C)}
    exact_gains = {k: sp.Rational(v) for k, v in gains.substitutions().items()}
    G2_gains = factors.G2.subs(exact_gains).subs(unit_C)
    general = random_realization(G2_gains, rng)
    eps_values = {k: v for k, v in general.params.items() if isinstance(k, sp.Symbol)}
    G2_num = G2_gains.subs(eps_values)
    n = general.n
    if n <= SYMBOLIC_P_MAX_ORDER:
        P = sp.Matrix(n, n, sp.symbols(f"p_1:{n + 1}(1:{n + 1})"))
    else:  # a fully symbolic P costs minutes beyond order 3: use the seeded one
        P = general.params["P"]
    out = {}
    for name, symbolic, numeric in (
        ("controllable", controllable_canonical(factors.G2), controllable_canonical(G2_num)),
        ("observable", observable_canonical(factors.G2), observable_canonical(G2_num)),
        ("general", general_realization(factors.G2, P), general),
    ):
        out[name] = RealizationRecord(
            name,
            symbolic,
            numeric,
            {**{str(k): v for k, v in eps_values.items()}, **{str(k): 1 for k in unit_C}},
            check_realization(symbolic, factors.G2),
            check_realization(numeric, G2_num),
        )
    return out
