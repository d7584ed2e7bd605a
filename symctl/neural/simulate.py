r"""Open- and closed-loop simulation of the plant with any realization of the controller.

The paper's section "Simulations": the linear plant of eq. (system) driven by a
pulse in firing rate (Fig. ol_sims); the loop closed with the optimal delayed
controller and hit by a pulse disturbance on the force (Fig. cl_sims); the same
loop closed with any realization of :math:`G = G_3 G_2 G_1` (Figs. full_diagram,
ccr_diagram, ocr_diagram), whose outputs agree while the neurons' firing
patterns differ; the linear controller around the original nonlinear muscle;
and a batch simulator vectorized over realizations.

The disturbance :math:`w` enters the state update (zero initial state),

.. math::
    \delta_f(t+1) = A\,\delta_f(t) + B\,\delta_r(t) + w(t),\qquad
    x_c(t+1) = F x_c(t) + H \delta_f(t),\qquad
    \delta_r(t) = M x_c(t) + N \delta_f(t),

so the closed loop is :math:`\xi(t+1) = A_{cl}\,\xi(t) + [I; 0]\,w(t)` with
:math:`\xi = [\delta_f; x_c]` and
:math:`A_{cl} = \begin{bmatrix} A + BN & BM \\ H & F \end{bmatrix}`. The
optimal controller itself is simulated on the augmented state,
:math:`\chi(t+1) = (\tilde A + \tilde B K)\chi(t) + [I; 0]\,w(t)`.

Defaults (documented choices; the paper gives none): a pulse of amplitude 1
(1 spike/s in firing rate, or 1 N of force per step), starting at step
``start = 5`` and lasting ``length = 10`` steps, over a horizon of
``steps = 50`` samples (0.5 s at the paper's :math:`T_s` = 10 ms). Time is
``t = k Ts`` in seconds; absolute force and rate add the plant's operating
point :math:`(\bar f, \bar r)` back.

>>> from symctl import MuscleModel, augment, lqr_gains
>>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
>>> res = closed_loop_response(gains)
>>> res.t.shape, res.delta_f.shape, round(float(res.f[0, 0]), 4)
((50,), (50, 1), 43.8635)
>>> round(float(res.delta_r.min()), 4)      # the motor neuron answers the push, 2 steps later
-0.0472
"""

from __future__ import annotations

import numbers
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
import scipy.integrate

from symctl._util.validate import nonneg_int, numeric_matrix, real_number
from symctl.design.augment import as_plant
from symctl.design.lqr import Gains
from symctl.design.plant import DiscretePlant, MuscleModel
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.realization.realization import Realization, controllable_canonical
from symctl.realization.realizers import ifp_realization

__all__ = [
    "DEFAULT_LENGTH",
    "DEFAULT_START",
    "DEFAULT_STEPS",
    "BatchResponse",
    "NonlinearCheck",
    "Response",
    "closed_loop_response",
    "nonlinear_check",
    "open_loop_response",
    "pulse",
    "simulate_batch",
    "simulate_realization",
]

DEFAULT_STEPS = 50
"""Default horizon in samples (0.5 s at the paper's Ts = 10 ms)."""
DEFAULT_START = 5
"""Default first step of the pulse."""
DEFAULT_LENGTH = 10
"""Default pulse length in steps."""

_EIG_LIMIT = 2000  # above this many realizations, stability is decided by the Schur-Cohn test
_CHUNK = 8192  # realizations per task of the time loop (their matrices stay in the CPU cache)
_WORKERS = os.cpu_count() or 1  # threads that run the tasks


# ---------------------------------------------------------------- arguments
def _positive_int(value, argname: str) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 1:
        raise ParameterError(f"{argname}: must be an integer >= 1, got {value!r}")
    return int(value)


def _float_array(value, argname: str) -> np.ndarray:
    if isinstance(value, str | bytes) or value is None:
        raise SymctlTypeError(f"{argname}: expected an array of numbers, got {value!r}")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise SymctlTypeError(
            f"{argname}: expected an array of real numbers, got {type(value).__name__}"
        ) from None
    if not np.all(np.isfinite(arr)):
        raise ParameterError(f"{argname}: entries must be finite (no NaN or inf)")
    return arr


def pulse(
    steps: int = DEFAULT_STEPS,
    amplitude: float = 1.0,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    size: int = 1,
) -> np.ndarray:
    r"""A pulse signal of shape ``(steps, size)``: ``amplitude`` for ``start <= k < start + length``.

    Examples
    --------
    >>> pulse(6, 2.0, start=1, length=3).ravel()
    array([0., 2., 2., 2., 0., 0.])
    """
    steps = _positive_int(steps, "steps")
    amp = real_number(amplitude, "amplitude")
    start = nonneg_int(start, "start")
    length = nonneg_int(length, "length")
    out = np.zeros((steps, _positive_int(size, "size")))
    out[start : start + length] = amp
    return out


