"""The overview of a structure too large to draw block by block: its parts and how they join.

A MIMO controller's :math:`G_2` in a block form has hundreds of gains (the
antagonist pair's general realization has 732 signals): no block diagram of it is
legible on a 6.9-inch page. :func:`draw_structure_overview` draws instead what a paper
would: the parts of :math:`G_3 G_2 G_1` in signal-flow order, one box each with its
counts of states, gains, adders and delays, rows snaking so that the figure stays
page-shaped; parallel pathways (:meth:`Structure.parallel
<symctl.compatibility.structure.Structure.parallel>`) one row each, joined by their
output adder. Text at its printed size (7 and 8 points), no wider than the page. The
arrows into the first part and out of the last carry the names the block diagram writes
at its ends (the plant's, when the report passes them): one arrow for all the inputs,
their names listed, a line per few names.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping

from symctl.compatibility.structure import Structure
from symctl.errors import SymctlTypeError
from symctl.plotting.common import figure_and_axes, fit_to_drawing, text_size, wrap
from symctl.plotting.structure_labels import end_labels
from symctl.plotting.style import FONT_SIZE, SMALL, TEXT_WIDTH

__all__ = ["draw_structure_overview", "parts_in_order"]

_BOX_W, _BOX_H, _GAP, _ROW = 1.0, 0.62, 0.3, 0.95  # inches
_END = 0.35  # room for the input or output label and its arrow, at least [in]
_LABEL_ROOM = 1.1  # the widest line of names at an end [in]
_LINE = 0.15  # pitch of those lines [in]


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


def _count_lines(k: dict[str, int]) -> tuple[str, str]:
    """The two lines of counts in a part's box."""
    return (
        f"{_plural(k['states'], 'state')}, {_plural(k['delay'], 'delay')}",
        f"{_plural(k['gain'], 'gain')}, {_plural(k['sum'], 'adder')}",
    )


def _rows(S: Structure, per_row: int) -> tuple[list[list[str]], bool]:
    """The parts in rows, and whether they are parallel pathways (one row each).

    A series snakes in rows of ``per_row``.
    """
    from symctl.plotting.structure_rows import series_parts

    order = [p for p, _ in parts_in_order(S) if p]
    if series_parts(S) is None and len({p.partition(".")[0] for p in order}) > 1:
        groups: dict[str, list[str]] = {}
        for p in order:
            groups.setdefault(p.partition(".")[0], []).append(p)
        if all(len(g) <= per_row for g in groups.values()):
            return list(groups.values()), True
    return [order[k : k + per_row] for k in range(0, len(order), per_row)], False


def _end_lines(names: list[str]) -> list[str]:
    """The names at one end (LaTeX) as mathtext lines, comma-separated, each at most
    :data:`_LABEL_ROOM` wide (a single name may be wider)."""
    lines: list[list[str]] = []
    for name in names:
        if lines and text_size(f"${', '.join([*lines[-1], name])}$", FONT_SIZE)[0] <= _LABEL_ROOM:
            lines[-1].append(name)
        else:
            lines.append([name])
    return [f"${', '.join(line)}$" for line in lines]


