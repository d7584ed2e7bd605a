r"""The report's figures (the paper's Figs. 2 to 11): their names, each built by the plotting
method of the object it shows, saved as PDF, SVG and PNG in worker processes. The captions are
the document's: the figures carry no heading. This module imports no matplotlib."""

from __future__ import annotations

import contextlib
import functools
from collections.abc import Callable
from pathlib import Path
from typing import NamedTuple

from symctl._util.display import latex
from symctl._util.texnames import signal_tex
from symctl._util.validate import callable_or_none
from symctl.compatibility.assignment import DelayAssignment
from symctl.errors import ParameterError
from symctl.neural.circuit import Circuit
from symctl.plotting import style
from symctl.report.workers import FigureWorkers

__all__ = ["DEFAULT_FORMATS", "figure_formats", "figure_names", "make_figure", "write_figures"]

DPI = style.PNG_DPI  # of the PNG files (the house style's)
FORMATS = style.FORMATS  # pdf, svg, png (the house style's)
DEFAULT_FORMATS = ("pdf", "png")  # derivation.tex includes the PDFs, report.md shows the PNGs
MAX_DRAWN_SIGNALS = 400  # a larger structure is drawn as the overview of its parts
MAX_DRAWN_PARTS = 6  # parts beyond which a structure is drawn as its overview (kept for reference)
MAX_PIXELS = 4000  # longest side of a PNG: a larger figure is written at a lower resolution


def figure_names(res) -> list[str]:
    """The names of the report's figures, in reading order."""
    names = ["open_loop", "closed_loop", "delay_graph"]
    if getattr(res, "closed_loop", True) is None:  # a derivation drawn before its closed loop
        names.remove("closed_loop")
    if getattr(res, "factors", None) is not None:
        names.append("g1g3_structures")
    for circuit in res.circuits:
        names += [f"structure_{circuit}", f"circuit_{circuit}", f"firing_{circuit}"]
    if getattr(res, "nonlinear", None) is not None:
        names.append("nonlinear")
    if getattr(res, "atlas", None) is not None:
        names.append("atlas_overview")
        names += [f"simplified_{c.circuit_class.label}" for c in simplified(res.candidates)]
    if getattr(res, "spiking_cost", None) is not None:
        names.append("spiking_cost")
    return names


def _labels(res) -> dict[str, tuple[str, str]] | None:
    """``name -> (description, unit)`` of the model's states and inputs."""
    spec = getattr(res, "spec", None)
    if spec is None:
        return None
    xs, us = spec.signal_names
    return {n: (spec.descriptions.get(n, ""), spec.unit(n)) for n in (*xs, *us)}


MAX_BOUND_OPS = 40  # the longest right-hand side (SymPy operations) whose limits are sought


def _state_bounds(res) -> list[tuple[float, str]]:
    r"""The limits of :math:`x^*(u) = -b(u)/a` as :math:`u \to \pm\infty` for a plant
    :math:`\dot x = a x + b(u)`, :math:`a < 0`, with their legend text (the muscle's :math:`f_\max`, 0).
    """
    import sympy as sp

    ode = getattr(getattr(res, "spec", None), "ode", None)
    if ode is None or ode.n != 1 or ode.m != 1:
        return []
    x, u = ode.states[0], ode.inputs[0]
    if sp.count_ops(ode.rhs[0]) > MAX_BOUND_OPS:  # a limit of a long expression is unbounded work
        return []
    a = sp.diff(ode.rhs[0], x)
    if a.free_symbols & {x, u} or not float(a.subs(ode.values)) < 0:
        return []
    steady = -sp.expand(ode.rhs[0] - a * x) / a
    unit = res.spec.unit(x.name)
    bounds = []
    for end, word in ((sp.oo, "most"), (-sp.oo, "least")):
        try:
            limit = sp.limit(steady, u, end)
        except (NotImplementedError, ValueError, TypeError, ZeroDivisionError):
            continue
        if not limit.is_finite:
            continue
        value = float(limit.subs(ode.values))
        name = f"${signal_tex(limit.name)}$ = " if isinstance(limit, sp.Symbol) else ""
        sym = signal_tex(x.name)
        amount = f"{value:.4g}" + (f" {unit}" if unit else "")
        bounds.append((value, f"{name}{amount}: the {word} ${sym}$ reaches without $w$"))
    return bounds