def _signal(value, argname: str, steps: int | None, size: int, start: int, length: int):
    """A ``(steps, size)`` signal from a pulse amplitude (a number) or an array."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return pulse(DEFAULT_STEPS if steps is None else steps, value, start, length, size)
    arr = _float_array(value, argname)
    if arr.ndim == 1 and size == 1:
        arr = arr[:, None]
    if arr.ndim != 2 or arr.shape[1] != size or arr.shape[0] == 0:
        raise DimensionError(
            f"{argname}: expected shape (steps, {size}) with steps >= 1, got {arr.shape}"
        )
    if steps is not None and _positive_int(steps, "steps") != arr.shape[0]:
        raise DimensionError(f"{argname}: has {arr.shape[0]} samples but steps = {steps}")
    return arr


def _plant(plant) -> tuple[DiscretePlant, np.ndarray, np.ndarray]:
    p = as_plant(plant)
    A, B = p.numeric()
    return p, A, B


def _equilibrium(value, size: int, argname: str) -> np.ndarray:
    if value is None:
        return np.zeros(size)
    return numeric_matrix(value, argname).ravel()


def _ts(p: DiscretePlant) -> float:
    return 1.0 if p.Ts is None else float(numeric_matrix(p.Ts, "Ts")[0, 0])


# ---------------------------------------------------------------- results
def _labels(p_names: tuple[str, ...], kind: str) -> tuple[str, str, str]:
    """(change label, absolute label, unit) for the muscle; neutral names otherwise."""
    muscle = {"delta_f": ("force change δf", "force f", "N"),
              "delta_r": ("rate change δr", "motor-neuron rate r", "spikes/s")}  # fmt: skip
    if p_names == (kind,) and kind in muscle:
        return muscle[kind]
    return ("change from equilibrium", "absolute value", "units")


@dataclass(frozen=True, eq=False)
class Response:
    r"""Traces of one simulation (open or closed loop), all sampled at ``t = k Ts``.

    Attributes
    ----------
    t : (steps,) array
        Time in seconds (in steps when the plant has no ``Ts``).
    delta_f, f : (steps, n) arrays
        Plant state change :math:`\delta_f` and absolute :math:`f = \bar f + \delta_f` [N].
    delta_r, r : (steps, m) arrays
        Motor-neuron rate change :math:`\delta_r` and absolute :math:`r = \bar r + \delta_r`
        [spikes/s].
    w : (steps, n) array
        Disturbance on the state (zeros in open loop).
    states : (steps, nc) array
        The controller's internal states (the neurons' firing-rate changes; for the
        optimal controller the delay chain :math:`\gamma_1, \dots, \delta_r`); ``nc = 0``
        in open loop.
    f_bar, r_bar : arrays
        The operating point (zeros when the plant records none).
    kind : str
        ``"open loop"`` or ``"closed loop"``.
    time_unit : str
        ``"s"``, or ``"steps"`` when the plant has no sampling time.
    """

    t: np.ndarray
    delta_f: np.ndarray
    delta_r: np.ndarray
    w: np.ndarray
    states: np.ndarray
    f_bar: np.ndarray
    r_bar: np.ndarray
    kind: str
    state_names: tuple[str, ...] = ("delta_f",)
    input_names: tuple[str, ...] = ("delta_r",)
    time_unit: str = "s"

    @property
    def f(self) -> np.ndarray:
        """Absolute force (state), :math:`\\bar f + \\delta_f`."""
        return self.delta_f + self.f_bar

    @property
    def r(self) -> np.ndarray:
        """Absolute motor-neuron rate (input), :math:`\\bar r + \\delta_r`."""
        return self.delta_r + self.r_bar

    def plot(self, states: bool | None = None):
        """Force and motor-neuron rate against time, absolute values on the right axes.

        ``states`` adds a panel with the controller's internal states (default: when
        there are any). Returns a :class:`matplotlib.figure.Figure`.
        """
        from matplotlib.figure import Figure

        states = self.states.shape[1] > 0 if states is None else states
        rows = 3 if states else 2
        fig = Figure(figsize=(7.5, 2.4 * rows + 0.6), layout="constrained")
        axes = fig.subplots(rows, 1, sharex=True)
        panels = [
            (axes[0], self.delta_f, self.f_bar, self.state_names, "delta_f"),
            (axes[1], self.delta_r, self.r_bar, self.input_names, "delta_r"),
        ]
        for ax, trace, bar, names, kind in panels:
            change, absolute, unit = _labels(names, kind)
            for i in range(trace.shape[1]):
                label = change if trace.shape[1] == 1 else f"{change} ({names[i]})"
                ax.plot(self.t, trace[:, i], marker=".", lw=1.5, label=label)
            if kind == "delta_f" and self.kind == "closed loop":
                for i in range(self.w.shape[1]):
                    ax.step(self.t, self.w[:, i], where="post", ls="--", color="gray",
                            label=f"disturbance w [{unit}/step]")  # fmt: skip
            ax.axhline(0, color="black", lw=0.5)
            ax.set_ylabel(f"{change} [{unit}]")
            if trace.shape[1] == 1:
                offset = float(bar[0])
                sec = ax.secondary_yaxis(
                    "right", functions=(lambda x, o=offset: x + o, lambda x, o=offset: x - o)
                )
                sec.set_ylabel(f"{absolute} [{unit}]")
            ax.legend(loc="best", fontsize="small")
            ax.grid(alpha=0.3)
        if states:
            ax = axes[2]
            for i in range(self.states.shape[1]):
                ax.plot(self.t, self.states[:, i], marker=".", lw=1.2, label=f"x_{i + 1}")
            ax.set_ylabel("controller state\n(rate change) [spikes/s]")
            ax.legend(loc="best", fontsize="small", ncol=min(4, self.states.shape[1]))
            ax.grid(alpha=0.3)
        axes[-1].set_xlabel(f"time [{self.time_unit}]")
        what = "pulse in firing rate" if self.kind == "open loop" else "pulse disturbance on force"
        fig.suptitle(f"{self.kind.capitalize()} response to a {what}")
        return fig


@dataclass(frozen=True, eq=False)
class BatchResponse:
    """Traces of many closed loops at once (see :func:`simulate_batch`).

    ``delta_f`` is ``(R, steps, n)``, ``delta_r`` ``(R, steps, m)``, ``states``
    ``(R, steps, nc)`` or ``None`` (when not asked for); ``t`` is ``(steps,)`` in seconds.
    The arrays may be non-contiguous views (time-major storage).
    """

    t: np.ndarray
    delta_f: np.ndarray
    delta_r: np.ndarray
    states: np.ndarray | None
    stability_checked: bool


# ---------------------------------------------------------------- the core
# Stacks of loops are stored realization-last, ``(rows, cols, R)``: every vectorized
# operation below then runs over contiguous memory, one realization per element.
def _chunks(count: int) -> list[slice]:
    """Consecutive slices of at most ``_CHUNK`` realizations covering ``range(count)``."""
    return [slice(lo, min(count, lo + _CHUNK)) for lo in range(0, count, _CHUNK)]


def _charpoly(A: np.ndarray) -> np.ndarray:
    r"""Characteristic polynomials of a stack ``(N, N, R)``, ascending: ``(N + 1, R)``.

    From the power sums :math:`p_k = \operatorname{tr} A^k = \operatorname{tr}(A^a A^b)`,
    :math:`a + b = k`, which need the powers up to :math:`\lceil N/2 \rceil` only, and
    Newton's identities :math:`k\,c_{N-k} = -\sum_{i=1}^{k} c_{N-k+i}\,p_i` with the
    leading coefficient :math:`c_N = 1`.
    """
    N, R = A.shape[0], A.shape[-1]
    powers = [np.broadcast_to(np.eye(N)[:, :, None], A.shape), A]
    while len(powers) <= (N + 1) // 2:
        powers.append(np.einsum("ijr,jkr->ikr", powers[-1], A))
    p = np.stack(
        [np.einsum("ijr,jir->r", powers[(k + 1) // 2], powers[k // 2]) for k in range(N + 1)]
    )
    c = np.zeros((N + 1, R))
    c[N] = 1.0
    for k in range(1, N + 1):
        c[N - k] = -np.einsum("ir,ir->r", c[N - k + 1 :], p[1 : k + 1]) / k
    return c


def _schur_stable(A: np.ndarray) -> np.ndarray:
    r"""Whether every eigenvalue of each ``A[:, :, r]`` is inside the unit circle (Schur-Cohn test).

    Reduces :math:`p(z) = \sum a_i z^i` to :math:`(a_d p(z) - a_0 p^*(z))/z` while
    :math:`|a_0| < |a_d|` (the reflection coefficient); vectorized over ``r``.
    """
    a = _charpoly(A)
    ok = np.ones(a.shape[1], dtype=bool)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for d in range(a.shape[0] - 1, 0, -1):
            lead, const = a[d], a[0]
            ok &= np.abs(const) < np.abs(lead)
            a = lead * a[1 : d + 1] - const * a[d - 1 :: -1]
            a /= np.where(a[-1] == 0, 1.0, np.abs(a[-1]))  # keeps the numbers in range
    return ok


def _stability(Acl: np.ndarray, argname: str) -> None:
    """Refuse an unstable closed loop (spectral radius >= 1), naming the first bad realization."""
    count = Acl.shape[-1]
    if count <= _EIG_LIMIT:
        eigs = np.linalg.eigvals(np.moveaxis(Acl, -1, 0)) if Acl.shape[0] else np.zeros((count, 1))
        bad = np.flatnonzero(np.max(np.abs(eigs), axis=-1) >= 1)
    else:  # in chunks, whose temporaries stay small
        bad = np.flatnonzero(~np.concatenate([_schur_stable(Acl[..., c]) for c in _chunks(count)]))
    if bad.size:
        i = int(bad[0])
        rho = float(np.max(np.abs(np.linalg.eigvals(Acl[:, :, i]))))
        where = f" (realization {i} of {count}; {bad.size} unstable)" if count > 1 else ""
        raise ParameterError(
            f"{argname}: the closed loop is unstable, spectral radius {rho:.6g} >= 1{where}; "
            "the controller does not stabilize this plant"
        )


def _closed_loop_matrices(A, B, F, H, M, N) -> tuple[np.ndarray, np.ndarray]:
    """``A_cl`` ``(n + nc, n + nc, R)`` and the rate output map ``[N, M]`` ``(m, n + nc, R)``.

    ``F, H, M, N`` are stacks ``(R, ., .)``; the results are realization-last.
    """
    R, n, nc = F.shape[0], A.shape[0], F.shape[1]
    Acl = np.empty((n + nc, n + nc, R))
    Acl[:n, :n] = A[:, :, None] + np.einsum("ij,rjk->ikr", B, N)
    Acl[:n, n:] = np.einsum("ij,rjk->ikr", B, M)
    Acl[n:, :n] = np.moveaxis(H, 0, -1)
    Acl[n:, n:] = np.moveaxis(F, 0, -1)
    return Acl, np.moveaxis(np.concatenate([N, M], axis=2), 0, -1)


def _run(
    Acl: np.ndarray,
    Cr: np.ndarray,
    n: int,
    w: np.ndarray,
    *,
    states: bool = True,
    argname: str = "disturbance",
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Simulate ``xi(t+1) = A_cl xi + [I; 0] w`` from zero for a stack of ``R`` loops.

    ``Acl`` is ``(size, size, R)``, ``Cr`` ``(m, size, R)`` and ``w`` ``(steps, n)``
    (shared) or ``(R, steps, n)``. Returns ``(delta_f, delta_r, states)`` as
    ``(R, steps, .)`` views of one time-major buffer, so that every step writes
    contiguous rows. The loops go in chunks of ``_CHUNK``, on ``_WORKERS`` threads. An
    inf or NaN in the outputs (an overflow) is an error naming the first step it is at.
    """
    size, _, R = Acl.shape
    m, steps = Cr.shape[0], w.shape[-2]
    wt = w[:, :, None] if w.ndim == 2 else np.moveaxis(w, 0, -1)  # (steps, n, R or 1)
    out = np.empty((steps, n + m + (size - n if states else 0), R))  # delta_f, delta_r, states
    parts = _chunks(R)

    def run(part: slice) -> int:
        w_part = wt if wt.shape[-1] == 1 else wt[..., part]
        return _run_chunk(Acl[..., part], Cr[..., part], n, w_part, out[..., part])

    # NumPy releases the GIL in einsum: the chunks, and the page faults of the fresh
    # output buffer (as costly as the arithmetic for 10^5 loops), share the cores.
    workers = min(len(parts), _WORKERS)
    if workers == 1:
        first_bad = min(map(run, parts))
    else:
        with ThreadPoolExecutor(workers) as pool:
            first_bad = min(pool.map(run, parts))
    if first_bad < steps:
        raise ParameterError(
            f"{argname}: the simulation blew up at step {first_bad} (values overflowed to "
            f"inf/NaN); reduce the {argname} or the horizon, or check the controller's stability"
        )
    loops = np.moveaxis(out, -1, 0)
    return loops[..., :n], loops[..., n : n + m], loops[..., n + m :] if states else None


