r"""Short forms the story writes when a plain form is wider than the line: products over an
index, :math:`b(z)/a(z)` with a table of coefficients, the entries :math:`N c_k`."""

from __future__ import annotations

import re
from fractions import Fraction

import numpy as np
import sympy as sp

from symctl import latex as L
from symctl._util.display import descending_latex
from symctl._util.exact import IntFractions, NotRational, fold, ring_fractions
from symctl.report import longform as LF
from symctl.report import matrixview as MV
from symctl.report.document import DocumentBlock, Math, Table, Text
from symctl.symbols import z

__all__ = ["COMPACT_LENGTH"]


def fmt(value: float, digits: int = 6) -> str:
    """A number as inline math (for prose and table cells), to ``digits`` significant digits."""
    return f"${L.number(value, digits)}$"


def display(rows, label: str, tables=()) -> list[DocumentBlock]:
    fitted = LF.fit_rows(rows)
    tall = sum(LF.height(rhs) for _, rhs in fitted) > LF.DISPLAY_MAX_LINES
    out: list[DocumentBlock] = [Math(tuple(fitted), label, breakable=tall)]
    for intro, header, body in tables:
        out += [Text(intro), Table(header, body)]
    return out


def fits(lhs: str, rhs: str) -> bool:
    return LF.width(lhs) + 3.0 + LF.width(rhs) <= LF.LINE_WIDTH


COMPACT_LENGTH = 300
"""A realization matrix whose LaTeX is longer is written with the symbols :math:`N c_k`."""


def sections_tex(cs, eps) -> str:
    """``C_1/(z - epsilon_1)`` and the like; too wide, the product over an index; 1 without any."""
    if not cs:
        return "1"
    tex = rf"\frac{{{L.to_latex(sp.Mul(*cs))}}}{{{zeros_tex(eps)}}}"
    C, e = indexed(cs), indexed(eps)
    if fits("G_1(z)", tex) or C is None or e is None or C[1:] != e[1:]:
        return tex
    return rf"\prod_{{k={C[1]}}}^{{{C[2]}}} \frac{{{C[0]}}}{{z - {e[0]}}}"


def zeros_tex(eps, product: bool = False) -> str:
    """``(z - epsilon_1)(z - epsilon_3)``; with ``product``, ``prod_k (z - epsilon_{1,k})``."""
    e = indexed(eps) if product else None
    if e is not None:
        return rf"\prod_{{k={e[1]}}}^{{{e[2]}}} \left(z - {e[0]}\right)"
    if len(eps) == 1:
        return f"z - {L.to_latex(eps[0])}"
    return "".join(rf"\left(z - {L.to_latex(e)}\right)" for e in eps) or "1"


_INDEXED = re.compile(r"(?P<stem>[A-Za-z]+)_(?:\{(?P<pre>(?:\d+,)*)(?P<k>\d+)\}|(?P<k1>\d+))")


def indexed(symbols) -> tuple[str, int, int] | None:
    """Symbols ``x_{a,lo}, ..., x_{a,hi}`` (or ``x_lo..x_hi``) as ``(LaTeX of x_{a,k}, lo, hi)``."""
    found = [_INDEXED.fullmatch(getattr(x, "name", "")) for x in symbols]
    if len(found) < 2 or not all(found):
        return None
    keys = {(m["stem"], m["pre"] or "") for m in found}
    ks = [int(m["k"] or m["k1"]) for m in found]
    if len(keys) != 1 or ks != list(range(ks[0], ks[0] + len(ks))):
        return None
    stem, pre = keys.pop()
    return L.to_latex(sp.Symbol(f"{stem}_{{{pre}k}}")), ks[0], ks[-1]


def _index_of(symbol) -> int:
    m = _INDEXED.fullmatch(symbol.name)
    return int(m["k"] or m["k1"])


def quotient_tex(expr) -> str:
    """A quotient by a product of indexed symbols, the product written over its indices."""
    num, den = expr.as_numer_denom()
    groups: dict[tuple, list] = {}
    rest = []
    for factor in sp.Mul.make_args(den):
        m = _INDEXED.fullmatch(getattr(factor, "name", ""))
        if m is None:
            rest.append(factor)
        else:
            groups.setdefault((m["stem"], m["pre"] or ""), []).append(factor)
    parts = [L.to_latex(sp.Mul(*rest))] if rest else []
    for group in groups.values():
        ix = indexed(sorted(group, key=_index_of))
        if ix is None:
            parts.append(L.to_latex(sp.Mul(*group)))
        else:
            parts.append(rf"\prod_{{k={ix[1]}}}^{{{ix[2]}}} {ix[0]}")
    return rf"\frac{{{L.to_latex(num)}}}{{{' '.join(parts)}}}"


