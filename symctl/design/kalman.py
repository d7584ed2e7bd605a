r"""Partial, noisy measurement: the delayed Kalman filter and the LQG compensator.

The plant :math:`x(t+1) = A x(t) + B \delta_r(t) + w(t)` is measured through
:math:`y(t) = C x(t) + v(t)`, with white noises of covariances :math:`W` (on the states;
a motor noise of covariance :math:`W_u` on the inputs adds :math:`B W_u B^\top`) and
:math:`V \succ 0`. As for the LQR, the sensor delay moves to the actuator side: on the
controller's clock the measurement that arrives is that of the present plant state, and
the delay-augmented state :math:`\chi` of :mod:`symctl.design.augment` is seen through
:math:`\tilde C = [C\ 0]`.

**Filter** (predictor form, :func:`kalman_gains`). The estimate obeys
:math:`\hat\chi(t+1) = \tilde A \hat\chi + \tilde B \mu + \tilde L (y - \tilde C \hat\chi)`
with :math:`\tilde L = \tilde A \tilde P \tilde C^\top (\tilde C \tilde P \tilde C^\top +
V)^{-1}`, :math:`\tilde P` the stabilizing solution of the dual DARE
(:func:`scipy.linalg.solve_discrete_are` on :math:`(\tilde A^\top, \tilde C^\top, \tilde W, V)`,
:math:`\tilde W = \operatorname{diag}(W, 0)`; the gain of python-control's ``dlqe``).

**The delay chain is known.** No noise enters the chain :math:`\gamma_1 \dots \delta_r`
(the controller's own past commands), so :math:`\tilde P = \operatorname{diag}(P, 0)` and
:math:`\tilde L = [L;\ 0]`, where :math:`P` and :math:`L = A P C^\top (C P C^\top + V)^{-1}`
are the plant's own filter: with :math:`\tilde P` so, the chain rows of :math:`\tilde A
\tilde P` are rows of :math:`\tilde P`'s chain block (zero), and the DARE reduces to the
plant's. The symbolic gain is therefore :math:`L` alone, :math:`n \times p` symbols
(:func:`~symctl.symbols.observer_gain_symbols`), kept symbolic as :math:`K_0 \dots K_T` are.

**Compensator** (:func:`lqg_state_space`, :func:`lqg_tf`). With :math:`\mu = K \hat\chi`,
the state :math:`\hat\chi`, the input :math:`y` at the sensor and the output
:math:`\delta_r` (the last block of :math:`\hat\chi`, exact since the chain is known):
:math:`F = \tilde A + \tilde B K - \tilde L \tilde C`, :math:`H = \tilde L`. Writing
:math:`\Phi(z) = zI - A + LC`, :math:`\varphi = \det \Phi` and :math:`D(z) = z^T I - \sum_k
K_k z^{T-k}` (:mod:`symctl.design.controller`), :math:`D \delta_r = K_0 \hat x` and
:math:`\Phi \hat x = B \delta_r + L y` give, without an inverse,

.. math::
    G(z) = P(z)^{-1} Q(z),\qquad P = \varphi D - K_0 \operatorname{adj}\Phi\, B,\qquad
    Q = K_0 \operatorname{adj}\Phi\, L,

of order :math:`n + Tm` and relative degree at least :math:`T + 1` (one step more than the
full-state :math:`G`: the predictor acts on :math:`y` up to the previous step).

**Proof** (:func:`prove_lqg_tf`). For a candidate :math:`G = N_G/d_G` put
:math:`W = [\operatorname{adj}\Phi (B N_G + L d_G);\ \varphi z^{T-1} N_G; \dots; \varphi N_G]`.
Then :math:`(zI - F) W = H \varphi d_G` and :math:`M W = \varphi N_G` are polynomial
identities in :math:`z`, the gains and the plant's symbols, and together they say
:math:`M (zI - F)^{-1} H = G` (as :math:`\varphi \ne 0`); each is checked exactly in
:math:`\mathbb{Q}[z, K, L]`.

**Separation.** The loop of plant and compensator has the poles of :math:`\tilde A +
\tilde B K` (the regulator's) and those of :math:`A - LC` (the filter's on the plant; the
augmented filter's :math:`\tilde A - \tilde L \tilde C` adds :math:`Tm` poles at 0).

**Current (filter) form** (``form="current"``). The command acts on the updated estimate
:math:`\hat\chi(t|t) = \hat\chi + \tilde M (y - \tilde C \hat\chi)`, :math:`\tilde M =
\tilde P \tilde C^\top (\tilde C \tilde P \tilde C^\top + V)^{-1} = [M;\ 0]` and
:math:`\tilde L = \tilde A \tilde M`: :math:`F = (\tilde A + \tilde B K)(I - \tilde M \tilde C)`,
:math:`H = (\tilde A + \tilde B K)\tilde M`; in the fraction :math:`K_0` becomes
:math:`K_0 (I - MC)` and :math:`Q` gains :math:`\varphi K_0 M`, the relative degree is
:math:`T`, and the proof is the same with :math:`M W + N \varphi d_G = \varphi N_G`.

**Limits.** With :math:`C = I` and :math:`V \to 0`, :math:`M \to I` and :math:`L \to A`: the
current form tends to the full-state :math:`G_0 = D^{-1} K_0`, the predictor form to
:math:`(I - z^{-1} G_0 B)^{-1} z^{-1} G_0 A` (:math:`G_0` on the one-step prediction of
:math:`x(t)`; the LQR's loop poles and :math:`n` at 0). With :math:`W \to 0` and a stable
plant, :math:`L \to 0` and :math:`G \to 0`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg
import sympy as sp

from symctl._util.display import LatexMixin, latex
from symctl._util.exact import NotRational
from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.validate import (
    check_magnitude,
    numeric_matrix,
    psd_matrix,
    read_only,
    to_matrix,
)
from symctl.design.augment import AugmentedSystem
from symctl.design.controller import _chain, _mat, _mul, _ring_of
from symctl.design.fraction import MatrixFractionTF, _adj_det
from symctl.design.lqr import Gains, _pbh_defect, sorted_poles
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.proof import Proof
from symctl.symbols import gain_matrix_symbols, observer_gain_symbols

__all__ = ["KalmanGains", "kalman_gains", "lqg_state_space", "lqg_tf", "prove_lqg_tf"]


@dataclass(frozen=True, eq=False)
class KalmanGains(ArrayValue, DictMixin, LatexMixin):
    r"""The stationary delayed Kalman filter (predictor form) of :func:`kalman_gains` (a value).

    Attributes
    ----------
    system : AugmentedSystem
    C : sympy.ImmutableMatrix
        The plant's output matrix, ``p x n``.
    W, V : numpy.ndarray
        Process covariance on the plant's states (motor noise included) and sensor covariance.
    L : numpy.ndarray
        Predictor gain :math:`\tilde L`, ``(n + T m) x p`` (its chain rows are zero).
    M : numpy.ndarray
        Innovation gain :math:`\tilde M = \tilde P \tilde C^\top (\tilde C \tilde P \tilde
        C^\top + V)^{-1}` of the current (filter) form, :math:`\tilde L = \tilde A \tilde M`.
    P : numpy.ndarray
        Stabilizing solution of the dual DARE, the prior error covariance.
    poles : numpy.ndarray
        Eigenvalues of :math:`\tilde A - \tilde L \tilde C`, by decreasing modulus.

    Examples
    --------
    >>> from symctl import MuscleModel, augment
    >>> from symctl.design.kalman import kalman_gains
    >>> kf = kalman_gains(augment(MuscleModel(), 1, 1), C=[[1]], W=1, V=1)
    >>> kf.L.shape, kf.spectral_radius < 1, sorted(map(str, kf.substitutions()))
    ((3, 1), True, ['L_1'])
    """

    system: AugmentedSystem
    C: sp.ImmutableMatrix
    W: np.ndarray
    V: np.ndarray
    L: np.ndarray
    M: np.ndarray
    P: np.ndarray
    poles: np.ndarray

    def __post_init__(self):
        for name in ("W", "V", "L", "M", "P", "poles"):
            object.__setattr__(self, name, read_only(getattr(self, name)))

    @property
    def p(self) -> int:
        """Measured outputs."""
        return self.C.rows

    def substitutions(self, exact: bool = False, form: str = "predictor") -> dict:
        """Map from the symbols of :func:`~symctl.symbols.observer_gain_symbols` (``L``; ``M`` in the
        current form) to the plant rows of the gain (``exact=True``: the floats' exact rationals)."""
        n, stem = self.system.n, _FORMS[_form(form)]
        value = (lambda v: sp.Rational(float(v))) if exact else float
        symbols = observer_gain_symbols(n, self.p, stem)
        gain = self.L if stem == "L" else self.M
        return {s: value(v) for s, v in zip(symbols, gain[:n].ravel(), strict=True)}

    @property
    def spectral_radius(self) -> float:
        """Largest pole modulus of the estimation error (< 1: the filter converges)."""
        return float(np.max(np.abs(self.poles)))

    def latex(self) -> str:
        return rf"L = {latex(sp.Matrix(self.L[: self.system.n]).evalf(6))}"


_FORMS = {"predictor": "L", "current": "M"}  # the form and the stem of its gain's symbols


def _form(form) -> str:
    if form not in _FORMS:
        raise ParameterError(f"form: expected 'predictor' or 'current', got {form!r}")
    return form


def _output_matrix(C, n: int) -> sp.ImmutableMatrix:
    Cm = sp.eye(n) if C is None else to_matrix(C, "C")
    if Cm.cols != n or Cm.rows == 0:
        raise DimensionError(f"C: expected p x {n} (one column per plant state), got {Cm.shape}")
    return sp.ImmutableMatrix(Cm)


def kalman_gains(system: AugmentedSystem, C=None, W=None, V=None, *, motor=None) -> KalmanGains:
    r"""The stationary Kalman filter of the delay-augmented system, in predictor form.

    Parameters
    ----------
    system : AugmentedSystem
        Numeric.
    C : matrix-like, optional
        Output matrix ``p x n`` of :math:`y = C x + v` (default: the identity).
    W, V : matrix-like, optional
        Process (``n x n``, PSD) and sensor (``p x p``, positive definite) noise covariances
        (default: identities).
    motor : matrix-like, optional
        Motor noise covariance on the inputs, ``m x m`` PSD; adds :math:`B W_u B^\top` to ``W``.

    Returns
    -------
    KalmanGains

    Raises
    ------
    SymctlTypeError
        ``system`` is not an AugmentedSystem.
    DimensionError
        ``C``, ``W``, ``V`` or ``motor`` of the wrong shape.
    ParameterError
        Free symbols; ``W``, ``V`` or ``motor`` not symmetric PSD; ``V`` singular; a mode
        with :math:`|\lambda| \ge 1` no output sees (``C``); no stabilizing DARE solution (``W``).

    Examples
    --------
    >>> import control, numpy as np
    >>> from symctl import augment
    >>> from symctl.design.kalman import kalman_gains
    >>> A, B = np.array([[1.0, 0.1], [0.0, 1.0]]), np.array([[0.0], [0.1]])
    >>> kf = kalman_gains(augment((A, B), 1, 1), C=[[1, 0]], W=np.eye(2), V=0.5)
    >>> L, _, _ = control.dlqe(A, np.eye(2), [[1, 0]], np.eye(2), 0.5)
    >>> bool(np.allclose(kf.L[:2], L)), bool(np.all(kf.L[2:] == 0))
    (True, True)
    >>> kalman_gains(augment((A, B), 1, 1), C=[[0, 1]])
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: C: the outputs leave the plant undetectable: ...
    """
    if not isinstance(system, AugmentedSystem):
        raise SymctlTypeError(f"system: expected an AugmentedSystem, got {type(system).__name__}")
    n, m = system.n, system.m
    Cm = _output_matrix(C, n)
    p = Cm.rows
    Cn = check_magnitude(numeric_matrix(Cm, "C"), "C")
    Wn = check_magnitude(psd_matrix(np.eye(n) if W is None else W, "W", n), "W")
    Vn = check_magnitude(psd_matrix(np.eye(p) if V is None else V, "V", p), "V")
    low = float(np.min(np.linalg.eigvalsh(Vn)))
    if low <= 1e-12 * max(1.0, float(np.max(np.abs(Vn)))):
        raise ParameterError(
            f"V: singular (smallest eigenvalue {low:.3g}); the filter divides by the sensor "
            f"covariance, so every output needs noise of its own (got {Vn.tolist()})"
        )
    A = check_magnitude(numeric_matrix(system.A, "plant"), "plant (A)")
    if motor is not None:
        Bp = numeric_matrix(system.plant.B, "plant")
        Wn = Wn + Bp @ psd_matrix(motor, "motor", m) @ Bp.T
    Ct = np.hstack([Cn, np.zeros((p, A.shape[0] - n))])
    mode = _pbh_defect(A, Ct, stack="v")
    if mode is not None:
        raise ParameterError(
            f"C: the outputs leave the plant undetectable: its mode {mode:.6g} (|lambda| >= 1) "
            "is seen by no output; measure a signal that it moves"
        )
    Wt = np.zeros_like(A)
    Wt[:n, :n] = Wn
    try:
        with np.errstate(over="raise", invalid="raise", divide="raise", under="ignore"):
            P = scipy.linalg.solve_discrete_are(A.T, Ct.T, Wt, Vn)
            M = P @ Ct.T @ np.linalg.inv(Ct @ P @ Ct.T + Vn)
    except (np.linalg.LinAlgError, ValueError, FloatingPointError) as exc:
        raise ParameterError(
            f"W: no stabilizing filter ({exc}); a mode on the unit circle that the process "
            "noise never excites has no stationary estimate: give it some noise"
        ) from None
    M[n:] = 0.0  # exactly zero in theory (module notes); remove the solver's rounding
    L = A @ M
    poles = sorted_poles(A - L @ Ct)
    if not np.all(np.abs(poles) < 1):
        raise ParameterError(f"W, V: the filter does not converge (poles {poles})")
    return KalmanGains(system, Cm, Wn, Vn, L, M, P, poles)


def lqg_state_space(A, B, C, K, L, n: int, m: int, T: int, form: str = "predictor"):
    r"""``(F, H, M, N)`` of the LQG compensator from ``y`` (at the sensor) to :math:`\delta_r`
    (module notes), state :math:`\hat\chi`; ``L`` the plant rows of :math:`\tilde L` (predictor)
    or :math:`\tilde M` (current). ``A``, ``B`` augmented, ``C`` the plant's, ``K`` the gain row;
    SymPy matrices and NumPy arrays alike."""
    symbolic = isinstance(A, sp.MatrixBase)
    zeros = sp.zeros if symbolic else (lambda r, c: np.zeros((r, c)))
    eye = sp.eye if symbolic else np.eye
    size, p = n + T * m, C.shape[0]
    Ct = zeros(p, size)
    Ct[:, :n] = C
    Lt = zeros(size, p)
    Lt[:n, :] = L
    closed = A + B @ K
    if _form(form) == "current":
        keep = eye(size) - Lt @ Ct
        F, H, out, N = closed @ keep, closed @ Lt, K @ keep, K @ Lt
    else:
        F, H, out, N = closed - Lt @ Ct, Lt, K, zeros(m, p)
    if T == 0:
        return F, H, out, N
    M = zeros(m, size)
    M[:, size - m :] = eye(m)
    return F, H, M, zeros(m, p)


def _check_design(system, C, gains, kalman, *, required: bool = False):
    """``C`` as a matrix (default: the filter's), ``gains`` and ``kalman`` (None unless
    ``required``) checked to be designs on ``system`` that measure it."""
    for value, name, kind in ((gains, "gains", Gains), (kalman, "kalman", KalmanGains)):
        if value is None and not required:
            continue
        if not isinstance(value, kind):
            raise SymctlTypeError(f"{name}: expected {kind.__name__}, got {value!r}")
        if value.system != system:
            raise ParameterError(f"{name}: designed for another system")
    Cm = _output_matrix(kalman.C if C is None and kalman is not None else C, system.n)
    if kalman is not None and kalman.C != Cm:
        raise ParameterError(f"C: the filter measures {kalman.C.tolist()}, not {Cm.tolist()}")
    return Cm


def _design_values(system, Cm, gains, kalman, form: str) -> dict:
    """The exact values of the gain symbols in the design ``gains``, ``kalman`` (or none)."""
    if gains is None and kalman is None:
        return {}
    _check_design(system, Cm, gains, kalman, required=True)
    return {**gains.substitutions(exact=True), **kalman.substitutions(exact=True, form=form)}


def _setup(system: AugmentedSystem, Cm, form: str, values: dict | None = None):
    """The ring, converter and plant map, the gains ``K`` and the filter's (symbols or ``values``),
    the predictor gain (``A M`` in the current form), ``adj Phi`` and ``det Phi``."""
    K = sp.Matrix.hstack(*gain_matrix_symbols(system.T, system.m, system.n))
    gain = sp.Matrix(observer_gain_symbols(system.n, Cm.rows, _FORMS[_form(form)]))
    if values:
        K, gain = K.xreplace(values), gain.xreplace(values)
    R, convert, ev = _ring(system, Cm, K, gain)
    A = ev(system.plant.A)
    L = gain if form == "predictor" else A * gain
    adj, phi = _observer(R, convert, A, ev(Cm), L, system.n)
    return R, convert, ev, K, gain, L, adj, phi


def _ring(system: AugmentedSystem, Cm, K, L):
    """``QQ[z, K, L, plant symbols]``, its converter, and a map making the plant convertible
    (floats for entries such as ``exp(-1/2)`` in a plant without symbols)."""
    parts = (system.plant.A, system.plant.B, Cm)
    plant = sorted(set().union(*(M.free_symbols for M in parts)), key=str)
    R, convert = _ring_of([*(s for s in (*K, *L) if s.is_Symbol), *plant])
    try:
        for M in parts:
            _mat(convert, M)
    except NotRational:
        if plant:
            raise ParameterError(
                f"plant: entries not rational in the symbols {', '.join(map(str, plant))}; "
                "substitute numbers first"
            ) from None
        return R, convert, lambda M: sp.Matrix(M).evalf()
    return R, convert, sp.Matrix


def _observer(R, convert, A, C, L, n: int):
    """``adj Phi`` and ``det Phi`` of :math:`\\Phi = zI - A + LC` in the ring."""
    Phi = _mat(convert, L * C - A)
    for i in range(n):
        Phi[i][i] += R.gens[0]
    return _adj_det(Phi, R.zero)


def lqg_tf(
    system: AugmentedSystem,
    C=None,
    gains: Gains | None = None,
    kalman: KalmanGains | None = None,
    *,
    form: str = "predictor",
) -> DiscreteTF:
    r"""The LQG compensator :math:`G(z) = P(z)^{-1} Q(z)` from the outputs to :math:`\delta_r`.

    Parameters
    ----------
    system : AugmentedSystem
        The plant (numbers, or symbols it is rational in) with its delays.
    C : matrix-like, optional
        Output matrix ``p x n``; default ``kalman.C``, else the identity.
    gains, kalman : Gains and KalmanGains, optional
        Substitute these gains for :math:`K_0 \dots K_T` and the filter's symbols.
    form : {"predictor", "current"}
        The command uses :math:`y` up to the previous step (symbols :math:`L`), or
        :math:`\hat\chi(t|t)` with :math:`y(t)` (symbols :math:`M`).

    Returns
    -------
    DiscreteTF
        ``m x p``, order :math:`n + Tm`, relative degree at least :math:`T + 1` (current:
        :math:`T`); a :class:`~symctl.design.fraction.MatrixFractionTF` for several inputs
        with symbols left.

    Raises
    ------
    SymctlTypeError
        ``system``, ``gains`` or ``kalman`` of another type.
    DimensionError
        ``C`` of the wrong shape.
    ParameterError
        ``gains`` or ``kalman`` designed on another system or with another ``C``; plant
        entries that are not rational in its symbols.

    Examples
    --------
    >>> from symctl import MuscleModel, augment
    >>> from symctl.design.kalman import lqg_tf, prove_lqg_tf
    >>> s = augment(MuscleModel(), 1, 1)
    >>> G = lqg_tf(s, C=[[1]])
    >>> G.num, G.relative_degree
    (K_0*L_1, 3)
    >>> bool(prove_lqg_tf(s, [[1]], G))
    True
    """
    if not isinstance(system, AugmentedSystem):
        raise SymctlTypeError(f"system: expected an AugmentedSystem, got {type(system).__name__}")
    Cm = _check_design(system, C, gains, kalman)
    n, m, T, p = system.n, system.m, system.T, Cm.rows
    R, convert, ev, K, gain, L, adj, phi = _setup(system, Cm, form)
    K0 = K[:, :n]
    E = K0 if form == "predictor" else K0 * (sp.eye(n) - gain * ev(Cm))  # acts on the prior
    D = _mat(convert, _chain(T, m, lambda k, i, j: K[i, n + (k - 1) * m + j]))
    Eadj = _mul(R, _mat(convert, E), adj)
    KB = _mul(R, Eadj, _mat(convert, ev(system.plant.B)))
    Pm = [[phi * D[i][j] - KB[i][j] for j in range(m)] for i in range(m)]
    Qm = _mul(R, Eadj, _mat(convert, L))
    if form == "current":  # plus phi K_0 M: the present measurement
        direct = _mul(R, _mat(convert, K0), _mat(convert, gain))
        Qm = [[Qm[i][j] + phi * direct[i][j] for j in range(p)] for i in range(m)]
    expr = sp.Matrix
    P_e = expr(m, m, lambda i, j: Pm[i][j].as_expr())
    Q_e = expr(m, p, lambda i, j: Qm[i][j].as_expr())
    dt = system.plant.dt
    if m == 1:
        G = DiscreteTF(Q_e, P_e[0, 0], dt)
    else:  # kept as the fraction while symbolic (its expansion is large and slow)
        G = MatrixFractionTF(P_e, Q_e, dt)
    if G.relative_degree < T + (form == "predictor") and any(e != 0 for e in Q_e):
        raise AssertionError(f"internal: relative degree {G.relative_degree} too small")
    rule = {} if gains is None else gains.substitutions()
    rule.update({} if kalman is None else kalman.substitutions(form=form))
    if not rule:
        return G
    G = G.subs(rule)
    return G.expanded() if isinstance(G, MatrixFractionTF) and not G.free_symbols else G


def prove_lqg_tf(
    system: AugmentedSystem,
    C=None,
    G: DiscreteTF | None = None,
    *,
    form: str = "predictor",
    gains: Gains | None = None,
    kalman: KalmanGains | None = None,
) -> Proof:
    r"""Prove that ``G`` (default :func:`lqg_tf`) is the LQG compensator of ``system``: the module
    notes' identities, exactly in :math:`\mathbb{Q}[z, K, L]` (with ``gains`` and ``kalman``, in
    :math:`\mathbb{Q}[z]` at their exact values); a left fraction is expanded first.

    Parameters
    ----------
    system : AugmentedSystem
    C : matrix-like, optional
        Output matrix (default: the identity).
    G : DiscreteTF, optional
        The candidate, ``m x p`` in :math:`K` and :math:`L` (or :math:`M`).
    form : {"predictor", "current"}
        As in :func:`lqg_tf`.
    gains, kalman : Gains and KalmanGains, optional
        The design whose exact gains replace the symbols (both or neither).

    Returns
    -------
    Proof
        Truthy when the identities hold; else the first nonzero entry as evidence.

    Raises
    ------
    SymctlTypeError
        ``system`` not an AugmentedSystem, ``G`` not a DiscreteTF.
    ParameterError
        ``G`` a left fraction too large to expand.

    Examples
    --------
    >>> from symctl import MuscleModel, augment
    >>> from symctl.design.kalman import lqg_tf, prove_lqg_tf
    >>> s = augment(MuscleModel(), 2, 1)
    >>> bool(prove_lqg_tf(s, [[1]])), bool(prove_lqg_tf(s, [[1]], 2 * lqg_tf(s, [[1]])))
    (True, False)
    """
    if not isinstance(system, AugmentedSystem):
        raise SymctlTypeError(f"system: expected an AugmentedSystem, got {type(system).__name__}")
    if G is not None and not isinstance(G, DiscreteTF):
        raise SymctlTypeError(f"G: expected a DiscreteTF, got {G!r}")
    Cm = _output_matrix(C, system.n)
    values = _design_values(system, Cm, gains, kalman, form)
    G = lqg_tf(system, Cm, form=form) if G is None else G
    if values and G.free_symbols:
        G = G.subs(values)
    if isinstance(G, MatrixFractionTF):
        G = G.expanded()
    n, m, T, p = system.n, system.m, system.T, Cm.rows
    claim = "G(z) is the transfer function of the delayed LQG compensator"
    method = (
        "polynomial identities (zI - F) W = H det(Phi) d_G and M W + N det(Phi) d_G = "
        "det(Phi) N_G in Q[z, K, L]"
    )
    if G.shape != (m, p):
        return Proof(False, claim, "shapes", f"G has shape {G.shape}, the compensator {(m, p)}")
    R, convert, ev, K, gain, L, adj, phi = _setup(system, Cm, form, values)
    if values:
        method = method.replace("Q[z, K, L]", "Q[z] at the design's exact gains")
    try:
        N_G, d_G = _mat(convert, G.num_matrix), convert(G.den)
    except (NotRational, KeyError):  # a symbol the compensator does not have
        return Proof(False, claim, method, f"G is not polynomial in z, K and {_FORMS[form]}")
    zz = R.gens[0]
    BN = _mul(R, _mat(convert, ev(system.plant.B)), N_G)
    Lr = _mat(convert, L)
    X = _mul(R, adj, [[BN[i][j] + Lr[i][j] * d_G for j in range(p)] for i in range(n)])
    W = X + [[phi * zz ** (T - 1 - k // m) * N_G[k % m][j] for j in range(p)] for k in range(T * m)]
    F, H, M, N = lqg_state_space(ev(system.A), ev(system.B), ev(Cm), K, gain, n, m, T, form)
    FW = _mul(R, _mat(convert, F), W)
    Hr, Nr = _mat(convert, H), _mat(convert, N)
    MW = _mul(R, _mat(convert, M), W)
    residues = (
        *(zz * W[i][j] - FW[i][j] - Hr[i][j] * phi * d_G for i in range(len(W)) for j in range(p)),
        *(MW[i][j] + Nr[i][j] * phi * d_G - phi * N_G[i][j] for i in range(m) for j in range(p)),
    )
    first = next((str(e.as_expr()) for e in residues if e), "")
    return Proof(not first, claim, method, first)
