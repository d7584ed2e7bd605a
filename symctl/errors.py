"""symctl's exception types.

Every error that bad input can cause is one of these. They subclass the
built-in :class:`ValueError` or :class:`TypeError`, so ``except ValueError``
keeps working, and each message names the offending argument and its value.
The command line turns them into a one-line message and exit code 2.
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


class SymctlError(ValueError):
    """Base class of symctl's value errors."""


class ParameterError(SymctlError):
    """An argument has a value outside its admissible range (e.g. ``tau <= 0``)."""


class DimensionError(SymctlError):
    """Matrices or signals whose shapes do not fit together."""


class NotStabilizableError(SymctlError):
    """The LQR problem has no stabilizing solution (not stabilizable or not detectable)."""


class ParseError(SymctlError):
    """User text that is not an admissible expression."""


class LatexError(SymctlError):
    """``pdflatex`` failed on a document symctl wrote (a bug in symctl: please report it)."""


class SymctlTypeError(TypeError):
    """An argument of the wrong type."""
