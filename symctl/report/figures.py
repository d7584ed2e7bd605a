r"""The report's figures, built from a :class:`~symctl.report.pipeline.PaperResults`.

Each figure is a :class:`matplotlib.figure.Figure` made by the plotting method of
the object it shows; :func:`paper_figures` collects them under stable file
names, :func:`save_all` writes each as PNG and SVG, and :func:`write_figures`
makes and writes them all, in parallel processes. The figures of the paper:

============================  ==================================================
name                          content
============================  ==================================================
``open_loop``                 Fig. ol_sims: the linear muscle's response to a
                              pulse in firing rate
``closed_loop``               Fig. cl_sims: the optimal delayed controller's
                              response to a pulse disturbance on the force
``nonlinear``                 the linear controller around the nonlinear muscle
``firing_<circuit>``          Figs. full_diagram, ccr_diagram, ocr_diagram: the
                              neurons' firing in several realizations
``structure_<circuit>``       the structure (gains, adders, unit delays)
``circuit_<circuit>``         the circuit of stylized neurons (for ``general``
                              the first simulated realization, with numbers)
============================  ==================================================

with ``<circuit>`` one of :data:`symctl.report.pipeline.CIRCUITS` (``ifp``, ``general``,
``controllable``, ``observable``).
"""

from __future__ import annotations

import multiprocessing
import os
from collections.abc import Mapping
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import TYPE_CHECKING

from symctl.errors import ParameterError

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from symctl.report.pipeline import PaperResults

__all__ = [
    "DPI",
    "FORMATS",
    "TITLES",
    "figure_names",
    "make_figure",
    "paper_figures",
    "save",
    "save_all",
    "write_figures",
]

DPI = 120
"""Resolution of the PNG files [dots per inch]."""
FORMATS = ("png", "svg")
TITLES = {
    "ifp": "IFP controller",
    "general": "G3 G2 G1, general realization of G2 (symbolic P)",
    "controllable": "G3 G2 G1, controllable canonical G2",
    "observable": "G3 G2 G1, observable canonical G2",
}
"""Titles of the structure and circuit diagrams, by circuit."""


def figure_names(res: PaperResults) -> list[str]:
    """The names of the report's figures, in reading order."""
    names = ["open_loop", "closed_loop"]
    for circuit in res.circuits:
        names += [f"structure_{circuit}", f"circuit_{circuit}", f"firing_{circuit}"]
    return [*names, "nonlinear"]


def make_figure(res: PaperResults, name: str) -> Figure:
    """The figure ``name`` (one of :func:`figure_names`)."""
    if name == "open_loop":
        return res.open_loop.plot()
    if name == "closed_loop":
        return res.closed_loop.plot()
    if name == "nonlinear":
        return res.nonlinear.plot()
    kind, _, circuit = name.partition("_")
    rec = res.circuits.get(circuit)
    if rec is None or kind not in ("structure", "circuit", "firing"):
        raise ParameterError(f"name: no figure {name!r}; the figures are {figure_names(res)}")
    if kind == "firing":
        return rec.firing.plot()
    if kind == "structure":
        return rec.structure.draw(title=f"Structure: {TITLES[circuit]}")
    if circuit == "general":  # weights rational in a symbolic P are unreadable: show numbers
        title = "Circuit: G3 G2 G1, general G2 (realization #1 of the simulations)"
        return rec.firing.circuits[0].draw(title=title)
    return rec.circuit.draw(title=f"Circuit: {TITLES[circuit]}")


def paper_figures(res: PaperResults) -> dict[str, Figure]:
    """Every figure of the report, keyed by file name (without extension), in reading order."""
    return {name: make_figure(res, name) for name in figure_names(res)}


def save(fig: Figure, out: Path, name: str, *, dpi: int = DPI) -> list[Path]:
    """Save ``fig`` as ``out/<name>.png`` and ``out/<name>.svg``; returns the paths.

    The layout is computed once, for the first format.
    """
    out = Path(out)
    if not out.is_dir():
        raise ParameterError(f"out: {str(out)!r} is not a folder")
    paths = []
    for ext in FORMATS:
        path = out / f"{name}.{ext}"
        fig.savefig(path, dpi=dpi, metadata=_metadata(ext))
        fig.set_layout_engine("none")  # keep the layout of the first save
        paths.append(path)
    return paths


def save_all(figs: Mapping[str, Figure], out: Path, *, dpi: int = DPI) -> list[Path]:
    """Save each figure as ``out/<name>.png`` and ``out/<name>.svg``; returns the paths."""
    return [path for name, fig in figs.items() for path in save(fig, out, name, dpi=dpi)]


_SHARED: dict = {}  # the results a forked worker reads (set by write_figures)


def _worker(name: str) -> list[Path]:
    res, out, dpi = _SHARED["job"]
    return save(make_figure(res, name), out, name, dpi=dpi)


def write_figures(
    res: PaperResults, out: Path, *, jobs: int | None = None, dpi: int = DPI
) -> list[Path]:
    """Make and save every figure of the report (PNG and SVG); returns the paths.

    Figures are independent, so with ``jobs > 1`` (default: the number of CPUs,
    at most 4) they are drawn in forked worker processes, which share ``res``
    without copying it; ``jobs=1``, or a platform without ``fork``, draws them here.
    """
    names = figure_names(res)
    out = Path(out)
    if not out.is_dir():
        raise ParameterError(f"out: {str(out)!r} is not a folder")
    if jobs is None:
        jobs = min(4, os.cpu_count() or 1)
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ParameterError(f"jobs: must be an integer >= 1, got {jobs!r}")
    if jobs == 1 or "fork" not in multiprocessing.get_all_start_methods():
        return [p for name in names for p in save(make_figure(res, name), out, name, dpi=dpi)]
    _SHARED["job"] = (res, out, dpi)
    try:
        context = multiprocessing.get_context("fork")
        with ProcessPoolExecutor(min(jobs, len(names)), mp_context=context) as pool:
            return [p for paths in pool.map(_worker, names) for p in paths]
    finally:
        _SHARED.clear()


def _metadata(ext: str) -> dict:
    """No dates in the files, so that the same derivation writes the same bytes."""
    if ext == "svg":
        return {"Date": None}
    return {"Software": "symctl (matplotlib)"}
