r"""The paper's symbols, made once.

Every module takes its symbols from here, so that expressions built in
different places share the same :class:`sympy.Symbol` objects and print as in
the paper: :math:`K_0, \dots, K_T`, :math:`\epsilon_1`, :math:`C_1`,
:math:`\tau`, :math:`f_{max}`, :math:`\bar r`, :math:`T_s` and :math:`z`.

Assumptions: the plant parameters ``tau``, ``f_max`` and ``T_s`` are positive,
``r_bar`` and all gains are real; ``z`` carries no assumption (it is the
complex variable of the Z-transform).

>>> from symctl.symbols import z, gain_symbols
>>> gain_symbols(2)
(K_0, K_1, K_2)
"""

from __future__ import annotations

from functools import cache

import sympy as sp

__all__ = [
    "C_1",
    "C_3",
    "T_s",
    "delta_f",
    "delta_r",
    "epsilon_1",
    "epsilon_3",
    "f",
    "f_max",
    "gain_symbols",
    "gamma",
    "mu",
    "r",
    "r_bar",
    "tau",
    "z",
]

z = sp.Symbol("z")
tau = sp.Symbol("tau", positive=True)
f_max = sp.Symbol("f_max", positive=True)
r_bar = sp.Symbol("r_bar", real=True)
T_s = sp.Symbol("T_s", positive=True)

f = sp.Symbol("f", real=True)
r = sp.Symbol("r", real=True)
delta_f = sp.Symbol("delta_f", real=True)
delta_r = sp.Symbol("delta_r", real=True)
gamma = sp.Symbol("gamma", real=True)
mu = sp.Symbol("mu", real=True)

epsilon_1 = sp.Symbol("epsilon_1", real=True)
epsilon_3 = sp.Symbol("epsilon_3", real=True)
C_1 = sp.Symbol("C_1", real=True)
C_3 = sp.Symbol("C_3", real=True)


@cache
def gain_symbols(T: int) -> tuple[sp.Symbol, ...]:
    """The scalar gains ``(K_0, K_1, ..., K_T)`` of the paper, as real symbols."""
    return tuple(sp.Symbol(f"K_{k}", real=True) for k in range(T + 1))


@cache
def gain_matrix_symbols(T: int, m: int, n: int) -> tuple[sp.Matrix, ...]:
    """Gain blocks ``(K_0, ..., K_T)`` for a plant with ``n`` states and ``m`` inputs.

    ``K_0`` is ``m x n`` (it multiplies the plant state), ``K_1 .. K_T`` are
    ``m x m`` (they multiply the delayed copies of the intended actuation).
    With ``m = n = 1`` the entries are the scalar symbols of :func:`gain_symbols`;
    otherwise entry ``(i, j)`` of ``K_k`` is the real symbol ``K_{k,ij}``
    (indices from 1, as in a paper).
    """
    if m == 1 and n == 1:
        return tuple(sp.Matrix([[k]]) for k in gain_symbols(T))
    blocks = []
    for k in range(T + 1):
        cols = n if k == 0 else m
        blocks.append(
            sp.Matrix(m, cols, lambda i, j, k=k: sp.Symbol(f"K_{{{k},{i + 1}{j + 1}}}", real=True))
        )
    return tuple(blocks)


@cache
def observer_gain_symbols(n: int, p: int, stem: str = "L") -> sp.ImmutableMatrix:
    """The Kalman gain on the plant's ``n`` states from ``p`` outputs, as real symbols.

    With one output the entries are ``L_1 .. L_n`` (one per state); otherwise entry
    ``(i, j)`` is ``L_{i,j}`` (indices from 1). ``stem`` ``"M"`` names the current form's gain.

    >>> from symctl.symbols import observer_gain_symbols
    >>> observer_gain_symbols(2, 1).T, observer_gain_symbols(1, 2)
    (Matrix([[L_1, L_2]]), Matrix([[L_{1,1}, L_{1,2}]]))
    """
    name = (
        (lambda i, j: f"{stem}_{i + 1}") if p == 1 else (lambda i, j: f"{stem}_{{{i + 1},{j + 1}}}")
    )
    return sp.ImmutableMatrix(n, p, lambda i, j: sp.Symbol(name(i, j), real=True))