@np.errstate(over="ignore", invalid="ignore")
def _run_chunk(A: np.ndarray, Cr: np.ndarray, n: int, w: np.ndarray, out: np.ndarray) -> int:
    """All steps of one chunk of loops into ``out`` ``(steps, rows, chunk)``.

    Each step's rows are ``delta_f``, ``delta_r`` and, if there are more rows, the
    controller states. Returns the first step with an inf or NaN output, or ``steps``.
    """
    steps, rows, _ = out.shape
    m = Cr.shape[0]
    states = rows > n + m
    A, Cr = np.ascontiguousarray(A), np.ascontiguousarray(Cr)  # to stay in the cache
    quiet = ~np.any(w, axis=(1, 2))  # the steps without input
    x, nxt = np.zeros(A.shape[1:]), np.empty(A.shape[1:])
    for t in range(steps):
        out[t, :n] = x[:n]
        np.einsum("mjr,jr->mr", Cr, x, out=out[t, n : n + m])
        if states:
            out[t, n + m :] = x[n:]
        np.einsum("ijr,jr->ir", A, x, out=nxt)
        if not quiet[t]:
            nxt[:n] += w[t]
        x, nxt = nxt, x
    finite = np.all(np.isfinite(out), axis=(1, 2))
    return steps if finite.all() else int(np.argmin(finite))


