r"""The trace model of :func:`symctl.fit`: every neuron's firing as a function of the parameters.

The loop's :math:`\delta_f` is the same for every realization of :math:`G`, computed once;
each neuron's trace is a linear filter of it, with coefficients :math:`\theta = (\epsilon,
C, P^{-1})`: the sensor sections :math:`s_k(t+1) = \epsilon_k s_k(t) + C_k s_{k-1}(t)`,
:math:`s_0 = \delta_f`; the states of :math:`G_2`, :math:`x = T x_c` with :math:`x_c` the
controllable canonical state driven by :math:`s_{d_s}` (:math:`T = P^{-1}` free for the
general class, entries ``Pinv[i,j]``; for a fixed pattern :math:`T(\epsilon, C) =
\mathcal{C}(\epsilon, C)\,\mathcal{C}_0^{-1}`, the controllability matrices' ratio,
lambdified once); the output ``G2.y`` :math:`= M_0 x_c + N y_1` (similarity-invariant);
the actuator sections, fed by ``G2.y``. Derivatives are exact forward sensitivities (a
filter's derivative in its pole is the filter applied to its own output).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import sympy as sp
from flint import fmpq
from scipy.signal import lfilter

from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, NotRealizableError, ParameterError
from symctl.realization.factorization import Factorization, factor
from symctl.realization.realization import Realization, controllable_canonical
from symctl.realization.realizers import REALIZERS, circuit_names, get_realizer

__all__ = ["FIXED_CLASSES", "TraceModel", "section_name"]

FIXED_CLASSES: tuple[str, ...]  # read from the registry at each access (__getattr__)


def fixed_classes() -> tuple[str, ...]:
    """The registry's fixed forms (no transform): :data:`FIXED_CLASSES`."""
    return tuple(k for k in circuit_names(whole=False) if not transformed(k))


def transformed(circuit) -> bool:
    """Whether ``circuit`` names a realizer with a free similarity transform (``"general"``)."""
    return isinstance(circuit, str) and circuit in REALIZERS and REALIZERS[circuit].takes_transform


def __getattr__(name: str):
    """``FIXED_CLASSES``: the registry's forms without a transform (only epsilons and Cs fitted).

    >>> from symctl.fitting.fitmodel import FIXED_CLASSES
    >>> FIXED_CLASSES
    ('controllable', 'observable')
    """
    if name == "FIXED_CLASSES":
        return fixed_classes()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def renamed_param(name: str) -> str | None:
    """The name of a parameter that was spelled ``Q[i,j]`` (the entries of :math:`P^{-1}`)."""
    return "Pinv[" + name[2:] if name.startswith("Q[") else None


def section_name(side: str, k: int, count: int) -> str:
    """The circuit's name of section ``k`` (1-based) of ``count``: ``G1.x1`` or ``G1.2.x1``."""
    return f"{side}.x1" if count == 1 else f"{side}.{k}.x1"


def _filter1(e: float, c: float, v: np.ndarray) -> np.ndarray:
    """:math:`x(t+1) = e\\,x(t) + c\\,v(t)`, :math:`x(0) = 0`, along axis 0."""
    return lfilter([0.0, c], [1.0, -e], v, axis=0)


def _state_filter(F: np.ndarray, v: np.ndarray) -> np.ndarray:
    r""":math:`x(t+1) = F x(t) + e_n v(t)` from rest, ``F`` companion: :math:`x_i(t) = w(t + i - 1)`,
    :math:`w = v / \det(zI - F)` delayed ``n`` steps; ``(steps, k)`` -> ``(steps, n, k)``."""
    steps, n = v.shape[0], F.shape[0]
    den = np.r_[1.0, -F[-1, ::-1]]
    padded = np.concatenate([v, np.zeros((n - 1, v.shape[1]))])
    w = lfilter(np.r_[np.zeros(n), 1.0], den, padded, axis=0)
    return np.stack([w[i : i + steps] for i in range(n)], axis=1)


def _exact_filter1(e, c, v: np.ndarray) -> np.ndarray:
    """:func:`_filter1` in exact arithmetic (object arrays)."""
    x = np.zeros_like(v)
    for t in range(len(v) - 1):
        x[t + 1] = e * x[t] + c * v[t]
    return x


def _exact_state_filter(F: sp.Matrix, v: np.ndarray) -> np.ndarray:
    """:func:`_state_filter` in exact arithmetic, ``F`` the companion matrix (SymPy rationals)."""
    F = _fmpq(F.tolist())
    x = np.zeros((v.shape[0], F.shape[0], v.shape[1]), dtype=object)
    for t in range(v.shape[0] - 1):
        x[t + 1] = F.dot(x[t])
        x[t + 1, -1] += v[t]
    return x


def _fmpq(a) -> np.ndarray:
    """SymPy rationals as an object array of fmpq."""
    return np.vectorize(lambda x: fmpq(int(x.p), int(x.q)), otypes=[object])(
        np.array(a, dtype=object)
    )


