r"""LaTeX and text display with the paper's spelling of the symbols, polynomials in descending powers.

>>> from symctl import z
>>> from symctl._util.display import descending_latex, descending_str, latex
>>> from symctl.symbols import epsilon_1, epsilon_3, f_max, r_bar
>>> latex(f_max / (1 + r_bar))
'\\frac{f_\\text{max}}{\\bar{r} + 1}'
>>> descending_str(z**2 - (epsilon_1 + epsilon_3) * z + epsilon_1 * epsilon_3)
'z**2 - (epsilon_1 + epsilon_3)*z + epsilon_1*epsilon_3'
>>> descending_latex(1 - z**2 / 2)
'-\\frac{1}{2} z^{2} + 1'
"""

from __future__ import annotations

import sympy as sp

from symctl import symbols as S
from symctl._util.exact import z_poly
from symctl._util.texnames import GREEK
from symctl.symbols import z

DISPLAY_DIGITS = 6  # significant digits of the floats an object prints (its str, repr and LaTeX)

_NAMES = {
    S.r_bar: r"\bar{r}",
    S.f_max: r"f_\text{max}",
    S.delta_f: r"\delta_f",
    S.delta_r: r"\delta_r",
}


def _indexed_name(symbol: sp.Symbol) -> str | None:
    """``epsilon_{3,1}`` -> ``\\epsilon_{3,1}`` (sympy leaves braced names alone)."""
    stem, sep, rest = symbol.name.partition("_{")
    return _stem(stem) + "_{" + rest if sep else None


def _stem(text: str) -> str:
    return "\\" + text if text in GREEK else text


def _word_name(symbol: sp.Symbol) -> str | None:
    r"""Names in the paper's style, for any symbol: ``x_bar`` -> :math:`\bar x`,
    ``u_max`` -> :math:`u_\text{max}`, ``delta_theta`` -> :math:`\delta_\theta`."""
    stem, sep, rest = symbol.name.partition("_")
    if not sep or not stem.isalpha():
        return None
    if rest == "bar" and len(stem) <= 8:
        return rf"\bar{{{_stem(stem)}}}"
    if stem == "delta" and rest.isidentifier():
        inner = _word_name(sp.Symbol(rest)) or sp.latex(sp.Symbol(rest))
        return rf"\delta_{{{inner}}}"
    if rest.isalpha() and len(rest) > 1 and rest not in GREEK:
        return rf"{_stem(stem)}_\text{{{rest}}}"
    return None


def shortened(expr, digits: int = DISPLAY_DIGITS):
    """``expr`` with its floats to ``digits`` significant digits for display (one that rounds
    to an integer becomes it: ``z**2``, not ``1.0*z**2``); exact numbers as they are."""
    if not isinstance(expr, sp.Basic | sp.MatrixBase):
        return expr
    floats = {}
    for f in expr.atoms(sp.Float):
        text = f"{float(f):.{digits}g}"
        value = float(text)
        if value.is_integer() and "e" not in text:
            floats[f] = sp.Integer(int(value))
        else:  # as many digits as the text has, so that it prints as written
            mantissa = text.lstrip("-").partition("e")[0].replace(".", "").lstrip("0")
            floats[f] = sp.Float(text, max(len(mantissa), 1))
    return expr.xreplace(floats) if floats else expr


def latex(expr, **settings) -> str:
    """LaTeX of a sympy object with the paper's symbol names (``x_bar`` as :math:`\bar x`, ...)."""
    names = dict(_NAMES)
    if isinstance(expr, sp.Basic | sp.MatrixBase):
        for sym in expr.free_symbols:
            if not isinstance(sym, sp.Symbol) or sym in names:
                continue
            tex = _indexed_name(sym) or _word_name(sym)
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


def _descending(expr: sp.Expr, printer, times: str, digits: int | None = None) -> str:
    """A polynomial in z as ``sign coefficient z^k`` terms in descending powers (sums in parentheses)."""
    poly = z_poly(expr)
    if poly.is_zero:
        return "0"
    terms = []
    for (power,), coeff in poly.terms():
        coeff = sp.factor_terms(coeff if digits is None else shortened(coeff, digits))
        negative = coeff.could_extract_minus_sign()
        mag = -coeff if negative else coeff
        if power == 0:
            body = printer(mag)
        else:
            zpart = printer(z**power)
            if mag == 1:
                body = zpart
            else:
                ctext = printer(mag)
                if isinstance(mag, sp.Add):
                    ctext = rf"\left({ctext}\right)" if printer is latex else f"({ctext})"
                body = f"{ctext}{times}{zpart}"
        sign = ("- " if negative else "+ ") if terms else ("-" if negative else "")
        terms.append(sign + body)
    return " ".join(terms)


def descending_latex(expr: sp.Expr, digits: int | None = None) -> str:
    """LaTeX of a polynomial in z in descending powers, floats :func:`shortened` to ``digits``."""
    return _descending(expr, latex, " ", digits)


def descending_str(expr: sp.Expr, digits: int | None = None) -> str:
    """Plain text of a polynomial in z in descending powers, floats :func:`shortened` to ``digits``."""
    return _descending(expr, sp.sstr, "*", digits)
