r"""LaTeX export of derived objects, sympy expressions and equations, with the paper's symbol
names (:math:`\delta_f`, :math:`\epsilon_1`, ...), for papers, Jupyter and scripts.

:func:`to_latex` writes one object as bare math, :func:`equations` splits a derived object into
``(lhs, rhs)`` pairs, :func:`equation`, :func:`align` and :func:`export` wrap them in an
environment and :func:`document` in a standalone document. Floats get ``digits`` significant
digits (an integer >= 1). A bad ``digits``, ``label`` (a LaTeX label: letters, digits and
``:._-``), ``labels`` count, ``name`` for several equations or package name is a
ParameterError naming it; an object that cannot be written is a SymctlTypeError.

>>> from symctl import controllable_canonical, controller_tf, factor
>>> from symctl.latex import align, document, export, number
>>> number(0.000123456789), number(float("inf")), number(1e20)
('0.000123457', '\\infty', '1 \\times 10^{20}')
>>> print(align([("a", 1), ("b", 2)], labels=["eq:a", None]))
\begin{align}
  a &= 1 \label{eq:a} \\
  b &= 2
\end{align}
>>> print(export(controllable_canonical(factor(controller_tf(2)).G2), numbered=False))
\begin{align*}
  F &= \left[\begin{matrix}0 & 1\\K_{2} & K_{1}\end{matrix}\right] \\
  H &= \left[\begin{matrix}0\\1\end{matrix}\right] \\
  M &= \left[...
>>> document(export(1.5, name="a"), title="Demo").splitlines()[0]
'\\documentclass[11pt]{article}'
"""

from __future__ import annotations

import functools
import math
import numbers
import re
from collections.abc import Callable, Iterable, Mapping

import numpy as np
import sympy as sp

from symctl._util.display import latex as _sympy_latex
from symctl._util.validate import positive_int
from symctl.errors import ParameterError, SymctlTypeError

__all__ = ["align", "document", "equation", "equations", "export", "number", "to_latex"]

DIGITS = 6
"""Significant digits of numbers written by :func:`to_latex`."""

_LABEL = re.compile(r"[A-Za-z0-9:._\-]+")
Pairs = list[tuple[str | None, str]]
PACKAGES = ("amsmath", "amssymb", "graphicx")
"""The packages :func:`document` loads (all in TeX Live's ``texlive-latex-base``)."""


def number(value: float, digits: int = DIGITS) -> str:
    r"""A real number in LaTeX: ``digits`` significant digits, ``\times 10^{n}``, ``\infty``, NaN."""
    x = float(value)
    if math.isnan(x):
        return r"\mathrm{NaN}"
    if math.isinf(x):
        return r"\infty" if x > 0 else r"-\infty"
    text = f"{x:.{digits}g}"
    mantissa, e, exponent = text.partition("e")
    if not e:
        return text
    return rf"{mantissa} \times 10^{{{int(exponent)}}}"


def _array_latex(arr: np.ndarray, digits: int) -> str:
    if arr.ndim == 0:
        return number(arr, digits)
    rows = arr.reshape(arr.shape[0], -1) if arr.ndim == 2 else arr.reshape(-1, 1)
    if arr.ndim > 2:
        raise ParameterError(f"obj: arrays of at most 2 dimensions, got shape {arr.shape}")
    body = r" \\ ".join(" & ".join(number(v, digits) for v in row) for row in rows)
    return r"\begin{bmatrix}" + body + r"\end{bmatrix}"


def _round_floats(expr, digits: int):
    """``expr`` with its floats shortened to ``digits`` significant digits."""
    floats = {f: sp.Float(f, digits) for f in expr.atoms(sp.Float)}
    return expr.xreplace(floats) if floats else expr


