r"""``results.json`` and the files of ``symctl paper``, written from a derivation."""

from __future__ import annotations

import contextlib
from collections.abc import Callable
from pathlib import Path

import numpy as np
import sympy as sp

from symctl._util.display import descending_str
from symctl._util.validate import positive_int
from symctl.derivation.derivation import CircuitRecord, PaperResults, RealizationRecord
from symctl.realization.check import _similarity_holds
from symctl.realization.factorization import remainder
from symctl.report import document, story
from symctl.report import figures as _figures
from symctl.report.estimation import estimation_json
from symctl.report.output import OutputFolder, write_json
from symctl.report.spec import SCHEMA_VERSION
from symctl.report.workers import FigureWorkers

__all__ = ["CircuitRecord", "PaperResults", "RealizationRecord", "results_json", "write_files"]


# characters of a realization's symbolic F, H, M beyond which results.json writes a transform by
# a drawn P as its base and P (transform), exactly
SYMBOLIC_TEXT_MAX = 20_000


def realization_json(self, base=None) -> dict:
    """The entry of ``results.json``'s ``factorization.realizations`` for this realization
    (``base``: the canonical form a drawn ``P`` transformed)."""
    return {
        "symbolic": _symbolic_json(self, base),
        "numeric": {k: _matrix(getattr(self.numeric, k)) for k in "FHMN"},
        "values": {k: float(v) for k, v in self.values.items()},
        "P": _matrix(self.P_numeric) if self.P_numeric is not None else None,
        "check": {"symbolic": _check(self.check_symbolic), "numeric": _check(self.check_numeric)},
    }


def _symbolic_json(self, base) -> dict:
    out = {k: _text_matrix(getattr(self.symbolic, k)) for k in "FHMN"}
    P = self.P
    drawn = base is not None and P is not None and not P.free_symbols
    if not drawn or sum(len(e) for k in "FHM" for r in out[k] for e in r) <= SYMBOLIC_TEXT_MAX:
        return out
    if not _similarity_holds(self.symbolic, base.symbolic, P):  # proved, never assumed
        return out
    return {"F": None, "H": None, "M": None, "N": out["N"]} | {
        "transform": {"of": base.name, "P": _text_matrix(P)}
    }


def circuit_json(self) -> dict:
    """The entry of ``results.json``'s ``circuits`` for this circuit."""
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
            {str(k): _value(v) for k, v in params.items()} | {c: 1.0 for c in _section_C(params)}
            for params in fp.params
        ],
        "peak_firing": {
            name: [None if np.isnan(v) else float(v) for v in peak[:, i]]
            for i, name in enumerate(fp.neurons)
        },
    } | ({} if self.realizes is None else {"realizes": _check(self.realizes)})


def parameters(self) -> dict:
    """The inputs of a derivation (:meth:`~symctl.derivation.Derivation.parameters`)."""
    s = self.system
    values = self.spec.ode.as_dict() if self.spec.ode is not None else {"Ts": self.spec.dt}
    return {
        **values,
        "sensor_delay": s.sensor_delay,
        "actuator_delay": s.actuator_delay,
        "Q": _matrix(s.Q_plant),
        "R": _matrix(s.R),
        "seed": self.seed,
    }


