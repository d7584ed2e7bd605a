r"""The similarity transform :math:`(P^{-1} F P,\ P^{-1} H,\ M P)`, fraction-free in python-flint.

With :math:`P = P_n / d_P`, by fraction-free Gauss-Jordan on :math:`[P_n \mid I]`
(:math:`\delta = \pm\det P_n`, :math:`A = \delta P_n^{-1}`, so :math:`P^{-1} F P = A F_n P_n /
(\delta\, d_F)`: one division per entry, at the end); rational entries only by ``fmpq_mat``
products. Each entry is written as SymPy terms directly, in the form
``factor_terms(cancel(.))`` gives; entries that are not rational with rational coefficients
return ``None`` (the SymPy path).
"""

from __future__ import annotations

from itertools import compress

import sympy as sp
from flint import fmpq, fmpq_mat, fmpz_mpoly_ctx
from sympy.core.basic import _args_sortkey, ordering_of_classes
from sympy.core.mul import _keep_coeff
from sympy.polys.polyutils import _sort_gens

from symctl._util.exact import NotRational, PolyFractions, fold, from_fmpq_mat

__all__ = ["similar_exact"]


def _symbols(exprs) -> list[sp.Symbol] | None:
    """The free symbols in SymPy's generator order, or None for floats or other atoms."""
    syms: set = set()
    for e in exprs:
        for node in sp.preorder_traversal(e):
            if node.is_Symbol:
                syms.add(node)
            elif not (
                node.is_Add
                or node.is_Mul
                or node.is_Rational
                or (node.is_Pow and node.exp.is_Integer)
            ):
                return None
    return list(_sort_gens(syms)) if syms else []