def _float_value(fn, theta: np.ndarray):
    return fn(theta)


def _exact_value(fn, theta: np.ndarray):
    """``fn(theta)`` of :func:`_lambdified` in fmpq, from its SymPy form; ZeroDivisionError at a pole."""
    mat, grads = fn.exact
    subs = {s: sp.Rational(int(v.p), int(v.q)) for s, v in zip(fn.free, theta, strict=True)}
    values = [m.xreplace(subs) for m in (mat, *grads)]
    if not all(e.is_Rational for m in values for e in m):
        raise ZeroDivisionError("a pole of T, M0 or N")
    arr = _fmpq([m.tolist() for m in values])
    return arr[0], np.moveaxis(arr[1:], 0, 2)


def _ctrb(R: Realization) -> sp.Matrix:
    cols = [R.H]
    for _ in range(R.n - 1):
        cols.append(R.F * cols[-1])
    return sp.Matrix.hstack(*cols)


@dataclass(frozen=True, eq=False)
class TraceModel:
    r"""Every neuron's trace, and its exact Jacobian, as a function of :math:`\theta` (by :meth:`build`;
    ``names``: epsilons, Cs unless fixed, then ``Pinv`` row-major for the general class).
    """

    G: DiscreteTF
    sensor_delay: int
    actuator_delay: int
    circuit: object  # a realizer's name (see transformed) or a CircuitClass
    C: float | None  # every C fixed to this value, or None (fitted)
    names: tuple[str, ...]
    neurons: tuple[str, ...]
    order: int
    F0: np.ndarray
    H0: np.ndarray
    _mn: object  # lambdified (M0, N) and their gradients over (eps, C)
    _T: object  # lambdified T and its gradient over (eps, C); None when transformed
    exact: tuple  # (F0, H0, free symbols) exact; _mn.exact, _T.exact: SymPy and its gradients

    @classmethod
    def build(cls, G: DiscreteTF, ds: int, da: int, circuit, C: float | None = None) -> TraceModel:
        """The model of ``G`` with ``ds`` sensor and ``da`` actuator sections in ``circuit``."""
        f0 = factor(G, ds, da)
        eps = (*f0.sensor_eps, *f0.actuator_eps)
        cs = (*f0.sensor_C, *f0.actuator_C)
        base = controllable_canonical(f0.G2)
        n = base.n
        if n == 0:
            raise ParameterError("G: G2 has no states, so its circuit has nothing to fit")
        F0 = np.array(base.F, dtype=float)
        H0 = np.array(base.H, dtype=float).ravel()
        free = eps + (() if C is not None else cs)
        fixed = {c: sp.Rational(C) for c in cs} if C is not None else {}
        M0 = base.M.subs(fixed)
        N = sp.Matrix([[base.N[0, 0]]]).subs(fixed)
        mn = _lambdified(sp.Matrix.vstack(M0.T, N), free)
        if transformed(circuit):
            T = None
            qnames = tuple(f"Pinv[{i + 1},{j + 1}]" for i in range(n) for j in range(n))
        else:
            R2 = _symbolic_realization(circuit, f0.G2, n)
            T = _lambdified((_ctrb(R2) * _ctrb(base).inv()).subs(fixed), free)
            qnames = ()
        names = tuple(map(str, free)) + qnames
        neurons = (
            *(section_name("G1", k + 1, ds) for k in range(ds)),
            *(f"G2.x{i + 1}" for i in range(n)),
            "G2.y",
            *(section_name("G3", k + 1, da) for k in range(da)),
        )
        return cls(G, ds, da, circuit, C, names, neurons, n, F0, H0, mn, T, (base.F, base.H, free))

    @property
    def n_params(self) -> int:
        return len(self.names)

    @property
    def n_sections(self) -> int:
        return self.sensor_delay + self.actuator_delay

    def split(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """``(eps, C, Q)`` of ``theta`` (``C`` filled in when fixed; ``Q`` None unless general)."""
        k = self.n_sections
        eps = theta[:k]
        if self.C is None:
            cs = theta[k : 2 * k]
            rest = theta[2 * k :]
        else:
            exact = theta.dtype == object  # the binary float's exact rational
            cs = np.full(k, fmpq(*Fraction(self.C).as_integer_ratio()) if exact else float(self.C))
            rest = theta[k:]
        Q = rest.reshape(self.order, self.order) if transformed(self.circuit) else None
        return eps, cs, Q

    def traces(self, theta, u, exact: bool = False) -> tuple[dict, dict]:
        """``({neuron: (steps,)}, {neuron: (steps, p)})``: traces and Jacobians, driven by ``u``;
        ``exact``: ``theta`` and ``u`` hold fmpq, and a pole of T, M0 or N raises ZeroDivisionError."""
        theta, u = (np.asarray(a, dtype=object if exact else float) for a in (theta, u))
        filter1, value = (_exact_filter1, _exact_value) if exact else (_filter1, _float_value)
        p, k, ds = self.n_params, self.n_sections, self.sensor_delay
        eps, cs, Q = self.split(theta)
        ci = (lambda j: k + j) if self.C is None else (lambda j: None)
        vals: dict[str, np.ndarray] = {}
        jacs: dict[str, np.ndarray] = {}

        def chain(side: str, offset: int, count: int, v: np.ndarray, dv: np.ndarray):
            for j in range(count):
                e, c = eps[offset + j], cs[offset + j]
                x = filter1(e, c, v)
                dx = filter1(e, c, dv)
                dx[:, offset + j] += filter1(e, 1, x)
                idx = ci(offset + j)
                if idx is not None:
                    dx[:, idx] += filter1(e, 1, v)
                name = section_name(side, j + 1, count)
                vals[name], jacs[name] = x, dx
                v, dv = x, dx
            return v, dv

        y1, dy1 = chain("G1", 0, ds, u, np.zeros((u.size, p), dtype=u.dtype))
        # x_c and its sensitivities in one pass: columns [y1, dy1/dtheta]
        columns = np.column_stack([y1, dy1])
        both = (
            _exact_state_filter(self.exact[0], columns)
            if exact
            else _state_filter(self.F0, columns)
        )
        xc, dxc = both[:, :, 0], both[:, :, 1:]  # (steps, n), (steps, n, p)
        e_c = theta[: 2 * k] if self.C is None else theta[:k]
        if Q is None:
            T, dT = value(self._T, e_c)  # (n, n), (n, n, q)
        else:
            T = Q
        x2 = xc @ T.T
        dx2 = np.einsum("ij,tjp->tip", T, dxc)
        if Q is None:
            dx2[:, :, : dT.shape[2]] += np.einsum("ijq,tj->tiq", dT, xc)
        else:
            off = p - self.order**2
            for i in range(self.order):
                dx2[:, i, off + i * self.order : off + (i + 1) * self.order] += xc
        for i in range(self.order):
            vals[f"G2.x{i + 1}"], jacs[f"G2.x{i + 1}"] = x2[:, i], dx2[:, i, :]
        mn, dmn = value(self._mn, e_c)  # (n+1, 1), (n+1, 1, q)
        M0, N = mn[: self.order, 0], mn[self.order, 0]
        y2 = xc @ M0 + N * y1
        dy2 = np.einsum("j,tjp->tp", M0, dxc) + N * dy1
        q = dmn.shape[2]
        dy2[:, :q] += xc @ dmn[: self.order, 0, :] + y1[:, None] * dmn[self.order, 0, :]
        vals["G2.y"], jacs["G2.y"] = y2, dy2
        chain("G3", ds, self.actuator_delay, y2, dy2)
        return vals, jacs

    def factorization(self, eps, cs) -> Factorization:
        """The exact factors at rational ``eps`` and ``cs``."""
        return factor(self.G, self.sensor_delay, self.actuator_delay, eps=list(eps), C=list(cs))

    def realize(self, fs: Factorization, Q=None) -> Realization:
        """The exact realization of ``fs.G2`` in the model's class (``Q`` = :math:`P^{-1}`)."""
        if transformed(self.circuit):
            return get_realizer(self.circuit)(fs.G2, P=sp.Matrix(Q).inv()).realization
        return _symbolic_realization(self.circuit, fs.G2, self.order)


def _symbolic_realization(circuit, G2, n: int) -> Realization:
    """``G2`` realized in a fixed class: a canonical form or an atlas class (closed form)."""
    if isinstance(circuit, str):
        return get_realizer(circuit, "circuit")(G2).realization
    if circuit.order != n:
        raise DimensionError(
            f"circuit: class {circuit.label} realizes controllers with G2 of order "
            f"{circuit.order}, this one has order {n}"
        )
    try:
        return circuit.realize(G2)
    except NotRealizableError as exc:
        raise NotRealizableError(
            f"circuit: class {circuit.label} cannot realize this controller in closed form "
            f"({str(exc).splitlines()[0][:160]}); choose 'general' or a closed-form class"
        ) from None


def _lambdified(mat: sp.Matrix, free: tuple):
    """``theta -> (values (r, c), gradients (r, c, q))`` of ``mat`` over ``free`` (``.exact``: SymPy)."""
    grads = [mat.diff(s) for s in free]
    f = sp.lambdify([free], [mat, *grads], "numpy", cse=True)
    r, c = mat.shape

    def evaluate(theta):
        out = f(tuple(theta))
        val = np.asarray(out[0], dtype=float).reshape(r, c)
        grad = np.stack([np.asarray(g, dtype=float).reshape(r, c) for g in out[1:]], axis=2)
        return val, grad

    evaluate.exact, evaluate.free = (mat, grads), free
    return evaluate
