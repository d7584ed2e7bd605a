"""Many closed loops at once: the plant around a stack of realizations, vectorized in NumPy."""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator, Mapping
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from functools import partial
from itertools import pairwise

import numpy as np

from symctl._util.deprecate import rng_argument
from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.validate import MAX_OUTPUT_BYTES, float_array, positive_int, read_only
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.neural.noise import Noise, _as_noise, _noisy_fill, _parts
from symctl.neural.simulate import (
    DEFAULT_LENGTH,
    DEFAULT_START,
    UNIT_CIRCLE,
    _closed_loop_matrices,
    _freeze,
    _plant,
    _signal,
    _stability,
    _steps,
    _ts,
)

__all__ = ["BatchResponse", "simulate_batch"]

_EIG_LIMIT = 2000  # above this many realizations, stability is decided by the Schur-Cohn test
_CHUNK = 32768  # most realizations per task of the time loop (their rows stay in the L3 cache)
_MIN_CHUNK = 4096  # fewest realizations per task worth a thread of its own
_WORKERS = os.cpu_count() or 1  # threads that run the tasks
_MAX_KEEP = 64  # most names in ``keep`` (there are six; an endless iterator is refused)

TRACES = ("delta_f", "delta_r", "states")  # in the order of BatchResponse
KEEP = TRACES + tuple("peak_" + name for name in TRACES)  # what simulate_batch can keep


@dataclass(frozen=True, eq=False)
class BatchResponse(ArrayValue, DictMixin):
    """Traces of many closed loops at once (:func:`simulate_batch`); read-only.

    Attributes
    ----------
    t : (steps,) array
        Time in seconds (in steps when the plant has no ``dt``).
    delta_f, delta_r, states : (R, steps, n), (R, steps, m), (R, steps, nc) arrays or None
        Each loop's plant state, motor-neuron rate and controller states (None when not kept).
    stability_checked : bool
        Whether every loop was checked to be stable before the run.
    peaks : mapping of str to (R, channels) arrays
        Each trace's largest magnitude over the horizon, by trace name, when asked for
        (``keep=("peak_delta_r", ...)``).
    first : int
        The index of the first loop here among all (with ``chunk=``; else 0).

    Examples
    --------
    >>> import numpy as np
    >>> from symctl import MuscleModel, simulate_batch
    >>> zero, one = np.zeros((2, 1, 1)), np.ones((2, 1, 1))
    >>> out = simulate_batch(MuscleModel(), zero, -0.05 * one, one, zero, steps=20)
    >>> out.delta_f.shape, out.states, out.stability_checked, out.delta_f.flags.writeable
    ((2, 20, 1), None, True, False)
    >>> dict(out.peaks), out.first
    ({}, 0)
    """

    t: np.ndarray
    delta_f: np.ndarray | None
    delta_r: np.ndarray | None
    states: np.ndarray | None
    stability_checked: bool
    peaks: Mapping[str, np.ndarray] = field(default_factory=dict)
    first: int = 0

    def __post_init__(self) -> None:  # read-only (views of simulate_batch's own buffer)
        _freeze(self, (*TRACES, "t"), ("peaks",))


