r"""Many closed loops at once: the plant around a stack of realizations, vectorized in NumPy.

:func:`simulate_batch` closes the plant with ``R`` realizations
:math:`(F_r, H_r, M_r, N_r)` of the controller at once, e.g. the paper's
:math:`G_3 G_2 G_1` for many random :math:`\epsilon_1, \epsilon_3` and similarity
transforms (``benchmarks/simulate.py``: :math:`10^5` loops of 500 steps). The time
steps are those of :mod:`symctl.neural.simulate` (one loop over time for every
simulation); this module adds the chunking (blocks of 8192 loops, on every core)
and the stability test of many loops: exact eigenvalues up to 2000 loops, the
Schur-Cohn test on the characteristic polynomials (from Newton's identities)
above.

>>> import numpy as np
>>> from symctl import MuscleModel, simulate_batch
>>> gain = np.array([-0.01, -0.05]).reshape(2, 1, 1)
>>> out = simulate_batch(MuscleModel(), np.zeros((2, 1, 1)), gain, np.ones((2, 1, 1)),
...                      np.zeros((2, 1, 1)))
>>> out.delta_r.shape
(2, 50, 1)
"""

from __future__ import annotations

import numbers
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from symctl._util.validate import float_array, positive_int, read_only
from symctl.errors import DimensionError
from symctl.neural.simulate import (
    DEFAULT_LENGTH,
    DEFAULT_START,
    UNIT_CIRCLE,
    _closed_loop_matrices,
    _plant,
    _refuse_unstable,
    _run,
    _signal,
    _stability,
    _ts,
)

__all__ = ["BatchResponse", "simulate_batch"]

_EIG_LIMIT = 2000  # above this many realizations, stability is decided by the Schur-Cohn test
_CHUNK = 8192  # realizations per task of the time loop (their matrices stay in the CPU cache)
_WORKERS = os.cpu_count() or 1  # threads that run the tasks


@dataclass(frozen=True, eq=False)
class BatchResponse:
    """Traces of many closed loops at once (see :func:`simulate_batch`).

    Attributes
    ----------
    t : (steps,) array
        Time in seconds (in steps when the plant has no ``Ts``).
    delta_f : (R, steps, n) array
        Each loop's plant state change.
    delta_r : (R, steps, m) array
        Each loop's motor-neuron rate change.
    states : (R, steps, nc) array or None
        The controller states, when asked for.
    stability_checked : bool
        Whether every loop was checked to be stable before the run.

    The arrays are read-only and may be non-contiguous views of one time-major
    buffer (no copy is made).

    Examples
    --------
    >>> import numpy as np
    >>> from symctl import MuscleModel, simulate_batch
    >>> zero, one = np.zeros((2, 1, 1)), np.ones((2, 1, 1))
    >>> out = simulate_batch(MuscleModel(), zero, -0.05 * one, one, zero, steps=20)
    >>> out.delta_f.shape, out.states, out.stability_checked, out.delta_f.flags.writeable
    ((2, 20, 1), None, True, False)
    """

    t: np.ndarray
    delta_f: np.ndarray
    delta_r: np.ndarray
    states: np.ndarray | None
    stability_checked: bool

    def __post_init__(self) -> None:  # read-only (views of simulate_batch's own buffer)
        for name in ("t", "delta_f", "delta_r", "states"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, read_only(getattr(self, name), float))