def _response(p, t, df, dr, w, xc, kind) -> Response:
    return Response(
        t,
        np.ascontiguousarray(df),
        np.ascontiguousarray(dr),
        w,
        np.ascontiguousarray(xc),
        _equilibrium(p.x_eq, p.n, "x_eq"),
        _equilibrium(p.u_eq, p.m, "u_eq"),
        kind,
        p.state_names,
        p.input_names,
        "s" if p.Ts is not None else "steps",
    )


# ---------------------------------------------------------------- public simulations
def open_loop_response(
    plant=None,
    pulse: float = 1.0,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    steps: int = DEFAULT_STEPS,
) -> Response:
    r"""The linear plant's response to a pulse in firing rate (the paper's Fig. ol_sims).

    :math:`\delta_f(t+1) = A\delta_f(t) + B\delta_r(t)` with
    :math:`\delta_r(t) =` ``pulse`` for ``start <= t < start + length`` (every input
    channel), from rest.

    Parameters
    ----------
    plant : DiscretePlant, MuscleModel or (A, B), optional
        Numeric; the paper's muscle by default.
    pulse : float
        Pulse amplitude [spikes/s]; default 1 (a unit pulse).
    start, length, steps : int
        First step of the pulse (default 5), its length (10) and the horizon (50).

    Returns
    -------
    Response

    Raises
    ------
    ParameterError
        Non-positive ``steps``, negative ``start``/``length``, non-finite values.

    Examples
    --------
    >>> res = open_loop_response()
    >>> round(float(res.delta_f[6, 0]), 6)   # one step after the pulse starts: B
    4.641646
    >>> open_loop_response(steps=0)
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: steps: must be an integer >= 1, got 0
    """
    p, A, B = _plant(MuscleModel() if plant is None else plant)
    u = _signal(
        real_number(pulse, "pulse"), "pulse", _positive_int(steps, "steps"), p.m, start, length
    )
    df, _, _ = _run(
        A[:, :, None], np.zeros((0, p.n, 1)), p.n, u @ B.T, states=False, argname="pulse"
    )
    t = np.arange(u.shape[0]) * _ts(p)
    return _response(p, t, df[0], u, np.zeros_like(df[0]), np.zeros((len(t), 0)), "open loop")


