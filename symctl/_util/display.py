r"""LaTeX display shared by every derived object.

:func:`latex` is :func:`sympy.latex` with the paper's spelling of the symbols
(:math:`\bar r`, :math:`f_\text{max}`, :math:`\delta_f`, ...). Classes that
define ``latex()`` get ``_repr_latex_`` for Jupyter from :class:`LatexMixin`.

>>> from symctl.symbols import r_bar, f_max
>>> latex(f_max / (1 + r_bar))
'\\frac{f_\\text{max}}{\\bar{r} + 1}'
"""

from __future__ import annotations

import sympy as sp

from symctl import symbols as S

__all__ = ["LatexMixin", "latex"]

_NAMES = {
    S.r_bar: r"\bar{r}",
    S.f_max: r"f_\text{max}",
    S.delta_f: r"\delta_f",
    S.delta_r: r"\delta_r",
    S.f: "f",
    S.r: "r",
}


_GREEK = {
    "alpha",
    "beta",
    "gamma",
    "delta",
    "epsilon",
    "zeta",
    "eta",
    "theta",
    "kappa",
    "lambda",
    "mu",
    "nu",
    "xi",
    "pi",
    "rho",
    "sigma",
    "tau",
    "phi",
    "chi",
    "psi",
    "omega",
}


def _indexed_name(symbol: sp.Symbol) -> str | None:
    """``epsilon_{3,1}`` -> ``\\epsilon_{3,1}`` (sympy leaves braced names alone)."""
    stem, sep, rest = symbol.name.partition("_{")
    if not sep:
        return None
    return ("\\" + stem if stem in _GREEK else stem) + "_{" + rest


def latex(expr, **settings) -> str:
    """LaTeX of a sympy object with the paper's symbol names."""
    names = dict(_NAMES)
    if isinstance(expr, sp.Basic | sp.MatrixBase):
        for sym in expr.free_symbols:
            tex = _indexed_name(sym) if isinstance(sym, sp.Symbol) else None
            if tex:
                names[sym] = tex
    names.update(settings.pop("symbol_names", {}))
    return sp.latex(expr, symbol_names=names, **settings)


class LatexMixin:
    """Gives ``_repr_latex_`` to a class that defines ``latex()``."""

    def latex(self) -> str:  # pragma: no cover - every subclass overrides it
        raise NotImplementedError

    def _repr_latex_(self) -> str:
        return f"$\\displaystyle {self.latex()}$"