class _Ring:
    """``fmpz_mpoly`` in the given symbols (lex order, so the leading term is SymPy's)."""

    def __init__(self, symbols):
        self.symbols = tuple(symbols)
        self.ctx = fmpz_mpoly_ctx.get(("x", len(self.symbols)), "lex")
        self.zero, self.one = self.ctx.constant(0), self.ctx.constant(1)
        self._algebra = PolyFractions(self.ctx, self.symbols)
        self._memo: dict = {}
        self._powers: dict = {}

    def pair(self, expr):
        """A reduced pair (numerator, denominator), the denominator's leading coefficient > 0."""
        num, den = fold(expr, self._algebra, self._memo)
        if den.is_zero():
            raise ZeroDivisionError(expr)
        return _reduce(num, den)

    def common(self, mat: sp.MatrixBase) -> tuple[list[list], object]:
        """The entries as numerators over one common denominator (the lcm of theirs)."""
        nums, den = over_lcm([self.pair(e) for e in mat.flat()], self.one)
        return [nums[i * mat.cols : (i + 1) * mat.cols] for i in range(mat.rows)], den

    def _ensure(self, degrees) -> None:
        """Put ``x_i**k`` for every ``k <= degrees[i]`` in the pool of factors, ranked as SymPy sorts."""
        grew = False
        for i, top in enumerate(degrees):
            for k in range(1, top + 1):
                if (i, k) not in self._powers:
                    base = self.symbols[i]
                    self._powers[(i, k)] = [base if k == 1 else sp.Pow(base, k), 0, None]
                    grew = True
        if grew:
            pool = sorted(self._powers.values(), key=lambda v: _args_sortkey(v[0]))
            for rank, entry in enumerate(pool):
                entry[1], entry[2] = rank, (_class_key(type(entry[0])), rank)

    def monomial(self, exps) -> sp.Expr:
        self._ensure(exps)
        return sp.Mul(*(self._powers[(i, k)][0] for i, k in enumerate(exps) if k))

    def expr(self, poly, q: int = 1) -> sp.Expr:
        """``poly / q`` as a SymPy sum in canonical order, built without evaluating ``Mul``/``Add``."""
        const, terms, powers, index = None, [], self._powers, range(len(self.symbols))
        self._ensure(poly.degrees())
        for exps, c in poly.terms():
            factors = [powers[i, exps[i]] for i in compress(index, exps)]
            factors.sort(key=_rank)
            coeff = sp.Integer(int(c)) if q == 1 else sp.Rational(int(c), q)
            if not factors:
                const = coeff
                continue
            if coeff is sp.S.One and len(factors) == 1:
                term, key = factors[0][0], factors[0][2]
            else:
                args = [f[0] for f in factors]
                keys = [f[2] for f in factors]
                if coeff is not sp.S.One:
                    args.insert(0, coeff)
                    keys.insert(0, _number_key(coeff))
                term = sp.Mul._from_args(args, True)
                key = (_MUL, len(args), tuple(keys))
            terms.append((key, term))
        if not terms:
            return sp.Integer(0) if const is None else const
        terms.sort(key=lambda t: t[0])
        args = [t for _, t in terms]
        if const is not None:
            args.insert(0, const)
        return args[0] if len(args) == 1 else sp.Add._from_args(args, True)

    def _over_number(self, num, q: int) -> sp.Expr:
        """``factor_terms`` of ``num / q`` (SymPy's rules on distributing a fraction over a sum)."""
        if len(num) == 1:
            ((exps, c),) = num.terms()
            return sp.Mul(sp.Rational(int(c), q), self.monomial(exps))
        cn, pn = num.primitive()
        sign = -1 if all(c < 0 for c in pn.coeffs()) else 1
        pn = pn * sign
        mono = _monomial_gcd(pn)
        rest = _div_monomial(self.ctx, pn, mono)
        if q != 1 and any(int(c) % q == 0 for c in pn.coeffs()):
            coeff, inner = sp.Integer(sign * int(cn)), self.expr(rest, q)  # q distributed
        else:
            coeff, inner = sp.Rational(sign * int(cn), q), self.expr(rest)
        if any(mono):
            inner = sp.Mul(self.monomial(mono), inner)
        return _keep_coeff(coeff, inner, clear=False, sign=True)

    def quotient(self, num, den) -> sp.Expr:
        """``cancel(num/den)``: the reduced numerator over the denominator, not tidied."""
        if num.is_zero():
            return sp.Integer(0)
        if den.is_constant():
            return self.expr(num) * sp.Rational(1, int(den.leading_coefficient()))
        return self.expr(num) / self.expr(den)

    def tidy(self, num, den) -> sp.Expr:
        """``factor_terms(cancel(num/den))``: common numbers and monomials of both pulled out."""
        if num.is_zero():
            return sp.Integer(0)
        if num.is_constant() and den.is_constant():
            return sp.Rational(int(num.leading_coefficient()), int(den.leading_coefficient()))
        if den.is_constant():
            return self._over_number(num, int(den.leading_coefficient()))
        cn, pn = num.primitive()
        cd, pd = den.primitive()
        sign = -1 if all(c < 0 for c in pn.coeffs()) else 1
        pn = pn * sign
        mn, md = _monomial_gcd(pn), _monomial_gcd(pd)
        return sp.Mul(
            sp.Rational(sign * int(cn), int(cd)),
            self.monomial(mn),
            self.expr(_div_monomial(self.ctx, pn, mn)),
            sp.Pow(self.monomial(md), -1),
            sp.Pow(self.expr(_div_monomial(self.ctx, pd, md)), -1),
        )


_KNOWN = {name: i for i, name in enumerate(ordering_of_classes)}


def _class_key(cls: type) -> tuple:
    """``_cmp_name`` of Basic.compare as a key: the listed classes in order, then by name."""
    name = cls.__name__
    return (_KNOWN.get(name, len(ordering_of_classes) + 1), name)


_MUL = _class_key(sp.Mul)
_NUMBER_KEYS: dict = {}


def _number_key(c: sp.Rational) -> tuple:
    """Basic.compare on rationals: the class first (One, NegativeOne, Half, Integer...), then p, q."""
    cls = type(c)
    got = _NUMBER_KEYS.get(cls)
    if got is None:
        got = _NUMBER_KEYS[cls] = _class_key(cls)
    return (got, c._hashable_content())


def _rank(entry) -> int:
    return entry[1]


def over_lcm(pairs: list, one) -> tuple[list, object]:
    """Reduced ``(num, den)`` pairs as numerators over the lcm of the denominators."""
    den = one
    for _, d in pairs:
        if d != den and not d.is_one():
            den = den * (d / den.gcd(d))
    return [n * (den / d) for n, d in pairs], den


def _reduce(num, den):
    g = num.gcd(den)
    if not g.is_one():
        num, den = num / g, den / g
    if den.leading_coefficient() < 0:
        num, den = -num, -den
    return num, den


