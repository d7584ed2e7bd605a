"""Rendering of a structure's block diagram at its printed size (layout:
:mod:`~symctl.plotting.structure_rows`), one data unit one inch; and its overview by parts.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence

from symctl.compatibility.structure import Structure
from symctl.errors import ParameterError, SymctlTypeError
from symctl.plotting.common import figure_and_axes, fit_to_drawing, key_columns, text_size, wrap
from symctl.plotting.layered import Wire, dashed_part
from symctl.plotting.structure_labels import end_labels
from symctl.plotting.structure_layout import ARROW, END_FONT, FONT, NAME_FONT, StructureLayout
from symctl.plotting.structure_rows import page_bound, series_parts, structure_rows
from symctl.plotting.style import FONT_SIZE, SMALL, TEXT_WIDTH, TITLE

_INK = "0.1"
_BAND = ("#e8eef4", "#f4f1e6")  # alternating tints of the vertex bands
_FRAME = "0.4"
_KEY_GAP = 0.3  # between two columns of the key [in]
_ABOVE = {"ha": "center", "va": "bottom", "color": "0.2", "zorder": 4}
_KEY_STYLE = {"ha": "left", "va": "center_baseline", "fontsize": SMALL, "zorder": 3, "gid": "key"}
_CENTRED = {"ha": "center", "va": "center_baseline"}
_NAME_STYLE = {"fontsize": NAME_FONT, "color": "0.15", "zorder": 4}


def vertex_map(S: Structure, assignment) -> dict[str, int] | None:
    """The vertex of every signal of ``S`` from a delay assignment (or a mapping), or None."""
    if assignment is None:
        return None
    where = getattr(assignment, "vertex_of", assignment)
    if not isinstance(where, Mapping):
        raise SymctlTypeError(
            "assignment: expected a DelayAssignment or a mapping of signal names to vertices, "
            f"got {type(assignment).__name__}"
        )
    missing = [n for n in S.blocks if n not in where]
    if missing:
        raise ParameterError(f"assignment: no vertex for the signals {missing[:5]}")
    out = {}
    for n in S.blocks:
        v = where[n]
        if isinstance(v, bool) or not isinstance(v, int) or v < 1:
            raise ParameterError(f"assignment: vertex of {n!r} must be an integer >= 1, got {v!r}")
        out[n] = v
    return out


def _names(vertex_names) -> dict[int, str] | None:
    if vertex_names is None:
        return None
    if isinstance(vertex_names, Mapping):
        return {int(k): str(v) for k, v in vertex_names.items()}
    if isinstance(vertex_names, Sequence) and not isinstance(vertex_names, str):
        return {k + 1: str(v) for k, v in enumerate(vertex_names)}
    raise SymctlTypeError(
        f"vertex_names: expected a sequence or mapping of names, got {vertex_names!r}"
    )


def draw_structure(
    S: Structure,
    ax=None,
    *,
    title: str | None = None,
    max_signals: int = 400,
    overview: bool = False,
    assignment=None,
    vertex_names=None,
    labels: Mapping[str, str] | None = None,
    width: float = TEXT_WIDTH,
):
    r"""Draw the structure ``S`` as a block diagram, at its printed size.

    Gains are boxes with their value (long ones by their entry's name, listed in a key),
    adders circles, one-step delays dashed wires into the delayed signal (a dot); each part
    of a series connection is framed, each delay-graph vertex's signals shaded in a band.

    ``ax``: draw into it (default: a new figure sized to the drawing); ``title``: the heading
    (default the counts of gains, adders and delays; ``""`` none); ``overview``: draw the
    parts' overview instead (:func:`draw_structure_overview`), ``"auto"`` when the diagram
    fits no page however folded or has more than ``max_signals`` signals (else those raise
    ParameterError); ``assignment``: a DelayAssignment or ``{signal: vertex}``, each vertex's
    signals shaded in a band, named by ``vertex_names`` (a sequence or mapping; default
    :math:`v_1, v_2, \dots`); ``labels``: LaTeX of the arrows into the inputs and out of the
    outputs, by signal name; ``width``: the widest the figure may be [in] (wider: folded into
    rows of parts). Raises SymctlTypeError when ``S`` is not a Structure.

    >>> from symctl import ifp_structure
    >>> from symctl.plotting.structure import draw_structure
    >>> fig = draw_structure(ifp_structure(2), title="IFP", labels={"x": "f", "u": "r"})
    >>> texts = [t.get_text() for t in fig.axes[0].texts]
    >>> texts[-1], {"$f$", "$r$"} <= set(texts), float(fig.get_size_inches()[0]) <= 6.91
    ('IFP', True, True)
    """
    if not isinstance(S, Structure):
        raise SymctlTypeError(f"S: expected a Structure, got {type(S).__name__}")
    if overview not in (True, False, "auto"):
        raise ParameterError(f"overview: must be True, False or 'auto', got {overview!r}")
    auto = overview == "auto"
    if len(S) > max_signals and not overview:
        raise ParameterError(
            f"max_signals: the structure has {len(S)} signals, more than {max_signals}; "
            "raise max_signals to draw it anyway"
        )
    rows = None
    if overview is not True and not (auto and len(S) > max_signals):
        where = vertex_map(S, assignment)
        kw = {"labels": labels, "vertex_of": where, "vertex_names": _names(vertex_names)}
        # too large even without text: no text measured, no layout made
        if not auto or page_bound(S, **kw, width=width):
            rows = structure_rows(S, text_size, **kw, width=width)
    if rows is None or (auto and not rows.fits):
        return draw_structure_overview(S, ax, title=title, width=width, labels=labels)
    fig, ax, own = figure_and_axes(ax)
    for layout, (dx, dy) in rows.placed:
        _draw_layout(ax, layout, dx, dy)
    key = list(rows.key)
    x_lo, x_hi, y_lo, y_hi = rows.bounds
    heading, legend = _heading(S, title), _legend(bool(where))
    if any(b.steps > 1 for b in S.blocks.values()):
        legend[2] = "dashed: delays ($z^{-k}$: an axon of k steps)"
    if rows.folded:
        legend.append("a row ends and the next begins with the signal they share")
    y_lo = _draw_key(ax, key, x_lo, y_lo - 0.08, min(width, x_hi - x_lo))
    return _finish(fig, ax, own, (x_lo, x_hi, y_lo, y_hi), heading, legend, width)


def draw_structures(panels, *, title: str = "", width: float = TEXT_WIDTH):
    """Several structures in one figure, one above the other: ``panels`` of ``(Structure, caption,
    assignment or None)``, each caption written above its structure; ``title`` (default none)
    and ``width`` as for :func:`draw_structure`.

    >>> from symctl import Structure
    >>> from symctl.plotting.structure import draw_structures
    >>> from symctl.realization.realization import first_order_realization
    >>> R = first_order_realization(0.5, 2)
    >>> fig = draw_structures([(Structure.from_realization(R, d), d, None) for d in ("branch", "state")])
    >>> [t.get_text() for t in fig.axes[0].texts if t.get_text() in ("branch", "state")]
    ['branch', 'state']
    """
    fig, ax, _ = figure_and_axes(None)
    top, x_hi, keys, banded = 0.0, 0.0, [], False
    for S, caption, assignment in panels:
        if not isinstance(S, Structure):
            raise SymctlTypeError(f"panels: expected Structures, got {type(S).__name__}")
        where = vertex_map(S, assignment)
        banded = banded or bool(where)
        rows = structure_rows(S, text_size, vertex_of=where, width=width)
        lines = wrap(caption.split(" "), width - 0.1, SMALL)
        for line in lines:
            ax.text(0.05, top - 0.02, line, ha="left", va="top", fontsize=SMALL, color="0.2")
            x_hi = max(x_hi, min(0.15 + 1.06 * text_size(line, SMALL)[0], width))
            top -= 0.14
        top -= 0.06
        for layout, (dx, dy) in rows.placed:
            _draw_layout(ax, layout, dx, dy + top)
        keys += [k for k in rows.key if k not in keys]
        top += rows.bounds[2] - 0.15
        x_hi = max(x_hi, rows.bounds[1])
    y_lo = _draw_key(ax, keys, 0.0, top, width)
    return _finish(fig, ax, True, (0.0, x_hi, y_lo, 0.0), title, _legend(banded), width)


def _heading(S: Structure, title: str | None) -> str:
    kinds = (("gain", "gain"), ("sum", "adder"), ("delay", "delay"))
    counts = ", ".join(_plural(S.count(k), word) for k, word in kinds)
    return f"Controller structure: {counts}" if title is None else title


def _legend(banded: bool) -> list[str]:
    legend = ["boxes: gains", "circles: adders", "dashed: one-step delays", "dots: signals"]
    return [*legend, "bands: delay-graph vertices"] if banded else legend


def _draw_layout(ax, layout: StructureLayout, dx: float, dy: float) -> None:
    """One layout, shifted by ``(dx, dy)``: bands, frames, wires, blocks, text."""
    from matplotlib.patches import Circle, FancyBboxPatch, Rectangle

    for k, b in enumerate(layout.bands):  # tints alternate from band to band
        corner, gid = (b.x0 + dx, b.y0 + dy), f"band:v{b.vertex}"
        tint = {"fc": _BAND[k % 2], "ec": "none", "zorder": 0, "gid": gid}
        ax.add_patch(Rectangle(corner, b.x1 - b.x0, b.y1 - b.y0, **tint))
        ax.text((b.x0 + b.x1) / 2 + dx, b.y1 + dy + 0.04, b.label, **_ABOVE, fontsize=FONT_SIZE)
    for f in layout.parts:
        corner, gid = (f.x0 + dx, f.y0 + dy), f"part:{f.part}"
        look = {"fc": "none", "ec": _FRAME, "lw": 0.7, "zorder": 0.5, "gid": gid}
        rounded = "round,pad=0,rounding_size=0.04"
        ax.add_patch(FancyBboxPatch(corner, f.x1 - f.x0, f.y1 - f.y0, boxstyle=rounded, **look))
        x, y = f.x0 + dx + 0.02, f.y1 + dy + 0.02
        ax.text(x, y, f.part, ha="left", va="bottom", fontsize=SMALL, color=_FRAME, zorder=4)
    every = (*layout.wires, *layout.arrows_in, *layout.arrows_out)
    for wire in every:
        _draw_wire(ax, wire, dx, dy, dashed_part(wire, every) if wire.delay else None)
    for x, y in layout.junctions:
        ax.add_patch(Circle((x + dx, y + dy), 0.02, fc=_INK, ec="none", zorder=2))
    for name, (xc, yc) in layout.positions.items():
        xc, yc = xc + dx, yc + dy
        w, h = layout.sizes[name]
        if name in layout.labels:
            gid = f"gain:{name}"
            look = {"fc": "white", "ec": _INK, "lw": 0.8, "zorder": 2, "gid": gid}
            ax.add_patch(Rectangle((xc - w / 2, yc - h / 2), w, h, **look))
            value = layout.labels[name]
            ax.text(xc, yc, value, **_CENTRED, fontsize=FONT, zorder=3, gid=gid)
        elif w > 0.05:  # an adder: a circle with a plus
            arm = min(0.3 * w, 0.045)
            look = {"fc": "white", "ec": _INK, "lw": 0.8, "gid": f"sum:{name}"}
            ax.add_patch(Circle((xc, yc), w / 2, zorder=2, **look))
            ax.plot([xc - arm, xc + arm], [yc, yc], color=_INK, lw=0.8, zorder=3)
            ax.plot([xc, xc], [yc - arm, yc + arm], color=_INK, lw=0.8, zorder=3)
        else:
            look = {"fc": _INK, "ec": "none", "gid": f"signal:{name}"}
            ax.add_patch(Circle((xc, yc), w / 2, zorder=2, **look))
    for lab in layout.names.values():
        ax.text(lab.x + dx, lab.y + dy, lab.text, ha=lab.ha, va=lab.va, **_NAME_STYLE)
    for lab in layout.ends:
        ax.text(lab.x + dx, lab.y + dy, lab.text, ha=lab.ha, va=lab.va, fontsize=END_FONT, zorder=4)


def _draw_wire(ax, wire: Wire, dx: float, dy: float, dashed=None) -> None:
    """A polyline ending in an arrow head; ``dashed`` (its own part) into a delay, z^-k for k."""
    from matplotlib.patches import Polygon

    pts = [(x + dx, y + dy) for x, y in (dashed or wire.points)]
    xs, ys = zip(*pts, strict=True)
    style = (0, (3.0, 2.0)) if wire.delay else "-"
    ax.plot(xs, ys, color=_INK, lw=0.8, linestyle=style, zorder=1, solid_capstyle="butt")
    (x0, y0), (x1, y1) = pts[-2], pts[-1]
    length = math.hypot(x1 - x0, y1 - y0)
    ux, uy = (x1 - x0) / length, (y1 - y0) / length
    bx, by = x1 - ARROW * ux, y1 - ARROW * uy
    half = 0.38 * ARROW
    head = [(x1, y1), (bx - half * uy, by + half * ux), (bx + half * uy, by - half * ux)]
    ax.add_patch(Polygon(head, closed=True, fc=_INK, ec="none", zorder=1.5))
    if wire.delay > 1:
        k = max(range(len(pts) - 1), key=lambda i: math.dist(pts[i], pts[i + 1]))
        (xa, ya), (xb, yb) = pts[k], pts[k + 1]
        box = {"fc": "white", "ec": "none", "pad": 0.3}
        at, lag = ((xa + xb) / 2, (ya + yb) / 2 + 0.02), f"$z^{{-{wire.delay}}}$"
        ax.text(*at, lag, ha="center", va="bottom", fontsize=SMALL, color=_INK, zorder=3, bbox=box)


def _draw_key(ax, lines: list[str], x: float, y: float, room: float) -> float:
    """The key's ``name = value`` lines under the drawing, in columns; returns its lowest y."""
    if not lines:
        return y + 0.08
    texts = [f"${line}$" for line in lines]
    sizes = [text_size(t, SMALL) for t in texts]
    columns = key_columns([w for w, _ in sizes], room - 0.2, _KEY_GAP)
    lefts = [x + 0.1]
    for col in columns:
        lefts.append(lefts[-1] + max(sizes[k][0] for k in col) + _KEY_GAP)
    top = y
    for r in range(len(columns[0])):
        row = [(c, col[r]) for c, col in enumerate(columns) if r < len(col)]
        height = max(sizes[k][1] for _, k in row)
        for c, k in row:
            ax.text(lefts[c], top - height / 2, texts[k], **_KEY_STYLE)
        top -= height + 0.07
    return top


def _finish(fig, ax, own, bounds, heading: str, legend: list[str], width: float, join=True):
    """Heading and legend (items joined on lines, unless not ``join``) above the drawing."""
    x_lo, x_hi, y_lo, y_hi = bounds
    room = min(width, max(x_hi - x_lo, 3.0)) - 0.1
    legend_lines = wrap(legend, room, SMALL, "   ") if join else legend
    heading_lines = wrap(heading.split(" "), room, TITLE) if heading else []
    y = y_hi + 0.06
    for line in reversed(legend_lines):
        ax.text(x_lo + 0.05, y, line, ha="left", va="bottom", fontsize=SMALL, color="0.35")
        y += 0.14
    y += 0.03 if heading_lines else 0.0
    for line in reversed(heading_lines):
        ax.text(x_lo + 0.05, y, line, ha="left", va="bottom", fontsize=TITLE)
        y += 0.16
    widths = [
        text_size(t, s)[0] * 1.06
        for t, s in [*((ln, TITLE) for ln in heading_lines), *((ln, SMALL) for ln in legend_lines)]
    ]
    x_hi = max(x_hi, min(x_lo + max(widths) + 0.15, x_lo + width))
    y_hi = y + 0.04
    return fit_to_drawing(fig, ax, own, x_lo, x_hi, y_lo - 0.04, y_hi)


_BOX_W, _BOX_H, _GAP, _ROW = 1.0, 0.62, 0.3, 0.95  # an overview's boxes and spacing [in]
_END = 0.35  # room for the input or output label and its arrow, at least [in]
_LABEL_ROOM = 1.1  # the widest line of names at an end [in]
_LINE = 0.15  # pitch of those lines [in]


def parts_in_order(S: Structure) -> list[tuple[str, dict[str, int]]]:
    """``(part, counts)`` in series order; counts of ``states``, ``gain``, ``sum``, ``delay``."""
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
    return (
        f"{_plural(k['states'], 'state')}, {_plural(k['delay'], 'delay')}",
        f"{_plural(k['gain'], 'gain')}, {_plural(k['sum'], 'adder')}",
    )


def _rows(S: Structure, per_row: int) -> tuple[list[list[str]], bool]:
    """The parts in rows of ``per_row``, and whether they are parallel pathways (a row each)."""
    order = [p for p, _ in parts_in_order(S) if p] or [""]  # no parts (IFP): one box
    if series_parts(S) is None and len({p.partition(".")[0] for p in order}) > 1:
        groups: dict[str, list[str]] = {}
        for p in order:
            groups.setdefault(p.partition(".")[0], []).append(p)
        if all(len(g) <= per_row for g in groups.values()):
            return list(groups.values()), True
    return [order[k : k + per_row] for k in range(0, len(order), per_row)], False


def _end_lines(names: list[str]) -> list[str]:
    """The names at one end as mathtext lines, comma-separated, each at most :data:`_LABEL_ROOM` wide."""
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
    """Draw ``S`` as its parts in signal-flow order, one box per part with its counts (rows snake
    to stay page-shaped; parallel pathways one row each, joined by their adder); ``ax``,
    ``title``, ``width`` and ``labels`` as for :func:`draw_structure`, which raises the same errors.

    >>> from symctl import controller_tf, factor, observable_canonical, Structure
    >>> from symctl.plotting.structure import draw_structure_overview
    >>> f = factor(controller_tf(6), 3, 3)
    >>> S = Structure.from_factorization(f, observable_canonical(f.abbreviated()))
    >>> texts = [t.get_text() for t in draw_structure_overview(S, labels={"G1.1.u": "f"}).axes[0].texts]
    >>> "G1.1" in texts, "$f$" in texts
    (True, True)
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
        look = {"fc": "0.96" if "G2" in part else "white", "ec": "black", "lw": 0.8}
        corner = (x - box_w / 2, y - _BOX_H / 2)
        ax.add_patch(FancyBboxPatch(corner, box_w, _BOX_H, boxstyle="round,pad=0.01", **look))
        ax.text(x, y + 0.17, part, ha="center", va="center", fontsize=FONT_SIZE)
        inner = {"ha": "center", "va": "center", "fontsize": SMALL - 0.5, "linespacing": 1.2}
        ax.text(x, y - 0.1, "\n".join(counts[part]), **inner)

    def arrow(a, b):
        look = {"arrowstyle": "-|>", "mutation_scale": 8, "shrinkA": 0, "shrinkB": 0}
        ax.add_patch(FancyArrowPatch(a, b, lw=0.8, color="black", **look))

    def names(lines, x, y, ha):
        for k, line in enumerate(lines):  # one line per few names, centred on the arrow
            at = (x, y + ((len(lines) - 1) / 2 - k) * _LINE)
            ax.text(*at, line, ha=ha, va="center", fontsize=FONT_SIZE)

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
    legend = [
        f"{_plural(len(S), 'signal')}, too many to draw block by block at print size: its parts,",
        "each with its counts, in signal-flow order (Structure.draw draws every block)",
    ]
    bounds = (0.0, min(max(x_hi, 4.6), width), y_lo, _BOX_H / 2 + 0.06)
    return _finish(fig, ax, own, bounds, _heading(S, title), legend, width, join=False)
