"""Conversions between symctl's objects and python-control / SciPy.

Kept in one small module (house style): :func:`tf_to_control` and
:func:`tf_from_control` for transfer functions, :func:`ss_to_control` and
:func:`ss_from_control` for realizations (the objects' ``to_control`` and
``from_control`` hand over to them). The sampling time is carried over
(``dt=True``, python-control's "discrete, unspecified", maps to ``None``).

>>> from symctl import z
>>> from symctl import DiscreteTF
>>> from symctl.interop import tf_from_control, tf_to_control
>>> sys = tf_to_control(DiscreteTF.from_expr(2 / (z - 0.5), dt=0.01))
>>> sys.dt
0.01
>>> tf_from_control(sys).expr
2.0/(z - 0.5)
"""

from __future__ import annotations

import control
import numpy as np
import sympy as sp

from symctl.design.tf import DiscreteTF
from symctl.errors import ParameterError, SymctlTypeError
from symctl.realization.realization import Realization
from symctl.symbols import z

__all__ = ["ss_from_control", "ss_to_control", "tf_from_control", "tf_to_control"]


def _floats(coeffs, what: str) -> list[float]:
    try:
        return [float(c) for c in coeffs]
    except TypeError:
        raise ParameterError(f"G: {what} has free symbols; substitute numbers first") from None


def tf_to_control(G: DiscreteTF) -> control.TransferFunction:
    """``control.TransferFunction`` (dt kept) of a numeric :class:`DiscreteTF`."""
    if not isinstance(G, DiscreteTF):
        raise SymctlTypeError(f"G: expected a DiscreteTF, got {type(G).__name__}")
    den = _floats(G.den_coeffs(), "the denominator")
    rows, cols = G.shape
    nums = [
        [_floats(G.num_coeffs(i, j), "the numerator") for j in range(cols)] for i in range(rows)
    ]
    dens = [[den for _ in range(cols)] for _ in range(rows)]
    dt = True if G.dt is None else float(G.dt)
    if G.is_siso:
        return control.tf(nums[0][0], den, dt)
    return control.tf(nums, dens, dt)


def _discrete(sys) -> None:
    if not isinstance(sys, control.LTI):
        raise SymctlTypeError(f"sys: expected a python-control system, got {type(sys).__name__}")
    if not sys.isdtime():
        raise ParameterError("sys: a continuous-time system; discretize it first (control.c2d)")


def tf_from_control(sys) -> DiscreteTF:
    """A :class:`DiscreteTF` from a discrete python-control system (TF or state space)."""
    _discrete(sys)
    tf = control.tf(sys)
    rows, cols = tf.noutputs, tf.ninputs
    entries = sp.zeros(rows, cols)
    for i in range(rows):
        for j in range(cols):
            num = sp.Poly(np.atleast_1d(tf.num_array[i, j]).tolist(), z).as_expr()
            den = sp.Poly(np.atleast_1d(tf.den_array[i, j]).tolist(), z).as_expr()
            entries[i, j] = num / den
    dt = None if sys.dt is True else sys.dt
    return DiscreteTF.from_expr(entries if (rows, cols) != (1, 1) else entries[0, 0], dt=dt)


def ss_to_control(R: Realization) -> control.StateSpace:
    """A discrete ``control.StateSpace`` of a numeric :class:`~symctl.Realization` (dt kept).

    >>> from symctl import Realization
    >>> from symctl.interop import ss_to_control
    >>> ss_to_control(Realization([[0.5]], [[1]], [[2]], 0, dt=0.1)).dt
    0.1
    """
    if not isinstance(R, Realization):
        raise SymctlTypeError(f"R: expected a Realization, got {type(R).__name__}")
    F, H, M, N = R.numeric()
    return control.ss(F, H, M, N, True if R.dt is None else float(R.dt))


def ss_from_control(sys) -> Realization:
    """A :class:`~symctl.Realization` of a discrete python-control system (made state space).

    >>> import control
    >>> from symctl.interop import ss_from_control
    >>> ss_from_control(control.tf([1], [1, -0.5], 0.1)).to_tf().expr
    1.0/(z - 0.5)
    """
    _discrete(sys)
    ss = control.ss(sys)
    dt = None if ss.dt is True else ss.dt
    return Realization(ss.A, ss.B, ss.C, ss.D, dt)
