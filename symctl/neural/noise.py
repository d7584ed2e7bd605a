r"""Noise in the closed loop: on the plant's states, on its inputs, on what the controller measures.

With the loop's state :math:`\xi = [x; x_c]` (plant, then controller), the command
:math:`u = C_r \xi` and noise drawn afresh at each step,

.. math::
    \xi(t+1) = A_{cl}\,\xi(t) + E_p\,(w(t) + p(t)) + E_u\,m(t) + E_v\,v(t),\qquad
    u(t) = C_r\,\xi(t) + D_v\,v(t),

- process noise :math:`p \sim N(0, W)` on the plant's states, :math:`E_p = [I; 0]`;
- motor noise :math:`m = m_a + \sigma \odot u \odot \varepsilon` on the plant's input,
  :math:`E_u = [B; 0]`: additive :math:`m_a \sim N(0, W_u)` and signal-dependent, of
  standard deviation :math:`\sigma_i |u_i|` (Harris and Wolpert 1998);
- sensor noise :math:`v \sim N(0, V)` on the measurement :math:`y = x + v`, so
  :math:`E_v = A_{cl}[:, :n] - [A; 0]` and :math:`D_v = C_r[:, :n]` (a compensator fed by
  an output :math:`C x` brings its own :math:`E_v, D_v, C`).

:math:`u` is the command, before the motor noise. Each step draws standard normals
``(k, loops)``: the process (n), motor (m), sensor (n) and signal-dependent (m) rows in
this order, each only when given, scaled by a square root of its covariance.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.validate import MAX_STATES, check_psd, float_array, read_only
from symctl.errors import DimensionError, ParameterError, SymctlTypeError

__all__ = ["Noise"]

_PARTS = ("process", "motor", "sensor", "signal_dependent")
_BLOCK = 64  # steps of normals drawn at once


def _covariance(value, name: str) -> np.ndarray:
    """A variance (number, times identity), variances (a list: the diagonal) or a covariance."""
    arr = float_array(value, name)
    if arr.ndim > 2 or any(k > MAX_STATES for k in arr.shape):
        raise DimensionError(
            f"{name}: expected a number, a list or a square matrix of at most {MAX_STATES} "
            f"rows, got shape {arr.shape}"
        )
    if arr.ndim == 2 and arr.shape[0] != arr.shape[1]:
        raise DimensionError(f"{name}: a covariance must be square, got shape {arr.shape}")
    if arr.ndim == 2:
        return check_psd(arr, name)
    if np.any(arr < 0):
        raise ParameterError(f"{name}: variances must be >= 0, got {arr.tolist()}")
    return arr


@dataclass(frozen=True, eq=False)
class Noise(ArrayValue, DictMixin):
    r"""Gaussian noise in a closed loop, drawn per step (module text).

    Parameters
    ----------
    process, motor, sensor : number, list or matrix, optional
        Covariances :math:`W` of the noise on the plant's states, :math:`W_u` of the additive
        noise on its inputs, :math:`V` of the noise on what the controller measures: a number
        (times the identity), a list (the diagonal) or a symmetric PSD matrix.
    signal_dependent : number or list, optional
        :math:`\sigma \ge 0`: motor noise of standard deviation :math:`\sigma_i |u_i|`.

    Raises
    ------
    ParameterError, DimensionError, SymctlTypeError
        A covariance not PSD or not square, a negative variance, an entry not a finite
        number; a size above ``MAX_STATES``, later one other than the loop's.

    References
    ----------
    C. M. Harris and D. M. Wolpert, "Signal-dependent noise determines motor planning",
    Nature 394, 780-784 (1998).

    Examples
    --------
    >>> from symctl import Noise
    >>> Noise(process=[1e-4, 1e-2], sensor=1e-6).matrices(2, 1)["sensor"]
    array([[1.e-06, 0.e+00],
           [0.e+00, 1.e-06]])
    >>> Noise(process=[[1, 2], [2, 1]])
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: process: must be positive semidefinite, but has eigenvalue -1 ...
    """

    process: np.ndarray | None = None
    motor: np.ndarray | None = None
    sensor: np.ndarray | None = None
    signal_dependent: np.ndarray | None = None

    def __post_init__(self) -> None:  # validated, read-only
        for name in _PARTS:
            if getattr(self, name) is not None:
                object.__setattr__(self, name, read_only(_covariance(getattr(self, name), name)))
        sd = self.signal_dependent
        if sd is not None and sd.ndim == 2:
            raise DimensionError(
                f"signal_dependent: expected a number or a list, got shape {sd.shape}"
            )

    @property
    def is_zero(self) -> bool:
        """Whether no noise is drawn (every part absent or zero)."""
        return all(getattr(self, k) is None or not np.any(getattr(self, k)) for k in _PARTS)

    def matrices(self, n: int, m: int, outputs: int | None = None) -> dict[str, np.ndarray]:
        """Each part given, sized for ``n`` states, ``m`` inputs and ``outputs`` measurements
        (default ``n``): covariances ``(k, k)``, ``signal_dependent`` ``(m,)``."""
        sizes = {"process": n, "motor": m, "sensor": n if outputs is None else outputs}
        out = {}
        for name, size in (*sizes.items(), ("signal_dependent", m)):
            value = getattr(self, name)
            if value is None:
                continue
            if value.ndim and value.shape[0] != size:
                raise DimensionError(
                    f"noise.{name}: expected {size} entries (a ({size}, {size}) covariance or "
                    f"{size} variances), got shape {value.shape}"
                )
            if name == "signal_dependent":
                out[name] = np.broadcast_to(value, (size,)).copy()
            else:
                out[name] = value if value.ndim == 2 else np.diag(np.broadcast_to(value, (size,)))
        return out


def _as_noise(noise) -> Noise | None:
    """``noise`` checked: a :class:`Noise`, or None for none (or an all-zero Noise)."""
    if noise is None:
        return None
    if not isinstance(noise, Noise):
        raise SymctlTypeError(f"noise: expected a symctl.Noise, got {type(noise).__name__}")
    return None if noise.is_zero else noise


def _factor(cov: np.ndarray) -> np.ndarray:
    """``L`` with ``L L^T = cov``."""
    if not np.any(cov - np.diag(np.diag(cov))):
        return np.diag(np.sqrt(np.diag(cov)))
    lam, U = np.linalg.eigh((cov + cov.T) / 2)
    return U * np.sqrt(np.clip(lam, 0.0, None))


def _apply(M: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``M x`` for a shared ``M`` or one per loop ``(rows, cols, R)``; ``x`` ``(cols, R)``."""
    if M.ndim == 2:
        return M @ x
    if M.shape[-1] == 1:
        return M[:, :, 0] @ x
    return np.einsum("ijr,jr->ir", M, x)


