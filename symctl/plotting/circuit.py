r"""Rendering of a circuit drawing: neurons as circles, synapses as arrows, weights as labels.

The positions come from :mod:`symctl.plotting.circuit_layout`; this module measures
the labels (a neuron's circle fits its self-dynamics), sets the weights in LaTeX
(long ones as :math:`w_1, w_2, \dots`, listed under the drawing) and draws with
matplotlib's patches on a pyplot-free figure.

>>> from symctl import Circuit, ifp_structure
>>> from symctl.plotting.circuit import draw_circuit
>>> fig = draw_circuit(Circuit.from_structure(ifp_structure(2)))
>>> [p.get_gid() for p in fig.axes[0].patches if p.get_gid()]
['neuron:mu']
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

import sympy as sp
from matplotlib.patches import Circle, FancyArrowPatch

from symctl._util.display import latex
from symctl._util.texnames import signal_tex
from symctl._util.validate import to_expr
from symctl.plotting.circuit_layout import MIN_RADIUS, circuit_layout
from symctl.plotting.common import figure_and_axes, finish_figure, text_size

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from symctl.neural.circuit import Circuit
    from symctl.neural.neuron import Neuron, Synapse

__all__ = ["draw_circuit"]

_COLOURS = {"+": "#1f5fa8", "-": "#c0392b", "?": "0.55", "0": "0.75"}
_FONT = 9
_MAX_LABEL = 14  # weights with more visible characters are shown as w_k
_DOT = 0.06  # radius of an input or output dot [in]


def _visible(tex: str) -> int:
    """The number of characters ``tex`` shows (a command counts as one)."""
    text = re.sub(r"\\(left|right|frac|dfrac|cdot)\b", "", tex)
    text = re.sub(r"\\[a-zA-Z]+", "m", text)
    return len(re.sub(r"[{}_^\s]", "", text))


def _weight_tex(weight) -> str:
    """LaTeX of a weight; numbers (e.g. exact rationals) to 3 significant digits."""
    w = to_expr(weight, "weight")
    if w.is_number and w.is_real:
        return f"{float(w):.3g}"
    return latex(w)


def _self_tex(n: Neuron) -> str:
    r"""``\epsilon_{1} z^{-1}``, ``K_{1} z^{-1} + K_{2} z^{-2}``; ``0`` without self-dynamics."""
    if not n.self_terms:
        return "0"
    parts = []
    for s in sorted(n.self_terms, key=lambda s: s.delay):
        w = to_expr(s.weight, "weight")
        tex = _weight_tex(w)
        if isinstance(w, sp.Add):
            tex = rf"\left({tex}\right)"
        parts.append(tex + (rf"\,z^{{-{s.delay}}}" if s.delay else ""))
    return " + ".join(parts).replace("+ -", "- ")


def _where(vertex: int | None, vertex_names) -> str:
    """``"  (v2)"``, ``"  (v2: spinal)"`` with names; empty for a neuron at no vertex."""
    if vertex is None:
        return ""
    name = vertex_names[vertex - 1] if vertex_names and vertex <= len(vertex_names) else ""
    if not name or name == f"v{vertex}":
        return f"  (v{vertex})"
    return f"  (v{vertex}: {name.replace('_', ' ')})".replace("$", r"\$")


def draw_circuit(c: Circuit, ax=None, *, title: str | None = None, vertex_names=None) -> Figure:
    r"""Draw the circuit: neurons as circles, synapses as arrows, layered left to right.

    Each circle holds the neuron's self-dynamics (:math:`\sum_k w_k z^{-d_k}`,
    ``0`` without), its name above it. Synapses carry their weights (long ones as
    :math:`w_1, w_2, \dots`, listed under the drawing); excitatory (positive) ones
    are blue with an arrow head, inhibitory (negative) red with a bar, symbolic
    sign grey; dashed arrows have a one-step delay (:math:`z^{-d}` is written for
    more). Inputs on the left, outputs on the right. A neuron placed on a delay
    graph (:attr:`Neuron.vertex <symctl.neural.neuron.Neuron.vertex>`) shows its
    vertex beside its name: ``(v2)``, or ``(v2: spinal)`` with ``vertex_names``.

    Parameters
    ----------
    c : Circuit
    ax : matplotlib Axes, optional
        Draw into it; by default a new figure sized to the drawing (1 unit = 1 inch).
    title : str, optional
        The heading (default ``"neural circuit: <n> neurons"``).
    vertex_names : sequence of str, optional
        The delay graph's vertex names, :math:`v_1` first.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> from symctl import Circuit, ifp_structure
    >>> from symctl.plotting.circuit import draw_circuit
    >>> fig = draw_circuit(Circuit.from_structure(ifp_structure(2)), title="IFP")
    >>> fig.axes[0].texts[-2].get_text()
    'IFP'

    Placed on the paper's chain sensor -> nervous system -> muscle:

    >>> from symctl import DelayGraph, Structure, check_compatibility, controllable_canonical
    >>> from symctl import controller_tf, factor
    >>> S = Structure.from_factorization(f := factor(controller_tf(2)), controllable_canonical(f.G2))
    >>> c = Circuit.from_structure(S, check_compatibility(S, DelayGraph.chain([1, 1])))
    >>> fig = draw_circuit(c, vertex_names=["sensor", "nervous_system", "muscle"])
    >>> sorted({t.get_text().partition("$  ")[2] for t in fig.axes[0].texts} - {""})
    ['(v2: nervous system)', '(v3: muscle)']
    """
    legend: list[str] = []

    def weight_label(s: Synapse) -> str:
        tex = _weight_tex(s.weight)
        if _visible(tex) > _MAX_LABEL:
            legend.append(rf"$w_{{{len(legend) + 1}}} = {tex}$")
            tex = rf"w_{{{len(legend)}}}"
        if s.delay > 1:
            tex += rf"\,z^{{-{s.delay}}}"
        return f"${tex}$"

    body, radius = {}, {}
    for n in c.neurons:
        tex = _self_tex(n)
        if _visible(tex) > 2 * _MAX_LABEL:
            legend.append(rf"$\mathrm{{self}}({signal_tex(n.name)}) = {tex}$")
            tex = rf"\mathrm{{self}}_{{{len(legend)}}}"
        body[n.name] = f"${tex}$"
        radius[n.name] = max(MIN_RADIUS, text_size(body[n.name], _FONT)[0] / 2 + 0.1)
    lay = circuit_layout(c, radius)
    pos = lay.pos
    fig, ax, own = figure_and_axes(ax)

    for arc in lay.arcs:
        s = arc.synapse
        sign = s.sign if s is not None else "+"
        colour = _COLOURS[sign] if s is not None else "0.15"
        style = "-[,widthB=0.7,lengthB=0" if sign == "-" else "-|>,head_length=0.5,head_width=0.25"
        dashed = s is not None and s.delay > 0
        ax.add_patch(
            FancyArrowPatch(
                pos[arc.source],
                pos[arc.target],
                connectionstyle=f"arc3,rad={arc.rad}",
                arrowstyle=style,
                mutation_scale=12,
                color=colour,
                lw=1.3,
                linestyle=(0, (4, 2.5)) if dashed else "-",
                shrinkA=radius.get(arc.source, _DOT) * 72,
                shrinkB=radius.get(arc.target, _DOT) * 72 + 1,
                zorder=1,
            )
        )
        if s is None:
            continue
        ax.text(
            *arc.label,
            weight_label(s),
            ha="center",
            va="center",
            fontsize=_FONT,
            color=colour if sign != "?" else "0.25",
            bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.9},
            zorder=3,
        )

    for n in c.neurons:
        x, y = pos[n.name]
        ax.add_patch(
            Circle(
                (x, y),
                radius[n.name],
                fc="#f3f3f3",
                ec="black",
                lw=1.2,
                zorder=2,
                gid=f"neuron:{n.name}",
            )
        )
        ax.text(x, y, body[n.name], ha="center", va="center", fontsize=_FONT, zorder=3)
        where = _where(n.vertex, vertex_names)
        ax.text(
            x,
            y + radius[n.name] + 0.08,
            f"${signal_tex(n.name)}${where}",
            ha="center",
            va="bottom",
            fontsize=_FONT,
            color="0.2",
            zorder=3,
        )
    for u in c.inputs:
        x, y = pos[u]
        ax.add_patch(Circle((x, y), _DOT, fc="black", zorder=2))
        ax.text(x - 0.12, y, f"${signal_tex(u)}$", ha="right", va="center", fontsize=_FONT + 1)
    for o in c.outputs:
        x, y = pos[("out", o.target)]
        ax.add_patch(Circle((x, y), _DOT, fc="black", zorder=2))
        name = "output" if o.target == o.source else f"${signal_tex(o.target)}$"
        ax.text(x + 0.12, y, name, ha="left", va="center", fontsize=_FONT + 1)

    x_lo, x_hi, y_lo, y_hi = lay.bounds
    heading = title or (f"neural circuit: {c.n_neurons} neuron{'s' if c.n_neurons != 1 else ''}")
    key = (
        "circles: neurons (their self-dynamics)   blue arrows: excitatory   "
        "red bars: inhibitory   grey: sign depends on symbols   dashed: one-step delay"
    )
    if any(n.vertex is not None for n in c.neurons):
        key += "   (v2): the delay-graph vertex the neuron sits at"
    width = 0.0
    for k, line in enumerate(legend):
        ax.text(x_lo + 0.1, y_lo - 0.05 - 0.28 * k, line, ha="left", va="top", fontsize=_FONT)
        width = max(width, text_size(line, _FONT)[0] + 0.3)
    y_lo -= 0.28 * len(legend) + 0.15
    x_hi = max(x_hi, x_lo + width)
    return finish_figure(fig, ax, own, (x_lo, x_hi, y_lo, y_hi), heading, key, top=0.65)
