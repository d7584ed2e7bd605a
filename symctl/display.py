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


def latex(expr, **settings) -> str:
    """LaTeX of a sympy object with the paper's symbol names."""
    names = dict(_NAMES)
    names.update(settings.pop("symbol_names", {}))
    return sp.latex(expr, symbol_names=names, **settings)


class LatexMixin:
    """Gives ``_repr_latex_`` to a class that defines ``latex()``."""

    def latex(self) -> str:  # pragma: no cover - every subclass overrides it
        raise NotImplementedError

    def _repr_latex_(self) -> str:
        return f"$\\displaystyle {self.latex()}$"
