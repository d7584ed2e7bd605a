"""Rendering of a delay graph (the paper's Fig. 2, right), laid out by
:mod:`~symctl.plotting.delaygraph_layout`.
"""

from __future__ import annotations

import textwrap
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

from matplotlib.colors import to_rgb
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch
from matplotlib.path import Path

from symctl.compatibility.delaygraph import DelayGraph
from symctl.errors import ParameterError, SymctlTypeError
from symctl.plotting import style
from symctl.plotting.common import figure_and_axes, fit_to_drawing, heading, text_size, wrap
from symctl.plotting.delaygraph_layout import delay_graph_layout

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["delay_graph_plot", "steps_text"]

_NAME = style.FONT_SIZE  # a vertex's name [pt]
_SMALL = style.SMALL  # its vertex and role, its description, the delays
_LINE = {_NAME: 0.15, _SMALL: 0.13}  # line heights [in]
_PAD = (0.06, 0.05)  # inside a box [in]
_WRAP = 24  # characters per line of a description
_KEY_ROOM = 4.6  # a key under a narrow drawing may be this wide [in]
_ARROW = {"arrowstyle": "-|>,head_length=0.55,head_width=0.3", "mutation_scale": 8}
_LABEL = {"ha": "center", "va": "center", "fontsize": _SMALL, "zorder": 3}
_LABEL["bbox"] = {"boxstyle": "square,pad=0.08", "fc": "white", "ec": "none"}


def _tint(colour: str, amount: float = 0.2) -> tuple[float, float, float]:
    """``colour`` mixed with white: a fill for black text."""
    return tuple(amount * c + (1 - amount) for c in to_rgb(colour))


_FILL = {
    "sensor": (_tint(style.SENSOR), style.SENSOR),
    "actuator": (_tint(style.ACTUATOR), style.ACTUATOR),
    "": ("#f4f4f4", style.NEUTRAL),
}
_INK = style.NEUTRAL
_ROUNDED = "round,pad=0,rounding_size=0.05"  # a vertex's box
_BACK = style.PALETTE[3]  # an edge laid out right to left (closing a cycle)


def steps_text(delay: int) -> str:
    """``"1 step"``, ``"2 steps"``: an edge's label."""
    return f"{delay} step" + ("" if delay == 1 else "s")


def _plain(text: str) -> str:  # a dollar sign does not start mathtext
    return text.replace("$", r"\$")


def _names(graph: DelayGraph, names) -> tuple[list[str], bool]:
    if names is None:
        return [f"v{k}" for k in range(1, graph.n + 1)], False
    if isinstance(names, str) or not isinstance(names, Sequence):
        raise SymctlTypeError(f"names: expected a sequence of {graph.n} strings, got {names!r}")
    if len(names) != graph.n:
        raise ParameterError(f"names: the graph has {graph.n} vertices, got {len(names)} names")
    for k, name in enumerate(names):
        if not isinstance(name, str):
            raise SymctlTypeError(f"names[{k}]: expected a string, got {name!r}")
    return list(names), list(names) != [f"v{k}" for k in range(1, graph.n + 1)]


def _role(graph, k: int) -> str:
    """``"sensor"``, ``"actuator"`` or ``""`` for vertex ``k`` (from 1)."""
    return "sensor" if k in graph.sensors else "actuator" if k in graph.actuators else ""


def _lines(graph, names, named, descriptions) -> dict[int, list[tuple[str, float, str]]]:
    """Each vertex's text lines ``(text, size, style)``: name, vertex and role, description."""
    out = {}
    for k, name in enumerate(names, start=1):
        role = _role(graph, k)
        lines = [(_plain(name.replace("_", " ")), _NAME, "bold")]
        tag = ", ".join(t for t in (f"v{k}" if named else "", role) if t)
        if tag:
            lines.append((tag, _SMALL, "normal"))
        about = descriptions.get(name, "") if descriptions else ""
        lines += [(_plain(t), _SMALL, "italic") for t in textwrap.wrap(about, _WRAP)[:3]]
        out[k] = lines
    return out