def tf_long(lhs: str, symbolic, numeric, *, label: str) -> list[DocumentBlock]:
    """A transfer function too wide for the line: ``b(z)/a(z)`` with a table of coefficients."""
    a_s, a_n = symbolic.den_coeffs(), numeric.den_coeffs()
    b_s, b_n = symbolic.num_coeffs(), numeric.num_coeffs()
    n, m = len(a_s) - 1, len(b_s) - 1
    rows = []
    if not symbolic.is_siso:  # a matrix: its numerator entry by entry
        rows.append((lhs, r"\frac{N(z)}{a(z)}"))
    elif m == 0:
        rows.append(
            (
                lhs,
                rf"\frac{{{L.to_latex(b_s[0])}}}{{a(z)}} = "
                rf"\frac{{{L.number(float(b_n[0]))}}}{{a(z)}}",
            )
        )
    else:
        rows += [(lhs, r"\frac{b(z)}{a(z)}"), ("b(z)", rf"\sum_{{k=0}}^{{{m}}} b_k\, z^{{{m}-k}}")]
    rows.append(("a(z)", rf"\sum_{{k=0}}^{{{n}}} a_k\, z^{{{n}-k}}"))

    def table(name, sym, num):
        body = tuple(
            (f"${k}$", f"${L.to_latex(cs)}$", fmt(float(cn)))
            for k, (cs, cn) in enumerate(zip(sym, num, strict=True))
        )
        intro = f"The coefficients ${name}_k$ of ${name}(z)$ (descending powers of $z$):"
        return intro, ("$k$", f"${name}_k$", "with the optimal gains"), body

    tables = [table("a", a_s, a_n)]
    if not symbolic.is_siso:
        entries = zip(symbolic.num_matrix, numeric.num_matrix, strict=True)
        cols = symbolic.shape[1]
        body = tuple(
            (
                f"$N_{{{k // cols + 1}{k % cols + 1}}}$",
                f"${descending_latex(sym)}$",
                f"${descending_latex(num, 6)}$",
            )
            for k, (sym, num) in enumerate(entries)
        )
        intro = "The entries of $N(z)$ (descending powers of $z$):"
        tables.append((intro, ("entry", "$N_{ij}(z)$", "with the optimal gains"), body))
    elif m:
        tables.append(table("b", b_s, b_n))
    return display(rows, label, tables)


def remainder_symbols(f) -> list[sp.Symbol]:
    """``c_1, ..., c_n``, one per remainder coefficient (of a factorization, or the list)."""
    coeffs = f if isinstance(f, list | tuple) else f.remainder_coeffs
    return [sp.Symbol(f"c_{{{k}}}") for k in range(1, len(coeffs) + 1)]


def remainder_poly(c: list[sp.Symbol]) -> sp.Expr:
    return sp.Add(*(ck * z ** (len(c) - 1 - k) for k, ck in enumerate(c)))


def compact(R, f, c, values=None) -> tuple[list[tuple[str, object]], bool]:
    """The rows ``F, H, M, N`` of ``R``, a long matrix with its entries :math:`N c_k` as symbols
    (``values``: ``(f.N, f.remainder_coeffs)`` when the caller has them)."""
    N = sp.Symbol("N")
    f_N, f_coeffs = values if values is not None else (f.N, f.remainder_coeffs)
    targets = [(f_N * coeff, N * ck) for coeff, ck in zip(f_coeffs, c, strict=True)]
    rows, short = [], False
    for k in "FHMN":
        mat = getattr(R, k)
        tex = L.to_latex(mat) if k in "HMN" else ""
        if k in "HMN" and (len(tex) > COMPACT_LENGTH or LF.width(tex) > LF.LINE_WIDTH - 12):
            mat = mat.applyfunc(_Matcher([*targets, (f_N, N)]))
            short = True
        rows.append((k, mat))
    return rows, short