def _numeric_realization(R, p: DiscretePlant) -> tuple[np.ndarray, ...]:
    if not isinstance(R, Realization):
        raise SymctlTypeError(f"R: expected a Realization, got {type(R).__name__}")
    if R.shape != (p.m, p.n):
        raise DimensionError(
            f"R: the controller maps the plant's {p.n} states to its {p.m} inputs, so it must "
            f"have shape (outputs, inputs) = {(p.m, p.n)}, got {R.shape}"
        )
    return tuple(a[None] for a in R.numeric())


def simulate_realization(
    plant,
    R: Realization,
    disturbance=1.0,
    *,
    steps: int | None = None,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
) -> Response:
    r"""The plant in closed loop with any realization ``R`` of the controller :math:`\delta_f \to \delta_r`.

    ``R`` is the whole controller, e.g. ``controller_realization(factor(G).subs(values), R2)``
    (:math:`G_3 G_2 G_1`) or :func:`ifp_realization`. The force and rate traces
    depend only on the transfer function; the internal states (``.states``, the
    neurons' firing-rate changes, in ``R``'s state order) depend on the realization.

    Parameters
    ----------
    plant : DiscretePlant, MuscleModel or (A, B)
    R : Realization
        Numeric, of shape (plant inputs, plant states).
    disturbance : float or array
        A number is the amplitude of the default pulse on every state (``start``,
        ``length``, horizon ``steps``, default 50); an array of shape ``(steps, n)``
        (``(steps,)`` for one state) is used as it is.

    Returns
    -------
    Response

    Raises
    ------
    ParameterError
        Unstable closed loop (spectral radius >= 1), non-finite values, bad horizon,
        or a run that overflows.
    DimensionError
        ``R`` or ``disturbance`` of the wrong shape.

    Examples
    --------
    >>> from symctl import Realization
    >>> res = simulate_realization(MuscleModel(), Realization([[0]], [[-0.05]], [[1]], 0))
    >>> res.states.shape
    (50, 1)
    >>> simulate_realization(MuscleModel(), Realization([[0]], [[-1]], [[1]], 0))
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: R: the closed loop is unstable, spectral radius 2.15445 >= 1; ...
    """
    p, A, B = _plant(plant)
    w = _signal(disturbance, "disturbance", steps, p.n, start, length)
    Acl, Cr = _closed_loop_matrices(A, B, *_numeric_realization(R, p))
    _stability(Acl, "R")
    df, dr, xc = _run(Acl, Cr, p.n, w)
    t = np.arange(w.shape[0]) * _ts(p)
    return _response(p, t, df[0], dr[0], w, xc[0], "closed loop")


