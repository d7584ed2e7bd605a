r"""Rendering of a circuit drawing: neurons as circles, synapses as arrows, weights as labels.

The positions come from :mod:`symctl.plotting.circuit_layout` and the text from
:mod:`symctl.plotting.circuit_labels` (long weights as :math:`w_1, w_2, \dots`, listed
in a key under the drawing); this module measures the labels (a neuron's circle fits
its self-dynamics) and draws with matplotlib's patches on a pyplot-free figure, the
key as the glyph outlines that measured it.

>>> from symctl import Circuit, ifp_structure
>>> from symctl.plotting.circuit import draw_circuit
>>> fig = draw_circuit(Circuit.from_structure(ifp_structure(2)))
>>> [p.get_gid() for p in fig.axes[0].patches if p.get_gid()]
['neuron:mu']
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from matplotlib.patches import Circle, FancyArrowPatch, PathPatch
from matplotlib.transforms import Affine2D, ScaledTranslation

from symctl._util.texnames import signal_tex
from symctl.plotting.circuit_labels import circuit_text, display_text
from symctl.plotting.circuit_layout import MIN_RADIUS, circuit_layout
from symctl.plotting.common import figure_and_axes, finish_figure, text_outline, text_size
from symctl.plotting.key import key_columns

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from symctl.neural.circuit import Circuit

__all__ = ["draw_circuit"]

_COLOURS = {"+": "#1f5fa8", "-": "#c0392b", "?": "0.55", "0": "0.75"}
_FONT = 9
_DOT = 0.06  # radius of an input or output dot [in]
_KEY_GAP = 0.4  # between two columns of the key [in]


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
    text = circuit_text(c)
    body = {name: display_text(tex) for name, tex in text.bodies.items()}
    radius = {
        name: max(MIN_RADIUS, text_size(tex, _FONT)[0] / 2 + 0.1) for name, tex in body.items()
    }
    lay = circuit_layout(c, radius)
    pos = lay.pos
    fig, ax, own = figure_and_axes(ax)

    for arc in lay.arcs:
        s = arc.synapse
        sign = s.sign if s is not None else "+"
        colour = _COLOURS[sign] if s is not None else "0.15"
        style = "-[,widthB=0.7,lengthB=0" if sign == "-" else "-|>,head_length=0.5,head_width=0.25"
        dashed = s is not None and s.delay > 0
        ax.add_artist(  # not add_patch: its data limits would route every arrow once more
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
            display_text(text.weights[s]),
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
    key_lo, key_hi = _draw_key(ax, text.key_lines(), x_lo + 0.1, y_lo - 0.05, x_hi - x_lo - 0.3)
    y_lo, x_hi = min(y_lo, key_lo), max(x_hi, key_hi)
    return finish_figure(fig, ax, own, (x_lo, x_hi, y_lo, y_hi), heading, key, top=0.65)


def _draw_key(ax, lines: list[str], x: float, y: float, room: float) -> tuple[float, float]:
    r"""The key's ``label = value`` lines from ``(x, y)`` down, in columns if they fit ``room``.

    Each line is drawn as the outlines of its glyphs (a ``PathPatch`` with gid
    ``key:w1``, ``key:self1``, ...), the path that also measured it: matplotlib parses
    a mathtext string again for every measure and every output format, and a key of
    forty long fractions took two thirds of the drawing's time, three times over. As many
    columns as fit (:func:`symctl.plotting.key.key_columns`), each as wide as its widest line, filled top to
    bottom; each row is as tall as its tallest line (a fraction is). The key is laid out
    in inches from its corner ``(x, y)``, as text is; returns its lowest ``y`` and
    rightmost ``x`` in data units of one inch (``y`` and ``x`` without lines).
    """
    if not lines:
        return y, x
    outlines = [text_outline(f"${line}$", _FONT) for line in lines]
    sizes = [((x1 - x0) / 72, (y1 - y0) / 72) for _, (x0, y0, x1, y1) in outlines]
    columns = key_columns([w for w, _ in sizes], room, _KEY_GAP)
    nrows = len(columns[0])
    # laid out in inches from its corner (x, y) in data units, as text is (a caller's axes
    # may scale its data): glyphs in points -> inches, the offset, then display units
    anchor = ax.figure.dpi_scale_trans + ScaledTranslation(x, y, ax.transData)
    lefts = [0.0]
    for col in columns:
        lefts.append(lefts[-1] + max(sizes[k][0] for k in col) + _KEY_GAP)
    top = 0.0
    for r in range(nrows):
        row = [(c, col[r]) for c, col in enumerate(columns) if r < len(col)]
        for c, k in row:
            path, (x0, _, _, y1) = outlines[k]
            if path is None:
                continue
            place = Affine2D().translate(-x0, -y1).scale(1 / 72).translate(lefts[c], top)
            name = re.sub(r"\\mathrm|[^A-Za-z0-9]", "", lines[k].partition(" = ")[0])
            ax.add_artist(  # not add_patch: its data limits would walk every glyph's curves
                PathPatch(path, transform=place + anchor, fc="black", lw=0, zorder=3,
                          gid=f"key:{name}")
            )  # fmt: skip
        top -= max(sizes[k][1] for _, k in row) + 0.1
    return y + top - 0.1, x + lefts[-1] - _KEY_GAP + 0.2
