r"""Open- and closed-loop simulation of the plant with any realization of the controller.

The paper's section "Simulations": the linear plant driven by a pulse in firing rate
(Fig. 3); the loop closed with the optimal delayed controller and hit by a pulse
disturbance on the force (Fig. 5), or with any realization of :math:`G = G_3 G_2 G_1`
(Figs. 9-11). Every simulation here, in :mod:`~symctl.neural.batch` and in
:mod:`~symctl.neural.firing` runs through one time loop, ``_run``. The disturbance
:math:`w` enters the state update (zero initial state),

.. math::
    \delta_f(t+1) = A\,\delta_f(t) + B\,\delta_r(t) + w(t),\qquad
    x_c(t+1) = F x_c(t) + H \delta_f(t),\qquad
    \delta_r(t) = M x_c(t) + N \delta_f(t),

so :math:`\xi = [\delta_f; x_c]` follows :math:`\xi(t+1) = A_{cl}\,\xi(t) + [I; 0]\,w(t)`,
:math:`A_{cl} = \begin{bmatrix} A + BN & BM \\ H & F \end{bmatrix}`; the optimal
controller runs on the augmented state, :math:`\chi(t+1) = (\tilde A + \tilde B K)\chi(t)
+ [I; 0]\,w(t)`. Defaults (the paper gives none): a pulse of amplitude 1 on steps 5..14
of 50 (0.5 s at :math:`T_s` = 10 ms). Time is ``t = k dt`` in seconds; absolute force
and rate add the operating point :math:`(\bar f, \bar r)` back.
"""

from __future__ import annotations

import dataclasses
import numbers
from dataclasses import dataclass

import numpy as np

from symctl._util.deprecate import rng_argument
from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.validate import (
    MAX_COUNT,
    MAX_STATES,
    MAX_STEPS,
    bounded_int,
    float_array,
    nonneg_int,
    numeric_matrix,
    positive_int,
    read_only,
    real_number,
)
from symctl.design.augment import as_plant, chain_names, same_dt
from symctl.design.lqr import Gains
from symctl.design.plant import DiscretePlant, MuscleModel
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.neural.noise import Noise, _as_noise, _noisy_loop, _Parts, _sensor_inputs
from symctl.neural.timeloop import _run_chunk
from symctl.realization.realization import Realization, controllable_canonical
from symctl.realization.realizers import ifp_realization

__all__ = [
    "DEFAULT_DRAWS",
    "DEFAULT_LENGTH",
    "DEFAULT_START",
    "DEFAULT_STEPS",
    "Response",
    "closed_loop_response",
    "open_loop_response",
    "pulse",
    "simulate_realization",
]

DEFAULT_STEPS = 50
"""Default horizon in samples (0.5 s at the paper's Ts = 10 ms)."""
DEFAULT_START = 5
"""Default first step of the pulse."""
DEFAULT_LENGTH = 10
"""Default pulse length in steps."""
DEFAULT_DRAWS = 100
"""Default number of noisy loops whose mean and spread a noisy simulation returns."""


def pulse(
    steps: int = DEFAULT_STEPS,
    amplitude: float = 1.0,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    size: int = 1,
) -> np.ndarray:
    r"""A pulse signal of shape ``(steps, size)``: ``amplitude`` for ``start <= k < start + length``.

    Parameters
    ----------
    steps : int
        The horizon, from 1 to ``MAX_STEPS`` (10**6; default 50).
    amplitude : float
        The value during the pulse (default 1).
    start, length : int
        First step of the pulse (default 5) and its length (default 10), >= 0;
        a pulse running past the horizon is cut there.
    size : int
        The number of channels (columns), >= 1.

    Returns
    -------
    (steps, size) array

    Raises
    ------
    ParameterError
        A non-integer or out-of-range ``steps``, ``start``, ``length`` or ``size``,
        or a non-finite ``amplitude``.
    SymctlTypeError
        ``amplitude`` is not a real number.

    Examples
    --------
    >>> from symctl import pulse
    >>> pulse(6, 2.0, start=1, length=3).ravel()
    array([0., 2., 2., 2., 0., 0.])
    """
    steps = bounded_int(steps, "steps", 1, MAX_STEPS)
    amp = real_number(amplitude, "amplitude")
    start = min(nonneg_int(start, "start"), steps)  # huge values: no index overflow
    length = min(nonneg_int(length, "length"), steps)
    out = np.zeros((steps, bounded_int(size, "size", 1, MAX_STATES)))
    out[start : start + length] = amp
    return out