def factored(mat):
    r"""A symbolic matrix with the factor common to its entries in front (LaTeX), as the paper writes
    :math:`M`; the matrix itself when they share none."""
    if not isinstance(mat, sp.MatrixBase) or len(mat) < 2 or len(mat) > LF.MATRIX_MAX_ROWS:
        return mat
    entries = [e for e in mat if e != 0]
    if len(entries) < 2:
        return mat
    common = entries[0]
    for e in entries[1:]:
        common = sp.gcd(common, e)
        if not common.free_symbols:
            return mat
    inner = mat.applyfunc(lambda e: sp.factor_terms(sp.cancel(e / common)))
    return rf"{L.to_latex(common)} {L.to_latex(inner)}"


def renamed(R, shortened: dict) -> dict[str, str]:
    """The LaTeX of each entry of ``R`` that :func:`compact` renamed, to its new LaTeX."""
    out = {}
    for k, mat in shortened.items():
        for old, new in zip(getattr(R, k), mat, strict=True):
            if old != new:
                out[L.to_latex(old)] = L.to_latex(new)
    return out


def named_weights(rows, names: dict[str, str]) -> list[tuple[str, str]]:
    """Circuit equations with the long weights of ``names`` written as their short names."""
    if not names:
        return list(rows)
    order = sorted(names, key=len, reverse=True)
    out = []
    for lhs, rhs in rows:
        for old in order:
            rhs = rhs.replace(old, names[old])
        out.append((lhs, rhs))
    return out


class _Matcher:
    """Entry -> the symbol of the target it equals exactly (compared only with the targets of equal
    value at a random rational point), else the entry itself."""

    def __init__(self, targets) -> None:
        self.targets = targets
        syms = sorted(set().union(*(v.free_symbols for v, _ in targets)), key=str)
        rng = np.random.default_rng(0)
        self.point = {
            x: Fraction(int(rng.integers(10**6, 10**7)), int(rng.integers(1, 997))) for x in syms
        }
        self.keys: dict[Fraction | None, list] = {}
        for value, symbol in targets:
            self.keys.setdefault(self._key(value), []).append((value, symbol))

    def _key(self, e) -> Fraction | None:
        if not e.free_symbols <= self.point.keys():
            return None
        try:
            p, q = fold(e, IntFractions(self.point))
        except (ZeroDivisionError, NotRational):
            return None
        return Fraction(p, q) if q else None

    def __call__(self, entry: sp.Expr) -> sp.Expr:
        key = self._key(entry)
        candidates = self.keys.get(key, []) if key is not None else self.targets
        for value, symbol in candidates:
            pairs = ring_fractions([entry, value])
            if pairs is None:
                continue
            (n1, d1), (n2, d2) = pairs
            if n1 * d2 == n2 * d1:
                return symbol
        return entry


def num(value):
    """Exact or symbolic-free numbers as floats (arrays stay arrays) for :func:`latex.to_latex`."""
    if isinstance(value, sp.MatrixBase):
        return np.array(value.evalf(), dtype=float)
    if isinstance(value, np.ndarray):
        return value.astype(float)
    return float(value)


def eq(*rows, label: str, tables=()) -> list[DocumentBlock]:
    """One numbered display of ``(lhs, rhs)`` rows fitted to the page (matrices as
    :func:`~symctl.report.matrixview.show_matrix` shows them), then their tables and ``tables``."""
    lead = max((LF.width(lhs) for lhs, _ in rows if lhs is not None), default=0.0) + 3.0
    shown, more = [], []
    for lhs, rhs in rows:
        if getattr(rhs, "shape", None) == (1, 1):  # a 1 x 1 matrix is its entry, as papers write it
            rhs = rhs[0, 0]
        if isinstance(rhs, sp.MatrixBase) or (isinstance(rhs, np.ndarray) and rhs.ndim == 2):
            view = MV.show_matrix(lhs, rhs, room=LF.LINE_WIDTH - lead)
            shown += view.rows
            more += view.tables
        else:
            shown.append((lhs, L.to_latex(rhs)))
    return display(shown, label, [*more, *tables])


def both(symbolic, numeric) -> str:
    """``symbolic = numeric`` as one right-hand side."""
    return f"{L.to_latex(symbolic)} = {L.to_latex(numeric)}"
