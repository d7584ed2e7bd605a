"""Old spellings of the public API (``seed``, ``Ts``, ...), kept for one release: they work and warn.

>>> import warnings
>>> from symctl._util.deprecate import renamed_keywords
>>> step = renamed_keywords(Ts="dt")(lambda *, dt=1: dt)
>>> with warnings.catch_warnings(record=True) as caught:
...     warnings.simplefilter("always")
...     step(Ts=3), caught[0].category.__name__
(3, 'DeprecationWarning')
"""

from __future__ import annotations

import functools
import inspect
import warnings
from collections.abc import Mapping

from symctl._util.validate import as_generator, as_random
from symctl.errors import SymctlTypeError


def warn_deprecated(old: str, new: str, where: str, stacklevel: int = 3) -> None:
    """Warn that ``old`` is the deprecated spelling of ``new`` in ``where``."""
    warnings.warn(
        f"{where}: {old!r} is deprecated and will be removed; use {new!r}",
        DeprecationWarning,
        stacklevel=stacklevel,
    )


def _moved(kwargs: dict, renames: dict, where: str) -> dict:
    for old, new in renames.items():
        if old in kwargs:
            if new in kwargs:
                raise SymctlTypeError(f"{where}: give {new!r} only ({old!r} is its old name)")
            warn_deprecated(old, new, where, stacklevel=4)
            kwargs[new] = kwargs.pop(old)
    return kwargs


def renamed_keywords(**renames: str):
    """A decorator: each keyword ``old=new`` of ``renames`` is accepted as ``new``, with a warning
    (also on a dataclass's ``__init__``)."""

    def decorate(func):
        where = func.__qualname__.removesuffix(".__init__")

        @functools.wraps(func)
        def wrapper(*args, **kwargs):
            return func(*args, **_moved(kwargs, renames, where))

        return wrapper

    return decorate


def renamed_attribute(old: str, new: str) -> property:
    """A read-only property ``old`` that warns and returns the attribute (or method) ``new``."""

    def getter(self):
        warn_deprecated(old, new, type(self).__name__)
        return getattr(self, new)

    getter.__name__ = old
    getter.__doc__ = f"Deprecated name of ``{new}``."
    return property(getter)


def rng_argument(kind: str = "numpy"):
    """A decorator: the keyword-only ``rng`` (an int seed, a Generator or None; ``seed=`` is its
    old name) becomes a NumPy ``Generator``, or with ``kind="random"`` a ``random.Random``."""
    convert = {"numpy": as_generator, "random": as_random}[kind]

    def decorate(func):
        param = inspect.signature(func).parameters["rng"]
        assert param.kind is inspect.Parameter.KEYWORD_ONLY, func
        where = func.__qualname__

        @functools.wraps(func)
        def wrapper(*args, **kwargs):
            kwargs = _moved(kwargs, {"seed": "rng"}, where)
            kwargs["rng"] = convert(kwargs.get("rng", param.default), "rng")
            return func(*args, **kwargs)

        return wrapper

    return decorate


class RenamedKeys(Mapping):
    """A read-only mapping whose old key names (``renamed(old)`` -> new) still work, with a warning.

    >>> import warnings
    >>> from symctl._util.deprecate import RenamedKeys
    >>> m = RenamedKeys({"Pinv[1,1]": 2}, lambda k: k.replace("Q[", "Pinv[", 1), "params")
    >>> with warnings.catch_warnings(record=True):
    ...     warnings.simplefilter("always")
    ...     m["Q[1,1]"], list(m)
    (2, ['Pinv[1,1]'])
    """

    __slots__ = ("_data", "_renamed", "_where")

    def __init__(self, data, renamed, where: str):
        self._data, self._renamed, self._where = dict(data), renamed, where

    def __getitem__(self, key):
        try:
            return self._data[key]
        except KeyError:
            new = self._renamed(key) if isinstance(key, str) else None
            if new is None or new == key or new not in self._data:
                raise
            warn_deprecated(key, new, self._where)
            return self._data[new]

    def __iter__(self):
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __repr__(self) -> str:
        return repr(self._data)

    def __reduce__(self):
        return (RenamedKeys, (self._data, self._renamed, self._where))
