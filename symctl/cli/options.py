"""Errors on a Python argument, reworded with the command-line option that gave it.

``symctl paper --ts 0`` calls ``derive_paper(dt=0)``; the error names ``--ts``.

>>> from symctl.cli.options import options_named
>>> from symctl.errors import ParameterError
>>> try:
...     with options_named({"dt": "--ts"}):
...         raise ParameterError("dt: must be a finite number > 0, got 0")
... except ParameterError as exc:
...     print(exc)
--ts: must be a finite number > 0, got 0
"""

from __future__ import annotations

import contextlib

from symctl.errors import ParameterError, SymctlTypeError

__all__ = ["options_named"]


@contextlib.contextmanager
def options_named(options: dict):
    """Name the option, not the Python argument, in an error on an argument of ``options``."""
    try:
        yield
    except (ParameterError, SymctlTypeError) as exc:
        name, sep, rest = str(exc).partition(": ")
        if not sep or name not in options:
            raise
        raise type(exc)(f"{options[name]}: {rest}") from exc
