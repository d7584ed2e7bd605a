r"""The report's figures: :func:`make_figure` builds each by the plotting method of the object
it shows, under the names of :func:`figure_names` (``open_loop``, ``closed_loop``,
``delay_graph``, ``nonlinear``, ``g1g3_structures`` and ``structure_``/``circuit_``/``firing_``
with each circuit's name, as the paper's Figs. 2 to 11); :func:`save` writes one as PDF, SVG
and PNG, :func:`write_figures` all of them in worker processes. The captions are the
document's: the figures carry no heading. This module imports no matplotlib.
"""

from __future__ import annotations

import contextlib
import functools
from collections.abc import Callable
from pathlib import Path

from symctl._util.display import latex
from symctl._util.texnames import signal_tex
from symctl._util.validate import callable_or_none
from symctl.compatibility.assignment import DelayAssignment
from symctl.errors import ParameterError
from symctl.neural.circuit import Circuit
from symctl.plotting import style
from symctl.report.workers import FigureWorkers

__all__ = [
    "DEFAULT_FORMATS",
    "DPI",
    "FORMATS",
    "MAX_DRAWN_SIGNALS",
    "MAX_PIXELS",
    "figure_formats",
    "figure_names",
    "make_figure",
    "save",
    "write_figures",
]

DPI = style.PNG_DPI
"""Resolution of the PNG files [dots per inch] (the house style's)."""
FORMATS = style.FORMATS
"""The formats a figure can be saved in: vector PDF and SVG, and PNG (the house style's)."""
DEFAULT_FORMATS = ("pdf", "png")
"""The formats the report writes unless asked for others: the PDF that ``derivation.tex``
includes and the PNG that ``report.md`` shows (SVG on request)."""
MAX_DRAWN_SIGNALS = 400
MAX_DRAWN_PARTS = 6  # parts beyond which a structure is drawn as its overview (kept for reference)
"""Structures up to this many signals are drawn block by block when they fit a page; larger
ones as the overview of their parts."""
MAX_PIXELS = 4000
"""Longest side of a PNG [pixels]: a larger figure is written at a lower resolution."""


def figure_names(res) -> list[str]:
    """The names of the report's figures, in reading order.

    Parameters
    ----------
    res : PaperResults
        The derivation (its ``circuits`` name the circuit figures).

    Returns
    -------
    list of str

    Examples
    --------
    >>> from symctl import derive_paper
    >>> from symctl.report.figures import figure_names
    >>> figure_names(derive_paper())[1:5]
    ['closed_loop', 'delay_graph', 'g1g3_structures', 'structure_ifp']
    """
    names = ["open_loop", "closed_loop", "delay_graph"]
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
    """``name -> (description, unit)`` of the model's states and inputs, for the plots."""
    spec = getattr(res, "spec", None)
    if spec is None:
        return None
    xs, us = spec.signal_names
    return {n: (spec.descriptions.get(n, ""), spec.unit(n)) for n in (*xs, *us)}


MAX_BOUND_OPS = 40
"""The longest right-hand side (SymPy operations) whose limits the nonlinear figure seeks."""


def _state_bounds(res) -> list[tuple[float, str]]:
    r"""The limits of :math:`x^*(u) = -b(u)/a` as :math:`u \to \pm\infty`, with their legend
    text, for a plant :math:`\dot x = a x + b(u)`, :math:`a < 0` (the muscle's :math:`f_\max`
    and 0): held between samples, the state stays within them unless disturbed."""
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
    """The model's names of the delay graph's vertices (None: ``v1 .. vN``) and their descriptions."""
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
    """The simulated ``circuit`` at delay-graph vertices: the witness of ``rec`` when it carries
    over (checked again), else the drawn structure's own; unplaced when it is not compatible."""
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


EPS_RANGE = (-0.9, 0.9)
"""The range the simulations draw every epsilon from: a circuit figure colours a weight by its
sign over it (with the gains' values and every C = 1)."""


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
    """The plant's names at the structure's ends (the measured states in, the plant's inputs out)."""
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
    """The structure of ``rec`` with its witness in bands; the first simulated realization's
    (numbers) when a symbolic gain is longer than :data:`KEY_LENGTH`."""
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
    """The paper's Fig. 7 (left): two structures of a first-order section, checked on one edge."""
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


KEY_LENGTH = 120
"""The longest gain value (visible characters) the key of a structure figure prints."""


def simplified(candidates, count: int = 2) -> list:
    """The degenerate candidates with the fewest neurons: the paper's simplified circuits."""
    if not candidates:
        return []
    return [c for c in candidates if c.degenerate][:count]


