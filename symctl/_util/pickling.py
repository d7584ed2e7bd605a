"""Pickling of symctl's values: read-only mappings, exact expressions as built, no caches.

>>> import pickle
>>> from types import MappingProxyType
>>> import symctl
>>> pickle.loads(pickle.dumps(MappingProxyType({"a": 1})))
mappingproxy({'a': 1})
"""

from __future__ import annotations

import copyreg
import dataclasses
import functools
from collections.abc import Mapping
from types import MappingProxyType


def read_only_mapping(items: dict) -> MappingProxyType:
    """A read-only view of ``items`` (what a pickled read-only mapping loads as)."""
    return MappingProxyType(items)


def _reduce(proxy: MappingProxyType):
    return read_only_mapping, (dict(proxy),)


def _unevaluated(cls, args):
    """A SymPy sum, product or power rebuilt from its arguments as they were (not evaluated)."""
    return cls(*args, evaluate=False)


def _reduce_operation(expr):
    return _unevaluated, (type(expr), expr.args)


def register() -> None:
    """Let :mod:`pickle` (and :mod:`copy`) handle read-only mappings; idempotent."""
    copyreg.pickle(MappingProxyType, _reduce)


def register_sympy() -> None:
    """Pickle SymPy sums, products and powers as built, unevaluated; idempotent.

    SymPy's own pickling evaluates them again (``(1353 K_1 + 2145)/3628`` would load with the
    rational distributed, and not compare equal).
    """
    import sympy

    for cls in (sympy.Add, sympy.Mul, sympy.Pow):
        copyreg.pickle(cls, _reduce_operation)


class CachedState:
    """A mixin for frozen values with ``functools.cached_property``: their caches are not pickled."""

    __slots__ = ()

    def __getstate__(self) -> dict:
        cached = {
            name
            for klass in type(self).__mro__
            for name, value in vars(klass).items()
            if isinstance(value, functools.cached_property)
        }
        return {k: v for k, v in self.__dict__.items() if k not in cached}

    def __setstate__(self, state: dict) -> None:
        for key, value in state.items():
            object.__setattr__(self, key, value)


class ArrayValue:
    """A mixin for frozen dataclasses holding arrays: equal when every field is (arrays by shape
    and entries, NaN equal to NaN), so a value loaded from a pickle equals the one saved."""

    __slots__ = ()

    def __eq__(self, other) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return self is other or all(
            _same(getattr(self, f.name), getattr(other, f.name)) for f in dataclasses.fields(self)
        )

    def __hash__(self) -> int:
        fields = (getattr(self, f.name) for f in dataclasses.fields(self))
        return hash((type(self).__qualname__, *map(_hash_part, fields)))


def _same(a, b) -> bool:
    import numpy as np  # here: importing symctl (which registers the pickling) stays quick

    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        try:  # False for other shapes
            return bool(np.array_equal(a, b, equal_nan=True))
        except TypeError:  # object arrays: no NaN test
            return bool(np.array_equal(a, b))
    if isinstance(a, Mapping) and isinstance(b, Mapping):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, tuple | list) and isinstance(b, tuple | list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) and isinstance(b, float) and a != a and b != b:
        return True  # both NaN
    result = a == b
    return bool(np.all(result)) if isinstance(result, np.ndarray) else bool(result)


def _hash_part(value):
    if hasattr(value, "shape") and hasattr(value, "dtype"):  # an array
        return tuple(value.shape)
    if isinstance(value, Mapping):
        return tuple(sorted(map(str, value)))
    if isinstance(value, tuple | list):
        return len(value)
    try:
        return hash(value)
    except TypeError:
        return 0