def _sensor_inputs(Acl: np.ndarray, Cr: np.ndarray, A: np.ndarray, n: int) -> tuple:
    """``(E_v, D_v)`` of a loop whose controller reads the plant's state."""
    Ev = Acl[:, :n].copy()
    Ev[:n] -= A if Acl.ndim == 2 else A[:, :, None]
    return Ev, Cr[:, :n]


def _parts(noise: Noise, n: int, m: int, outputs: int | None = None) -> dict[str, np.ndarray]:
    """The parts given, in the order drawn: square roots of the covariances, ``signal_dependent``."""
    mats = noise.matrices(n, m, outputs)
    return {k: v if k == "signal_dependent" else _factor(v) for k, v in mats.items()}


def _noisy_loop(
    Acl, Cr, B, n, w, parts: dict, gen, count: int, visit, Ev=None, Dv=None, C=None, y=True
):
    """Run ``count`` loops from rest, calling ``visit(t, xi, u, y or None)`` at each step."""
    steps = w.shape[-2]
    wt = w[:, :, None] if w.ndim == 2 else np.moveaxis(w, 0, -1)  # (steps, n, count or 1)
    quiet = not np.any(w)
    parts = dict(parts)
    if "process" in parts and "motor" in parts:  # one draw of W + B W_u B^T
        P, BM = parts.pop("process"), B @ parts.pop("motor")
        parts = {"process": _factor(P @ P.T + BM @ BM.T), **parts}
    rows, k = {}, 0  # each part's rows among the normals drawn per step
    for name, value in parts.items():
        rows[name], k = slice(k, k + len(value)), k + len(value)
    G, Du, Ly = _noise_inputs(Acl, B, n, parts, rows, k, Ev, Dv)
    sd = parts.get("signal_dependent")
    x = np.zeros((Acl.shape[0], count))
    with np.errstate(over="ignore", invalid="ignore"):
        for t, zt in enumerate(_normals(gen, steps, k, count)):
            u = _apply(Cr, x)
            if Du is not None:
                u += _apply(Du, zt)
            visit(t, x, u, _measured(x[:n], zt, C, Ly) if y else None)
            nxt = _apply(Acl, x)
            if not quiet:
                nxt[:n] += wt[t]
            nxt += _apply(G, zt)
            if sd is not None:
                nxt[:n] += B @ (sd[:, None] * u * zt[rows["signal_dependent"]])
            x = nxt
    if not np.all(np.isfinite(x)):  # an overflow stays inf or NaN to the end
        raise ParameterError(
            "noise: the simulation blew up (values overflowed to inf/NaN); reduce the noise "
            "or the disturbance, or check the loop's stability"
        )


