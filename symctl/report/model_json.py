"""The model's entries of ``results.json``: ``plant`` (with the equilibrium) and ``model``.

>>> from symctl import derive_paper
>>> from symctl.report import model_json
>>> res = derive_paper()
>>> model_json.plant(res)["equilibrium"]["method"], model_json.model(res)["vertices"]
('given', ['v1', 'v2', 'v3'])
"""

from __future__ import annotations

import numpy as np
import sympy as sp

__all__ = ["float_rows", "model", "plant"]


def float_rows(mat: sp.MatrixBase) -> list[list[float]]:
    """A matrix as nested lists of floats (rows), for JSON."""
    return np.array(mat.evalf(), dtype=float).tolist()


def plant(res) -> dict:
    """The ``plant`` entry: the discrete plant, its closed forms and the equilibrium."""
    spec, ode = res.spec, res.spec.ode
    sym = res.plant_symbolic
    x_eq = ode.x_bar.tolist() if ode is not None else None
    u_eq = ode.u_bar.tolist() if ode is not None else None
    return {
        "f_bar": x_eq[0] if x_eq else None,
        "r_bar": u_eq[0] if u_eq else None,
        "A": float_rows(res.plant.A),
        "B": float_rows(res.plant.B),
        "Ts": spec.dt,
        "symbolic": {
            "A": sp.sstr(sym.A[0, 0]) if sym is not None else None,
            "B": sp.sstr(sym.B[0, 0]) if sym is not None else None,
            "f_bar": sp.sstr(ode.x_eq[0]) if ode is not None else None,
        },
        "states": list(res.names[0]),
        "inputs": list(res.names[1]),
        "equilibrium": None
        if ode is None
        else {
            "states": dict(zip(res.names[0], x_eq, strict=True)),
            "inputs": dict(zip(res.names[1], u_eq, strict=True)),
            "symbolic": [sp.sstr(e) for e in ode.x_eq],
            "method": ode.equilibrium_method,
        },
    }


def model(res) -> dict:
    """The ``model`` entry: name, units, the delay graph's names, notes, what was skipped, and
    the ``file`` that re-creates the model."""
    spec = res.spec
    out = {
        "name": spec.name,
        "title": spec.title,
        "units": dict(spec.units),
        "vertices": list(spec.vertices),
        "edges": [list(e) for e in spec.edges],
        "circuits_built": list(spec.circuits),
        "notes": list(spec.notes),
        "skipped": res.skipped,
        "longest_delay": None,
        "file": spec.to_dict() if spec.source else None,  # re-creates the model (load_results)
    }
    if res.longest is not None:
        L = res.longest
        out["longest_delay"] = {
            "longest": L.longest,
            "limited": L.limited,
            "tolerance": L.tolerance,
            "delays": list(L.delays),
            "final_deviation": [None if np.isinf(v) else float(v) for v in L.final_deviation],
            "stabilized": list(L.stabilized),
        }
    return out
