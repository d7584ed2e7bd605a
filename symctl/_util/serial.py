"""Results as dicts of JSON types and back: ``to_dict()`` and ``from_dict()`` for every result.

What JSON cannot hold is a tagged dict: ``{"@array": lists, "dtype": ...}``, ``@complex``,
``@fraction``, ``@tuple``, ``@set``, ``@mapping`` (read-only), ``@items`` (keys that are not
strings); a SymPy object is its tree ``{"@sympy": "Add", "args": [...]}`` with exact leaves
(floats by mantissa and exponent; no text is ever parsed, only SymPy's classes rebuilt by
name); a symctl value ``{"@type": "Neuron", "@module": "symctl.neural.neuron", fields...}``
(only symctl's classes rebuilt, field by field as :mod:`pickle` does: the round trip is exact).

>>> import sympy as sp
>>> from symctl._util.serial import decode, encode
>>> K = sp.Symbol("K_0", real=True)
>>> data = encode(sp.Rational(1, 3) * K + sp.Float(0.5))
>>> decode(data) == sp.Rational(1, 3) * K + sp.Float(0.5)
True
"""

from __future__ import annotations

import dataclasses
import importlib
import numbers
from fractions import Fraction
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl.errors import ParameterError, SymctlTypeError


def _encode_sympy(x) -> dict:
    if isinstance(x, sp.MatrixBase):
        return {
            "@sympy": "ImmutableDenseMatrix",
            "shape": list(x.shape),
            "args": [_encode_sympy(e) for e in x],
        }
    if isinstance(x, sp.Symbol) and type(x) is sp.Symbol:
        return {"@sympy": "Symbol", "name": x.name, "assumptions": dict(x._assumptions_orig)}
    if isinstance(x, sp.Float):
        sign, man, exp, bc = x._mpf_
        return {"@sympy": "Float", "mpf": [sign, hex(man), exp, bc], "prec": x._prec}
    if isinstance(x, sp.Integer):
        return {"@sympy": "Integer", "p": int(x)}
    if isinstance(x, sp.Rational):
        return {"@sympy": "Rational", "p": int(x.p), "q": int(x.q)}
    if not x.args:  # a singleton such as pi, E, I, oo, zoo, nan
        return {"@sympy": "S", "name": type(x).__name__}
    return {"@sympy": type(x).__name__, "args": [_encode_sympy(a) for a in x.args]}


def _sympy_class(name: str):
    cls = getattr(sp, name, None) if isinstance(name, str) and name.isidentifier() else None
    if not (isinstance(cls, type) and issubclass(cls, sp.Basic)):
        raise ParameterError(f"data: {name!r} is not a SymPy class")
    return cls


def _decode_sympy(d: dict):
    if not isinstance(d, dict) or "@sympy" not in d:
        raise ParameterError(f"data: expected a tagged SymPy tree, got {d!r}")
    kind = d["@sympy"]
    if kind == "ImmutableDenseMatrix":
        rows, cols = d["shape"]
        return sp.ImmutableMatrix(rows, cols, [_decode_sympy(e) for e in d["args"]])
    if kind == "Symbol":
        return sp.Symbol(str(d["name"]), **{str(k): bool(v) for k, v in d["assumptions"].items()})
    if kind == "Float":
        sign, man, exp, bc = d["mpf"]
        mpf = (int(sign), int(man, 16), int(exp), int(bc))
        if mpf == (0, 0, 0, 0):  # Float._new would give the Integer 0
            return sp.Float(0.0, precision=int(d["prec"]))
        return sp.Float._new(mpf, int(d["prec"]))
    if kind == "Integer":
        return sp.Integer(int(d["p"]))
    if kind == "Rational":
        return sp.Rational(int(d["p"]), int(d["q"]))
    if kind == "S":
        name = d["name"]
        value = getattr(sp.S, name, None) if isinstance(name, str) and name.isidentifier() else None
        if not isinstance(value, sp.Basic):
            raise ParameterError(f"data: {name!r} is not a SymPy constant")
        return value
    cls = _sympy_class(kind)
    return cls(*(_decode_sympy(a) for a in d["args"]), evaluate=False)


def _fields(x) -> list[str]:
    if dataclasses.is_dataclass(x):
        return [f.name for f in dataclasses.fields(x)]
    return list(x._fields)  # a named tuple