def closed_loop_response(
    controller,
    plant=None,
    *,
    disturbance=1.0,
    steps: int | None = None,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
) -> Response:
    r"""The closed loop under a pulse disturbance on the force (the paper's Fig. cl_sims).

    Parameters
    ----------
    controller : Gains, DiscreteTF or Realization
        :class:`~symctl.design.lqr.Gains` simulate the optimal controller on the augmented
        state, :math:`\chi(t+1) = (\tilde A + \tilde B K)\chi + [I; 0] w` (the
        states reported are the delay chain :math:`\gamma_1 \dots \delta_r`); with a
        ``plant`` given, the gains' :func:`ifp_realization` is closed around that plant.
        A numeric SISO :class:`DiscreteTF` is realized in controllable canonical form;
        a :class:`Realization` goes to :func:`simulate_realization`.
    plant : DiscretePlant, MuscleModel or (A, B), optional
        Required unless ``controller`` is ``Gains``.
    disturbance, steps, start, length
        As in :func:`simulate_realization` (default: a unit pulse, 1 N per step, on
        steps 5..14 of 50).

    Returns
    -------
    Response

    Examples
    --------
    >>> from symctl import MuscleModel, augment, lqr_gains, controller_tf
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> a = closed_loop_response(gains)
    >>> b = closed_loop_response(controller_tf(gains), MuscleModel())
    >>> bool(np.allclose(a.delta_r, b.delta_r, rtol=0, atol=1e-12))
    True
    >>> closed_loop_response(gains, disturbance=[1.0, 2.0], steps=3)
    Traceback (most recent call last):
    ...
    symctl.errors.DimensionError: disturbance: has 2 samples but steps = 3
    """
    if isinstance(controller, Gains):
        if plant is not None:
            return simulate_realization(
                plant, ifp_realization(controller), disturbance,
                steps=steps, start=start, length=length,
            )  # fmt: skip
        s = controller.system
        p, n, m = s.plant, s.n, s.m
        Acl = numeric_matrix(s.A, "controller") + numeric_matrix(s.B, "controller") @ controller.K
        Cr = np.zeros((m, Acl.shape[0]))
        if s.T:
            Cr[:, -m:] = np.eye(m)
        else:
            Cr[:] = controller.K
        w = _signal(disturbance, "disturbance", steps, n, start, length)
        _stability(Acl[:, :, None], "controller")
        df, dr, xc = _run(Acl[:, :, None], Cr[:, :, None], n, w)
        t = np.arange(w.shape[0]) * _ts(p)
        return _response(p, t, df[0], dr[0], w, xc[0], "closed loop")
    if plant is None:
        raise ParameterError(
            "plant: needed unless the controller is Gains (which carry their plant)"
        )
    if isinstance(controller, Realization):
        R = controller
    elif isinstance(controller, DiscreteTF):
        R = controllable_canonical(controller)
    else:
        raise SymctlTypeError(
            "controller: expected Gains, a DiscreteTF or a Realization, "
            f"got {type(controller).__name__}"
        )
    return simulate_realization(plant, R, disturbance, steps=steps, start=start, length=length)


