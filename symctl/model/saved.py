"""A model saved as data (:meth:`Model.to_dict <symctl.model.model.Model.to_dict>`), read back.

>>> from symctl.model.presets import muscle
>>> from symctl.model.saved import model_from_dict
>>> m = muscle().replace(tau=0.05, Q=[[2]])
>>> model_from_dict(m.to_dict()) == m
True
"""

from __future__ import annotations

import sympy as sp

from symctl._util.parse import parse_expr
from symctl.errors import ParameterError
from symctl.model.modelfile import Model, read_model

__all__ = ["model_from_dict"]


def model_from_dict(data) -> Model:
    """The model that ``Model.to_dict`` wrote: its file read again (checked, never evaluated),
    then the values replaced (read by the safe parser); ModelFileError, ParameterError or
    ParseError for bad data."""
    if not isinstance(data, dict) or not {"source", "path"} <= set(data):
        raise ParameterError("data: expected a mapping with source, path and replaced")
    replaced = data.get("replaced") or {}
    if not isinstance(replaced, dict):
        raise ParameterError("data: replaced must be a mapping of names to values")
    model = read_model(data["source"], str(data["path"]))
    return model.replace(**{k: _parsed(v, k) for k, v in replaced.items()}) if replaced else model


def _parsed(value, name: str, *, entry: bool = False):
    """A replaced value as ``Model.to_dict`` writes it, read back (text by the safe parser)."""
    if isinstance(value, bool):
        raise ParameterError(f"replaced.{name}: expected a number, text or rows, got {value!r}")
    if isinstance(value, int):
        return sp.Integer(value) if entry else value
    if isinstance(value, float):
        return sp.Float(value) if entry else value
    if isinstance(value, str):
        return parse_expr(value, argname=f"replaced.{name}")
    if not entry and isinstance(value, list) and value and all(isinstance(r, list) for r in value):
        return sp.ImmutableMatrix([[_parsed(e, name, entry=True) for e in row] for row in value])
    raise ParameterError(f"replaced.{name}: expected a number, text or rows, got {value!r}")