def results_json(self) -> dict:
    """The ``results.json`` document (:meth:`~symctl.derivation.Derivation.to_dict`)."""
    s = self.system
    G = self.G
    numerator, denominator = controller_coeffs(G)
    out = {
        "schema_version": SCHEMA_VERSION,
        "parameters": parameters(self),
        "plant": _plant_json(self),
        "augmented": {"T": s.T, "state": list(s.state_names)}
        | {k: _matrix(getattr(s, k)) for k in "ABQ"},
        "gains": {
            "K": self.gains.K.tolist(),
            "names": [str(k) for k in self.gains.substitutions()],
        },
        "controller": {
            "numerator": numerator,
            "denominator": denominator,
            "relative_degree": G.relative_degree,
            "dt": self.spec.dt,
            "symbolic": {
                "numerator": _poly_text(self.G_symbolic.num),
                "denominator": descending_str(self.G_symbolic.den),
                "latex": self.G_symbolic.latex(),
            },
            "proved": bool(self.proved),
        },
        "factorization": _factorization_json(self) if self.factors is not None else None,
        "closed_loop": {
            "poles": [[float(p.real), float(p.imag)] for p in self.gains.poles],
            "spectral_radius": self.gains.spectral_radius,
        },
        "delay_graph": {
            "E": _delays(self.graph.E),
            "vertices": self.graph.n,
            "chain_delays": list(self.graph.chain_delays or ()),
            "edges": [list(e) for e in self.graph.edges],
            "sensors": list(self.graph.sensors),
            "actuators": list(self.graph.actuators),
            "theorem": _theorem_json(self.pathways),
        },
        "circuits": {name: circuit_json(rec) for name, rec in self.circuits.items()},
        "simulation": _simulation_json(self),
        "atlas": _atlas_json(self),
        "model": _model_json(self),
    }
    if self.reduction is not None and not self.reduction:  # only a reduced controller has it
        out["reduction"] = reduction_json(self.reduction)
    if self.kalman is not None:  # only an estimating controller has it
        out["estimation"] = estimation_json(self)
    if getattr(self, "spiking_cost", None) is not None:  # symctl paper --spiking
        out["spiking"] = self.spiking_cost.summary()
    return out


def reduction_json(r) -> dict:
    """The ``reduction`` entry: the non-minimal controller's reduction, with its reason."""
    return (
        {"minimal": bool(r)}
        | _attrs(r, "order minimal_order never_driven unseen reason")
        | {"ties": {str(k): str(v) for k, v in r.relations.items()}, "method": r.method}
    )


def controller_coeffs(G) -> tuple[list, list[float]]:
    """The numerator (``[i][j]`` lists for MIMO) and denominator coefficients of ``G`` as floats."""
    rows, cols = G.shape
    numerator = [[_floats(G.num_coeffs(i, j)) for j in range(cols)] for i in range(rows)]
    return numerator[0][0] if G.is_siso else numerator, _floats(G.den_coeffs())


def _atlas_json(self) -> dict | None:
    if self.atlas is None:
        return None
    from symctl.report.atlas import candidates_json, claim_json

    return {**claim_json(self.atlas), "candidates": candidates_json(self.candidates)}


def _simulation_json(self) -> dict:
    ol, cl, nl = self.open_loop, self.closed_loop, self.nonlinear
    out = {
        "t": _floats(cl.t),
        "open_loop": {"pulse": _floats(ol.delta_r[:, 0]), "delta_f": _floats(ol.delta_f[:, 0])},
        "closed_loop": {
            "disturbance": _floats(cl.w[:, 0]),
            "delta_f": _floats(cl.delta_f[:, 0]),
            "delta_r": _floats(cl.delta_r[:, 0]),
        },
        "nonlinear": None
        if nl is None
        else {
            "amplitudes": _floats(nl.amplitudes),
            "max_deviation": _finite(nl.max_deviation),
            "relative_deviation": _finite(nl.relative_deviation),
        },
    }
    if self.plant.n > 1 or self.plant.m > 1:  # every state and input, by name
        out["states"] = {
            n: {"open_loop": _floats(ol.delta_f[:, i]), "closed_loop": _floats(cl.delta_f[:, i])}
            for i, n in enumerate(self.names[0])
        }
        out["inputs"] = {n: _floats(cl.delta_r[:, i]) for i, n in enumerate(self.names[1])}
    return out


