"""A structure's equations, one per adder and delay (the methods of :class:`Structure`)."""

from __future__ import annotations

import sympy as sp

__all__ = ["structure_equations", "structure_latex"]


def structure_equations(S) -> list[sp.Eq]:
    r"""``S.equations()``: one equation per adder and delay, with the gains written into them.

    >>> from symctl import ifp_structure
    >>> from symctl.compatibility.equations import structure_equations
    >>> structure_equations(ifp_structure(2))[-1]
    Eq(mu(t), K_0*x(t) + K_1*gamma(t) + K_2*u(t))
    """
    return S.equations()


def structure_latex(S) -> str:
    """``S.latex()``: the equations of ``S`` as an ``aligned`` block."""
    return S.latex()