def _vertex_names(res) -> tuple[tuple[str, ...] | None, dict]:
    """The model's names of the delay graph's vertices (None: ``v1 .. vN``), their descriptions."""
    spec = getattr(res, "spec", None)
    names = tuple(getattr(spec, "vertices", ()))
    if len(names) != res.graph.n:
        return None, {}
    return names, dict(getattr(spec, "vertex_descriptions", {}))


def _graph_title(res) -> str:
    spec = getattr(res, "spec", None)
    if spec is not None and spec.graph_given:
        title = f"Delay graph of {spec.name}"
    else:
        title = "Delay graph: the chain of the delays (sensor, a relay per further step, actuator)"
    Ts = getattr(spec, "dt", None)
    if Ts:
        title += f"; one step is {Ts * 1000:g} ms" if Ts < 1 else f"; one step is {Ts:g} s"
    return title


def _placed(circuit, rec, graph):
    """The simulated ``circuit`` at the vertices of ``rec``'s witness when it carries over, else
    at the structure's own; unplaced when not compatible."""
    verdict = rec.compatibility
    if not verdict.ok:
        return circuit
    S = circuit.structure
    if verdict.assignment is not None:
        where = verdict.assignment.vertex_of
        if all(k in where for k in S.blocks):
            try:
                return Circuit.from_structure(
                    S, DelayAssignment(S, graph, {k: where[k] for k in S.blocks})
                )
            except ParameterError:
                pass
    from symctl.compatibility.check import check_compatibility

    own = check_compatibility(S, graph)
    return Circuit.from_structure(S, own) if own.ok and own.assignment is not None else circuit


EPS_RANGE = (-0.9, 0.9)  # the simulations' epsilon: a weight is coloured by its sign over it


def _signs_at(res, circuit) -> dict:
    """The values a circuit figure reads its signs at: the gains, C = 1, epsilon's range."""
    free = circuit.free_symbols
    values = {k: v for k, v in res.gains.substitutions().items() if k in free}
    for sym in free - set(values):
        if str(sym).startswith("epsilon"):
            values[sym] = EPS_RANGE
        elif str(sym).startswith("C"):
            values[sym] = 1
    return values


def _end_labels(res, S) -> dict[str, str] | None:
    """The plant's names at the structure's ends (measured states in, inputs out)."""
    spec = getattr(res, "spec", None)
    if spec is None:
        return None
    xs, us = spec.signal_names
    if len(xs) != len(S.inputs) or len(us) != len(S.outputs):
        return None
    pairs = (*zip(S.inputs, xs, strict=True), *zip(S.outputs, us, strict=True))
    return {n: signal_tex(v) for n, v in pairs}


def _dense(circuit: str) -> bool:
    """Whether ``circuit`` realizes G2 by a transform P (symbolic in the derivation)."""
    from symctl.realization.realizers import REALIZERS

    return circuit in REALIZERS and REALIZERS[circuit].takes_transform


def _structure_figure(res, rec, circuit: str, names):
    """The structure of ``rec``, witness in bands; the first simulated realization's when
    a symbolic gain is longer than :data:`KEY_LENGTH`."""
    from symctl.plotting.circuit_labels import visible_length

    title = ""  # the caption names the structure; the figure notes only what departs from it
    S, verdict = rec.structure, rec.compatibility
    where = verdict.assignment.vertex_of if verdict.ok and verdict.assignment else None
    gains = (b.gain for b in S.blocks.values() if b.kind == "gain" and b.gain is not None)
    if (
        _dense(circuit)
        and rec.firing is not None
        and any(visible_length(latex(g)) > KEY_LENGTH for g in gains)  # stops at the first
    ):
        S = rec.firing.circuits[0].structure
        title = "Realization #1 of the simulations, with numbers (its symbolic gains are too long)"
    if where is not None and not set(S.blocks) <= set(where):
        where = None
    if where is None and verdict.ok is False:
        title = "; ".join(t for t in (title, "not compatible (no vertex bands)") if t)
        title = title[:1].upper() + title[1:]  # a heading of its own starts with a capital
    return S.draw(
        title=title,
        overview="auto",
        max_signals=MAX_DRAWN_SIGNALS,
        assignment=where,
        vertex_names=names,
        labels=_end_labels(res, S),
    )


