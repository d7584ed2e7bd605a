"""The time loop of a stack of linear closed loops, ``xi(t+1) = A xi(t) + [I; 0] w(t)``.

Two loops give the same bits (each row summed in the dense order, coefficients zero in every
loop left out): :func:`_run_rows` for many loops, :func:`_run_groups` for a large sparse circuit
of few loops; ``benchmarks/simulate.py`` times both.
"""

from __future__ import annotations

import numpy as np


def _groups(mat: np.ndarray, nonzero=None) -> list[tuple[np.ndarray, np.ndarray, list]]:
    """The rows of a stack grouped by their number ``k`` of nonzero terms: ``(rows, sources,
    k coefficient stacks)``."""
    if not mat.shape[0]:
        return []
    if nonzero is None:
        nonzero = np.any(mat != 0, axis=2)  # (rows, cols)
    counts = nonzero.sum(axis=1)
    groups = []
    for k in np.unique(counts):
        rows = np.flatnonzero(counts == k)
        sources = np.array([np.flatnonzero(nonzero[i]) for i in rows], dtype=np.intp)
        sources = sources.reshape(len(rows), int(k))
        coefficients = []
        for c in range(int(k)):
            a = mat[rows, sources[:, c], :]  # (len(rows), R)
            coefficients.append(a[:, :1].copy() if np.all(a == a[:, :1]) else a.copy())
        groups.append((rows, sources, coefficients))
    return groups


def _combine_groups(groups, x: np.ndarray, dst: np.ndarray) -> None:
    """``dst[i] = sum_j a_ij x_j`` for every row of ``groups``, in the dense sum's order."""
    for rows, sources, coefficients in groups:
        if not coefficients:
            dst[rows] = 0.0
            continue
        acc = x[sources[:, 0]] * coefficients[0]
        for c in range(1, len(coefficients)):
            acc += x[sources[:, c]] * coefficients[c]
        dst[rows] = acc


def _setup(A, Cr, n, w, out, rows, peaks, peak_rows) -> tuple:
    """Each kept signal's slot, each state's signal, the rates to compute, the quiet steps and
    the last step at rest."""
    m = Cr.shape[0]
    slot = {signal: k for k, signal in enumerate(rows)}
    state = [j if j < n else m + j for j in range(A.shape[0])]
    rates = [k for k in range(m) if n + k in slot or n + k in peak_rows]
    quiet = ~np.any(w, axis=(1, 2))
    if peaks is not None:
        peaks[...] = 0.0
    return slot, state, rates, quiet, out.shape[0] if quiet.all() else int(np.argmin(quiet))


def _first_bad(out: np.ndarray, rows) -> int:
    """The first step of ``out`` with an inf or NaN, or ``steps``."""
    finite = np.all(np.isfinite(out), axis=(1, 2)) if len(rows) else np.ones(1, dtype=bool)
    return out.shape[0] if finite.all() else int(np.argmin(finite))


@np.errstate(over="ignore", invalid="ignore")
def _run_groups(A, Cr, n, w, out, rows, peaks=None, peak_rows=(), *, nonzero=None) -> int:
    """:func:`_run_chunk` for few loops: the rows with as many terms at once (:func:`_groups`)."""
    steps, size, m, count = out.shape[0], A.shape[0], Cr.shape[0], A.shape[-1]
    slot, state, rates, quiet, rest = _setup(A, Cr, n, w, out, rows, peaks, peak_rows)
    kept = [(j, slot[s]) for j, s in enumerate(state) if s in slot]
    kept_state = np.array([j for j, _ in kept], dtype=np.intp)
    kept_slot = np.array([k for _, k in kept], dtype=np.intp)
    rate_out = [(r, slot[n + k]) for r, k in enumerate(rates) if n + k in slot]
    # each peak's signal: a state (delta_f, or a controller state after the rates) or a rate
    peak_src = [
        (False, s) if s < n else (True, rates.index(s - n)) if s < n + m else (False, s - m)
        for s in peak_rows
    ]
    a_groups = _groups(A, nonzero)
    c_groups = _groups(Cr[rates]) if rates else []
    x, nxt = np.zeros((size, count)), np.empty((size, count))
    rate = np.zeros((len(rates), count))
    tmp = np.empty(count)
    for t in range(steps):
        out[t, kept_slot] = x[kept_state]
        if t <= rest:  # at rest: exact zeros (+0, as the dense sum 0 + a 0 gives)
            rate[...] = 0.0
            nxt[...] = 0.0
        else:
            _combine_groups(c_groups, x, rate)
            _combine_groups(a_groups, x, nxt)
        for r, at in rate_out:
            out[t, at] = rate[r]
        if not quiet[t]:
            nxt[:n] += w[t]
        for p, (is_rate, i) in enumerate(peak_src):
            src = rate[i] if is_rate else x[i]
            np.maximum(peaks[p], np.abs(src, out=tmp), out=peaks[p])
        x, nxt = nxt, x
    return _first_bad(out, rows)