def to_latex(obj, *, digits: int = DIGITS) -> str:
    r"""LaTeX of one object, without an environment.

    ``obj`` is a sympy expression, matrix or ``Eq``; a number or array of at most 2 dimensions
    (a ``bmatrix``); a string (LaTeX already); or anything with a ``latex()`` method (every
    derived object of symctl); anything else is a SymctlTypeError.
    """
    positive_int(digits, "digits")
    if isinstance(obj, str):
        return obj
    if isinstance(obj, sp.Basic | sp.MatrixBase):
        return _sympy_latex(_round_floats(obj, digits))
    if isinstance(obj, numbers.Number) and not isinstance(obj, bool):
        if isinstance(obj, numbers.Integral):
            return str(int(obj))
        return number(obj, digits)
    if isinstance(obj, np.ndarray | list | tuple):
        try:
            arr = np.asarray(obj, dtype=float)
        except (TypeError, ValueError):
            arr = None
        if arr is not None:
            return _array_latex(arr, digits)
        if isinstance(obj, list | tuple) and obj and all(isinstance(e, sp.Basic) for e in obj):
            return _sympy_latex(sp.Matrix(obj))
    method = getattr(obj, "latex", None)
    if callable(method):
        return method()
    raise SymctlTypeError(
        f"obj: cannot write a {type(obj).__name__} as LaTeX (expected a sympy object, a number, "
        "an array, a string or a derived object of symctl)"
    )


@functools.cache
def _rules() -> dict[type, Callable[[object, Callable[[object], str]], Pairs]]:
    """The equations of each derived type, ``rule(obj, tex)``; built on first use."""
    from symctl.compatibility.assignment import DelayAssignment
    from symctl.compatibility.check import CompatibilityResult
    from symctl.compatibility.controller import ControllerCompatibility
    from symctl.compatibility.delaygraph import DelayGraph
    from symctl.design.augment import AugmentedSystem
    from symctl.design.lqr import Gains
    from symctl.design.plant import DiscretePlant, Linearization, MuscleModel
    from symctl.design.tf import DiscreteTF
    from symctl.neural.circuit import Circuit
    from symctl.realization.factorization import Factorization
    from symctl.realization.realization import Realization

    def compatibility(obj, tex) -> Pairs:
        if obj.ok:
            return [(r"\tilde E", tex(obj.E_tilde) + r" \ge E")]
        return [(None, r"\text{not compatible (" + obj.method + ")}")]

    return {
        MuscleModel: lambda o, tex: [
            (r"\frac{df}{dt}", tex(o.ode)),
            (r"\bar f", tex(o.f_bar_symbolic)),
        ],
        Linearization: lambda o, tex: [("a", tex(o.a)), ("b", tex(o.b))],
        DiscretePlant: lambda o, tex: [("A", tex(o.A)), ("B", tex(o.B))],
        AugmentedSystem: lambda o, tex: [
            (r"\chi", tex(o.chi)),
            (r"\tilde A", tex(o.A)),
            (r"\tilde B", tex(o.B)),
            (r"\tilde Q", tex(o.Q)),
        ],
        Gains: lambda o, tex: [("K", tex(np.asarray(o.K, dtype=float)))],
        DiscreteTF: lambda o, tex: [("G(z)", o.latex())],
        Factorization: lambda o, tex: [
            ("G_1(z)", o.G1.latex()),
            ("G_2(z)", o.G2.latex()),
            ("G_3(z)", o.G3.latex()),
            ("N", tex(o.N)),
        ],
        Realization: lambda o, tex: [(k, tex(getattr(o, k))) for k in "FHMN"],
        DelayGraph: lambda o, tex: [("E", tex(o.E))],
        DelayAssignment: lambda o, tex: [(r"\tilde E", tex(o.E_tilde))],
        CompatibilityResult: compatibility,
        ControllerCompatibility: lambda o, tex: [(None, o.latex())],
        Circuit: lambda o, tex: [tuple(eq.split(" = ", 1)) for eq in o.equations()],
    }


def equations(obj, *, digits: int = DIGITS) -> list[tuple[str | None, str]]:
    r"""``obj`` as a list of ``(lhs, rhs)`` LaTeX pairs (``lhs`` None: a bare formula).

    ``obj`` is a derived object (a plant gives ``A`` and ``B``, a realization ``F, H, M, N``, a
    circuit one equation per neuron, ...), a ``sympy.Eq``, a pair, a mapping ``{lhs: rhs}``, or
    a list of these; anything else is one bare formula.
    """

    def tex(value) -> str:
        return to_latex(value, digits=digits)

    if isinstance(obj, sp.Eq):
        return [(tex(obj.lhs), tex(obj.rhs))]
    rules = _rules()
    for cls in type(obj).__mro__:
        if cls in rules:
            return rules[cls](obj, tex)
    if isinstance(obj, Mapping):
        return [(tex(k), tex(v)) for k, v in obj.items()]
    if isinstance(obj, tuple) and len(obj) == 2 and not isinstance(obj[0], tuple):
        return [(None if obj[0] is None else tex(obj[0]), tex(obj[1]))]
    if isinstance(obj, list | tuple):
        return [pair for item in obj for pair in equations(item, digits=digits)]
    return [(None, tex(obj))]


