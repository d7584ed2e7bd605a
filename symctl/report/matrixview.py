r"""Matrices laid out the way a paper shows them, so that every display fits the page."""

from __future__ import annotations

from collections import Counter
from itertools import groupby

import numpy as np
import sympy as sp

from symctl import latex as L
from symctl.report import longform as LF

__all__ = ["MatrixView", "show_matrix"]


class MatrixView:
    r"""Display ``rows``, ``tables`` ``(intro, header, rows)`` to follow, and whether in ``full``."""

    def __init__(self, rows, tables=(), full: bool = False) -> None:
        self.rows, self.tables, self.full = list(rows), list(tables), full


def _entries(M) -> tuple[list[list[object]], bool]:
    """The entries of ``M`` as a list of rows, and whether they are plain floats."""
    if isinstance(M, sp.MatrixBase):
        return M.tolist(), False
    arr = np.asarray(M, dtype=float)
    return arr.reshape(arr.shape[0], -1).tolist() if arr.ndim else [[float(arr)]], True


def _entry_tex(e, numeric: bool, digits: int) -> str:
    if numeric:
        return L.number(e, digits)
    return L.to_latex(e, digits=digits)


def _is(e, value) -> bool:
    try:
        return bool(e == value)
    except TypeError:  # pragma: no cover - a relational entry
        return False


def _runs(items: list[str]) -> str:
    """Items joined by commas, a run of four or more equal ones braced with its length."""
    out = []
    for item, group in groupby(items):
        run = len(list(group))
        out.append(
            rf"\underbrace{{{item}, \dots, {item}}}_{{{run}}}"
            if run >= 4
            else ", ".join([item] * run)
        )
    return ", ".join(out)


def _companion(E) -> str | None:
    """``"row"`` or ``"column"``: the companion form with a free last row or column; else None."""
    n = len(E)
    if n < 3 or any(len(r) != n for r in E):
        return None
    if all(_is(E[i][j], 1 if j == i + 1 else 0) for i in range(n - 1) for j in range(n)):
        return "row"
    if all(_is(E[i][j], 1 if i == j + 1 else 0) for i in range(n) for j in range(n - 1)):
        return "column"
    return None


def _index(base: str, i: str, j: str) -> str:
    return f"{{{base}}}_{{{i},{j}}}"


def _offset(k: int) -> str:
    return "i" if k == 0 else (f"i+{k}" if k > 0 else f"i-{-k}")


def _sparse_table(lhs: str, E, background, tex) -> list[tuple[str, str, str]]:
    """The entries other than ``background``, a run of three or more along a diagonal in one row."""
    n, m = len(E), len(E[0])
    found: dict[tuple[int, int], tuple[str, str, str]] = {}
    for k in range(-(n - 1), m):
        cells = [(i, i + k) for i in range(n) if 0 <= i + k < m]
        for value, group in groupby(cells, key=lambda cell: E[cell[0]][cell[1]]):
            run = list(group)
            if _is(value, background):
                continue
            shown = f"${tex(value)}$"
            if len(run) >= 3:
                rows = f"$i = {run[0][0] + 1}, \\dots, {run[-1][0] + 1}$"
                found[run[0]] = (f"${_index(lhs, 'i', _offset(k))}$", rows, shown)
            else:
                for i, j in run:
                    found[(i, j)] = (f"${_index(lhs, i + 1, j + 1)}$", "", shown)
    return [found[key] for key in sorted(found)]


def _shown(count: int, corner: int) -> list[int | None]:
    """The indices shown of ``count``: all when few, else the first ``corner``, a gap, the last."""
    if count <= corner + 2:
        return list(range(count))
    return [*range(corner), None, count - 1]


def _corners(E, tex, corner: int) -> str:
    lines = []
    for i in _shown(len(E), corner):
        if i is None:
            cells = [r"\vdots" if j is not None else r"\ddots" for j in _shown(len(E[0]), corner)]
        else:
            cells = [
                tex(E[i][j]) if j is not None else r"\cdots" for j in _shown(len(E[0]), corner)
            ]
        lines.append(" & ".join(cells))
    return r"\begin{bmatrix}" + r" \\ ".join(lines) + r"\end{bmatrix}"