def factor_texts(self) -> dict:
    """``G1``, ``G2``, ``G3`` and ``N`` of the factorization as text, the sections as products."""
    f = self.factors
    N = remainder(self.G2_symbolic)[0] if f.is_siso else f.N
    G1, G3 = map(_diagonal_text, f.section_channels)
    if not self.abbreviated:
        G2 = str(f.G2)
    elif f.is_siso:
        gain = f.G.num / sp.Mul(*f.sensor_C, *f.actuator_C)
        G2 = f"({sp.sstr(gain)})*{_zeros_text(f.poles)}/({descending_str(f.G.den)})"
    else:
        sensors, actuators = f.section_channels
        rows = [[""] * len(sensors) for _ in actuators]
        for (i, j), poles in f.entry_poles:
            gain = f.G.num_matrix[i - 1, j - 1] / sp.Mul(*actuators[i - 1][1], *sensors[j - 1][1])
            rows[i - 1][j - 1] = f"({sp.sstr(gain)})*{_zeros_text(poles)}"
        G2 = "[" + ", ".join(f"[{', '.join(r)}]" for r in rows) + f"]/({descending_str(f.G.den)})"
    N = _text_matrix(N) if isinstance(N, sp.MatrixBase) else sp.sstr(N)
    return {"G1": G1, "G2": G2, "G3": G3, "N": N}


def _factorization_json(self) -> dict:
    f = self.factors
    # a MIMO G has a matrix feed-through; the rewritten G2 is the SISO form
    coeffs = remainder(self.G2_symbolic)[1] if f.is_siso else []
    return {
        **factor_texts(self),
        "channels": list(f.channels),
        "remainder_coeffs": [sp.sstr(c) for c in coeffs],
        "abbreviations": {
            str(s): f"e_{k}({', '.join(map(str, poles))})"
            for s, (k, poles) in f.sigma_poles.items()
        }
        if self.abbreviated
        else {},
        "verified": bool(self.verified),
        "realizations": {
            name: realization_json(rec, self.realizations.get("controllable"))
            for name, rec in self.realizations.items()
        },
    }


def write(
    self,
    out: Path | str,
    *,
    jobs: int | None = None,
    formats: str | tuple[str, ...] = _figures.DEFAULT_FORMATS,
    **kw,
) -> list[Path]:
    """Write every file of ``symctl paper`` into ``out`` (:meth:`~symctl.derivation.Derivation.write`)."""
    if jobs is not None:
        positive_int(jobs, "jobs")
    formats = _figures.figure_formats(formats)
    with OutputFolder(out, "out") as folder:
        written = write_files(self, folder.staging, jobs=jobs, formats=formats, **kw)
        return folder.final(written)


def write_files(
    self,
    out: Path,
    *,
    figures: bool = True,
    pdf: bool = True,
    jobs: int | None = None,
    progress: Callable[[str], None] | None = None,
    formats: tuple[str, ...] = _figures.DEFAULT_FORMATS,
    workers=None,
    parts: Callable[[str], None] | None = None,
    drawn: _figures.Drawing | None = None,
) -> list[Path]:
    """Write every file into the existing folder ``out``; ``progress`` gets each step's name,
    ``parts`` each figure's as it is saved; the figures ``drawn`` are in the ``workers`` already."""
    step = progress or (lambda _name: None)
    started = contextlib.nullcontext(workers) if workers or not figures else FigureWorkers(jobs)
    with started as drawing:  # the figures are drawn while the documents are written
        pending = (
            _figures.start_figures(self, out, drawing, formats=formats, drawn=drawn)
            if figures
            else None
        )
        written = [write_json(out / "results.json", results_json(self), allow_nan=False)]
        step("documents")
        # derivation.tex includes the PDFs, report.md shows the PNGs
        names = _figures.figure_names(self) if figures else []
        shown = {ext: names if ext in formats else [] for ext in ("pdf", "png")}
        blocks = story.story(self, figures=shown["pdf"])
        md_blocks = (
            blocks if shown["png"] == shown["pdf"] else story.story(self, figures=shown["png"])
        )
        title = self.spec.title if self.spec is not None else document.TITLE
        docs = [
            document.write_tex(blocks, out / "derivation.tex", title=title),
            document.write_markdown(md_blocks, out / "report.md", title=title),
        ]
        if figures:
            step("figures")
            written += pending.paths(parts)
    written += docs
    if pdf:
        step("pdflatex")
        compiled = document.compile_pdf(out / "derivation.tex")
        if compiled is not None:
            written.append(compiled)
    return written


