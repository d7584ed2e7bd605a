"""symctl's exception types: one tree under :class:`SymctlError`.

Each also subclasses the matching built-in (``ValueError``, ``TypeError``), and each message
names the offending argument and its value; the command line prints it as one line, exit code 2.
"""

from __future__ import annotations

import functools

__all__ = [
    "DimensionError",
    "LatexError",
    "MissingDependencyError",
    "ModelFileError",
    "NotRealizableError",
    "NotStabilizableError",
    "ParameterError",
    "ParseError",
    "SymctlError",
    "SymctlTypeError",
]


class SymctlError(Exception):
    """Base class of every error symctl raises on bad input (values and types alike).

    Examples
    --------
    >>> import symctl
    >>> issubclass(symctl.SymctlTypeError, symctl.SymctlError)
    True
    """


class ParameterError(SymctlError, ValueError):
    """An argument has a value outside its admissible range (e.g. ``tau <= 0``).

    Examples
    --------
    >>> import symctl
    >>> symctl.MuscleModel(dt=0)
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: dt: must be a finite number > 0, got 0
    """


class DimensionError(SymctlError, ValueError):
    """Matrices or signals whose shapes do not fit together.

    Examples
    --------
    >>> import symctl
    >>> symctl.DiscretePlant([[1, 0], [0, 1]], [[1]])
    Traceback (most recent call last):
    ...
    symctl.errors.DimensionError: B: must have 2 rows like A, got shape (1, 1)
    """


class NotStabilizableError(SymctlError, ValueError):
    """The LQR problem has no stabilizing solution (not stabilizable or not detectable).

    Examples
    --------
    >>> import symctl
    >>> symctl.lqr_gains(symctl.augment(([[2]], [[0]]), 0, 1))
    Traceback (most recent call last):
    ...
    symctl.errors.NotStabilizableError: ...
    """


class ParseError(SymctlError, ValueError):
    """User text that is not an admissible expression.

    Examples
    --------
    >>> import symctl
    >>> symctl.DiscretePlant([["__import__('os')"]], [[1]])
    Traceback (most recent call last):
    ...
    symctl.errors.ParseError: A: function '__import__' is not allowed; use one of: ...
    """


class LatexError(SymctlError, RuntimeError):
    """``pdflatex`` failed on a document symctl wrote (a bug in symctl: please report it).

    Examples
    --------
    >>> from symctl import LatexError, SymctlError
    >>> issubclass(LatexError, SymctlError)
    True
    """


class SymctlTypeError(SymctlError, TypeError):
    """An argument of the wrong type.

    Examples
    --------
    >>> import symctl
    >>> symctl.MuscleModel(tau="fast")
    Traceback (most recent call last):
    ...
    symctl.errors.SymctlTypeError: tau: expected a real number, got 'fast'
    """


class MissingDependencyError(SymctlError, ImportError):
    """An optional package a function needs is not installed; the message says how to install it.

    Examples
    --------
    >>> from symctl import MissingDependencyError
    >>> issubclass(MissingDependencyError, ImportError)
    True
    """


class NotRealizableError(SymctlError, ValueError):
    """A controller that a circuit class (or every class of an atlas) cannot realize, and why.

    Examples
    --------
    >>> from symctl import NotRealizableError, ParameterError
    >>> issubclass(NotRealizableError, ValueError), issubclass(NotRealizableError, ParameterError)
    (True, False)
    """


class ModelFileError(ParameterError):
    """A model file that cannot be read: one line, ``FILE:LINE: FIELD: problem``.

    Its attributes ``path`` (``"<text>"`` for a string), ``line`` (1-based, None when not found)
    and ``field`` (a dotted path such as ``states[0].rhs``) say where.

    Examples
    --------
    >>> from symctl import ModelFileError
    >>> str(ModelFileError("no value", path="m.toml", line=3, field="parameters.tau"))
    'm.toml:3: parameters.tau: no value'
    """

    def __init__(self, problem: str, *, path: str = "<text>", line=None, field: str = ""):
        self.path, self.line, self.field, self.problem = path, line, field, problem
        where = f"{path}:{line}" if line else path
        super().__init__(f"{where}: {field}: {problem}" if field else f"{where}: {problem}")

    def __reduce__(self):
        """Pickled with its parts (the default would read the whole message as the problem)."""
        parts = {"path": self.path, "line": self.line, "field": self.field}
        return functools.partial(ModelFileError, **parts), (self.problem,)