def _label(label) -> str:
    if label is None:
        return ""
    if not isinstance(label, str) or not _LABEL.fullmatch(label):
        raise ParameterError(
            f"label: must be letters, digits and ':._-' only (a LaTeX label), got {label!r}"
        )
    return rf"\label{{{label}}}"


def equation(lhs, rhs=None, *, label: str | None = None, numbered: bool = True) -> str:
    r"""An ``equation`` environment ``lhs = rhs`` (``lhs`` alone when ``rhs`` is None); ``label``
    (letters, digits and ``:._-``) only when ``numbered``, else ``equation*``."""
    body = to_latex(lhs) if rhs is None else f"{to_latex(lhs)} = {to_latex(rhs)}"
    env = "equation" if numbered else "equation*"
    tag = _label(label) if numbered else ""
    lines = [rf"\begin{{{env}}}", f"  {body}"] + ([f"  {tag}"] if tag else [])
    return "\n".join([*lines, rf"\end{{{env}}}"])


def align(
    rows: Iterable,
    *,
    labels: Iterable[str | None] | None = None,
    numbered: bool = True,
) -> str:
    r"""An ``align`` environment, one row per equation of ``rows`` (as for :func:`equations`),
    aligned at ``=``, with one label or None per row; ``align*`` without labels when not
    ``numbered``."""
    pairs = equations(list(rows) if not isinstance(rows, Mapping) else rows)
    if not pairs:
        raise ParameterError("rows: no equations to write")
    tags = [None] * len(pairs) if labels is None else list(labels)
    if len(tags) != len(pairs):
        raise ParameterError(f"labels: expected {len(pairs)} labels (one per row), got {len(tags)}")
    env = "align" if numbered else "align*"
    lines = []
    for (lhs, rhs), tag in zip(pairs, tags, strict=True):
        row = f"{lhs} &= {rhs}" if lhs is not None else f"& {rhs}"
        tex = _label(tag) if numbered else ""
        lines.append(f"  {row} {tex}".rstrip())
    return "\n".join([rf"\begin{{{env}}}", " \\\\\n".join(lines), rf"\end{{{env}}}"])


def export(
    obj,
    *,
    name: str | None = None,
    label: str | None = None,
    numbered: bool = True,
    digits: int = DIGITS,
) -> str:
    r"""Anything :func:`equations` accepts as one ``equation`` (its left side ``name`` when given)
    or, for several, an ``align`` with ``label`` on its first row."""
    pairs = equations(obj, digits=digits)
    if not pairs:
        raise ParameterError("obj: no equations to write")
    if len(pairs) == 1:
        lhs, rhs = pairs[0]
        lhs = name if name is not None else lhs
        return equation(
            rhs if lhs is None else lhs,
            None if lhs is None else rhs,
            label=label,
            numbered=numbered,
        )
    if name is not None:
        raise ParameterError(f"name: only for a single equation; this object has {len(pairs)}")
    return align(pairs, labels=[label] + [None] * (len(pairs) - 1), numbered=numbered)


def document(
    body: str | Iterable[str],
    *,
    title: str = "",
    author: str = "",
    packages: Iterable[str] = (),
    preamble: str = "",
) -> str:
    r"""A standalone ``article`` around ``body`` (parts separated by blank lines), loading
    ``geometry``, :data:`PACKAGES` and ``packages``; ``\maketitle`` (no date) when titled."""
    extra = list(packages)
    for p in extra:
        if not isinstance(p, str) or not re.fullmatch(r"[A-Za-z0-9\-]+", p):
            raise ParameterError(f"packages: expected package names, got {p!r}")
    parts = [body] if isinstance(body, str) else list(body)
    head = [
        r"\documentclass[11pt]{article}",
        r"\usepackage[margin=2cm]{geometry}",
        *(rf"\usepackage{{{p}}}" for p in (*PACKAGES, *extra)),
        r"\allowdisplaybreaks",
        r"\setcounter{MaxMatrixCols}{20}",
        *([preamble] if preamble else []),
    ]
    if title:
        head += [rf"\title{{{title}}}", rf"\author{{{author}}}", r"\date{}"]
    start = [r"\begin{document}"] + ([r"\maketitle"] if title else [])
    return "\n".join([*head, *start, "", "\n\n".join(parts), "", r"\end{document}", ""])