def _signal(value, argname: str, steps: int | None, size: int, start: int, length: int):
    """A ``(steps, size)`` signal from a pulse amplitude (a number) or an array."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return pulse(DEFAULT_STEPS if steps is None else steps, value, start, length, size)
    arr = float_array(value, argname)
    if arr.ndim == 1 and size == 1:
        arr = arr[:, None]
    if arr.ndim != 2 or arr.shape[1] != size or arr.shape[0] == 0:
        raise DimensionError(
            f"{argname}: expected shape (steps, {size}) with steps >= 1, got {arr.shape}"
        )
    if steps is not None and positive_int(steps, "steps") != arr.shape[0]:
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
    return 1.0 if p.dt is None else float(numeric_matrix(p.dt, "dt")[0, 0])


_SPREADS = ("delta_f_sd", "delta_r_sd", "states_sd")


@dataclass(frozen=True, eq=False)
class Response(ArrayValue, DictMixin):
    r"""Traces of one simulation (open or closed loop), sampled at ``t = k dt``, read-only.

    Attributes
    ----------
    t : (steps,) array
        Time in seconds (in steps when the plant has no ``dt``).
    delta_f, f : (steps, n) arrays
        Plant state change :math:`\delta_f` and absolute :math:`f = \bar f + \delta_f` [N].
    delta_r, r : (steps, m) arrays
        Motor-neuron rate change :math:`\delta_r` and absolute :math:`r = \bar r + \delta_r`
        [spikes/s].
    w : (steps, n) array
        Disturbance on the state (zeros in open loop).
    states : (steps, nc) array
        The controller's states (the neurons' firing-rate changes; the optimal
        controller's delay chain); ``nc = 0`` in open loop.
    f_bar, r_bar : arrays
        The operating point (zeros when the plant records none).
    kind : str
        ``"open loop"`` or ``"closed loop"``.
    state_names, input_names : tuple of str
        The plant's names of its states and inputs.
    time_unit : str
        ``"s"``, or ``"steps"`` when the plant has no sampling time.
    controller_state_names : tuple of str
        Of ``states``: the delay chain (:func:`~symctl.design.augment.chain_names`) or ``x_1, ...``.
    delta_f_sd, delta_r_sd, states_sd : arrays or None
        With noise: the standard deviation over the ``draws`` noisy loops of each trace
        (the traces are then their mean; the rate is the command, before the motor noise).
    draws : int
        The noisy loops simulated (0 without noise).

    Examples
    --------
    >>> from symctl import open_loop_response
    >>> res = open_loop_response(steps=8, start=1, length=2)
    >>> res.kind, res.t[:3], res.delta_r[:4, 0]
    ('open loop', array([0.  , 0.01, 0.02]), array([0., 1., 1., 0.]))
    >>> res.delta_f.flags.writeable
    False
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
    controller_state_names: tuple[str, ...] = ()
    delta_f_sd: np.ndarray | None = None
    delta_r_sd: np.ndarray | None = None
    states_sd: np.ndarray | None = None
    draws: int = 0

    def __post_init__(self) -> None:  # the arrays are read-only copies
        for name in ("t", "delta_f", "delta_r", "w", "states", "f_bar", "r_bar", *_SPREADS):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, read_only(getattr(self, name), float))

    @property
    def f(self) -> np.ndarray:
        """Absolute force (state), :math:`\\bar f + \\delta_f`."""
        return self.delta_f + self.f_bar

    @property
    def r(self) -> np.ndarray:
        """Absolute motor-neuron rate (input), :math:`\\bar r + \\delta_r`."""
        return self.delta_r + self.r_bar

    def plot(self, states: bool | None = None):
        """Force and motor-neuron rate against time, absolute values on the right axes (``states``:
        a panel of the controller's states, by default when there are any); a Figure by
        :func:`symctl.plotting.response.response_plot`.

        Examples
        --------
        >>> from symctl import MuscleModel, augment, closed_loop_response, lqr_gains
        >>> fig = closed_loop_response(lqr_gains(augment(MuscleModel(), 1, 1))).plot()
        >>> fig.axes[-1].get_xlabel()
        'time [s]'
        """
        from symctl.plotting.response import response_plot

        return response_plot(self, states)