def _monomial_gcd(poly) -> tuple[int, ...]:
    """The exponents of the gcd of the monomials of a nonzero polynomial."""
    return tuple(poly.term_content().monoms()[0])


def _div_monomial(ctx, poly, exps):
    if not any(exps):
        return poly
    return poly / ctx.term(exp_vec=exps, coeff=1)


def _matmul(A: list[list], B: list[list], zero) -> list[list]:
    cols = list(zip(*B, strict=True)) if B else []
    return [
        [
            sum((a * b for a, b in zip(row, col, strict=True) if not a.is_zero()), zero)
            for col in cols
        ]
        for row in A
    ]


def _gauss_jordan(Pn: list[list], ring: _Ring):
    r"""``(delta, A)``: :math:`\delta = \pm\det P_n`, :math:`A = \delta P_n^{-1}` (None if singular),
    by Bareiss elimination, a zero pivot swapped with the sparsest nonzero lower row."""
    n = len(Pn)
    rows = [
        [*row, *(ring.one if i == j else ring.zero for j in range(n))] for i, row in enumerate(Pn)
    ]
    prev = ring.one
    for k in range(n):
        candidates = [r for r in range(k, n) if not rows[r][k].is_zero()]
        if not candidates:
            return None
        r = min(candidates, key=lambda r: len(rows[r][k]))
        rows[k], rows[r] = rows[r], rows[k]
        pivot, prow = rows[k][k], rows[k]
        for i in range(n):
            if i == k:
                continue
            row, lead = rows[i], rows[i][k]
            if lead.is_zero():
                new = [pivot * x for x in row]
            else:
                new = [pivot * x - lead * y for x, y in zip(row, prow, strict=True)]
            rows[i] = new if prev.is_one() else [x / prev for x in new]
        prev = pivot
    # every row was last scaled at a later pivot: row k's diagonal is delta for all k
    return prev, [row[n:] for row in rows]


def _symbolic(F, H, M, P, ring: _Ring):
    Pn, dP = ring.common(P)
    got = _gauss_jordan(Pn, ring)
    if got is None:
        return None
    delta, A = got
    Fn, dF = ring.common(F)
    Hn, dH = ring.common(H)
    Mn, dM = ring.common(M)
    zero = ring.zero
    Fs = _matmul(A, _matmul(Fn, Pn, zero), zero)
    Hs = _matmul(A, Hn, zero)
    Ms = _matmul(Mn, Pn, zero)
    F_den, H_den, M_den = delta * dF, delta * dH, dM * dP
    tidy = ring.tidy
    return (
        [[tidy(*_reduce(x, F_den)) for x in row] for row in Fs],
        [[tidy(*_reduce(x * dP, H_den)) for x in row] for row in Hs],
        [[tidy(*_reduce(x, M_den)) for x in row] for row in Ms],
        [[ring.quotient(*_reduce(x * dP, delta)) for x in row] for row in A],
    )


def _fmpq_mat(mat: sp.MatrixBase) -> fmpq_mat:
    return fmpq_mat(mat.rows, mat.cols, [fmpq(int(e.p), int(e.q)) for e in mat.flat()])


def _rational(F, H, M, P):
    """Rational entries only: ``fmpq_mat`` products, nothing else."""
    Pq = _fmpq_mat(P)
    if Pq.det() == 0:
        return "singular"
    Pinv = Pq.inv()
    products = (Pinv * _fmpq_mat(F) * Pq, Pinv * _fmpq_mat(H), _fmpq_mat(M) * Pq, Pinv)
    return tuple(from_fmpq_mat(X) for X in products)


def similar_exact(F, H, M, P):
    """``(F', H', M', P^{-1})`` as SymPy matrices; ``"singular"``; or None (not rational: the SymPy path)."""
    entries = [*F.flat(), *H.flat(), *M.flat(), *P.flat()]
    if all(e.is_Rational for e in entries):
        return _rational(F, H, M, P)
    syms = _symbols(entries)
    if syms is None:
        return None
    try:
        got = _symbolic(F, H, M, P, _Ring(syms))
    except (NotRational, ZeroDivisionError):
        return None
    if got is None:
        return "singular"
    shapes = (F.shape, H.shape, M.shape, P.shape)
    return tuple(
        sp.Matrix(r, c, [e for row in rows for e in row])
        for rows, (r, c) in zip(got, shapes, strict=True)
    )