def _g1g3_figure(factors):
    """The paper's Fig. 7 (left): two structures of a first-order section on one edge."""
    from symctl.compatibility.check import check_compatibility
    from symctl.compatibility.delaygraph import DelayGraph
    from symctl.compatibility.structure import Structure
    from symctl.plotting.structure import draw_structures
    from symctl.realization.realization import first_order_realization

    eps = (*factors.sensor_eps, *factors.actuator_eps)[0]
    C = (*factors.sensor_C, *factors.actuator_C)[0]
    section = first_order_realization(eps, C)
    edge = DelayGraph.chain([1])
    panels = []
    for delays, words in (
        ("branch", "one delay on each branch into the adder (the paper's choice)"),
        ("state", "one delay after the adder"),
    ):
        S = Structure.from_realization(section, delays)
        verdict = check_compatibility(S, edge)
        fits = "compatible" if verdict.ok else "not compatible"
        caption = f'delays="{delays}": {words}; {fits} with one edge v1 -> v2 of one step'
        panels.append((S, caption, verdict.assignment if verdict.ok else None))
    return draw_structures(panels)  # the caption names the section


KEY_LENGTH = 120  # the longest gain (visible characters) a structure figure's key prints


def simplified(candidates, count: int = 2) -> list:
    """The degenerate candidates with the fewest neurons: the paper's simplified circuits."""
    if not candidates:
        return []
    return [c for c in candidates if c.degenerate][:count]