def delay_graph_plot(
    graph: DelayGraph,
    names: Sequence[str] | None = None,
    *,
    title: str | None = None,
    descriptions: Mapping[str, str] | None = None,
    ax=None,
) -> Figure:
    """Draw the delay graph: vertices as boxes, direct edges as arrows with their delays, from
    the sensors (green) to the actuators (orange); edges against the flow purple.

    ``names`` of the vertices, :math:`v_1` first (default ``v1 .. vN``; else each box also
    shows its ``v<k>``); ``title`` a heading wrapped to the drawing's width; ``descriptions`` a
    line or two under a vertex's name, by name; ``ax`` to draw into (default: a new figure sized
    to the drawing, one unit one inch).

    Raises SymctlTypeError (``graph`` not a DelayGraph, ``names`` not strings, ``descriptions``
    not a mapping) or ParameterError (``names`` not one per vertex, or more than
    :data:`~symctl.plotting.delaygraph_layout.MAX_DRAWN_VERTICES` vertices).

    >>> from symctl import DelayGraph
    >>> from symctl.plotting.delaygraph import delay_graph_plot
    >>> g = DelayGraph.from_edges(4, [(1, 2, 1), (2, 4, 1), (1, 3, 1), (3, 2, 1)])
    >>> fig = delay_graph_plot(g, ["receptor", "spinal", "cortex", "muscle"], title="Reflex")
    >>> sorted(t.get_text() for t in fig.axes[0].texts if t.get_text().endswith("step"))
    ['1 step', '1 step', '1 step', '1 step']
    """
    if not isinstance(graph, DelayGraph):
        raise SymctlTypeError(f"graph: expected a DelayGraph, got {type(graph).__name__}")
    if descriptions is not None and not isinstance(descriptions, Mapping):
        raise SymctlTypeError(
            f"descriptions: expected a mapping of vertex names to text, got {descriptions!r}"
        )
    names, named = _names(graph, names)
    lines = _lines(graph, names, named, descriptions)
    height = max(sum(_LINE[s] for _, s, _ in ls) for ls in lines.values()) + 2 * _PAD[1]
    sizes = {
        k: (max(1.06 * text_size(t, s)[0] for t, s, _ in ls) + 2 * _PAD[0], height)
        for k, ls in lines.items()
    }
    labels = {(i, j): steps_text(d) for i, j, d in graph.edges}
    label_sizes = {e: (text_size(t, _SMALL)[0] * 1.06 + 0.1, 0.2) for e, t in labels.items()}
    lay = delay_graph_layout(graph, sizes, label_sizes)
    fig, ax, own = figure_and_axes(ax)

    for r in lay.routes:
        colour = _BACK if r.back else _INK
        path = Path(r.bezier, [Path.MOVETO] + [Path.CURVE4] * (len(r.bezier) - 1))
        gid = f"edge:{r.source}-{r.target}"
        ax.add_patch(FancyArrowPatch(path=path, **_ARROW, color=colour, lw=0.9, zorder=1, gid=gid))
        ax.text(*r.label, labels[r.source, r.target], **_LABEL, color=colour)

    for k, (x, y) in lay.pos.items():
        w, h = lay.size[k]
        role = _role(graph, k)
        fill, edge = _FILL[role]
        look = {"fc": fill, "ec": edge, "lw": 1.1 if role else 0.8, "gid": f"vertex:{k}"}
        ax.add_patch(FancyBboxPatch((x - w / 2, y - h / 2), w, h, _ROUNDED, zorder=2, **look))
        top = y + sum(_LINE[s] for _, s, _ in lines[k]) / 2
        for text, size, kind in lines[k]:
            bold = kind == "bold"
            font = {"fontweight": "bold" if bold else "normal", "color": "black" if bold else "0.3"}
            font["fontstyle"] = "italic" if kind == "italic" else "normal"
            at = (x, top - _LINE[size] / 2)
            ax.text(*at, text, ha="center", va="center", fontsize=size, zorder=3, **font)
            top -= _LINE[size]

    ends = (1,), (graph.n,)
    if (tuple(graph.sensors), tuple(graph.actuators)) == ends:
        roles = f"v1 the sensor (green) to v{graph.n} the actuator (orange)"
    else:
        roles = "sensors green, actuators orange (one per channel)"
    key = [f"boxes: vertices, {roles}", "arrows: direct edges, with their delays in steps"]
    if any(r.back for r in lay.routes):
        key.append("purple, curved: edges against the flow (a cycle)")
    return _finish(fig, ax, own, lay.bounds, title, key)


def _finish(fig, ax, own: bool, bounds, title: str | None, key: list[str]):
    """The key under the drawing and the heading (if any) above, both wrapped to its width."""
    x_lo, x_hi, y_lo, y_hi = bounds
    room = max(x_hi - x_lo, min(style.TEXT_WIDTH, _KEY_ROOM)) - 0.1
    lines = wrap(key, room, _SMALL, "   ", 1.08)
    step = _SMALL / 72 * 1.35
    y = y_lo - 0.04
    for line in lines:
        ax.text(x_lo + 0.05, y, line, ha="left", va="top", fontsize=_SMALL, color="0.3")
        y -= step
    right = max(1.04 * text_size(line, _SMALL)[0] for line in lines) + x_lo + 0.1
    y_lo = y - 0.04
    if title:
        top, end = heading(ax, _plain(title), x_lo + 0.05, y_hi + 0.04, room, style.TITLE)
        right, y_hi = max(right, end + 0.05), top + 0.04
    x_hi = max(x_hi, right)
    return fit_to_drawing(fig, ax, own, x_lo, x_hi, y_lo, y_hi)
