"""python-control systems as symctl plants (control is imported only when such an object
arrives), and the one realization of a numeric transfer function."""

from __future__ import annotations

from functools import reduce

import numpy as np
import scipy.linalg

from symctl._util.validate import MAX_STATES, sampling_time
from symctl.design.plant import DiscretePlant
from symctl.errors import DimensionError, ParameterError, SymctlTypeError

__all__ = ["canonical_columns", "control_dt", "is_control_system", "plant_from_control"]


def is_control_system(obj) -> bool:
    """Whether ``obj`` is a python-control object (read from its type, without importing control)."""
    return type(obj).__module__.partition(".")[0] == "control"


def control_dt(sys, argname: str):
    """The sampling time of a discrete python-control system (``dt=True`` or None: None)."""
    dt = sys.dt
    if dt is True or dt is None:  # python-control's "discrete, unspecified" (None: either)
        return None
    if dt is False or dt == 0:
        raise ParameterError(
            f"{argname}: a continuous-time system (dt = 0); discretize it first "
            "(control.c2d, or symctl.discretize for (a, b))"
        )
    return sampling_time(float(dt), argname)


def _finite(arr, argname: str) -> np.ndarray:
    arr = np.asarray(arr)
    if np.iscomplexobj(arr):
        if np.any(arr.imag):
            raise ParameterError(f"{argname}: complex coefficients, expected real ones")
        arr = arr.real
    arr = np.asarray(arr, dtype=float)
    if not np.all(np.isfinite(arr)):
        raise ParameterError(f"{argname}: coefficients must be finite, got {arr.tolist()}")
    return arr


def _monic(num, den, where: str) -> tuple[np.ndarray, np.ndarray]:
    num = np.trim_zeros(np.atleast_1d(_finite(num, where)), "f")
    den = np.trim_zeros(np.atleast_1d(_finite(den, where)), "f")
    if den.size == 0:
        raise ParameterError(f"{where}: the denominator is zero")
    if num.size > den.size:
        raise ParameterError(
            f"{where}: improper (numerator degree above denominator's): not causal"
        )
    return (num if num.size else np.zeros(1)) / den[0], den / den[0]


def _column(entries: list[tuple[np.ndarray, np.ndarray]]) -> tuple[np.ndarray, ...]:
    """``(F, H, M, N)`` of one input column, ``entries`` monic ``(num, den)`` pairs."""
    distinct: list[np.ndarray] = []
    for _, den in entries:
        if not any(np.array_equal(den, d) for d in distinct):
            distinct.append(den)
    col_den = reduce(np.polymul, distinct, np.ones(1))
    r = col_den.size - 1
    a = col_den[1:]  # descending, z^{r-1} .. z^0
    M, N = np.zeros((len(entries), r)), np.zeros((len(entries), 1))
    for i, (num, den) in enumerate(entries):
        full = reduce(np.polymul, [d for d in distinct if not np.array_equal(d, den)], num)
        full = np.concatenate([np.zeros(r + 1 - full.size), full])
        N[i, 0] = full[0]
        M[i] = (full[1:] - full[0] * a)[::-1]  # ascending powers z^0 .. z^{r-1}
    F = np.eye(r, k=1)
    H = np.zeros((r, 1))
    if r:
        F[-1] = -a[::-1]
        H[-1, 0] = 1.0
    return F, H, M, N


def canonical_columns(nums, dens, argname: str) -> tuple[np.ndarray, ...]:
    r"""``(F, H, M, N)``: the column-wise controllable canonical form of ``nums[i][j]/dens[i][j]``
    (descending coefficients, ``[outputs][inputs]``): column :math:`j` over the product of its
    entries' distinct denominators, blocks on the diagonal in input order. Refuses improper,
    complex or non-finite entries (ParameterError), over ``MAX_STATES`` states (DimensionError)."""
    rows = len(nums)
    cols = len(nums[0]) if rows else 0
    if not rows or not cols:
        raise DimensionError(f"{argname}: a transfer function with no inputs or outputs")
    blocks = [
        _column([_monic(nums[i][j], dens[i][j], f"{argname}[{i}, {j}]") for i in range(rows)])
        for j in range(cols)
    ]
    n = sum(b[0].shape[0] for b in blocks)
    if n > MAX_STATES:
        raise DimensionError(f"{argname}: realizes with {n} states, more than {MAX_STATES}")
    F, H = (scipy.linalg.block_diag(*(b[k] for b in blocks)) for k in (0, 1))
    M, N = (np.hstack([b[k] for b in blocks]) for k in (2, 3))
    return F, H, M, N


def _labels(labels) -> tuple[str, ...]:
    """User labels when all are distinct identifiers, else () (python-control's ``x[0]``: defaults)."""
    names = tuple(labels or ())
    ok = all(isinstance(s, str) and s.isidentifier() for s in names)
    return names if ok and len(set(names)) == len(names) else ()


def plant_from_control(sys, argname: str = "plant") -> DiscretePlant:
    """A DiscretePlant from a discrete python-control system: a ``StateSpace``'s ``A``, ``B``, a
    ``TransferFunction`` by :func:`canonical_columns`; distinct identifier labels name states and
    inputs. Refuses continuous time or bad coefficients (ParameterError), another object
    (SymctlTypeError), no or too many states (DimensionError).

    >>> import control
    >>> from symctl.design._foreign import plant_from_control
    >>> sys = control.ss([[1, 0.1], [0, 1]], [[0], [0.1]], [[1, 0]], 0, 0.1,
    ...                  states=["pos", "vel"], inputs=["force"])
    >>> p = plant_from_control(sys)
    >>> p.state_names, p.input_names, p.dt
    (('pos', 'vel'), ('force',), 0.100000000000000)
    >>> plant_from_control(control.tf([2], [1, -0.5], True)).A
    Matrix([[0.5]])
    """
    import control

    if not isinstance(sys, control.StateSpace | control.TransferFunction):
        raise SymctlTypeError(
            f"{argname}: expected a python-control StateSpace or TransferFunction, "
            f"got {type(sys).__name__}"
        )
    Ts = control_dt(sys, argname)
    if isinstance(sys, control.TransferFunction):
        A, B, _, _ = canonical_columns(sys.num_array, sys.den_array, argname)
        states = ()
    else:
        A, B = _finite(sys.A, argname), _finite(sys.B, argname)
        states = _labels(sys.state_labels)
    if A.shape[0] == 0:
        raise DimensionError(f"{argname}: a static gain (no states) is not a plant")
    if A.shape[0] > MAX_STATES:
        raise DimensionError(f"{argname}: at most {MAX_STATES} states, got {A.shape[0]}")
    return DiscretePlant(A, B, Ts, states, _labels(sys.input_labels))
