r"""The regions of a structure drawing: the delay-graph vertices' bands and the parts' frames.

Compatibility is a statement about where signals sit: a delay assignment puts every
signal of a structure at a vertex of the delay graph (the sensor :math:`v_1`, the
actuator :math:`v_N`, ...). The drawing shows it: the columns of the layout are
ordered by *vertex level* (:func:`vertex_levels`: the longest chain of vertices that
the structure's wires lead through before reaching it), so every vertex's signals sit
in one vertical band (:func:`vertex_bands`), shaded and labelled; several vertices of
one level (sensors read in parallel) share the band's columns, one region each. The
parts of a series connection (:math:`G_1, G_2, G_3`) are framed (:func:`frames`).
Numbers only; no matplotlib.

>>> from symctl import Structure, controllable_canonical, controller_tf, factor
>>> from symctl.compatibility.check import check_compatibility
>>> from symctl.compatibility.delaygraph import DelayGraph
>>> from symctl.plotting.structure_regions import vertex_levels
>>> f = factor(controller_tf(2))
>>> S = Structure.from_factorization(f, controllable_canonical(f.G2))
>>> where = check_compatibility(S, DelayGraph.chain([1, 1])).assignment.vertex_of
>>> level = vertex_levels(S, where)
>>> level["G1.u"], level["G2.x1"], level["G3.x1"]
(0, 1, 2)
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import NamedTuple

import networkx as nx

from symctl.compatibility.structure import Structure
from symctl.plotting.style import FONT_SIZE, SMALL

__all__ = ["Band", "Frame", "frames", "vertex_bands", "vertex_levels"]

FRAME_PAD = 0.03  # between a part's blocks and its frame [in]


class Band(NamedTuple):
    """The region of one delay-graph vertex: ``x0 .. x1`` by ``y0 .. y1``, its label above."""

    vertex: int
    label: str
    x0: float
    x1: float
    y0: float
    y1: float


class Frame(NamedTuple):
    """The frame around one part of a series connection."""

    part: str
    x0: float
    x1: float
    y0: float
    y1: float


def vertex_levels(S: Structure, vertex: Mapping[str, int]) -> dict[str, int]:
    """The level of each signal: 0, 1, ... along the vertices its wires lead through.

    The vertices that the structure's wires join form a directed graph; its cycles
    (wires back to an earlier vertex) are broken at the wire going furthest back in
    vertex number, and a vertex's level is the longest path to it. Without an
    assignment every signal has level 0.

    Parameters
    ----------
    S : Structure
    vertex : mapping of signal name to int
        The vertex of each signal (a delay assignment's ``vertex_of``); may be empty.

    Returns
    -------
    dict of str to int
    """
    if not vertex:
        return dict.fromkeys(S.blocks, 0)
    vg = nx.DiGraph()
    vg.add_nodes_from(sorted(set(vertex.values())))
    for a, b, _ in S.wires():
        va, vb = vertex.get(a), vertex.get(b)
        if va is not None and vb is not None and va != vb:
            vg.add_edge(va, vb)
    while True:
        try:
            cycle = nx.find_cycle(vg)
        except nx.NetworkXNoCycle:
            break
        back = max(cycle, key=lambda e: (e[0] - e[1], e[0]))
        vg.remove_edge(back[0], back[1])
    level: dict[int, int] = {}
    for v in nx.lexicographical_topological_sort(vg):
        level[v] = max((level[p] + 1 for p in vg.predecessors(v)), default=0)
    return {n: level[vertex[n]] if n in vertex else 0 for n in S.blocks}


def vertex_label(v: int, names: Mapping[int, str] | None) -> str:
    r"""``$v_{2}$``, or ``spinal ($v_{2}$)`` with the model's name of the vertex.

    >>> from symctl.plotting.structure_regions import vertex_label
    >>> vertex_label(2, None), vertex_label(2, {2: "spinal"})
    ('$v_{2}$', 'spinal ($v_{2}$)')
    """
    name = (names or {}).get(v, "")
    tex = f"$v_{{{v}}}$"
    if not name or name == f"v{v}":
        return tex
    return f"{name.replace('_', ' ').replace('$', '')} ({tex})"


def vertex_bands(vertex, level, boxes, x, hw, gaps, col, y_range, names, measure):
    """The band of each vertex and the drawing's new top (the labels sit above the bands).

    A level's band runs from the middle of the gap before its first column to the middle
    of the gap after its last one; alone at its level, a vertex has the whole height,
    else the height of its own signals.
    """
    if not vertex:
        return (), y_range[1]
    y_lo, y_hi = y_range
    ncol = len(x)
    by_level: dict[int, set[int]] = {}
    cols: dict[int, list[int]] = {}
    for n, v in vertex.items():
        if n in boxes:
            by_level.setdefault(level[n], set()).add(v)
            if n in col:
                cols.setdefault(level[n], []).append(col[n])
    label_h = measure("$v_{1}$", FONT_SIZE)[1]
    bands = []
    for lev in sorted(by_level):
        if lev not in cols:
            continue
        c0, c1 = min(cols[lev]), max(cols[lev])
        x0 = x[c0] - hw[c0] - (gaps[c0] / 2 if lev > min(cols) else 0.06)
        last = c1 == ncol - 1
        x1 = x[c1] + hw[c1] + (gaps[c1 + 1] * (0.85 if last else 0.5))
        members = sorted(by_level[lev])
        for v in members:
            if len(members) == 1:
                y0, y1 = y_lo, y_hi
            else:
                ys = [
                    (b[1] - b[3] / 2, b[1] + b[3] / 2)
                    for n, b in boxes.items()
                    if vertex.get(n) == v
                ]
                y0 = max(y_lo, min(a for a, _ in ys) - 0.12)
                y1 = min(y_hi, max(b for _, b in ys) + 0.12)
            bands.append(Band(v, vertex_label(v, names), x0, x1, y0, y1))
    return tuple(bands), y_hi + label_h + 0.08


def frames(S: Structure, boxes, names, name_sizes, wires, y_hi, measure):
    """The frame of each part (none for a structure of one part) and the drawing's new top.

    A frame holds its part's blocks, their names and the wires between them (a
    state's feedback arc); its label sits above its top left corner.
    """
    parts: dict[str, list[str]] = {}
    for n, block in S.blocks.items():
        parts.setdefault(block.part, []).append(n)
    parts.pop("", None)  # blocks of no part (the output adder of parallel pathways)
    for n in S.inputs:  # an input read by several parts (parallel pathways) is no one's
        readers = {b.part for b in S.blocks.values() if n in b.inputs}
        if len(readers) > 1 and n in parts.get(S.blocks[n].part, []):
            parts[S.blocks[n].part].remove(n)
    if len(parts) <= 1:
        return (), y_hi
    label_h = measure("G1", SMALL)[1]
    out = []
    top = y_hi
    for part, members in parts.items():
        inside = set(members)
        xs, ys = [], []
        for n in members:
            bx, by, bw, bh = boxes[n]
            xs += [bx - bw / 2, bx + bw / 2]
            ys += [by - bh / 2, by + bh / 2]
            if n in names:
                lab, (_, w, h) = names[n], name_sizes[n]
                left = {"center": lab.x - w / 2, "right": lab.x - w, "left": lab.x}[lab.ha]
                xs += [left, left + w]
                ys.append(lab.y + h if lab.va == "bottom" else lab.y - h)
        for w in wires:
            if w.source in inside and w.target in inside:
                xs += [p[0] for p in w.points]
                ys += [p[1] for p in w.points]
        frame = Frame(
            part,
            min(xs) - FRAME_PAD,
            max(xs) + FRAME_PAD,
            min(ys) - FRAME_PAD,
            max(ys) + FRAME_PAD,
        )
        out.append(frame)
        top = max(top, frame.y1 + label_h + 0.06)
    return tuple(out), top