# ---------------------------------------------------------------- chunks and stability
# Stacks of loops are stored realization-last, ``(rows, cols, R)``: every vectorized
# operation then runs over contiguous memory, one realization per element.
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
    r"""Whether every eigenvalue of each ``A[:, :, r]`` has modulus below ``UNIT_CIRCLE``.

    The Schur-Cohn test on :math:`p(\rho z)`, :math:`\rho` = ``UNIT_CIRCLE`` (so the
    threshold is the eigenvalue path's): reduces :math:`p(z) = \sum a_i z^i` to
    :math:`(a_d p(z) - a_0 p^*(z))/z` while :math:`|a_0| < |a_d|` (the reflection
    coefficient); vectorized over ``r``.
    """
    a = _charpoly(A)
    a = a * (UNIT_CIRCLE ** np.arange(a.shape[0]))[:, None]
    ok = np.ones(a.shape[1], dtype=bool)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for d in range(a.shape[0] - 1, 0, -1):
            lead, const = a[d], a[0]
            ok &= np.abs(const) < np.abs(lead)
            a = lead * a[1 : d + 1] - const * a[d - 1 :: -1]
            a /= np.where(a[-1] == 0, 1.0, np.abs(a[-1]))  # keeps the numbers in range
    return ok


def _batch_stability(Acl: np.ndarray, argname: str, n: int) -> None:
    """Refuse an unstable loop among many: eigenvalues up to ``_EIG_LIMIT``, Schur-Cohn above.

    ``n`` (the plant's states) lets the message name a hidden mode of the controller.
    """
    count = Acl.shape[-1]
    if count <= _EIG_LIMIT:
        _stability(Acl, argname, n)
        return
    # in chunks, whose temporaries stay small
    bad = np.flatnonzero(~np.concatenate([_schur_stable(Acl[..., c]) for c in _chunks(count)]))
    _refuse_unstable(Acl, bad, argname, n)


def _in_chunks(run, count: int) -> int:
    """``min(run(part))`` over the chunks of ``range(count)``, on ``_WORKERS`` threads.

    NumPy releases the GIL in einsum: the chunks, and the page faults of the fresh
    output buffer (as costly as the arithmetic for 10^5 loops), share the cores.
    """
    parts = _chunks(count)
    workers = min(len(parts), _WORKERS)
    if workers == 1:
        return min(map(run, parts))
    with ThreadPoolExecutor(workers) as pool:
        return min(pool.map(run, parts))


# ---------------------------------------------------------------- the function
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
    >>> import numpy as np
    >>> from symctl import MuscleModel, simulate_batch
    >>> F = np.full((3, 1, 1), 0.0); H = np.array([-0.01, -0.03, -0.05]).reshape(3, 1, 1)
    >>> out = simulate_batch(MuscleModel(), F, H, np.ones((3, 1, 1)), np.zeros((3, 1, 1)))
    >>> out.delta_f.shape, out.delta_r.shape
    ((3, 50, 1), (3, 50, 1))
    >>> bool(np.all(np.diff(out.delta_r.min(axis=(1, 2))) < 0))   # stronger gain, larger answer
    True
    """
    p, A, B = _plant(plant)
    mats = {k: float_array(v, k) for k, v in zip("FHMN", (F, H, M, N), strict=True)}
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
        disturbance = float_array(disturbance, "disturbance")
    if np.ndim(disturbance) < 3:
        w = _signal(disturbance, "disturbance", steps, p.n, start, length)
    else:
        w = disturbance
        if w.ndim != 3 or w.shape[0] != R or w.shape[2] != p.n or w.shape[1] == 0:
            raise DimensionError(
                f"disturbance: expected shape (steps, {p.n}) or ({R}, steps, {p.n}), got {w.shape}"
            )
        if steps is not None and positive_int(steps, "steps") != w.shape[1]:
            raise DimensionError(f"disturbance: has {w.shape[1]} samples but steps = {steps}")
    Acl, Cr = _closed_loop_matrices(A, B, *mats.values())
    if check_stability:
        _batch_stability(Acl, "F, H, M, N", p.n)
    df, dr, xc = _run(Acl, Cr, p.n, w, states=states, schedule=_in_chunks)
    t = np.arange(w.shape[-2]) * _ts(p)
    for arr in (df, dr) if xc is None else (df, dr, xc):
        arr.setflags(write=False)  # no copy: the buffer is ours alone
    return BatchResponse(t, df, dr, xc, bool(check_stability))
