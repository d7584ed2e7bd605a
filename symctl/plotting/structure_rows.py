"""A structure too wide for the page, folded into rows of parts; whether it can fit at all.

A series connection is cut between parts, as many consecutive parts per row as fit; a row
ends with an arrow out of the signal the next begins with, both labelled. A layout only
grows with its texts, so a part too large without text fits no page (:func:`page_bound`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from symctl.compatibility.structure import Block, Structure
from symctl.plotting.structure_labels import StructureText, signal_label, structure_text
from symctl.plotting.structure_layout import Measure, StructureLayout, structure_layout
from symctl.plotting.style import TEXT_WIDTH

ROW_GAP = 0.2  # between two rows of a folded drawing [in]
PAGE_HEIGHT = 8.6  # the tallest drawing that fits a page with its caption [in]


@dataclass(frozen=True)
class StructureRows:
    """The rows of a (possibly folded) structure drawing: ``placed`` each row's layout and its
    shift ``(dx, dy)``, top to bottom; ``key`` the key's LaTeX lines; ``bounds`` of all rows;
    ``folded`` when cut into rows, ``fits`` when within ``width`` and :data:`PAGE_HEIGHT`.
    """

    placed: tuple[tuple[StructureLayout, tuple[float, float]], ...]
    key: tuple[str, ...]
    bounds: tuple[float, float, float, float]
    folded: bool
    fits: bool


@dataclass(frozen=True)
class PageBound:
    """Lower bounds [in] on a structure drawing's ``width`` and ``height`` (its largest part laid
    out alone without text); ``part`` sets the larger excess ("" the whole); truthy when it ``fits``.
    """

    width: float
    height: float
    part: str
    fits: bool

    def __bool__(self) -> bool:
        return self.fits


def _no_text(text: str, points: float) -> tuple[float, float]:
    return 0.0, 0.0


def page_bound(
    S: Structure,
    *,
    labels: Mapping[str, str] | None = None,
    vertex_of: Mapping[str, int] | None = None,
    vertex_names: Mapping[int, str] | None = None,
    width: float = TEXT_WIDTH,
) -> PageBound:
    """Whether the drawing of ``S`` can fit the page: no part (the whole, when no series) laid out
    alone without text is wider than ``width`` or taller than :data:`PAGE_HEIGHT`.
    """
    text = structure_text(S, labels)
    where = dict(vertex_of or {})
    order = series_parts(S)
    if order is None:
        layouts = {"": _lay(S, _no_text, text, where, vertex_names)}
    else:
        layouts = {p: _row(S, [p], _no_text, text, where, vertex_names) for p in order}
    widest, tallest, part, excess = 0.0, 0.0, "", -math.inf
    for name, layout in layouts.items():
        w, h = _width(layout), layout.bounds[3] - layout.bounds[2]
        widest, tallest = max(widest, w), max(tallest, h)
        if max(w - width, h - PAGE_HEIGHT) > excess:
            part, excess = name, max(w - width, h - PAGE_HEIGHT)
    fits = widest <= width + 1e-9 and tallest <= PAGE_HEIGHT
    return PageBound(widest, tallest, part, fits)


def series_parts(S: Structure) -> list[str] | None:
    """The parts of ``S`` in series order (every wire between parts goes to the next), or None."""
    order = list(dict.fromkeys(b.part for b in S.blocks.values()))
    if len(order) < 2 or "" in order:
        return None
    rank = {p: k for k, p in enumerate(order)}
    for a, b, _ in S.wires():
        pa, pb = rank[S.blocks[a].part], rank[S.blocks[b].part]
        if pb not in (pa, pa + 1):
            return None
    return order


def _row(S: Structure, parts: list[str], measure, text: StructureText, where, names):
    """The layout of the parts ``parts`` of ``S`` alone: the signals they read from earlier parts
    become inputs, and its own ends are named as signals."""
    inside = {n for n, b in S.blocks.items() if b.part in parts}
    blocks: dict[str, Block] = {}
    entering: list[str] = []
    for n, b in S.blocks.items():
        if n not in inside:
            continue
        for src in b.inputs:
            if src not in inside and src not in entering:
                entering.append(src)
                blocks[src] = Block("input", part=b.part)
        blocks[n] = b
    inputs = [n for n in S.inputs if n in inside] + entering
    leaving = [  # in the structure's order of blocks: the same row every run
        n
        for n in S.blocks
        if n in inside
        and (n in S.outputs or any(n in b.inputs for m, b in S.blocks.items() if m not in inside))
    ]
    sub = Structure(blocks, inputs, leaving)
    ends = {n: text.ends.get(n, signal_label(n)) for n in (*sub.inputs, *sub.outputs)}
    named = {n: t for n, t in text.names.items() if n in sub.blocks and ends.get(n) != t}
    gains = {n: t for n, t in text.gains.items() if n in sub.blocks}
    return _lay(sub, measure, StructureText(gains, named, ends, ()), where, names)


def _lay(sub: Structure, measure, text, where, names) -> StructureLayout:
    vertex_of = {n: where[n] for n in sub.blocks} if where else None
    return structure_layout(sub, measure, text=text, vertex_of=vertex_of, vertex_names=names)


def _width(layout: StructureLayout) -> float:
    x_lo, x_hi, _, _ = layout.bounds
    return x_hi - x_lo


def structure_rows(
    S: Structure,
    measure: Measure,
    *,
    labels: Mapping[str, str] | None = None,
    vertex_of: Mapping[str, int] | None = None,
    vertex_names: Mapping[int, str] | None = None,
    width: float = TEXT_WIDTH,
) -> StructureRows:
    """The layout of ``S`` in one row, or folded into rows of parts no wider than ``width`` [in];
    ``labels``, ``vertex_of`` and ``vertex_names`` as for
    :func:`~symctl.plotting.structure_layout.structure_layout`.
    """
    text = structure_text(S, labels)
    where = dict(vertex_of or {})
    whole = _lay(S, measure, text, where, vertex_names)
    order = series_parts(S) if _width(whole) > width else None
    rows: list[StructureLayout] = []
    if order is None:
        rows = [whole]
    else:
        start = 0
        while start < len(order):
            best = None
            for stop in range(start + 1, len(order) + 1):
                layout = _row(S, order[start:stop], measure, text, where, vertex_names)
                if best is not None and _width(layout) > width:
                    break
                best = (stop, layout)
            stop, layout = best
            rows.append(layout)
            start = stop
    placed = []
    top = 0.0
    for layout in rows:
        x_lo, _, y_lo, y_hi = layout.bounds
        placed.append((layout, (-x_lo, top - y_hi)))
        top -= (y_hi - y_lo) + ROW_GAP
    x_hi = max(lay_.bounds[1] + dx for lay_, (dx, _) in placed)
    bounds = (0.0, x_hi, top + ROW_GAP, 0.0)
    fits = x_hi <= width + 1e-9 and -bounds[2] <= PAGE_HEIGHT
    return StructureRows(tuple(placed), tuple(text.key_lines()), bounds, len(rows) > 1, fits)