UNIT_CIRCLE = 1 - 1e-9  # |eigenvalue| >= this is unstable (a marginal mode rounds inside)


# Stacks of loops are stored realization-last, ``(rows, cols, R)``: every vectorized
# operation below then runs over contiguous memory, one realization per element.
def _stability(Acl: np.ndarray, argname: str, n: int | None = None) -> None:
    """Refuse a spectral radius >= ``UNIT_CIRCLE`` (a marginal mode, e.g. epsilon = 1, rounds
    inside); ``n``, the plant's states, lets the message name a hidden mode of the controller."""
    count = Acl.shape[-1]
    eigs = np.linalg.eigvals(np.moveaxis(Acl, -1, 0)) if Acl.shape[0] else np.zeros((count, 1))
    _refuse_unstable(Acl, np.flatnonzero(np.max(np.abs(eigs), axis=-1) >= UNIT_CIRCLE), argname, n)


def _refuse_unstable(Acl: np.ndarray, bad: np.ndarray, argname: str, n: int | None = None) -> None:
    """Raise for the unstable realizations ``bad`` (indices into the stack), if any."""
    if bad.size:
        count = Acl.shape[-1]
        i = int(bad[0])
        eigs = np.linalg.eigvals(Acl[:, :, i])
        lam = complex(eigs[np.argmax(np.abs(eigs))])
        rho = abs(lam)
        where = f" (realization {i} of {count}; {bad.size} unstable)" if count > 1 else ""
        raise ParameterError(
            f"{argname}: the closed loop is unstable, spectral radius {rho:.6g} >= 1{where}; "
            f"unstable eigenvalue {_eig_text(lam)}; {_unstable_cause(Acl[:, :, i], lam, n, argname)}"
        )


def _eig_text(lam: complex) -> str:
    if abs(lam.imag) <= 1e-12 * max(1.0, abs(lam)):
        return f"{lam.real:.6g}"
    return f"{lam.real:.6g}{lam.imag:+.6g}j"


def _unstable_cause(Acl: np.ndarray, lam: complex, n: int | None, argname: str) -> str:
    """Why: a hidden mode of the controller's own states, or a controller that does not stabilize."""
    if n is not None and _is_hidden(Acl, lam, n):
        return (
            f"it is a mode of {argname}'s own states (its F) that the loop cannot move, "
            "hidden from the transfer function (a pole cancelled by a zero, e.g. "
            "|epsilon| >= 1 in G3 G2 G1); realize the controller with every mode "
            "inside the unit circle"
        )
    return "the controller does not stabilize this plant"


def _is_hidden(Acl: np.ndarray, lam: complex, n: int) -> bool:
    """Whether the loop eigenvalue ``lam`` is one of the controller's own ``F`` (rel. 1e-8)."""
    if Acl.shape[0] <= n:
        return False
    own = np.linalg.eigvals(Acl[n:, n:])
    return bool(np.min(np.abs(own - lam)) <= 1e-8 * max(1.0, abs(lam)))