def _attrs(obj, names: str) -> dict:
    """The attributes ``names`` (separated by spaces) of ``obj``, tuples as lists."""
    values = {k: getattr(obj, k) for k in names.split()}
    return {k: list(v) if isinstance(v, tuple) else v for k, v in values.items()}


def _check(check) -> dict:
    return {"ok": check.ok, "method": check.method}


def _section_C(params: dict) -> list[str]:
    """The C of each section drawn (all 1)."""
    return [str(k).replace("epsilon", "C", 1) for k in params if str(k).startswith("epsilon")]


def _zeros_text(poles) -> str:
    """``(z - p1)*(z - p2)*...``, nothing multiplied out ("1": no poles)."""
    return (
        "*".join(f"(z - {sp.sstr(p)})" if p.is_Atom else f"(z - ({sp.sstr(p)}))" for p in poles)
        or "1"
    )


def _diagonal_text(channels) -> str:
    """``G1`` or ``G3``: ``(C...)/((z - e1)*...)`` per channel, a diagonal matrix for several."""
    entries = []
    for e, c in channels:
        zeros = _zeros_text(e)
        den = zeros if len(e) == 1 else f"({zeros})"
        entries.append(f"({sp.sstr(sp.Mul(*c))})/{den}" if e else "1")
    if len(entries) == 1:
        return entries[0]
    rows = (
        ", ".join(x if i == j else "0" for j in range(len(entries))) for i, x in enumerate(entries)
    )
    return "[" + ", ".join(f"[{r}]" for r in rows) + "]"


def _poly_text(value) -> str | list:
    if isinstance(value, sp.MatrixBase):
        return [[descending_str(e) for e in row] for row in value.tolist()]
    return descending_str(value)


def _text_matrix(mat: sp.MatrixBase) -> list[list[str]]:
    return [[sp.sstr(e) for e in row] for row in mat.tolist()]


def _floats(values) -> list[float]:
    return [float(v) for v in values]


def _finite(values) -> list[float | None]:
    """Floats, with None for inf (a nonlinear run that failed)."""
    return [None if not np.isfinite(v) else float(v) for v in values]


def _delays(E: np.ndarray) -> list[list[int | None]]:
    """A delay matrix for JSON: integers, ``None`` for infinity (no path)."""
    return [[None if np.isinf(v) else int(v) for v in row] for row in np.asarray(E)]


def _value(v):
    """An exact or numeric parameter value for JSON (a float, or nested lists for a matrix)."""
    if isinstance(v, sp.MatrixBase | np.ndarray):
        return _matrix(sp.Matrix(v))
    return float(v)


def _theorem_json(verdict) -> dict | None:
    """The exact verdict of :func:`symctl.controller_compatibility` on the model's delay graph."""
    if verdict is None:
        return None
    parts = [
        {"label": p.label, "path": list(p.path), "edge_delays": list(p.delays), "delay": p.delay}
        for p in verdict.parts
    ]
    return {"compatible": verdict.ok} | _attrs(verdict, "scope method reason") | {"parts": parts}


def _matrix(mat: sp.MatrixBase) -> list[list[float]]:
    return np.array(mat.evalf(), dtype=float).tolist()


def _plant_json(res) -> dict:
    """The ``plant`` entry: the discrete plant, its closed forms and the equilibrium."""
    spec, ode = res.spec, res.spec.ode
    sym = res.plant_symbolic
    x_eq = ode.x_bar.tolist() if ode is not None else None
    u_eq = ode.u_bar.tolist() if ode is not None else None
    return {
        "f_bar": x_eq[0] if x_eq else None,
        "r_bar": u_eq[0] if u_eq else None,
        "A": _matrix(res.plant.A),
        "B": _matrix(res.plant.B),
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


def _model_json(res) -> dict:
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
        final = [None if np.isinf(v) else float(v) for v in L.final_deviation]
        out["longest_delay"] = _attrs(L, "longest limited tolerance delays") | {
            "final_deviation": final,
            "stabilized": list(L.stabilized),
        }
    return out