# ---------------------------------------------------------------- batch
def simulate_batch(
    plant,
    F,
    H,
    M,
    N,
    disturbance=1.0,
    *,
    steps: int | None = None,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    states: bool = False,
    check_stability: bool = True,
) -> BatchResponse:
    r"""Simulate the plant in closed loop with ``R`` realizations at once (vectorized in NumPy).

    Parameters
    ----------
    plant : DiscretePlant, MuscleModel or (A, B)
    F, H, M, N : arrays of shapes (R, nc, nc), (R, nc, n), (R, m, nc), (R, m, n)
        E.g. ``Realization.lambdify(symbols)(*values)`` with arrays of values.
    disturbance : float or array
        A pulse amplitude (as in :func:`simulate_realization`), an array ``(steps, n)``
        shared by every loop, or ``(R, steps, n)``.
    states : bool
        Also return the controller states ``(R, steps, nc)`` (memory: ``8 R steps nc`` bytes).
    check_stability : bool
        Refuse any unstable loop first (exact eigenvalues up to 2000 loops, the
        vectorized Schur-Cohn test on the characteristic polynomial above).

    Returns
    -------
    BatchResponse
        ``delta_f`` ``(R, steps, n)`` and ``delta_r`` ``(R, steps, m)``.

    Raises
    ------
    DimensionError, ParameterError, SymctlTypeError
        Also a run whose outputs overflow to inf or NaN (a :class:`ParameterError`).

    Notes
    -----
    Batches of more than 8192 loops run in chunks, on every core (threads: NumPy
    releases the GIL in its products).

    Examples
    --------
    >>> F = np.full((3, 1, 1), 0.0); H = np.array([-0.01, -0.03, -0.05]).reshape(3, 1, 1)
    >>> out = simulate_batch(MuscleModel(), F, H, np.ones((3, 1, 1)), np.zeros((3, 1, 1)))
    >>> out.delta_f.shape, out.delta_r.shape
    ((3, 50, 1), (3, 50, 1))
    >>> bool(np.all(np.diff(out.delta_r.min(axis=(1, 2))) < 0))   # stronger gain, larger answer
    True
    """
    p, A, B = _plant(plant)
    mats = {k: _float_array(v, k) for k, v in zip("FHMN", (F, H, M, N), strict=True)}
    if any(v.ndim != 3 for v in mats.values()):
        shapes = {k: v.shape for k, v in mats.items()}
        raise DimensionError(f"F, H, M, N: expected stacks of matrices (3 dims), got {shapes}")
    R, nc = mats["F"].shape[:2]
    want = {"F": (R, nc, nc), "H": (R, nc, p.n), "M": (R, p.m, nc), "N": (R, p.m, p.n)}
    for k, shape in want.items():
        if mats[k].shape != shape:
            raise DimensionError(f"{k}: expected shape {shape}, got {mats[k].shape}")
    if R == 0:
        raise DimensionError("F: no realizations (R = 0)")
    if not isinstance(disturbance, numbers.Real):
        disturbance = _float_array(disturbance, "disturbance")
    if np.ndim(disturbance) < 3:
        w = _signal(disturbance, "disturbance", steps, p.n, start, length)
    else:
        w = disturbance
        if w.ndim != 3 or w.shape[0] != R or w.shape[2] != p.n or w.shape[1] == 0:
            raise DimensionError(
                f"disturbance: expected shape (steps, {p.n}) or ({R}, steps, {p.n}), got {w.shape}"
            )
        if steps is not None and _positive_int(steps, "steps") != w.shape[1]:
            raise DimensionError(f"disturbance: has {w.shape[1]} samples but steps = {steps}")
    Acl, Cr = _closed_loop_matrices(A, B, *mats.values())
    if check_stability:
        _stability(Acl, "F, H, M, N")
    df, dr, xc = _run(Acl, Cr, p.n, w, states=states)
    t = np.arange(w.shape[-2]) * _ts(p)
    return BatchResponse(t, df, dr, xc, bool(check_stability))


# ---------------------------------------------------------------- nonlinear muscle
@dataclass(frozen=True, eq=False)
class NonlinearCheck:
    r"""The linear controller around the nonlinear muscle, against the linear prediction.

    Attributes
    ----------
    amplitudes : (k,) array
        Disturbance pulse amplitudes [N per step].
    t : (steps,) array
        Time [s].
    f_linear, f_nonlinear : (k, steps) arrays
        Absolute force [N] of the linear model and of the nonlinear ODE.
    r_nonlinear : (k, steps) array
        Absolute motor-neuron rate [spikes/s] driving the nonlinear muscle.
    max_deviation : (k,) array
        :math:`\max_t |f_\text{nonlinear} - f_\text{linear}|` [N].
    relative_deviation : (k,) array
        ``max_deviation`` over :math:`\max_t |\delta_f^\text{linear}|`.
    """

    amplitudes: np.ndarray
    t: np.ndarray
    f_linear: np.ndarray
    f_nonlinear: np.ndarray
    r_nonlinear: np.ndarray
    max_deviation: np.ndarray
    relative_deviation: np.ndarray

    def table(self) -> str:
        """A plain-text table: amplitude, peak linear force change, max and relative deviation."""
        peak = np.max(np.abs(self.f_linear - self.f_linear[:, :1]), axis=1)  # f(0) = f_bar
        lines = [
            " amplitude [N] | peak |δf| linear [N] | max |f_nl - f_lin| [N] | relative",
            "-" * 78,
        ]
        for a, pk, d, rel in zip(
            self.amplitudes, peak, self.max_deviation, self.relative_deviation, strict=True
        ):
            lines.append(f" {a:13.4g} | {pk:20.4g} | {d:22.4g} | {rel:8.2e}")
        return "\n".join(lines)

    def plot(self):
        """Force traces (nonlinear solid, linear dashed) and the deviation against amplitude."""
        from matplotlib.figure import Figure

        fig = Figure(figsize=(11, 4.2), layout="constrained")
        ax1, ax2 = fig.subplots(1, 2, width_ratios=[1.6, 1])
        colors = [f"C{i % 10}" for i in range(len(self.amplitudes))]
        for a, lin, nl, c in zip(
            self.amplitudes, self.f_linear, self.f_nonlinear, colors, strict=True
        ):
            ax1.plot(self.t, nl, color=c, lw=1.6, label=f"w = {a:g} N per step")
            ax1.plot(self.t, lin, color=c, lw=1.2, ls="--")
        ax1.plot([], [], color="gray", lw=1.6, label="nonlinear muscle (solid)")
        ax1.plot([], [], color="gray", lw=1.2, ls="--", label="linear model (dashed)")
        ax1.set_xlabel("time [s]")
        ax1.set_ylabel("force f [N]")
        ax1.set_title("Linear controller around the nonlinear muscle")
        ax1.legend(fontsize="small", loc="best")
        ax1.grid(alpha=0.3)
        ax2.loglog(self.amplitudes, self.max_deviation, "o-", label="max |f_nl - f_lin| [N]")
        ax2.loglog(self.amplitudes, self.relative_deviation, "s--", label="relative to peak |δf|")
        ax2.set_xlabel("disturbance pulse amplitude [N per step]")
        ax2.set_ylabel("deviation [N] / relative [1]")
        ax2.set_title("Departure from the linear prediction")
        ax2.legend(fontsize="small")
        ax2.grid(alpha=0.3, which="both")
        return fig


