r"""The blocks of a controller structure: inputs, gains, adders and delays of k steps (an axon
whose conduction takes :math:`k` steps is one block :math:`z^{-k}`, not :math:`k` relays)."""

from __future__ import annotations

import numbers
from collections.abc import Iterable
from typing import NamedTuple

import sympy as sp

from symctl._util.validate import to_expr
from symctl.errors import ParameterError, SymctlTypeError

__all__ = ["KINDS", "MAX_WIRE_STEPS", "Block", "block", "signal_name", "signal_names"]

KINDS = ("input", "gain", "sum", "delay")
"""The block kinds of a structure."""

MAX_WIRE_STEPS = 100_000
"""The longest delay block, in steps (a bound on every shift register built from one)."""


class Block(NamedTuple):
    """One block of a structure and the signal it produces (a named tuple).

    Parameters
    ----------
    kind : str
        One of :data:`KINDS`.
    inputs : tuple of str
        The signals it reads (none for an input, one for a gain or a delay, any for a sum).
    gain : sympy expression or None
        A gain block's value (for display; the structure ignores it).
    part : str
        The part of a series connection it came from (``""`` if none).
    steps : int, default 1
        A delay block's delay in steps (an axon, :math:`z^{-k}`); 1 for every other kind.

    Examples
    --------
    >>> from symctl import Block
    >>> Block("gain", ("u",), 2)
    Block(kind='gain', inputs=('u',), gain=2, part='', steps=1)
    >>> Block("delay", ("mu",), steps=4).delay
    4
    """

    kind: str
    inputs: tuple[str, ...] = ()
    gain: sp.Expr | None = None
    part: str = ""
    steps: int = 1

    @property
    def delay(self) -> int:
        """The delay of the wires into this block."""
        return self.steps if self.kind == "delay" else 0


def signal_name(value, argname: str) -> str:
    """``value`` as a signal name, or a SymctlTypeError naming ``argname``."""
    if not isinstance(value, str) or not value:
        raise SymctlTypeError(f"{argname}: signal names must be non-empty strings, got {value!r}")
    return value


def signal_names(value, argname: str) -> tuple[str, ...]:
    """One signal name or an iterable of them, as a tuple."""
    if isinstance(value, str):
        return (value,)
    if not isinstance(value, Iterable):
        raise SymctlTypeError(f"{argname}: expected a signal name or names, got {value!r}")
    return tuple(signal_name(v, argname) for v in value)


def block(name: str, value) -> Block:
    """``value`` (a Block or a tuple of its fields) checked as signal ``name``'s block."""
    if isinstance(value, Block):
        out = value
    elif isinstance(value, tuple | list) and 1 <= len(value) <= 5:
        out = Block(*value)
    else:
        raise SymctlTypeError(
            f"blocks[{name!r}]: expected a Block or a tuple (kind, inputs, gain), got {value!r}"
        )
    if out.kind not in KINDS:
        raise ParameterError(f"blocks[{name!r}]: kind must be one of {KINDS}, got {out.kind!r}")
    inputs = (out.inputs,) if isinstance(out.inputs, str) else tuple(out.inputs)
    for src in inputs:
        signal_name(src, f"blocks[{name!r}].inputs")
    count = {"input": 0, "gain": 1, "delay": 1}.get(out.kind)  # a sum reads any number
    if count is not None and len(inputs) != count:
        raise ParameterError(
            f"blocks[{name!r}]: a {out.kind} block takes exactly {count} input(s), "
            f"got {list(inputs)}"
        )
    gain = None
    if out.kind == "gain" and out.gain is not None:
        gain = to_expr(out.gain, f"blocks[{name!r}].gain")
    if not isinstance(out.part, str):
        raise SymctlTypeError(f"blocks[{name!r}].part: expected a string, got {out.part!r}")
    steps = out.steps
    integer = isinstance(steps, numbers.Integral) and not isinstance(steps, bool)
    if out.kind != "delay" and (not integer or steps != 1):
        raise ParameterError(
            f"blocks[{name!r}].steps: only a delay block has steps; a {out.kind} block "
            f"keeps 1, got {steps!r}"
        )
    if not integer or not 1 <= steps <= MAX_WIRE_STEPS:
        raise ParameterError(
            f"blocks[{name!r}].steps: a delay block delays by an integer number of steps "
            f"1..{MAX_WIRE_STEPS}, got {steps!r}"
        )
    return Block(out.kind, inputs, gain, out.part, int(steps))