def make_figure(res, name: str):
    """The figure ``name`` of the report, as a matplotlib ``Figure``.

    Parameters
    ----------
    res : PaperResults
        The derivation.
    name : str
        One of :func:`figure_names`.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ParameterError
        ``name`` is not one of :func:`figure_names`.

    Examples
    --------
    >>> from symctl import derive_paper
    >>> from symctl.report.figures import make_figure
    >>> type(make_figure(derive_paper(), "structure_observable")).__name__
    'Figure'
    """
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
    """``formats`` (a comma-separated text or a sequence of names) as names of :data:`FORMATS`.

    Parameters
    ----------
    formats : str or sequence of str
        Some of ``pdf``, ``svg`` and ``png``, e.g. ``"pdf,png,svg"``.
    argname : str
        The name in the messages (``"--formats"`` for the command line).

    Returns
    -------
    tuple of str
        The formats, each once, in the order of :data:`FORMATS` (the first is the one
        whose renderer lays the figure out).

    Raises
    ------
    ParameterError
        ``formats`` is empty or names an unknown format.

    Examples
    --------
    >>> from symctl.report.figures import figure_formats
    >>> figure_formats("png, svg,png")
    ('svg', 'png')
    >>> figure_formats("pdf,jpg")
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: formats: unknown format 'jpg'; choose among pdf, svg, png
    """
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
    """Save ``fig`` as ``out/<name>.pdf``, ``.svg`` and ``.png`` (``formats``); returns the paths.

    PDF and SVG are vector drawings at the figure's size (fonts embedded); the PNG is the
    PDF rasterized when there is one. The layout is computed once, so the formats agree,
    and the files carry no date: the same figure writes the same bytes.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    out : path
        An existing folder.
    name : str
        The file name without extension.
    dpi : int
        Resolution of the PNG, lowered for a figure whose longest side would
        exceed :data:`MAX_PIXELS`.
    formats : sequence of str
        Some of :data:`FORMATS` (:func:`figure_formats`); default all three.

    Returns
    -------
    list of Path
        In the order of :data:`FORMATS`.

    Raises
    ------
    ParameterError
        ``out`` is not a folder, or ``formats`` names an unknown format.

    Examples
    --------
    >>> import tempfile
    >>> from symctl import MuscleModel, open_loop_response
    >>> from symctl.report.figures import save
    >>> fig = open_loop_response(MuscleModel().plant()).plot()
    >>> with tempfile.TemporaryDirectory() as out:
    ...     [p.name for p in save(fig, out, "open_loop")]
    ['open_loop.pdf', 'open_loop.svg', 'open_loop.png']
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
    dpi: int = DPI,
    formats: tuple[str, ...] = DEFAULT_FORMATS,
    workers=None,
    progress: Callable[[str], None] | None = None,
) -> list[Path]:
    """Make and save every figure of the report; returns the paths.

    With ``jobs > 1`` they are drawn in worker processes
    (:class:`~symctl.report.workers.FigureWorkers`), stopped and reaped when anything fails.

    Parameters
    ----------
    res : PaperResults
        The derivation.
    out : path
        An existing folder.
    jobs : int, optional
        Processes drawing figures; default the number of CPUs, at most 4.
    dpi : int
        Resolution of the PNGs.
    formats : sequence of str
        The formats of each figure (:func:`figure_formats`).
    workers : FigureWorkers, optional
        Workers started (entered) earlier; ``jobs`` is then not used.
    progress : callable, optional
        Called with each figure's name once it is saved (in the order they finish).

    Returns
    -------
    list of Path
        One per figure and format, in the order of :func:`figure_names`.

    Raises
    ------
    ParameterError
        ``out`` is not a folder, ``jobs`` is not an integer >= 1, or ``formats``
        names an unknown format.
    SymctlTypeError
        ``progress`` is not callable.
    SymctlError
        A worker died (killed by a signal or out of memory).

    Examples
    --------
    >>> import tempfile
    >>> from symctl import derive_paper
    >>> from symctl.report.figures import write_figures
    >>> with tempfile.TemporaryDirectory() as out:
    ...     write_figures(derive_paper(), out, jobs=0)
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: jobs: must be an integer >= 1, got 0
    """
    out, formats = _folder(out), figure_formats(formats)
    progress = callable_or_none(progress, "progress")
    with contextlib.nullcontext(workers) if workers else FigureWorkers(jobs) as started:
        return start_figures(res, out, started, dpi=dpi, formats=formats)(progress)


def start_figures(res, out: Path, workers, *, dpi: int = DPI, formats=DEFAULT_FORMATS):
    """Hand every figure to the started ``workers``; returns ``paths(progress=None)``, which waits."""
    names = figure_names(res)
    task = functools.partial(_draw, out=_folder(out), dpi=dpi, formats=figure_formats(formats))
    first = sorted(names, key=_drawing_rank)  # the longest first: no straggler at the end
    wait = workers.submit(task, res, first)

    def paths(progress=None) -> list[Path]:
        done = wait(progress)
        return [p for name in names for p in done[name]]

    return paths


def _draw(res, name: str, *, out: Path, dpi: float, formats: tuple[str, ...]) -> list[Path]:
    return save(make_figure(res, name), out, name, dpi=dpi, formats=formats)


_SLOWEST = ("circuit_", "firing_", "structure_", "atlas_", "simplified_")  # slowest to draw first


def _drawing_rank(name: str) -> int:
    return next((k for k, prefix in enumerate(_SLOWEST) if name.startswith(prefix)), len(_SLOWEST))


def _folder(out: Path | str) -> Path:
    out = Path(out)
    if not out.is_dir():
        raise ParameterError(f"out: {str(out)!r} is not a folder")
    return out