def show_matrix(lhs: str, M, *, room: float | None = None, digits: int = L.DIGITS) -> MatrixView:
    r"""Matrix ``M`` (SymPy, or an array of floats with ``inf``) named ``lhs`` as it fits ``room``
    glyphs after ``lhs =`` (default the line less 12), decided by size (:mod:`~symctl.report.longform`).

    A large diagonal matrix is :math:`\operatorname{diag}(d_1, \dots, d_n)`; one that fits is written
    in full (numbers to ``digits``); beyond that a unit vector is :math:`e_k`, a vector a list, a
    companion matrix its dots picture, a sparse one its pattern with a table of its entries, a
    dense one its corners."""
    room = LF.LINE_WIDTH - 12.0 if room is None else room
    E, numeric = _entries(M)
    n, m = len(E), len(E[0]) if E else 0
    if n == m >= LF.DIAGONAL_MIN and all(
        _is(E[i][j], 0) for i in range(n) for j in range(n) if i != j
    ):
        diag = [_entry_tex(E[i][i], numeric, digits) for i in range(n)]
        return MatrixView([(lhs, rf"\operatorname{{diag}}\left({_runs(diag)}\right)")])
    full = L.to_latex(M if not numeric else np.asarray(M, dtype=float), digits=digits)
    small = n <= LF.MATRIX_MAX_ROWS and m <= LF.MATRIX_MAX_COLUMNS
    if min(n, m) == 1:
        small = max(n, m) <= LF.VECTOR_MAX_ENTRIES
    if small and LF.width(full) <= room:
        return MatrixView([(lhs, full)], full=True)

    def tex(e) -> str:
        return _entry_tex(e, numeric, digits)

    size = rf"\quad ({n} \times {m})"
    flat = [e for row in E for e in row]
    if n == 1 or m == 1:
        ones = [k for k, e in enumerate(flat) if not _is(e, 0)]
        if len(ones) == 1 and _is(flat[ones[0]], 1):
            unit = f"e_{{{ones[0] + 1}}}" + (r"^{\top}" if n == 1 else "")
            return MatrixView([(lhs, unit + size)])
        items = ", ".join(tex(e) for e in flat)
        return MatrixView([(lhs, f"({items})" + ("" if n == 1 else r"^{\top}"))])
    kind = _companion(E)
    if kind is not None:  # the pattern of ones drawn, the free row or column listed
        corner = _index(lhs, n, n)
        if kind == "row":
            free, first = E[n - 1], _index(lhs, n, 1)
            row = " & ".join([first, _index(lhs, n, 2), r"\cdots", ""])
            picture = r"0 & 1 & & \\ & \ddots & \ddots & \\ & & 0 & 1 \\ " + row
        else:
            free, first = [E[i][n - 1] for i in range(n)], _index(lhs, 1, n)
            picture = (
                rf"0 & & & {first} \\ 1 & \ddots & & \vdots \\ & \ddots & 0 & \vdots \\ & & 1 & "
            )
        items = ", ".join(tex(e) for e in free)
        matrix = rf"\begin{{bmatrix}}{picture}{corner}\end{{bmatrix}}"
        return MatrixView([(lhs, matrix + size), (rf"({first}, \dots, {corner})", f"({items})")])
    counts = Counter(flat)
    background, repeats = counts.most_common(1)[0]
    table = _sparse_table(lhs, E, background, tex)
    if 4 * repeats >= len(flat) > repeats and len(table) <= LF.PATTERN_TABLE_ROWS * max(n, m):
        cells = [r" & ".join(r"\cdot" if _is(e, background) else r"\ast" for e in row) for row in E]
        pattern = r"\left[\begin{smallmatrix}" + r" \\ ".join(cells) + r"\end{smallmatrix}\right]"
        fits = LF.width(pattern + size) <= room
        rows = [(lhs, pattern + size if fits else rf"\text{{(its entries below)}}{size}")]
        intro = f"The entries $\\ast$ of ${lhs}$ (those marked $\\cdot$ are ${tex(background)}$):"
        return MatrixView(rows, [(intro, ("entry", "for", "value"), tuple(table))])

    def short(e) -> str:
        return _entry_tex(e, numeric, LF.LARGE_DIGITS)

    for corner in (LF.CORNER, 1):
        picture = _corners(E, short, corner)
        if LF.width(picture + size) <= room:
            return MatrixView([(lhs, picture + size)])
    return MatrixView([(lhs, rf"\text{{a dense matrix}}{size}")])