def make_figure(res, name: str):
    """The figure ``name`` (of :func:`figure_names`) as a matplotlib ``Figure``; ParameterError
    for another name."""
    if name in ("open_loop", "closed_loop", "nonlinear"):
        from symctl.plotting.response import nonlinear_plot, response_plot

        labels = _labels(res)
        if name == "nonlinear" and res.nonlinear is not None:
            return nonlinear_plot(res.nonlinear, labels=labels, bounds=_state_bounds(res))
        if name != "nonlinear":
            return response_plot(getattr(res, name), labels=labels)
    names, about = _vertex_names(res)
    if name == "delay_graph":
        return res.graph.draw(names, title=_graph_title(res), descriptions=about)
    if name == "g1g3_structures" and getattr(res, "factors", None) is not None:
        return _g1g3_figure(res.factors)
    if name == "atlas_overview" and res.atlas is not None:
        return res.atlas.draw()
    if name == "spiking_cost" and getattr(res, "spiking_cost", None) is not None:
        return res.spiking_cost.plot()
    if name.startswith("simplified_") and res.candidates:
        for c in res.candidates:
            if c.degenerate and f"simplified_{c.circuit_class.label}" == name:
                return c.circuit.draw(vertex_names=names)  # the caption names it
    kind, _, circuit = name.partition("_")
    rec = res.circuits.get(circuit)
    if rec is None or kind not in ("structure", "circuit", "firing"):
        raise ParameterError(f"name: no figure {name!r}; the figures are {figure_names(res)}")
    if kind == "firing":
        from symctl.plotting.firing import firing_plot

        # at most about five rows of neuron panels: the figure stays within a page
        cols = max(3, -(-len(rec.firing.neurons) // 5))
        return firing_plot(rec.firing, cols, labels=_labels(res))
    if kind == "structure":
        return _structure_figure(res, rec, circuit, names)
    # no heading in the figure: the report's caption names the circuit
    if _dense(circuit):  # weights rational in a symbolic P are unreadable: show numbers
        drawn = _placed(rec.firing.circuits[0], rec, res.graph)
    else:
        drawn = rec.circuit
    return drawn.draw(vertex_names=names, signs_at=_signs_at(res, drawn))


def figure_formats(formats, argname: str = "formats") -> tuple[str, ...]:
    """``formats`` (comma-separated text or names) as names of :data:`FORMATS`, each once, in
    its order (the first lays the figure out); ParameterError names ``argname``."""
    items = formats.split(",") if isinstance(formats, str) else formats
    if not isinstance(items, list | tuple) or not all(isinstance(f, str) for f in items):
        raise ParameterError(f"{argname}: expected format names such as 'pdf,png', got {formats!r}")
    names = {f.strip().lower() for f in items} - {""}
    unknown = sorted(names - set(FORMATS))
    if unknown:
        raise ParameterError(
            f"{argname}: unknown format {unknown[0]!r}; choose among {', '.join(FORMATS)}"
        )
    if not names:
        raise ParameterError(
            f"{argname}: name at least one of {', '.join(FORMATS)}, got {formats!r}"
        )
    return tuple(f for f in FORMATS if f in names)


def save(
    fig, out: Path | str, name: str, *, dpi: int = DPI, formats: tuple[str, ...] = FORMATS
) -> list[Path]:
    """Save ``fig`` as ``out/<name>.<ext>`` for each of ``formats``; returns the paths.

    PDF and SVG are vector drawings (fonts embedded), the PNG the PDF rasterized when there is one,
    at ``dpi`` lowered to keep its longest side within :data:`MAX_PIXELS`. The layout is computed
    once, so the formats agree, and the files carry no date: the same figure writes the same bytes.
    """
    from symctl.plotting.png import render_pdf, write_png
    from symctl.plotting.vector import write_vector

    out = _folder(out)
    paths = []
    dpi = min(dpi, MAX_PIXELS / max(*fig.get_size_inches(), 1e-3))
    png = {"dpi": dpi, "metadata": {"Software": "symctl (matplotlib)"}}
    for ext in figure_formats(formats):
        path = out / f"{name}.{ext}"
        if ext == "png" and paths and paths[0].suffix == ".pdf":  # the PDF rasterized
            render_pdf(paths[0], path, **png)
        elif ext == "png":  # RGB, not matplotlib's RGBA: smaller, and pdflatex copies it
            write_png(fig, path, **png)
        else:  # no date, fixed ids: the same bytes every time
            write_vector(fig, path)
        fig.set_layout_engine("none")  # keep the layout of the first save
        paths.append(path)
    return paths


def write_figures(
    res,
    out: Path | str,
    *,
    jobs: int | None = None,
    formats: tuple[str, ...] = DEFAULT_FORMATS,
    workers=None,
    progress: Callable[[str], None] | None = None,
) -> list[Path]:
    """Make and save every figure of ``res`` into the folder ``out``; returns the paths in the
    order of :func:`figure_names`, each format in turn.

    ``jobs`` processes draw them (:class:`~symctl.report.workers.FigureWorkers`; default the CPUs, at
    most 4), or the started ``workers``; ``progress`` gets each figure's name once saved."""
    out, formats = _folder(out), figure_formats(formats)
    progress = callable_or_none(progress, "progress")
    with contextlib.nullcontext(workers) if workers else FigureWorkers(jobs) as started:
        return start_figures(res, out, started, formats=formats).paths(progress)


class Drawing(NamedTuple):
    """Figures handed to the workers: the names of a derivation's figures, in reading order, and
    the functions ``wait(progress=None) -> {name: paths}`` of the workers drawing them."""

    names: tuple[str, ...]
    waits: tuple[Callable, ...]

    def paths(self, progress: Callable[[str], None] | None = None) -> list[Path]:
        """Wait for every figure; their paths in the order of :attr:`names`."""
        done = {name: p for wait in self.waits for name, p in wait(progress).items()}
        return [p for name in self.names for p in done[name]]


def start_figures(res, out: Path, workers, *, formats=DEFAULT_FORMATS, drawn=None) -> Drawing:
    """Hand the figures of ``res`` to the started ``workers``, but those of the :class:`Drawing`
    ``drawn`` (started on a part of the same derivation, as :func:`~symctl.derive`'s ``early``)."""
    names = tuple(figure_names(res))
    before = drawn.names if drawn is not None else ()
    task = functools.partial(_draw, out=out, formats=formats)
    first = sorted((n for n in names if n not in before), key=_drawing_rank)  # longest first
    wait = workers.submit(task, res, first)
    return Drawing(names, (*(drawn.waits if drawn is not None else ()), wait))


def _draw(res, name: str, *, out: Path, formats: tuple[str, ...]) -> list[Path]:
    return save(make_figure(res, name), out, name, formats=formats)


_SLOWEST = ("circuit_", "firing_", "structure_", "atlas_", "simplified_")  # slowest to draw first


def _drawing_rank(name: str) -> int:
    return next((k for k, prefix in enumerate(_SLOWEST) if name.startswith(prefix)), len(_SLOWEST))


def _folder(out: Path | str) -> Path:
    out = Path(out)
    if not out.is_dir():
        raise ParameterError(f"out: {str(out)!r} is not a folder")
    return out