def _closed_loop_matrices(A, B, F, H, M, N) -> tuple[np.ndarray, np.ndarray]:
    """``A_cl`` ``(n + nc, n + nc, R)`` and the rate map ``[N, M]`` ``(m, n + nc, R)``."""
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
    schedule=None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Simulate ``xi(t+1) = A_cl xi + [I; 0] w`` from zero for a stack of ``R`` loops.

    ``Acl`` ``(size, size, R)``, ``Cr`` ``(m, size, R)``, ``w`` ``(steps, n)`` or ``(R, steps, n)``;
    returns ``(delta_f, delta_r, states)`` as ``(R, steps, .)`` views of one time-major buffer.
    ``schedule(run, R)`` runs slices of the loops (the batch's chunks) and returns the smallest result.
    """
    size, m = Acl.shape[0], Cr.shape[0]
    rows = range(n + m + (size - n if states else 0))  # delta_f, delta_r, states
    out = np.empty((w.shape[-2], len(rows), Acl.shape[-1]))
    _steps(Acl, Cr, n, w, out, rows, argname=argname, schedule=schedule)
    loops = np.moveaxis(out, -1, 0)
    return loops[..., :n], loops[..., n : n + m], loops[..., n + m :] if states else None


def _steps(Acl, Cr, n, w, out, rows, peaks=None, peak_rows=(), *, argname, schedule=None):
    """Fill ``out`` ``(steps, len(rows), R)`` with the signals ``rows`` (``delta_f``, ``delta_r``,
    states) and ``peaks`` with the largest ``|signal|`` of ``peak_rows``; overflow raises."""
    steps, R = out.shape[0], Acl.shape[-1]
    wt = w[:, :, None] if w.ndim == 2 else np.moveaxis(w, 0, -1)  # (steps, n, R or 1)

    def loops(part: slice) -> tuple:
        return Acl[..., part], Cr[..., part], n, wt if wt.shape[-1] == 1 else wt[..., part]

    def run(part: slice) -> int:
        peak_part = None if peaks is None else peaks[:, part]
        return _run_chunk(*loops(part), out[..., part], rows, peak_part, peak_rows)

    first_bad = run(slice(None)) if schedule is None else schedule(run, R)
    if first_bad == steps and peaks is not None and not np.all(np.isfinite(peaks)):
        i = int(np.flatnonzero(~np.all(np.isfinite(peaks), axis=0))[0])  # its traces tell when
        trace = np.empty((steps, len(peak_rows), 1))
        first_bad = _run_chunk(*loops(slice(i, i + 1)), trace, peak_rows)
    if first_bad < steps:
        raise ParameterError(
            f"{argname}: the simulation blew up at step {first_bad} (values overflowed to "
            f"inf/NaN); reduce the {argname} or the horizon, or check the controller's stability"
        )


def _response(p, df, dr, w, xc, kind, names=()) -> Response:
    return Response(
        np.arange(df.shape[0]) * _ts(p),
        df,
        dr,
        w,
        xc,
        _equilibrium(p.x_eq, p.n, "x_eq"),
        _equilibrium(p.u_eq, p.m, "u_eq"),
        kind,
        p.state_names,
        p.input_names,
        "s" if p.dt is not None else "steps",
        tuple(names) or tuple(f"x_{i + 1}" for i in range(xc.shape[1])),
    )


def open_loop_response(
    plant=None,
    pulse: float = 1.0,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    steps: int = DEFAULT_STEPS,
) -> Response:
    r"""The linear plant's response to a pulse in firing rate (the paper's Fig. 3).

    :math:`\delta_f(t+1) = A\delta_f(t) + B\delta_r(t)` with
    :math:`\delta_r(t) =` ``pulse`` for ``start <= t < start + length`` (every input
    channel), from rest.

    Parameters
    ----------
    plant : DiscretePlant, MuscleModel, (A, B) or python-control system (as_plant), optional
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
    >>> from symctl import open_loop_response
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
        real_number(pulse, "pulse"), "pulse", positive_int(steps, "steps"), p.m, start, length
    )
    df, _, _ = _run(
        A[:, :, None], np.zeros((0, p.n, 1)), p.n, u @ B.T, states=False, argname="pulse"
    )
    return _response(p, df[0], u, np.zeros_like(df[0]), np.zeros((len(u), 0)), "open loop")