def draw_structure_overview(
    S: Structure,
    ax=None,
    *,
    title: str | None = None,
    width: float = TEXT_WIDTH,
    labels: Mapping[str, str] | None = None,
):
    """Draw ``S`` as its parts, one box per part with its counts.

    Parameters
    ----------
    S : Structure
    ax : matplotlib Axes, optional
        Draw into these axes; by default a new figure sized to the drawing.
    title : str, optional
        The heading (default: the structure's counts; ``""``: none, for a figure whose
        caption names it).
    width : float, default TEXT_WIDTH
        The widest the figure may be [in].
    labels : mapping of str to str, optional
        LaTeX labels of the inputs and outputs, by signal name, as for
        :func:`~symctl.plotting.structure.draw_structure` (default: the signals' own
        names).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    SymctlTypeError
        ``S`` is not a Structure, or ``labels`` not a mapping of strings.
    ParameterError
        ``labels`` names a signal that is no input or output.

    Examples
    --------
    >>> from symctl import controller_tf, factor, observable_canonical, Structure
    >>> from symctl.plotting.structure_overview import draw_structure_overview
    >>> f = factor(controller_tf(6), 3, 3)
    >>> S = Structure.from_factorization(f, observable_canonical(f.abbreviated()))
    >>> fig = draw_structure_overview(S, labels={"G1.1.u": "f", "G3.3.x1": "r"})
    >>> texts = [t.get_text() for t in fig.axes[0].texts]
    >>> "G1.1" in texts, "$f$" in texts, "$r$" in texts
    (True, True, True)
    """
    if not isinstance(S, Structure):
        raise SymctlTypeError(f"S: expected a Structure, got {type(S).__name__}")
    from matplotlib.patches import FancyArrowPatch, FancyBboxPatch

    ends = end_labels(S, labels)
    ins = _end_lines([ends[n] for n in S.inputs])
    outs = _end_lines([ends[n] for n in S.outputs])
    widest = max(text_size(t, FONT_SIZE)[0] for t in (*ins, *outs))
    end = max(_END, 0.3 + 1.06 * widest)  # room for an end's arrow and its names, either side
    counts = {part: _count_lines(k) for part, k in parts_in_order(S)}
    box_w = max(  # a part of hundreds of gains gets a wider box: its counts stay inside
        [_BOX_W] + [text_size(t, SMALL - 0.5)[0] * 1.06 + 0.14 for c in counts.values() for t in c]
    )
    step = box_w + _GAP
    per_row = max(1, int((width - 2 * end - 0.2 + _GAP) // step))
    rows, parallel = _rows(S, per_row)
    fig, ax, own = figure_and_axes(ax)
    centres: dict[str, tuple[float, float]] = {}
    for r, row in enumerate(rows):
        for c, part in enumerate(row):
            if not parallel and r % 2:  # a series snakes, so its arrows stay short
                c = per_row - 1 - c
            centres[part] = (end + box_w / 2 + c * step, -r * _ROW)
    for part, (x, y) in centres.items():
        ax.add_patch(
            FancyBboxPatch(
                (x - box_w / 2, y - _BOX_H / 2),
                box_w,
                _BOX_H,
                boxstyle="round,pad=0.01",
                fc="0.96" if "G2" in part else "white",
                ec="black",
                lw=0.8,
            )
        )
        ax.text(x, y + 0.17, part, ha="center", va="center", fontsize=FONT_SIZE)
        ax.text(
            x,
            y - 0.1,
            "\n".join(counts[part]),
            ha="center",
            va="center",
            fontsize=SMALL - 0.5,
            linespacing=1.2,
        )

    def arrow(a, b):
        ax.add_patch(
            FancyArrowPatch(
                a,
                b,
                arrowstyle="-|>",
                mutation_scale=8,
                lw=0.8,
                color="black",
                shrinkA=0,
                shrinkB=0,
            )
        )

    def names(lines, x, y, ha):
        for k, line in enumerate(lines):  # one line per few names, centred on the arrow
            ax.text(
                x,
                y + ((len(lines) - 1) / 2 - k) * _LINE,
                line,
                ha=ha,
                va="center",
                fontsize=FONT_SIZE,
            )

    half = box_w / 2
    chains = rows if parallel else [[p for row in rows for p in row]]
    ends_x = []
    for chain in chains:
        x0, y0 = centres[chain[0]]
        arrow((x0 - half - 0.21, y0), (x0 - half, y0))
        names(ins, x0 - half - 0.24, y0, "right")
        for a, b in itertools.pairwise(chain):
            (xa, ya), (xb, yb) = centres[a], centres[b]
            if ya == yb:
                d = 1 if xb > xa else -1
                arrow((xa + d * half, ya), (xb - d * half, yb))
            else:
                arrow((xa, ya - _BOX_H / 2), (xb, yb + _BOX_H / 2))
        xe, ye = centres[chain[-1]]
        ends_x.append((xe, ye))
    if parallel:  # the output adder joins the pathways
        xs = max(x for x, _ in ends_x) + half + 0.25
        ys = sum(y for _, y in ends_x) / len(ends_x)
        for xe, ye in ends_x:  # orthogonal: along the row, then down or up to the adder
            ax.plot([xe + half, xs - 0.12, xs - 0.12], [ye, ye, ys], color="black", lw=0.8)
            arrow((xs - 0.12, ys), (xs - 0.02, ys))
        ax.text(xs + 0.03, ys, "+", ha="left", va="center", fontsize=FONT_SIZE)
        names(outs, xs + 0.2, ys, "left")
        x_hi = max(xs + 0.35, xs + 0.25 + widest)
    else:
        xe, ye = ends_x[0]
        d = 1 if len(rows) % 2 else -1
        arrow((xe + d * half, ye), (xe + d * (half + 0.23), ye))
        names(outs, xe + d * (half + 0.27), ye, "left" if d > 0 else "right")
        x_hi = end * 2 + min(per_row, max(len(r) for r in rows)) * step - _GAP
    y_lo = -(len(rows) - 1) * _ROW - _BOX_H / 2 - 0.1
    total = ", ".join(
        _plural(S.count(k), word)
        for k, word in (("gain", "gain"), ("sum", "adder"), ("delay", "delay"))
    )
    heading = f"Controller structure: {total}" if title is None else title
    y = _BOX_H / 2 + 0.12
    for line in (
        f"{_plural(len(S), 'signal')}, too many to draw block by block at print size: its parts,",
        "each with its counts, in signal-flow order (Structure.draw draws every block)",
    )[::-1]:
        ax.text(0.05, y, line, ha="left", va="bottom", fontsize=SMALL, color="0.35")
        y += 0.13
    room = width - 0.15
    heading_lines = wrap(heading.split(" "), room, FONT_SIZE + 0.5) if heading else []
    for line in heading_lines[::-1]:
        ax.text(0.05, y + 0.04, line, ha="left", va="bottom", fontsize=FONT_SIZE + 0.5)
        y += 0.16
    y_hi = y + 0.09
    wide = max((text_size(line, FONT_SIZE + 0.5)[0] * 1.06 for line in heading_lines), default=0)
    x_hi = min(max(x_hi, 4.6, 0.15 + wide), width)
    return fit_to_drawing(fig, ax, own, 0.0, x_hi, y_lo, y_hi)
