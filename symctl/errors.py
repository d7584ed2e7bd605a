"""symctl's exception types: one tree under :class:`SymctlError`.

Every error that bad input can cause is one of these, so ``except SymctlError``
catches them all. Each also subclasses the matching built-in, so ``except
ValueError`` and ``except TypeError`` keep working:

- a value outside its admissible range: :class:`ParameterError` (a ``ValueError``);
- shapes that do not fit: :class:`DimensionError` (a ``ValueError``);
- user text that is not an admissible expression: :class:`ParseError` (a ``ValueError``);
- an argument of the wrong type: :class:`SymctlTypeError` (a ``TypeError``);
- an LQR problem without a stabilizing solution: :class:`NotStabilizableError`;
- ``pdflatex`` failing on a document symctl wrote: :class:`LatexError`.

Each message names the offending argument and its value. The command line
turns them into a one-line message and exit code 2.

Examples
--------
>>> import symctl
>>> try:
...     symctl.MuscleModel(tau=-1)
... except symctl.SymctlError as err:
...     print(type(err).__name__, err)
ParameterError tau: must be a finite number > 0, got -1
>>> issubclass(symctl.SymctlTypeError, symctl.SymctlError)
True
"""

from __future__ import annotations

__all__ = [
    "DimensionError",
    "LatexError",
    "NotStabilizableError",
    "ParameterError",
    "ParseError",
    "SymctlError",
    "SymctlTypeError",
]


class SymctlError(Exception):
    """Base class of every error symctl raises on bad input (values and types alike)."""


class ParameterError(SymctlError, ValueError):
    """An argument has a value outside its admissible range (e.g. ``tau <= 0``)."""


class DimensionError(SymctlError, ValueError):
    """Matrices or signals whose shapes do not fit together."""


class NotStabilizableError(SymctlError, ValueError):
    """The LQR problem has no stabilizing solution (not stabilizable or not detectable)."""


class ParseError(SymctlError, ValueError):
    """User text that is not an admissible expression."""


class LatexError(SymctlError, RuntimeError):
    """``pdflatex`` failed on a document symctl wrote (a bug in symctl: please report it)."""


class SymctlTypeError(SymctlError, TypeError):
    """An argument of the wrong type."""
