r"""Certified real roots of polynomial systems: Newton from random starts, then Krawczyk.

A real root found in floating point is **proved** to exist by the Krawczyk test (Krawczyk 1969;
Moore 1977) in ball arithmetic (python-flint ``arb``, on the exact rational coefficients): for a
box :math:`X` around :math:`\tilde x`, any matrix :math:`Y` and the interval Jacobian
:math:`J(X)`, if :math:`K(X) = \tilde x - Y f(\tilde x) + (I - Y J(X))(X - \tilde x)` lies in
the interior of :math:`X`, then :math:`f` has exactly one root in :math:`X`; it is real, and a
coordinate whose interval excludes 0 is nonzero there.

>>> import sympy as sp
>>> from symctl.circuitatlas.certify import certified_real_root
>>> x, y = sp.symbols("x y")
>>> root = certified_real_root([x**2 + y - 3, x - y + 1], [x, y], seed=1)
>>> sorted(round(v, 6) for v in root.values)
[1.0, 2.0]
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import sympy as sp
from flint import arb, arb_mat, fmpq

__all__ = ["CertifiedRoot", "certified_point", "certified_real_root"]

STARTS = 24  # random starting points of the Newton search


class CertifiedRoot(NamedTuple):
    """A real root proved to lie in a box: midpoints ``values`` and radii ``radii``."""

    values: tuple[float, ...]
    radii: tuple[float, ...]
    nonzero: bool


class _Poly:
    """A polynomial as (exact coefficient, exponents) terms, evaluated in balls."""

    def __init__(self, expr, gens):
        poly = sp.Poly(expr, *gens)
        self.terms = [(fmpq(int(sp.numer(c)), int(sp.denom(c))), m) for m, c in poly.terms()]

    def __call__(self, x):
        total = arb(0)
        for c, m in self.terms:
            term = arb(c)
            for xi, e in zip(x, m, strict=True):
                if e:
                    term = term * xi**e
            total = total + term
        return total


def _compile(eqs, gens):
    f = [_Poly(e, gens) for e in eqs]
    J = [[_Poly(sp.diff(e, g), gens) for g in gens] for e in eqs]
    return f, J


class _Floats:
    """The system and its Jacobian in floats, through one vector of monomials."""

    def __init__(self, f, J):
        polys = [*f, *(p for row in J for p in row)]
        monos = sorted({m for p in polys for _, m in p.terms})
        index = {m: k for k, m in enumerate(monos)}
        width = len(J[0]) if J else 0
        self.exps = np.array(monos, dtype=float).reshape(len(monos), width)
        C = np.zeros((len(polys), len(monos)))
        for i, p in enumerate(polys):
            for c, m in p.terms:
                C[i, index[m]] += float(c.p) / float(c.q)
        self.m = len(f)
        self.Cf, self.CJ = C[: self.m], C[self.m :]

    def __call__(self, x):
        with np.errstate(over="ignore", invalid="ignore"):
            mono = np.prod(np.power(x, self.exps), axis=1)
        return self.Cf @ mono, (self.CJ @ mono).reshape(self.m, len(x))


def _newton(system: _Floats, x0, steps: int = 60):
    x = np.array(x0, dtype=float)
    best = np.inf
    for step in range(steps):
        fx, Jx = system(x)
        if not np.all(np.isfinite(fx)):
            return None
        size = np.max(np.abs(fx))
        if step % 10 == 9:  # stalled far from a root: give up this start
            if size > 0.5 * best and size > 1e-6:
                return None
            best = size
        best = min(best, size) if step < 10 else best
        if np.max(np.abs(fx)) < 1e-13 * (1 + np.max(np.abs(x))):
            return x
        try:
            dx = np.linalg.lstsq(Jx, -fx, rcond=None)[0]
        except np.linalg.LinAlgError:
            return None
        x = x + dx
        if not np.all(np.isfinite(x)) or np.max(np.abs(x)) > 1e8:
            return None
    fx, _ = system(x)
    return x if np.max(np.abs(fx)) < 1e-9 * (1 + np.max(np.abs(x))) else None


def _krawczyk(f, J, system, x) -> CertifiedRoot | None:
    m = len(x)
    Jx = system(x)[1]
    try:
        Yf = np.linalg.inv(Jx)
    except np.linalg.LinAlgError:
        return None
    Y = arb_mat([[arb(float(v)) for v in row] for row in Yf])
    mid = [arb(float(v)) for v in x]
    fmid = arb_mat([[p(mid)] for p in f])
    for scale in (1e-10, 1e-8, 1e-6):
        r = [float(scale * (1 + abs(v))) for v in x]
        X = [arb(float(v), ri) for v, ri in zip(x, r, strict=True)]
        JX = arb_mat([[p(X) for p in row] for row in J])
        D = arb_mat([[X[i] - mid[i]] for i in range(m)])
        eye = arb_mat([[arb(1 if i == j else 0) for j in range(m)] for i in range(m)])
        K = arb_mat([[v] for v in mid]) - Y * fmid + (eye - Y * JX) * D
        if all(X[i].contains_interior(K[i, 0]) for i in range(m)):
            nonzero = all(not X[i].contains(0) for i in range(m))
            return CertifiedRoot(tuple(float(v) for v in x), tuple(r), nonzero)
    return None


def _converged(eqs, gens, seed, starts, scale):
    """The compiled system and each point Newton converges to from seeded random starts."""
    f, J = _compile(eqs, gens)
    system = _Floats(f, J)
    rng = np.random.default_rng(seed)
    for _ in range(starts):
        x = _newton(system, rng.normal(0, scale, len(gens)))
        if x is not None:
            yield f, J, system, x


def certified_real_root(eqs, gens, *, seed: int = 0, starts: int = STARTS, scale: float = 2.0):
    """A real root of the square system ``eqs = 0`` in ``gens``, proved by Krawczyk; or None.

    Newton from ``starts`` seeded normal starts of spread ``scale``; the first root with every
    coordinate nonzero, else the first certified one (``nonzero`` False).
    """
    if len(eqs) != len(gens):
        raise ValueError("certified_real_root: the system must be square")
    fallback = None
    for f, J, system, x in _converged(eqs, gens, seed, starts, scale):
        root = _krawczyk(f, J, system, x)
        if root is not None and root.nonzero:
            return root
        fallback = fallback or root
    return fallback


def certified_point(
    eqs, gens, *, seed: int = 0, starts: int = STARTS, scale: float = 1.0, accept=None
):
    """A real point of ``eqs = 0`` (at least as many unknowns as equations), proved by Krawczyk.

    Gauss-Newton with minimum-norm steps finds a point; the unknowns a pivoted QR of the
    Jacobian leaves out are fixed there, and the square rest is certified. ``accept(values)``
    may reject a point (the search goes on). Returns ``{"values": {gen: float}, "fixed": [gen,
    ...], "radius": float}`` or None.
    """
    from scipy.linalg import qr

    m = len(eqs)
    for _f, _J, system, x in _converged(eqs, gens, seed, starts, scale):
        if accept is not None and not accept(dict(zip(gens, x, strict=True))):
            continue
        _, _, piv = qr(system(x)[1], pivoting=True)
        free = sorted(piv[:m])
        fixed = [k for k in range(len(gens)) if k not in free]
        rule = {gens[k]: sp.Rational(float(x[k])) for k in fixed}
        square = [sp.expand(e.xreplace(rule)) for e in eqs]
        fs, Js = _compile(square, [gens[k] for k in free])
        root = _krawczyk(fs, Js, _Floats(fs, Js), np.array([x[k] for k in free]))
        if root is None:
            continue
        values = {gens[k]: float(x[k]) for k in fixed}
        values.update({gens[k]: v for k, v in zip(free, root.values, strict=True)})
        return {"values": values, "fixed": [gens[k] for k in fixed], "radius": max(root.radii)}
    return None
