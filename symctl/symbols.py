r"""The paper's symbols, made once, so that expressions built anywhere share them.

``tau``, ``f_max`` and ``T_s`` are positive, ``r_bar`` and all gains real; ``z`` carries no
assumption (the complex variable of the Z-transform).

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
    """Gain blocks ``K_0`` (``m x n``, on the state) and ``K_1 .. K_T`` (``m x m``, on the delayed
    inputs): the scalars of :func:`gain_symbols` when ``m = n = 1``, else ``K_{k,ij}`` (from 1)."""
    if m == 1 and n == 1:
        return tuple(sp.Matrix([[k]]) for k in gain_symbols(T))
    return tuple(
        sp.Matrix(
            m,
            n if k == 0 else m,
            lambda i, j, k=k: sp.Symbol(f"K_{{{k},{i + 1}{j + 1}}}", real=True),
        )
        for k in range(T + 1)
    )


@cache
def observer_gain_symbols(n: int, p: int, stem: str = "L") -> sp.ImmutableMatrix:
    """The Kalman gain (``n`` states, ``p`` outputs) as real symbols: ``L_1 .. L_n`` for one
    output, else ``L_{i,j}`` (from 1); ``stem`` ``"M"`` names the current form's gain.

    >>> from symctl.symbols import observer_gain_symbols
    >>> observer_gain_symbols(2, 1).T, observer_gain_symbols(1, 2)
    (Matrix([[L_1, L_2]]), Matrix([[L_{1,1}, L_{1,2}]]))
    """
    name = (
        (lambda i, j: f"{stem}_{i + 1}") if p == 1 else (lambda i, j: f"{stem}_{{{i + 1},{j + 1}}}")
    )
    return sp.ImmutableMatrix(n, p, lambda i, j: sp.Symbol(name(i, j), real=True))