def _chunks(count: int) -> list[slice]:
    """Equal slices of at most ``_CHUNK`` (a multiple of ``_WORKERS`` of them when large)."""
    k = -(-count // _CHUNK)
    if count >= _WORKERS * _MIN_CHUNK:
        k = -(-k // _WORKERS) * _WORKERS
    bounds = [count * i // k for i in range(k + 1)]
    return [slice(lo, hi) for lo, hi in pairwise(bounds) if hi > lo]


def _charpoly(A: np.ndarray) -> np.ndarray:
    r"""Characteristic polynomials of a stack ``(N, N, R)``, ascending, by Newton's identities
    on the power sums :math:`\operatorname{tr}(A^a A^b)`, :math:`a + b = k`."""
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
    r"""Whether each ``A[:, :, r]`` has spectral radius below ``UNIT_CIRCLE``: the Schur-Cohn
    test, :math:`p \to (a_d p - a_0 p^*)/z` while :math:`|a_0| < |a_d|`, on :math:`p(\rho z)`."""
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


def _batch_stability(loops, count: int, argname: str, n: int) -> None:
    """Refuse an unstable loop: eigenvalues up to ``_EIG_LIMIT`` loops, Schur-Cohn above."""
    bad = None
    if count > _EIG_LIMIT:  # in chunks, whose temporaries stay small
        bad = np.flatnonzero(~np.concatenate([_schur_stable(loops(c)[0]) for c in _chunks(count)]))
    if bad is None or bad.size:
        _stability(loops(slice(None))[0], argname, n, bad)


def _in_chunks(run, count: int) -> int:
    """``min(run(part))`` over the chunks, on ``_WORKERS`` threads (ufuncs release the GIL)."""
    parts = _chunks(count)
    workers = min(len(parts), _WORKERS)
    if workers == 1:
        return min(map(run, parts))
    with ThreadPoolExecutor(workers) as pool:
        return min(pool.map(run, parts))


def _selection(keep, states: bool) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The traces and the peaks to keep, each in the order of ``TRACES``."""
    names = {"delta_f", "delta_r"} if keep is None else set()
    keep = (keep,) if isinstance(keep, str) else () if keep is None else keep
    if not isinstance(keep, Iterable) or isinstance(keep, bytes):
        raise SymctlTypeError(f"keep: expected names among {KEEP}, got {keep!r}")
    for k, name in enumerate(keep):
        if k >= _MAX_KEEP:
            raise ParameterError(f"keep: at most {_MAX_KEEP} names, got more")
        if not isinstance(name, str):
            raise SymctlTypeError(f"keep: expected names among {KEEP}, got {name!r}")
        if name not in KEEP:
            raise ParameterError(f"keep: expected names among {KEEP}, got {name!r}")
        names.add(name)
    if not names:
        raise ParameterError(f"keep: nothing to keep, got {keep!r}; name one of {KEEP}")
    if states:
        names.add("states")
    return tuple(t for t in TRACES if t in names), tuple(t for t in TRACES if "peak_" + t in names)


def _check_memory(count, steps, widths, traces, peaks, chunk) -> None:
    """Refuse, before any work, outputs over ``MAX_OUTPUT_BYTES`` in one result or chunk."""
    per_loop = 8 * (steps * sum(widths[t] for t in traces) + sum(widths[t] for t in peaks))
    loops = count if chunk is None else min(chunk, count)
    if per_loop * loops <= MAX_OUTPUT_BYTES:
        return
    fit = MAX_OUTPUT_BYTES // per_loop
    kept = ", ".join(traces + tuple("peak_" + t for t in peaks))
    instead = "keep fewer traces, or only their peaks (e.g. keep=('peak_delta_r',))"
    if fit:
        instead = f"stream them with chunk={fit} or less (an iterator of results), or {instead}"
    raise ParameterError(
        f"{'keep' if chunk is None else 'chunk'}: keeping {kept} of {loops} realizations x "
        f"{steps} steps takes {per_loop * loops / 1e9:.3g} GB, over the limit of "
        f"{MAX_OUTPUT_BYTES / 2**30:g} GiB (MAX_OUTPUT_BYTES); {instead}"
    )


def _simulate_part(
    loops, n, w, widths, traces, peaks, t, checked, noisy, part: slice
) -> BatchResponse:
    """The loops ``part`` in fresh buffers; ``noisy``: ``(A, B, parts, gen)`` or None."""
    Acl, Cr = loops(part)
    w, count = w if w.ndim == 2 else w[part], Acl.shape[-1]
    ends = dict(zip(TRACES, np.cumsum([widths[u] for u in TRACES]).tolist(), strict=True))
    rows = [r for u in traces for r in range(ends[u] - widths[u], ends[u])]
    peak_rows = [r for u in peaks for r in range(ends[u] - widths[u], ends[u])]
    out = np.empty((len(t), len(rows), count))
    top = np.empty((len(peak_rows), count)) if peaks else None
    if noisy is None:
        _steps(Acl, Cr, n, w, out, rows, top, peak_rows, argname="disturbance", schedule=_in_chunks)
    else:
        A, B, parts, gen = noisy
        _noisy_fill(Acl, Cr, A, B, n, w, parts, gen, out, rows, top, peak_rows)
    out.setflags(write=False)  # no copy: the buffers are ours alone

    def split(a: np.ndarray, names) -> dict:  # a's last axis by names (none: the whole, unnamed)
        cuts = np.cumsum([widths[u] for u in names])[:-1]
        return dict(zip(names, np.split(a, cuts, -1), strict=False))

    arrays, peak_map = split(np.moveaxis(out, -1, 0), traces), split(top.T, peaks) if peaks else {}
    traced = [arrays.get(name) for name in TRACES]
    return BatchResponse(t, *traced, checked, peak_map, part.start or 0)


@rng_argument()
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
    keep=None,
    chunk: int | None = None,
    noise: Noise | None = None,
    rng=0,
) -> BatchResponse | Iterator[BatchResponse]:
    r"""Simulate the plant in closed loop with ``R`` realizations at once (vectorized in NumPy).

    Parameters
    ----------
    plant : DiscretePlant, MuscleModel, (A, B) or python-control system (as_plant)
    F, H, M, N : arrays of shapes (R, nc, nc), (R, nc, n), (R, m, nc), (R, m, n)
        E.g. ``Realization.lambdify(symbols)(*values)`` with arrays of values.
    disturbance : float or array
        A pulse amplitude (as in :func:`simulate_realization`), or ``(steps, n)`` shared by
        every loop, or ``(R, steps, n)``.
    states : bool
        Also keep the controller states ``(R, steps, nc)``.
    check_stability : bool
        Refuse any unstable loop first (eigenvalues up to 2000 loops, Schur-Cohn above).
    keep : str or iterable of str, optional
        Traces ``"delta_f"``, ``"delta_r"``, ``"states"`` and their peaks ``"peak_..."`` (in
        ``.peaks``); default ``("delta_f", "delta_r")``. Over ``MAX_OUTPUT_BYTES`` (8 bytes a
        value) in one result or chunk is refused before any work.
    chunk : int, optional
        Stream the loops in chunks of ``chunk`` realizations: an iterator of results, each
        simulated when reached (arguments and stability checked first).
    noise, rng : Noise, int, Generator or None, optional
        Noise drawn per step for each loop, and its seed.

    Returns
    -------
    BatchResponse or iterator of BatchResponse

    Raises
    ------
    DimensionError, ParameterError, SymctlTypeError
        Also outputs that overflow to inf or NaN, and outputs over the memory limit.

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
    >>> peaks = simulate_batch(MuscleModel(), F, H, np.ones((3, 1, 1)), np.zeros((3, 1, 1)),
    ...                        keep="peak_delta_r")
    >>> peaks.delta_r is None, bool(np.all(peaks.peaks["delta_r"] == abs(out.delta_r).max(1)))
    (True, True)
    >>> [part.first for part in simulate_batch(MuscleModel(), F, H, np.ones((3, 1, 1)),
    ...                                        np.zeros((3, 1, 1)), chunk=2)]
    [0, 2]
    """
    traces, peaks = _selection(keep, bool(states))
    if chunk is not None:
        chunk = positive_int(chunk, "chunk")
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
    w = _signal(disturbance, "disturbance", steps, p.n, start, length, R)
    widths = {"delta_f": p.n, "delta_r": p.m, "states": nc}
    _check_memory(R, w.shape[-2], widths, traces, peaks, chunk)
    if chunk is None:  # the closed loops at once, else each chunk's when it runs
        Acl, Cr = _closed_loop_matrices(A, B, *mats.values())

        def loops(part: slice) -> tuple[np.ndarray, np.ndarray]:
            return Acl[..., part], Cr[..., part]
    else:

        def loops(part: slice) -> tuple[np.ndarray, np.ndarray]:
            return _closed_loop_matrices(A, B, *(v[part] for v in mats.values()))

    if check_stability:
        _batch_stability(loops, R, "F, H, M, N", p.n)
    t = read_only(np.arange(w.shape[-2]) * _ts(p))
    checked = bool(check_stability)
    noise = _as_noise(noise)
    noisy = None if noise is None else (A, B, _parts(noise, p.n, p.m), rng)
    run = partial(_simulate_part, loops, p.n, w, widths, traces, peaks, t, checked, noisy)
    if chunk is None:
        return run(slice(None))
    return (run(slice(lo, min(R, lo + chunk))) for lo in range(0, R, chunk))
