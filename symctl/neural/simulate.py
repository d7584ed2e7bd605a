r"""Open- and closed-loop simulation of the plant with any realization of the controller.

The paper's Figs. 3, 5 and 9-11. From rest, the disturbance :math:`w` entering the state,

.. math::
    \delta_f(t+1) = A\,\delta_f(t) + B\,\delta_r(t) + w(t),\qquad
    x_c(t+1) = F x_c(t) + H \delta_f(t),\qquad
    \delta_r(t) = M x_c(t) + N \delta_f(t),

so :math:`\xi = [\delta_f; x_c]` follows :math:`\xi(t+1) = A_{cl}\,\xi(t) + [I; 0]\,w(t)`,
:math:`A_{cl} = \begin{bmatrix} A + BN & BM \\ H & F \end{bmatrix}` (the optimal
controller: :math:`\chi(t+1) = (\tilde A + \tilde B K)\chi(t) + [I; 0]\,w(t)`).
"""

from __future__ import annotations

import dataclasses
import numbers
from dataclasses import dataclass
from types import MappingProxyType

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
from symctl.neural.noise import Noise, _as_noise, _noisy_fill, _parts
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

DEFAULT_STEPS = 50  # horizon in samples (0.5 s at the paper's Ts = 10 ms)
DEFAULT_START = 5  # first step of the pulse
DEFAULT_LENGTH = 10  # pulse length in steps
DEFAULT_DRAWS = 100  # noisy loops whose mean and spread a noisy simulation returns


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
    steps, size : int
        The horizon, 1 to ``MAX_STEPS`` (10**6), and the number of channels, >= 1.
    amplitude : float
    start, length : int
        First step of the pulse and its length, >= 0 (cut at the horizon).

    Returns
    -------
    (steps, size) array

    Raises
    ------
    ParameterError, SymctlTypeError
        An argument out of range; an ``amplitude`` that is not a finite real number.

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


def _signal(value, argname: str, steps, size: int, start: int, length: int, loops=None):
    """A ``(steps, size)`` signal from a pulse amplitude or an array (or ``(loops, steps, size)``)."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return pulse(DEFAULT_STEPS if steps is None else steps, value, start, length, size)
    arr = float_array(value, argname)
    if arr.ndim == 1 and size == 1:
        arr = arr[:, None]
    lead = () if arr.ndim == 2 or loops is None else (loops,)
    if arr.ndim < 2 or arr.shape[:-2] != lead or arr.shape[-1] != size or arr.shape[-2] == 0:
        each = f" or ({loops}, steps, {size})" if loops else ""
        raise DimensionError(
            f"{argname}: expected shape (steps, {size}){each} with steps >= 1, got {arr.shape}"
        )
    if steps is not None and positive_int(steps, "steps") != arr.shape[-2]:
        raise DimensionError(f"{argname}: has {arr.shape[-2]} samples but steps = {steps}")
    return arr


def _freeze(value, arrays=(), mappings=()) -> None:
    """Make ``value``'s fields ``arrays`` and ``mappings`` (of arrays) read-only floats."""
    for name in arrays:
        if getattr(value, name) is not None:
            object.__setattr__(value, name, read_only(getattr(value, name), float))
    for name in mappings:
        if getattr(value, name) is not None:
            items = {k: read_only(v, float) for k, v in getattr(value, name).items()}
            object.__setattr__(value, name, MappingProxyType(items))


def _plant(plant) -> tuple[DiscretePlant, np.ndarray, np.ndarray]:
    p = as_plant(plant)
    A, B = p.numeric()
    return p, A, B


def _ts(p: DiscretePlant) -> float:
    return 1.0 if p.dt is None else float(numeric_matrix(p.dt, "dt")[0, 0])