def _numeric_realization(R, p: DiscretePlant, argname: str = "R", C=None) -> tuple[np.ndarray, ...]:
    """``R``'s matrices (stacks of one); fed by the outputs ``y = C x`` when ``C`` is given."""
    if not isinstance(R, Realization):
        raise SymctlTypeError(f"{argname}: expected a Realization, got {type(R).__name__}")
    same_dt(p, R.dt, argname)
    q, what = (p.n, "states") if C is None else (C.shape[0], "outputs")
    if R.shape != (p.m, q):
        raise DimensionError(
            f"{argname}: the controller maps the plant's {q} {what} to its {p.m} inputs, so it "
            f"must have shape (outputs, inputs) = {(p.m, q)}, got {R.shape}"
        )
    F, H, M, N = R.numeric()
    if C is not None:
        H, N = H @ C, N @ C
    return tuple(a[None] for a in (F, H, M, N))


def _as_realization(controller) -> Realization:
    """The controller to close around a plant: :func:`ifp_realization` of ``Gains``, else itself."""
    return ifp_realization(controller) if isinstance(controller, Gains) else controller


@rng_argument()
def simulate_realization(
    plant,
    R: Realization,
    disturbance=1.0,
    *,
    steps: int | None = None,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    noise: Noise | None = None,
    draws: int = DEFAULT_DRAWS,
    rng=0,
) -> Response:
    r"""The plant in closed loop with any realization ``R`` of the controller :math:`\delta_f \to \delta_r`.

    ``R`` is the whole controller (e.g. ``controller_realization(factor(G).subs(values), R2)``
    or :func:`ifp_realization`); force and rate depend only on its transfer function, the
    internal states (``.states``, in ``R``'s state order) on the realization.

    Parameters
    ----------
    plant : DiscretePlant, MuscleModel, (A, B) or python-control system (as_plant)
    R : Realization
        Numeric, of shape (plant inputs, plant states).
    disturbance : float or array
        A number is the amplitude of the default pulse on every state (``start``,
        ``length``, horizon ``steps``, default 50); an array of shape ``(steps, n)``
        (``(steps,)`` for one state) is used as it is.
    noise : Noise, optional
        Process, motor and sensor noise drawn per step (:mod:`~symctl.neural.noise`):
        the traces are then the mean over ``draws`` noisy loops, their standard
        deviation in ``delta_f_sd``, ``delta_r_sd`` and ``states_sd``. A Noise
        that is all zero is no noise (the result is the noise-free one, exactly).
    draws : int
        Noisy loops simulated with ``noise``, 1 to ``MAX_COUNT`` (default 100).
    rng : int, numpy Generator or None, default 0
        Seeds the noise.

    Returns
    -------
    Response

    Raises
    ------
    ParameterError
        Unstable closed loop over every state (the message names the eigenvalue, and a
        hidden mode of ``R``'s own ``F``; :func:`~symctl.neural.stability.loop_stability`
        decides without raising), non-finite values, bad horizon, an overflow, or an
        ``R.dt`` other than the plant's.
    DimensionError
        ``R``, ``disturbance`` or a part of ``noise`` of the wrong shape.

    Examples
    --------
    >>> from symctl import MuscleModel, Noise, Realization, simulate_realization
    >>> res = simulate_realization(MuscleModel(), Realization([[0]], [[-0.05]], [[1]], 0))
    >>> res.states.shape
    (50, 1)
    >>> noisy = simulate_realization(MuscleModel(), Realization([[0]], [[-0.05]], [[1]], 0),
    ...                              noise=Noise(process=0.01), draws=20, rng=1)
    >>> noisy.draws, noisy.delta_f_sd.shape
    (20, (50, 1))
    >>> simulate_realization(MuscleModel(), Realization([[0]], [[-1]], [[1]], 0))
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: R: the closed loop is unstable, spectral radius 2.15445 >= 1; ...
    """
    p, A, B = _plant(plant)
    w = _signal(disturbance, "disturbance", steps, p.n, start, length)
    Acl, Cr = _realization_loop(p, A, B, R)
    return _simulate(p, Acl, Cr, w, noise, draws, rng)


def _realization_loop(p, A, B, R, argname: str = "R", C=None) -> tuple[np.ndarray, np.ndarray]:
    """``(A_cl, C_r)`` (stacks of one) of the plant around the realization ``R`` (fed by ``C x``
    when ``C`` is given), checked stable."""
    Acl, Cr = _closed_loop_matrices(A, B, *_numeric_realization(R, p, argname, C))
    _stability(Acl, argname, p.n)
    return Acl, Cr