def encode(x):
    """``x`` as JSON types, tagged where JSON has no type of its own."""
    if x is None or isinstance(x, bool | str):
        return x
    if isinstance(x, np.bool_):
        return bool(x)
    if isinstance(x, numbers.Integral) and not isinstance(x, sp.Basic):
        return int(x)
    if isinstance(x, float | np.floating):
        return float(x)
    if isinstance(x, complex | np.complexfloating):
        return {"@complex": [float(x.real), float(x.imag)]}
    if isinstance(x, Fraction):
        return {"@fraction": [x.numerator, x.denominator]}
    if isinstance(x, sp.Basic | sp.MatrixBase):
        return _encode_sympy(x)
    if isinstance(x, np.ndarray):
        data = x.tolist()
        if np.iscomplexobj(x):
            data = np.stack([x.real, x.imag], axis=-1).tolist()
        return {"@array": data, "dtype": str(x.dtype)}
    if dataclasses.is_dataclass(x) or (isinstance(x, tuple) and hasattr(x, "_fields")):
        cls = type(x)
        if not cls.__module__.startswith("symctl."):
            raise SymctlTypeError(f"to_dict: cannot write a {cls.__name__}")
        out = {"@type": cls.__qualname__, "@module": cls.__module__}
        out.update({name: encode(getattr(x, name)) for name in _fields(x)})
        return out
    if isinstance(x, tuple):
        return {"@tuple": [encode(v) for v in x]}
    if isinstance(x, list):
        return [encode(v) for v in x]
    if isinstance(x, MappingProxyType):
        return {"@mapping": encode(dict(x))}
    if isinstance(x, dict) or hasattr(x, "items"):
        items = list(x.items())
        if all(isinstance(k, str) and not k.startswith("@") for k, _ in items):
            return {k: encode(v) for k, v in items}
        return {"@items": [[encode(k), encode(v)] for k, v in items]}
    if isinstance(x, frozenset | set):
        return {"@set": [encode(v) for v in x]}
    raise SymctlTypeError(f"to_dict: cannot write a {type(x).__name__}")


def _symctl_class(module: str, name: str):
    if not (isinstance(module, str) and module.startswith("symctl.")):
        raise ParameterError(f"data: {module!r} is not a symctl module")
    cls = importlib.import_module(module)
    for part in str(name).split("."):
        cls = getattr(cls, part)
    if not isinstance(cls, type):
        raise ParameterError(f"data: {module}.{name} is not a class")
    return cls


def _rebuild(cls, values: dict):
    if not dataclasses.is_dataclass(cls):
        return cls(**values)  # a named tuple
    obj = object.__new__(cls)
    for name, value in values.items():
        object.__setattr__(obj, name, value)
    return obj


def decode(d):
    """The value :func:`encode` wrote."""
    if isinstance(d, list):
        return [decode(v) for v in d]
    if not isinstance(d, dict):
        return d
    if "@sympy" in d:
        return _decode_sympy(d)
    if "@array" in d:
        dtype = np.dtype(d["dtype"])
        arr = np.array(d["@array"], dtype=float if dtype.kind == "c" else dtype)
        if dtype.kind == "c":
            arr = (arr[..., 0] + 1j * arr[..., 1]).astype(dtype)
        arr.flags.writeable = False
        return arr
    for tag, read in _TAGGED.items():
        if tag in d:
            return read(d[tag])
    if "@type" in d:
        cls = _symctl_class(d["@module"], d["@type"])
        return _rebuild(cls, {k: decode(v) for k, v in d.items() if not k.startswith("@")})
    return {k: decode(v) for k, v in d.items()}


def _hashable(key):
    return tuple(key) if isinstance(key, list) else key


_TAGGED = {  # the tags decode reads, in the order it tries them
    "@complex": lambda v: complex(*v),
    "@fraction": lambda v: Fraction(*v),
    "@tuple": lambda v: tuple(decode(x) for x in v),
    "@set": lambda v: frozenset(decode(x) for x in v),
    "@mapping": lambda v: MappingProxyType(decode(v)),
    "@items": lambda v: {_hashable(decode(k)): decode(x) for k, x in v},
}


class DictMixin:
    """``to_dict()`` and ``from_dict()`` for a result type, written with :func:`encode`."""

    __slots__ = ()

    def to_dict(self) -> dict:
        """The result as a dict of JSON types (:mod:`symctl._util.serial`); ``from_dict`` reads it."""
        return encode(self)

    @classmethod
    def from_dict(cls, data: dict):
        """The result :meth:`to_dict` wrote."""
        if not isinstance(data, dict):
            raise SymctlTypeError(f"data: expected a dict, got {type(data).__name__}")
        if data.get("@type") != cls.__qualname__:
            raise ParameterError(f"data: a {data.get('@type')!r}, not a {cls.__qualname__}")
        return decode(data)