def nonlinear_check(
    model: MuscleModel | None = None,
    controller=None,
    amplitudes=(0.1, 0.3, 1.0, 3.0, 10.0),
    *,
    steps: int = DEFAULT_STEPS,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    rtol: float = 1e-10,
) -> NonlinearCheck:
    r"""Close the linear controller around the nonlinear muscle ODE and compare with the linear loop.

    At each sample the controller reads :math:`\delta_f = f - \bar f`, its output
    :math:`r = \bar r + \delta_r` is held constant over the step, and
    :math:`\dot f = f_\text{max}/(\tau(1+e^{-r})) - f/\tau` (:meth:`MuscleModel.rhs`)
    is integrated over :math:`T_s` with :func:`scipy.integrate.solve_ivp` (DOP853,
    ``rtol``, all amplitudes as one vector ODE); the disturbance is added to the
    force at the sample, as in the linear model.

    Parameters
    ----------
    model : MuscleModel, optional
        The paper's by default.
    controller : Gains or Realization, optional
        Default: the optimal delayed controller for ``Q = R = 1``, one step of delay
        each way (as the IFP realization).
    amplitudes : sequence of float
        Disturbance pulse amplitudes [N per step]; default 0.1 .. 10.

    Returns
    -------
    NonlinearCheck

    Examples
    --------
    >>> chk = nonlinear_check(amplitudes=[0.01, 1.0], steps=30)
    >>> bool(chk.relative_deviation[0] < 1e-3 < chk.relative_deviation[1])
    True
    """
    from symctl.design.augment import augment
    from symctl.design.lqr import lqr_gains

    model = MuscleModel() if model is None else model
    if not isinstance(model, MuscleModel):
        raise SymctlTypeError(f"model: expected a MuscleModel, got {type(model).__name__}")
    if controller is None:
        controller = lqr_gains(augment(model, 1, 1))
    R = ifp_realization(controller) if isinstance(controller, Gains) else controller
    amps = _float_array(amplitudes, "amplitudes").ravel()
    if amps.size == 0:
        raise DimensionError("amplitudes: give at least one amplitude")
    linear = simulate_realization(model, R, 1.0, steps=steps, start=start, length=length)
    F, H, M, N = (a[0] for a in _numeric_realization(R, model.plant()))
    w = linear.w[:, 0]
    f_bar, r_bar, Ts = model.f_bar, model.r_bar, model.Ts
    f = np.full(amps.size, f_bar)
    xc = np.zeros((amps.size, F.shape[0]))
    f_nl = np.empty((amps.size, linear.t.size))
    r_nl = np.empty_like(f_nl)
    for k in range(linear.t.size):
        df = f - f_bar
        r = r_bar + (xc @ M.T)[:, 0] + N[0, 0] * df
        f_nl[:, k], r_nl[:, k] = f, r
        sol = scipy.integrate.solve_ivp(
            lambda _t, y, r=r: model.rhs(y, r), (0.0, Ts), f,
            method="DOP853", rtol=rtol, atol=rtol * max(1.0, abs(f_bar)),
        )  # fmt: skip
        if not sol.success or not np.all(np.isfinite(sol.y[:, -1])):
            raise ParameterError(f"amplitudes: the nonlinear ODE failed at step {k}: {sol.message}")
        f = sol.y[:, -1] + amps * w[k]
        xc = xc @ F.T + df[:, None] @ H.T
    f_lin = f_bar + amps[:, None] * linear.delta_f[:, 0]
    dev = np.max(np.abs(f_nl - f_lin), axis=1)
    peak = np.abs(amps) * np.max(np.abs(linear.delta_f))
    rel = np.divide(dev, peak, out=np.zeros_like(dev), where=peak > 0)
    return NonlinearCheck(amps, linear.t, f_lin, f_nl, r_nl, dev, rel)