def _measured(x, zt, C, Ly) -> np.ndarray:
    """The controller's measurement :math:`C x + v` (``C`` None: the identity)."""
    y = x if C is None else C @ x
    return y if Ly is None else y + Ly @ zt


def _normals(gen, steps: int, k: int, count: int):
    """The normals of each step, ``(k, count)``, drawn in blocks, the next on a thread."""
    with ThreadPoolExecutor(1) as pool:
        block = pool.submit(gen.standard_normal, (min(_BLOCK, steps), k, count))
        for start in range(0, steps, _BLOCK):
            z = block.result()
            if start + _BLOCK < steps:
                size = (min(_BLOCK, steps - start - _BLOCK), k, count)
                block = pool.submit(gen.standard_normal, size)
            yield from z


def _noise_inputs(Acl, B, n, parts: dict, rows, k, Ev, Dv) -> tuple:
    """How a step's normals enter: ``G`` the state, ``Du`` the command, ``Ly`` the measurement."""
    stack = (Acl.shape[-1],) if Acl.ndim == 3 else ()
    G = np.zeros((Acl.shape[0], k, *stack))
    if "process" in parts:
        G[:n, rows["process"]] = parts["process"][..., None] if stack else parts["process"]
    if "motor" in parts:
        BM = B @ parts["motor"]
        G[:n, rows["motor"]] = BM[..., None] if stack else BM
    if "sensor" not in parts:
        return G, None, None
    Ly = np.zeros((len(parts["sensor"]), k))
    Ly[:, rows["sensor"]] = parts["sensor"]
    G += np.einsum("ij...,jk->ik...", Ev, Ly)
    return G, np.einsum("ij...,jk->ik...", Dv, Ly), Ly


def _noisy_fill(
    Acl, Cr, A, B, n, w, parts, gen, out, rows, peaks=None, peak_rows=(), *, sensor=None, y=False
) -> None:
    """:func:`_noisy_loop` into ``out`` ``(steps, rows, loops)`` and ``peaks``; ``sensor``:
    ``(E_v, D_v, C)`` of a controller fed by outputs (default: the state)."""
    peak_rows = list(peak_rows)
    if peaks is not None:
        peaks[...] = 0.0

    def visit(t, x, u, meas):
        signals = np.concatenate([x[:n], u, x[n:], *([meas] if y else [])])
        out[t] = signals[rows]
        if peak_rows:
            np.maximum(peaks, np.abs(signals[peak_rows]), out=peaks)

    Ev, Dv, C = (*_sensor_inputs(Acl, Cr, A, n), None) if sensor is None else sensor
    _noisy_loop(Acl, Cr, B, n, w, parts, gen, out.shape[-1], visit, Ev, Dv, C, y)
