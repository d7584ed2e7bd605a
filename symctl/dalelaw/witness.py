r"""A numeric search for an E/I witness of the general circuit, made exact.

Over :math:`(Q F_0 Q^{-1}, Q H_0, M_0 Q^{-1})` of :math:`G_2`'s controllable canonical form,
Nelder-Mead maximizes the **Dale margin**, the least over neurons of
:math:`\max(\min_k w_k, \min_k -w_k)/\max_k |w_k|` (positive exactly when E/I); a positive
margin is rounded to rationals, rebuilt exactly and every sign checked.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.optimize import minimize

from symctl._util.deadline import Deadline
from symctl._util.exact import nearest_rational
from symctl.dalelaw.signs import _expr
from symctl.realization.factorization import factor
from symctl.realization.realizers import general_realization
from symctl.symbols import z

__all__ = ["dale_margin", "search_general"]


def dale_margin(groups) -> float:
    """The least normalized sign margin over the neurons' weight groups (> 0: Dale holds)."""
    worst = np.inf
    for w in groups:
        scale = float(np.max(np.abs(w)))
        if not np.isfinite(scale) or scale == 0:
            return -np.inf
        worst = min(worst, max(float(np.min(w)), float(np.min(-w))) / scale)
    return worst


def _coefficients(G, eps: np.ndarray, gain: float):
    """``(a, c)`` of :math:`G_2 = N + c/a` (ascending, monic ``a``) for sections ``eps`` (floats)."""
    num = np.array([float(x) for x in G.num_coeffs()])  # descending
    den = np.array([float(x) for x in G.den_coeffs()])
    for e in eps:
        num = np.convolve(num, [1.0, -e])
    num = num / gain
    n = den.size - 1
    num = np.concatenate([np.zeros(n + 1 - num.size), num])
    rest = num[1:] - num[0] * den[1:]
    return den[1:][::-1], rest[::-1]


def search_general(G, t, *, deadline: Deadline, starts: int = 48, seed: int = 0):
    """An exact witness ``{symbol: Rational}`` for the general template ``t``, or None."""
    fs = t.factorization
    eps_syms = (*fs.sensor_eps, *fs.actuator_eps)
    c_syms = (*fs.sensor_C, *fs.actuator_C)
    n = fs.G2.order
    k = len(eps_syms)
    order = [*t.unknowns, *eps_syms, *c_syms]
    fns = [sp.lambdify(order, list(ws), "numpy") for ws in t.outgoing.values() if ws]
    rng = np.random.default_rng(seed)

    def margin(theta, sign):
        eps = 0.95 * np.tanh(theta[:k])
        cs = np.ones(len(c_syms))
        if cs.size:
            cs[0] = sign
        a, c = _coefficients(G, eps, float(np.prod(cs)))
        F0 = np.eye(n, k=1)  # the controllable canonical form of c/a
        F0[-1, :] = -a
        Q = theta[k:].reshape(n, n)
        try:
            Qi = np.linalg.inv(Q)
        except np.linalg.LinAlgError:
            return -np.inf
        vals = [*(Q @ F0 @ Qi).ravel(), *Q[:, -1], *(c @ Qi), *eps, *cs]
        groups = [np.atleast_1d(np.asarray(f(*vals), dtype=float)) for f in fns]
        return dale_margin(groups) - 1e-4 * np.log10(max(np.linalg.cond(Q), 1.0))

    def stop(_x):  # Nelder-Mead's callback, once per iteration
        if deadline.expired():
            raise StopIteration

    for i in range(starts):
        if deadline.expired():
            break
        sign = 1.0 if i % 2 == 0 else -1.0
        theta0 = np.concatenate([rng.uniform(-1.5, 1.5, k), rng.normal(size=n * n)])
        res = minimize(
            lambda th, s=sign: -margin(th, s),
            theta0,
            method="Nelder-Mead",
            callback=stop,
            options={"maxiter": 400 * (k + n * n), "xatol": 1e-9, "fatol": 1e-12},
        )
        if -res.fun > 1e-3 and not deadline.expired():
            exact = _exact(G, t, res.x, sign, k, n, deadline)
            if exact is not None:
                return exact
    return None


def _exact(G, t, theta, sign, k, n, deadline):
    """The search's point in exact rationals, or None when rounding breaks a sign (or time is out)."""
    fs = t.factorization
    eps_syms = (*fs.sensor_eps, *fs.actuator_eps)
    c_syms = (*fs.sensor_C, *fs.actuator_C)
    poles = sp.Poly(G.den, z)
    for den in (100, 10**4, 10**6):
        if deadline.expired():
            return None
        eps = [nearest_rational(0.95 * np.tanh(x), den) for x in theta[:k]]
        if any(abs(e) >= 1 or e == 0 or poles.eval(e) == 0 for e in eps):
            continue
        cs = [sp.Integer(1)] * len(c_syms)
        if cs:
            cs[0] = sp.Integer(int(sign))
        Q = sp.zeros(n, n)
        for i, x in enumerate(theta[k:]):
            Q[i // n, i % n] = nearest_rational(x, den)
        if Q.det() == 0:
            continue
        sub = factor(G, len(fs.sensor_eps), len(fs.actuator_eps), eps=eps, C=cs)
        R2 = general_realization(sub.G2, Q.inv())
        entries = [*R2.F, *R2.H, *R2.M]
        if any(e == 0 for e in entries):
            continue
        values = dict(zip(eps_syms, eps, strict=True)) | dict(zip(c_syms, cs, strict=True))
        values |= dict(zip(t.unknowns, entries, strict=True))
        groups = ([_expr(w).xreplace(values) for w in ws] for ws in t.outgoing.values())
        if all(all(w > 0 for w in ws) or all(w < 0 for w in ws) for ws in groups):  # E or I
            return values
    return None