@dataclass(frozen=True, eq=False)
class Response(ArrayValue, DictMixin):
    r"""Traces of one simulation (open or closed loop), sampled at ``t = k dt``; read-only.

    Attributes
    ----------
    t : (steps,) array
        Time in ``time_unit``: ``"s"``, or ``"steps"`` when the plant has no ``dt``.
    delta_f, f : (steps, n) arrays
        Plant state change and absolute :math:`f = \bar f + \delta_f` [N].
    delta_r, r : (steps, m) arrays
        Motor-neuron rate change and absolute :math:`r = \bar r + \delta_r` [spikes/s].
    w : (steps, n) array
        Disturbance on the state (zeros in open loop).
    states : (steps, nc) array
        The controller's states, named by ``controller_state_names``; ``nc = 0`` in open loop.
    f_bar, r_bar : arrays
        The operating point (zeros when the plant records none).
    kind : str
        ``"open loop"`` or ``"closed loop"``.
    state_names, input_names : tuple of str
    delta_f_sd, delta_r_sd, states_sd : arrays or None
        With noise: each trace's standard deviation over the ``draws`` noisy loops (0 without
        noise); the traces are then their mean, the rate the command before the motor noise.
    draws : int

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

    def __post_init__(self) -> None:
        arrays = ("t", "delta_f", "delta_r", "w", "states", "f_bar", "r_bar")
        _freeze(self, (*arrays, "delta_f_sd", "delta_r_sd", "states_sd"))

    @property
    def f(self) -> np.ndarray:
        """Absolute force (state), :math:`\\bar f + \\delta_f`."""
        return self.delta_f + self.f_bar

    @property
    def r(self) -> np.ndarray:
        """Absolute motor-neuron rate (input), :math:`\\bar r + \\delta_r`."""
        return self.delta_r + self.r_bar

    def plot(self, states: bool | None = None):
        """Force and rate (and the controller's ``states``, by default when any): a Figure."""
        from symctl.plotting.response import response_plot

        return response_plot(self, states)


UNIT_CIRCLE = 1 - 1e-9  # |eigenvalue| >= this is unstable (a marginal mode rounds inside)


# Stacks of loops are stored realization-last, ``(rows, cols, R)``: every vectorized
# operation then runs over contiguous memory, one realization per element.
def _stability(Acl: np.ndarray, argname: str, n: int | None = None, bad=None) -> None:
    """Refuse the unstable loops ``bad`` (default: by eigenvalues); ``n`` names hidden modes."""
    if bad is None:
        eigs = np.linalg.eigvals(np.moveaxis(Acl, -1, 0)) if Acl.shape[0] else np.zeros((1, 1))
        bad = np.flatnonzero(np.max(np.abs(eigs), axis=-1) >= UNIT_CIRCLE)
    if bad.size:
        count, i = Acl.shape[-1], int(bad[0])
        eigs = np.linalg.eigvals(Acl[:, :, i])
        lam = complex(eigs[np.argmax(np.abs(eigs))])
        rho = abs(lam)
        where = f" (realization {i} of {count}; {bad.size} unstable)" if count > 1 else ""
        cause = "the controller does not stabilize this plant"
        if n is not None and _is_hidden(Acl[:, :, i], lam, n):
            cause = (
                f"it is a mode of {argname}'s own states (its F) that the loop cannot move, "
                "hidden from the transfer function (a pole cancelled by a zero, e.g. "
                "|epsilon| >= 1 in G3 G2 G1); realize the controller with every mode "
                "inside the unit circle"
            )
        raise ParameterError(
            f"{argname}: the closed loop is unstable, spectral radius {rho:.6g} >= 1{where}; "
            f"unstable eigenvalue {_eig_text(lam)}; {cause}"
        )


def _eig_text(lam: complex) -> str:
    if abs(lam.imag) <= 1e-12 * max(1.0, abs(lam)):
        return f"{lam.real:.6g}"
    return f"{lam.real:.6g}{lam.imag:+.6g}j"


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


def _run(Acl, Cr, n: int, w, *, states: bool = True, argname: str = "disturbance") -> tuple:
    """``(delta_f, delta_r, states)``, each ``(R, steps, .)``, of ``xi(t+1) = A_cl xi + [I; 0] w``."""
    size, m = Acl.shape[0], Cr.shape[0]
    rows = range(n + m + (size - n if states else 0))  # delta_f, delta_r, states
    out = np.empty((w.shape[-2], len(rows), Acl.shape[-1]))
    _steps(Acl, Cr, n, w, out, rows, argname=argname)
    loops = np.moveaxis(out, -1, 0)
    return loops[..., :n], loops[..., n : n + m], loops[..., n + m :] if states else None


def _steps(Acl, Cr, n, w, out, rows, peaks=None, peak_rows=(), *, argname, schedule=None):
    """Fill ``out`` with the signals ``rows`` and ``peaks`` with the largest ``|signal|`` of
    ``peak_rows``; overflow raises. ``schedule(run, R)`` runs slices of the loops."""
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
        np.zeros(p.n) if p.x_eq is None else numeric_matrix(p.x_eq, "x_eq").ravel(),
        np.zeros(p.m) if p.u_eq is None else numeric_matrix(p.u_eq, "u_eq").ravel(),
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
    r"""The linear plant's response to a pulse ``pulse`` on every input (the paper's Fig. 3).

    Parameters
    ----------
    plant : DiscretePlant, MuscleModel, (A, B) or python-control system (as_plant), optional
        Numeric; the paper's muscle by default.
    pulse : float
        Pulse amplitude [spikes/s], from ``start`` for ``length`` steps.
    start, length, steps : int

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
    """``R``'s matrices (stacks of one), fed by ``y = C x`` when ``C`` is given."""
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

    Parameters
    ----------
    plant : DiscretePlant, MuscleModel, (A, B) or python-control system (as_plant)
    R : Realization
        Numeric, of shape (plant inputs, plant states).
    disturbance : float or array
        The pulse's amplitude (``start``, ``length``, horizon ``steps``, default 50) on every
        state, or an array ``(steps, n)`` (``(steps,)`` for one state).
    noise : Noise, optional
        Noise drawn per step: the traces are then the mean of ``draws`` noisy loops (1 to
        ``MAX_COUNT``), their standard deviations in ``..._sd``.
    rng : int, numpy Generator or None, default 0
        Seeds the noise.

    Returns
    -------
    Response

    Raises
    ------
    ParameterError
        An unstable loop (naming the eigenvalue and a hidden mode of ``R``'s ``F``;
        :func:`~symctl.loop_stability` does not raise), non-finite values, a bad horizon, an
        overflow, or an ``R.dt`` other than the plant's.
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
    """``(A_cl, C_r)`` of the plant around ``R`` (fed by ``C x``), checked stable."""
    Acl, Cr = _closed_loop_matrices(A, B, *_numeric_realization(R, p, argname, C))
    _stability(Acl, argname, p.n)
    return Acl, Cr


def _simulate(p, Acl, Cr, w, noise, draws, gen, names=(), sensor=None) -> Response:
    """The loop's :class:`Response`, noise-free or the mean and spread of ``draws`` noisy runs."""
    noise = _as_noise(noise)
    df, dr, xc, _ = _traces(p, Acl, Cr, w, noise, draws, gen, sensor)
    return _closed_response(p, w, df, dr, xc, names, noise is not None)


def _closed_response(p, w, df, dr, xc, names=(), noisy=False) -> Response:
    """The :class:`Response` of runs ``(draws, steps, .)``: their mean, and with ``noisy`` spread."""
    res = _response(p, df.mean(0), dr.mean(0), w, xc.mean(0), "closed loop", names)
    if not noisy:
        return res
    spread = {"delta_f_sd": df.std(0), "delta_r_sd": dr.std(0), "states_sd": xc.std(0)}
    return dataclasses.replace(res, **spread, draws=df.shape[0])


def _traces(p, Acl, Cr, w, noise, draws, gen, sensor=None) -> tuple[np.ndarray, ...]:
    """``delta_f``, ``delta_r``, states and measurement ``y``, each ``(draws or 1, steps, .)``."""
    if noise is None:
        df, dr, xc = (np.ascontiguousarray(a) for a in _run(Acl, Cr, p.n, w))
        return df, dr, xc, df if sensor is None else (df[0] @ sensor[2].T)[None]
    draws = bounded_int(draws, "draws", 1, MAX_COUNT)
    _, A, B = _plant(p)
    Acl, Cr, n = Acl[:, :, 0], Cr[:, :, 0], p.n
    q = n if sensor is None else sensor[2].shape[0]
    out = np.empty((w.shape[0], Acl.shape[0] + Cr.shape[0] + q, draws))
    _noisy_fill(
        Acl, Cr, A, B, n, w, _parts(noise, n, p.m, q), gen, out, slice(None), sensor=sensor, y=True
    )
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
        Gains run the optimal controller on the augmented state (with a ``plant``: their
        :func:`ifp_realization`); a numeric SISO DiscreteTF is realized in controllable
        canonical form.
    plant : DiscretePlant, MuscleModel, (A, B) or python-control system, optional
        Required unless ``controller`` is ``Gains``.
    disturbance, steps, start, length, noise, draws, rng
        As in :func:`simulate_realization`.
    outputs : matrix-like, optional
        ``p x n``: the controller (not Gains, ``m x p``) reads :math:`y = C x` (plus the
        sensor noise) instead of the state, as :func:`~symctl.lqg_realization` does.

    Returns
    -------
    Response

    Raises
    ------
    ParameterError
        No ``plant`` for a controller other than ``Gains``, or a plant of another ``dt``.

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
    """``(plant, A_cl, C_r, state names, sensor)``, stable; ``sensor``: ``(E_v, D_v, C)`` or None."""
    if isinstance(controller, Gains) and plant is None and outputs is None:
        s = controller.system
        Acl = numeric_matrix(s.A, "controller") + numeric_matrix(s.B, "controller") @ controller.K
        Cr = np.zeros((s.m, Acl.shape[0]))
        if s.T:
            Cr[:, -s.m :] = np.eye(s.m)
        else:
            Cr[:] = controller.K
        _stability(Acl[:, :, None], "controller")
        return s.plant, Acl[:, :, None], Cr[:, :, None], chain_names(s.T, s.m), None
    if plant is None:
        raise ParameterError(
            "plant: needed unless the controller is Gains (which carry their plant)"
        )
    p, A, B = _plant(plant)
    if outputs is None:
        return (p, *_realization_loop(p, A, B, _controller_realization(controller, p)), (), None)
    if isinstance(controller, Gains):
        raise SymctlTypeError("controller: Gains read the state; with outputs, give a Realization")
    C = numeric_matrix(outputs, "outputs")
    if C.ndim != 2 or C.shape[1] != p.n:
        raise DimensionError(f"outputs: expected p x {p.n}, got shape {C.shape}")
    R = _controller_realization(controller, p)
    _, H, _, N = R.numeric()
    sensor = (np.vstack([B @ N, H]), N, C)
    return (p, *_realization_loop(p, A, B, R, "controller", C), (), sensor)


def _controller_realization(controller, plant: DiscretePlant, kinds: str = "") -> Realization:
    """Gains as their IFP realization, a DiscreteTF in controllable canonical form; ``kinds``:
    other types the caller accepts, for the message."""
    if isinstance(controller, Gains):
        same_dt(plant, controller.system.plant.dt, "plant", "the gains' plant")
        return ifp_realization(controller)
    if isinstance(controller, DiscreteTF):
        controller = controllable_canonical(controller)
    elif not isinstance(controller, Realization):
        raise SymctlTypeError(
            f"controller: expected Gains, a DiscreteTF{kinds} or a Realization, "
            f"got {type(controller).__name__}"
        )
    same_dt(plant, controller.dt, "controller")
    return controller