def _simulate(p, Acl, Cr, w, noise, draws, gen, names=(), sensor=None) -> Response:
    """The loop's :class:`Response`, noise-free or the mean and spread of ``draws`` noisy runs."""
    noise = _as_noise(noise)
    if noise is None:
        df, dr, xc = _run(Acl, Cr, p.n, w)
        return _response(p, df[0], dr[0], w, xc[0], "closed loop", names)
    traces = _noisy_traces(p, Acl, Cr, w, noise, draws, gen, sensor)
    return _spread_response(p, w, *traces[:3], names)


def _spread_response(p, w, df, dr, xc, names=()) -> Response:
    """The :class:`Response` of noisy runs ``(draws, steps, .)``: their mean and spread."""
    res = _response(p, df.mean(0), dr.mean(0), w, xc.mean(0), "closed loop", names)
    spread = {"delta_f_sd": df.std(0), "delta_r_sd": dr.std(0), "states_sd": xc.std(0)}
    return dataclasses.replace(res, **spread, draws=df.shape[0])


def _noisy_traces(p, Acl, Cr, w, noise: Noise, draws, gen, sensor=None) -> tuple[np.ndarray, ...]:
    """``delta_f``, ``delta_r``, states and the controller's measurement ``y`` of ``draws`` noisy
    runs of the loop (stacks of one), each ``(draws, steps, .)``; ``sensor`` is the ``(E_v, D_v,
    C)`` of a controller fed by outputs (:func:`_loop`)."""
    draws = bounded_int(draws, "draws", 1, MAX_COUNT)
    _, A, B = _plant(p)
    Acl, Cr, n = Acl[:, :, 0], Cr[:, :, 0], p.n
    Ev, Dv, C = (*_sensor_inputs(Acl, Cr, A, n), None) if sensor is None else sensor
    q = n if C is None else C.shape[0]
    out = np.empty((w.shape[0], Acl.shape[0] + Cr.shape[0] + q, draws))

    def visit(t, x, u, y):
        out[t] = np.concatenate([x[:n], u, x[n:], y])

    parts = _Parts.of(noise, n, p.m, q)
    _noisy_loop(Acl, Cr, B, n, w, parts, gen, draws, visit, Ev, Dv, C)
    loops, m = np.moveaxis(out, -1, 0), Cr.shape[0]
    return loops[..., :n], loops[..., n : n + m], loops[..., n + m : -q], loops[..., -q:]


@rng_argument()
def closed_loop_response(
    controller,
    plant=None,
    *,
    disturbance=1.0,
    steps: int | None = None,
    start: int = DEFAULT_START,
    length: int = DEFAULT_LENGTH,
    noise: Noise | None = None,
    draws: int = DEFAULT_DRAWS,
    rng=0,
    outputs=None,
) -> Response:
    r"""The closed loop under a pulse disturbance on the force (the paper's Fig. 5).

    Parameters
    ----------
    controller : Gains, DiscreteTF or Realization
        Gains simulate the optimal controller on the augmented state (with a ``plant``:
        their :func:`ifp_realization` around it); a numeric SISO DiscreteTF is realized in
        controllable canonical form; a Realization goes to :func:`simulate_realization`.
    plant : DiscretePlant, MuscleModel, (A, B) or python-control system (as_plant), optional
        Required unless ``controller`` is ``Gains``.
    disturbance, steps, start, length
        As in :func:`simulate_realization` (default: a unit pulse, 1 N per step, on
        steps 5..14 of 50).
    noise, draws, rng
        As in :func:`simulate_realization`: the mean and standard deviation of ``draws``
        loops under :class:`~symctl.neural.noise.Noise` (none by default).
    outputs : matrix-like, optional
        ``p x n``: the controller (a DiscreteTF or Realization, ``m x p``) reads the outputs
        :math:`y = C x` (plus the sensor noise, ``p x p``) instead of the state, as the LQG
        compensator (:func:`~symctl.neural.compensator.lqg_realization`) does.

    Returns
    -------
    Response

    Raises
    ------
    ParameterError
        No ``plant`` for a controller other than ``Gains``, or a plant whose ``dt`` is
        not the controller's ``dt`` (named ``plant`` for ``Gains``, else ``controller``).

    Examples
    --------
    >>> import numpy as np
    >>> from symctl import MuscleModel, Noise, augment, closed_loop_response, controller_tf, lqr_gains
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> a = closed_loop_response(gains)
    >>> b = closed_loop_response(controller_tf(gains), MuscleModel())
    >>> bool(np.allclose(a.delta_r, b.delta_r, rtol=0, atol=1e-12))
    True
    >>> c = closed_loop_response(gains, noise=Noise(motor=0.1, sensor=1e-4), draws=500, rng=2)
    >>> error = 4 * c.delta_f_sd / np.sqrt(c.draws)   # the mean is the noise-free loop's
    >>> bool(np.all(abs(c.delta_f - a.delta_f) <= error)), bool(c.delta_f_sd[-1, 0] > 0)
    (True, True)
    >>> closed_loop_response(gains, disturbance=[1.0, 2.0], steps=3)
    Traceback (most recent call last):
    ...
    symctl.errors.DimensionError: disturbance: has 2 samples but steps = 3
    """
    p, Acl, Cr, names, sensor = _loop(controller, plant, outputs)
    w = _signal(disturbance, "disturbance", steps, p.n, start, length)
    return _simulate(p, Acl, Cr, w, noise, draws, rng, names, sensor)


