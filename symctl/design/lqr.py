r"""Optimal gains of the delay-augmented LQR problem.

The paper minimizes :math:`J = \sum_t \chi^\top \tilde Q \chi` with
:math:`\tilde Q = \operatorname{diag}(Q, 0, \dots, 0, R)` and no penalty on the
intended actuation :math:`\mu` (eq. augmented_cost). For :math:`T \ge 1` we
solve the equivalent problem with the penalty moved onto :math:`\mu`:

**Equivalence.** Since :math:`\delta_r(t) = \mu(t - T)` for :math:`t \ge T`,

.. math::
    \sum_{t \ge 0} \delta_r(t)^\top R\, \delta_r(t)
    = \sum_{k=1}^{T} \gamma_k(0)^\top R\, \gamma_k(0) + \sum_{t \ge 0} \mu(t)^\top R\, \mu(t),

and the first sum is fixed by the initial state. So the paper's cost and
:math:`\sum_t \chi^\top \operatorname{diag}(Q, 0, \dots, 0)\chi + \mu^\top R \mu`
differ by a term no control can change: both have the same optimal feedback.
The second is a standard DARE with :math:`R \succ 0`, better conditioned. Stabilizability and
detectability are checked first (PBH). Sign: the paper's :math:`\mu = K\chi`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg
import sympy as sp

from symctl._util.display import LatexMixin, latex
from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.validate import check_magnitude, numeric_matrix, psd_matrix, read_only
from symctl.design.augment import AugmentedSystem
from symctl.errors import NotStabilizableError, ParameterError, SymctlTypeError
from symctl.symbols import gain_matrix_symbols

__all__ = ["Gains", "lqr_gains"]

_TOL = 1e-9


@dataclass(frozen=True, eq=False)
class Gains(ArrayValue, DictMixin, LatexMixin):
    r"""Optimal gains :math:`K = [K_0\ K_1 \dots K_T]` of :math:`\mu = K\chi` (read-only, a value).

    Attributes
    ----------
    system : AugmentedSystem
    K, X : numpy.ndarray
        The ``m x (n + T m)`` gain; the stabilizing DARE solution of the equivalent problem.
    poles : numpy.ndarray
        Eigenvalues of :math:`\tilde A + \tilde B K`, by decreasing modulus.

    Examples
    --------
    >>> from symctl import MuscleModel, augment, lqr_gains
    >>> g = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> g.K.shape, g.spectral_radius < 1, g.K.flags.writeable
    ((1, 3), True, False)
    >>> sorted(map(str, g.substitutions()))
    ['K_0', 'K_1', 'K_2']
    """

    system: AugmentedSystem
    K: np.ndarray
    X: np.ndarray
    poles: np.ndarray

    def __post_init__(self):
        for name in ("K", "X", "poles"):
            object.__setattr__(self, name, read_only(getattr(self, name)))

    @property
    def blocks(self) -> list[np.ndarray]:
        """``[K_0, K_1, ..., K_T]``: ``K_0`` is ``m x n``, the others ``m x m``."""
        n, m, T = self.system.n, self.system.m, self.system.T
        return [self.K[:, :n]] + [self.K[:, n + k * m : n + (k + 1) * m] for k in range(T)]

    def substitutions(self, exact: bool = False) -> dict:
        """The gain symbols (entries, for MIMO) to these values (``exact``: as exact rationals)."""
        s = self.system
        out = {}
        for sym, val in zip(gain_matrix_symbols(s.T, s.m, s.n), self.blocks, strict=True):
            out.update(zip(sym, np.asarray(val).ravel(), strict=True))
        value = (lambda v: sp.Rational(float(v))) if exact else float
        return {k: value(v) for k, v in out.items()}

    @property
    def spectral_radius(self) -> float:
        """Largest closed-loop pole modulus (< 1: Schur stable)."""
        return float(np.max(np.abs(self.poles))) if self.poles.size else 0.0

    def latex(self) -> str:
        return rf"K = {latex(sp.Matrix(self.K).evalf(6))}"


def sorted_poles(M: np.ndarray) -> np.ndarray:
    """The eigenvalues of ``M`` by decreasing modulus."""
    poles = np.linalg.eigvals(M)
    return poles[np.argsort(-np.abs(poles), kind="stable")]


def _pbh_defect(A: np.ndarray, other: np.ndarray, *, stack: str) -> complex | None:
    """An eigenvalue with ``|lambda| >= 1`` that fails the PBH rank test, or None."""
    n = A.shape[0]
    for lam in np.linalg.eigvals(A):
        if abs(lam) < 1 - _TOL:
            continue
        shifted = A - lam * np.eye(n)
        test = np.hstack([shifted, other]) if stack == "h" else np.vstack([shifted, other])
        sv = np.linalg.svd(test, compute_uv=False)
        scale = max(1.0, float(np.max(np.abs(test))))
        if np.sum(sv > 1e-9 * scale) < n:
            return complex(lam)
    return None


def lqr_gains(system: AugmentedSystem, Q=None, R=None) -> Gains:
    r"""Solve the delayed LQR problem; gains in the paper's sign, :math:`\mu = K \chi`.

    Parameters
    ----------
    system : AugmentedSystem
        Numeric.
    Q, R : matrix-like, optional
        Override the penalties stored in ``system``.

    Returns
    -------
    Gains

    Raises
    ------
    SymctlTypeError, ParameterError
        ``system`` not an AugmentedSystem; free symbols, Q/R not symmetric PSD or above 1e100,
        an overflow.
    NotStabilizableError
        Not stabilizable or detectable; no stabilizing DARE solution or unique gain.

    Examples
    --------
    >>> from symctl import MuscleModel, augment, lqr_gains
    >>> g = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> [round(float(k), 6) for k in g.K[0]]
    [-0.045972, -0.580041, -0.351813]
    """
    if not isinstance(system, AugmentedSystem):
        raise SymctlTypeError(
            "system: expected an AugmentedSystem (from symctl.augment), "
            f"got {type(system).__name__}"
        )
    n, m = system.n, system.m
    Qp = check_magnitude(psd_matrix(system.Q_plant if Q is None else Q, "Q", n), "Q")
    Rm = check_magnitude(psd_matrix(system.R if R is None else R, "R", m), "R")
    A = check_magnitude(numeric_matrix(system.A, "plant"), "plant (A)")
    B = check_magnitude(numeric_matrix(system.B, "plant"), "plant (B)")
    with np.errstate(over="raise", invalid="raise", divide="raise", under="ignore"):
        try:
            return _solve(system, A, B, Qp, Rm)
        except FloatingPointError as exc:
            raise ParameterError(
                f"Q, R, plant: the LQR overflowed ({exc}); the problem is badly scaled: "
                f"Q up to {np.max(np.abs(Qp)):g}, R up to {np.max(np.abs(Rm)):g}, "
                f"plant B up to {np.max(np.abs(B)):g}"
            ) from None


def _solve(system: AugmentedSystem, A, B, Qp, Rm) -> Gains:
    n = system.n
    Qeq = np.zeros_like(A)
    Qeq[:n, :n] = Qp

    mode = _pbh_defect(A, B, stack="h")
    if mode is not None:
        raise NotStabilizableError(
            f"plant: not stabilizable, the mode {mode:.6g} (|lambda| >= 1) "
            "cannot be reached by the input"
        )
    w, v = np.linalg.eigh(Qeq)
    q_half = (v * np.sqrt(np.clip(w, 0, None))) @ v.T
    mode = _pbh_defect(A, q_half, stack="v")
    if mode is not None:
        raise NotStabilizableError(
            f"Q: the cost is not detectable, the mode {mode:.6g} (|lambda| >= 1) "
            "is invisible to Q; penalize it to get a stabilizing controller"
        )
    try:
        X = scipy.linalg.solve_discrete_are(A, B, Qeq, Rm)
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise NotStabilizableError(
            f"R: no stabilizing DARE solution ({exc}); is R singular?"
        ) from None
    try:
        K = -np.linalg.solve(Rm + B.T @ X @ B, B.T @ X @ A)
    except np.linalg.LinAlgError:
        raise NotStabilizableError(
            f"R: R + B' X B is singular, no unique optimal gain (R = {Rm.tolist()}); "
            "penalize the input with R > 0"
        ) from None
    if not (np.all(np.isfinite(K)) and np.all(np.isfinite(X))):
        raise ParameterError(
            "Q, R: the DARE solution is not finite; the problem is badly scaled "
            f"(Q up to {np.max(np.abs(Qp)):g}, R up to {np.max(np.abs(Rm)):g})"
        )
    poles = sorted_poles(A + B @ K)
    if not np.all(np.abs(poles) < 1):
        raise NotStabilizableError(
            f"plant: the DARE solution does not stabilize the loop (poles {poles}); check Q and R"
        )
    return Gains(system, K, X, poles)
