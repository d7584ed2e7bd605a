"""Public names loaded on first use (PEP 562), from one table ``{name: module}``.

>>> from symctl._util.lazy import attach
>>> getattr_, dir_, all_ = attach("symctl", {"z": "symctl.symbols"})
>>> all_
['z']
>>> getattr_("z")
z
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Iterable, Mapping


def attach(
    package: str, table: Mapping[str, str], submodules: Iterable[str] = ()
) -> tuple[Callable[[str], object], Callable[[], list[str]], list[str]]:
    """``(__getattr__, __dir__, __all__)`` for ``package`` from ``{name: module}``: a name is
    imported on first use and cached in the package; ``submodules`` are reached as attributes."""
    table = dict(table)
    subs = frozenset(submodules)
    names = sorted(table)

    def __getattr__(name: str):
        if name in subs:
            return importlib.import_module(f"{package}.{name}")
        module = table.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(module), name)
        setattr(sys.modules[package], name, value)
        return value

    def __dir__() -> list[str]:
        return sorted(set(vars(sys.modules[package])) | set(names) | subs)

    return __getattr__, __dir__, names
