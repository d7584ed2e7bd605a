"""The overview of a structure too large to draw block by block: its parts in series.

A structure of a long delay (the general realization at T = 20 has about a
thousand signals) makes a block diagram over a hundred inches wide, unreadable
in print and slow to lay out. :func:`draw_structure_overview` draws instead
what a paper would: the parts of :math:`G_3 G_2 G_1` in signal-flow order, one
box each with its counts of states, gains, adders and one-step delays, rows
wrapped so that the figure stays page-shaped.
"""

from __future__ import annotations

import itertools

from symctl.compatibility.structure import Structure
from symctl.errors import SymctlTypeError
from symctl.plotting.common import figure_and_axes, finish_figure

__all__ = ["draw_structure_overview", "parts_in_order"]

_BOX_W, _BOX_H, _GAP, _ROW = 1.55, 0.9, 0.45, 1.5  # inches
_PER_ROW = 6
_FONT = 7.5


def parts_in_order(S: Structure) -> list[tuple[str, dict[str, int]]]:
    """``(part, counts)`` in series order; counts of ``states``, ``gain``, ``sum``, ``delay``.

    >>> from symctl import controller_tf, factor, controllable_canonical, Structure
    >>> from symctl.plotting.structure_overview import parts_in_order
    >>> f = factor(controller_tf(2))
    >>> S = Structure.from_factorization(f, controllable_canonical(f.G2))
    >>> [(p, c["states"]) for p, c in parts_in_order(S)]
    [('G1', 1), ('G2', 2), ('G3', 1)]
    """
    parts: dict[str, dict[str, int]] = {}
    for name, block in S.blocks.items():
        counts = parts.setdefault(block.part, {"states": 0, "gain": 0, "sum": 0, "delay": 0})
        if block.kind in counts:
            counts[block.kind] += 1
        local = name[len(block.part) + 1 :] if block.part else name
        if local.startswith("x") and local[1:].isdigit():  # the states x1 .. xn
            counts["states"] += 1
    return list(parts.items())


def _plural(k: int, word: str) -> str:
    return f"{k} {word}{'' if k == 1 else 's'}"


def draw_structure_overview(S: Structure, ax=None, *, title: str | None = None):
    """Draw ``S`` as its parts in series, one box per part with its counts.

    Parameters
    ----------
    S : Structure
    ax : matplotlib Axes, optional
        Draw into these axes; by default a new figure sized to the drawing.
    title : str, optional
        The heading (default: the structure's counts).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    SymctlTypeError
        ``S`` is not a Structure.

    Examples
    --------
    >>> from symctl import controller_tf, factor, observable_canonical, Structure
    >>> from symctl.plotting.structure_overview import draw_structure_overview
    >>> f = factor(controller_tf(6), 3, 3)
    >>> S = Structure.from_factorization(f, observable_canonical(f.abbreviated()))
    >>> fig = draw_structure_overview(S)
    >>> [t.get_text() for t in fig.axes[0].texts][1]
    'G1.1'
    """
    if not isinstance(S, Structure):
        raise SymctlTypeError(f"S: expected a Structure, got {type(S).__name__}")
    from matplotlib.patches import FancyArrowPatch, FancyBboxPatch

    parts = parts_in_order(S)
    fig, ax, own = figure_and_axes(ax)
    step = _BOX_W + _GAP
    centres = []
    for k, _ in enumerate(parts):
        row, col = divmod(k, _PER_ROW)
        col = col if row % 2 == 0 else _PER_ROW - 1 - col  # rows snake, so arrows stay short
        centres.append((0.5 + col * step + _BOX_W / 2, -row * _ROW))
    ends = [("u", centres[0][0] - _BOX_W / 2 - 0.45, centres[0][1])]
    last_row = (len(parts) - 1) // _PER_ROW
    sign = 1 if last_row % 2 == 0 else -1
    ends.append(("y", centres[-1][0] + sign * (_BOX_W / 2 + 0.45), centres[-1][1]))
    ax.text(*ends[0][1:], ends[0][0], ha="center", va="center", fontsize=_FONT + 1)
    for (part, counts), (x, y) in zip(parts, centres, strict=True):
        ax.add_patch(
            FancyBboxPatch(
                (x - _BOX_W / 2, y - _BOX_H / 2),
                _BOX_W,
                _BOX_H,
                boxstyle="round,pad=0.02",
                fc="0.96" if part.startswith("G2") else "white",
                ec="black",
                lw=1.0,
            )
        )
        ax.text(x, y + 0.24, part or "structure", ha="center", va="center", fontsize=_FONT + 1)
        lines = [
            _plural(counts["states"], "state"),
            f"{_plural(counts['gain'], 'gain')}, {_plural(counts['sum'], 'adder')}",
            _plural(counts["delay"], "delay"),
        ]
        ax.text(x, y - 0.1, "\n".join(lines), ha="center", va="center", fontsize=_FONT - 1)
    ax.text(*ends[1][1:], ends[1][0], ha="center", va="center", fontsize=_FONT + 1)
    points = [ends[0][1:], *centres, ends[1][1:]]
    for (x0, y0), (x1, y1) in itertools.pairwise(points):
        if y0 == y1:
            d = 1 if x1 > x0 else -1
            start = (x0 + d * (_BOX_W / 2 if (x0, y0) in centres else 0.12), y0)
            end = (x1 - d * (_BOX_W / 2 if (x1, y1) in centres else 0.12), y1)
        else:  # down to the next row
            start, end = (x0, y0 - _BOX_H / 2), (x1, y1 + _BOX_H / 2)
        ax.add_patch(
            FancyArrowPatch(start, end, arrowstyle="-|>", mutation_scale=10, lw=0.9, color="black")
        )
    xs = [x for x, _ in points] + [x + d * _BOX_W / 2 for x, _ in centres for d in (-1, 1)]
    ys = [y for _, y in points]
    bounds = (min(xs) - 0.4, max(xs) + 0.4, min(ys) - _BOX_H / 2 - 0.2, max(ys) + _BOX_H / 2 + 0.1)
    counts = ", ".join(
        _plural(S.count(k), word)
        for k, word in (("gain", "gain"), ("sum", "adder"), ("delay", "one-step delay"))
    )
    heading = title or f"controller structure: {counts}"
    key = (
        f"overview: {_plural(len(S), 'signal')}, too many to draw block by block   "
        "boxes: the parts of G3 G2 G1 in signal-flow order, with their counts   "
        "Structure.draw(max_signals=...) draws every block"
    )
    return finish_figure(fig, ax, own, bounds, heading, key, top=0.5)