def _terms(mat: np.ndarray) -> list[list[tuple[int, float | np.ndarray]]]:
    """Each row of a stack as ``(j, coefficient)`` terms (a float when equal in every loop)."""
    terms = []
    for row in mat:
        terms.append([])
        for j, v in enumerate(row):
            if np.all(v == v[0]):
                if v[0] != 0:
                    terms[-1].append((j, float(v[0])))
            else:
                terms[-1].append((j, np.ascontiguousarray(v)))
    return terms


def _combine(terms, x: list[np.ndarray], dst: np.ndarray, tmp: np.ndarray) -> None:
    """``dst = sum_j a_j x_j`` over ``terms``, in place (the first product written directly)."""
    if not terms:
        dst[...] = 0.0
        return
    j, a = terms[0]
    np.multiply(x[j], a, out=dst)
    for j, a in terms[1:]:
        np.multiply(x[j], a, out=tmp)
        np.add(dst, tmp, out=dst)


@np.errstate(over="ignore", invalid="ignore")
def _run_rows(A, Cr, n, w, out, rows, peaks=None, peak_rows=()) -> int:
    """:func:`_run_chunk` for many loops: each row of ``x(t+1)`` straight into its row of ``out``."""
    steps, size, m, count = out.shape[0], A.shape[0], Cr.shape[0], A.shape[-1]
    slot, state, rates, quiet, rest = _setup(A, Cr, n, w, out, rows, peaks, peak_rows)
    a_terms, c_terms = _terms(A), _terms(Cr)
    scratch, rate_rows, tmp = np.empty((2, size, count)), np.empty((m, count)), np.empty(count)

    def at(t: int) -> list[np.ndarray]:  # the rows that hold x(t)
        if t == steps:  # the state after the horizon, which nobody sees
            return list(scratch[t % 2])
        o = out[t]
        return [o[slot[s]] if s in slot else scratch[t % 2, j] for j, s in enumerate(state)]

    x = at(0)
    for row in x:
        row[...] = 0.0
    for t in range(steps):
        rate = [out[t, slot[n + k]] if n + k in slot else rate_rows[k] for k in range(m)]
        nxt = at(t + 1)
        if t <= rest:  # at rest: exact zeros (+0, as the dense sum 0 + a 0 gives)
            for row in [rate[k] for k in rates] + nxt:
                row[...] = 0.0
        else:
            for k in rates:
                _combine(c_terms[k], x, rate[k], tmp)
            for i in range(size):
                _combine(a_terms[i], x, nxt[i], tmp)
        if not quiet[t]:
            for i in range(n):
                nxt[i] += w[t, i]
        for p, s in enumerate(peak_rows):
            src = x[s] if s < n else rate[s - n] if s < n + m else x[s - m]
            np.maximum(peaks[p], np.abs(src, out=tmp), out=peaks[p])
        x = nxt
    return _first_bad(out, rows)


GROUPED_LOOPS = 4096  # most loops for _run_groups, when it makes a quarter of the NumPy calls


def _run_chunk(A, Cr, n, w, out, rows, peaks=None, peak_rows=()) -> int:
    """All steps of one chunk into ``out``: the first step with an inf or NaN, or ``steps``."""
    if A.shape[-1] <= GROUPED_LOOPS:
        nonzero = np.any(A != 0, axis=2)  # read once: the choice, then the groups
        counts = np.count_nonzero(nonzero, axis=1)  # terms per row
        if 4 * int(np.unique(counts).sum()) <= int(counts.sum()):
            return _run_groups(A, Cr, n, w, out, rows, peaks, peak_rows, nonzero=nonzero)
    return _run_rows(A, Cr, n, w, out, rows, peaks, peak_rows)