def _loop(controller, plant, outputs=None) -> tuple:
    """``(plant, A_cl, C_r, controller state names, sensor)`` of :func:`closed_loop_response`,
    stable; ``sensor`` the ``(E_v, D_v, C)`` of a controller fed by ``outputs`` (else None)."""
    if isinstance(controller, Gains) and plant is None and outputs is None:
        s = controller.system
        return (s.plant, *_gains_loop(controller), chain_names(s.T, s.m), None)
    if plant is None:
        raise ParameterError(
            "plant: needed unless the controller is Gains (which carry their plant)"
        )
    p, A, B = _plant(plant)
    if outputs is not None:
        if isinstance(controller, Gains):
            raise SymctlTypeError(
                "controller: Gains read the state; with outputs, give a Realization"
            )
        C = numeric_matrix(outputs, "outputs")
        if C.ndim != 2 or C.shape[1] != p.n:
            raise DimensionError(f"outputs: expected p x {p.n}, got shape {C.shape}")
        R = _controller_realization(controller, p)
        _, H, _, N = R.numeric()
        return (
            p,
            *_realization_loop(p, A, B, R, "controller", C),
            (),
            (np.vstack([B @ N, H]), N, C),
        )
    if isinstance(controller, Gains):
        same_dt(p, controller.system.plant.dt, "plant", "the gains' plant")
        R = ifp_realization(controller)
    else:
        R = _controller_realization(controller, p)
    return (p, *_realization_loop(p, A, B, R), (), None)


def _gains_loop(gains: Gains) -> tuple[np.ndarray, np.ndarray]:
    """``(A_cl, C_r)`` (stacks of one) of the optimal controller on the augmented state, stable."""
    s = gains.system
    Acl = numeric_matrix(s.A, "controller") + numeric_matrix(s.B, "controller") @ gains.K
    Cr = np.zeros((s.m, Acl.shape[0]))
    if s.T:
        Cr[:, -s.m :] = np.eye(s.m)
    else:
        Cr[:] = gains.K
    _stability(Acl[:, :, None], "controller")
    return Acl[:, :, None], Cr[:, :, None]


def _controller_realization(controller, plant: DiscretePlant) -> Realization:
    """A Realization or a DiscreteTF (controllable canonical form), its ``dt`` the plant's."""
    if isinstance(controller, Realization):
        R = controller
    elif isinstance(controller, DiscreteTF):
        R = controllable_canonical(controller)
    else:
        raise SymctlTypeError(
            "controller: expected Gains, a DiscreteTF or a Realization, "
            f"got {type(controller).__name__}"
        )
    same_dt(plant, R.dt, "controller")
    return R
