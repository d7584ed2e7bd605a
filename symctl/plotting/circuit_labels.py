r"""The text of a circuit drawing: each synapse's weight, each neuron's body, and the key.

A weight showing more than :data:`LONG_WEIGHT` characters is drawn as :math:`w_k`, a
self-dynamics longer than :data:`LONG_SELF` as :math:`\mathrm{self}_k`, the key reading
the value in full; equal values share a label.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING

import sympy as sp

from symctl._util.display import latex
from symctl._util.validate import to_expr

if TYPE_CHECKING:
    from symctl.neural.circuit import Circuit
    from symctl.neural.neuron import Neuron, Synapse

LONG_WEIGHT = 14  # a longer weight is drawn as w_k (14 characters fit between two columns)
LONG_SELF = 2 * LONG_WEIGHT  # a longer self-dynamics is drawn as self_k, else in its circle

_NUMBER = re.compile(r"-?\d+(\.\d*)?(e[+-]?\d+)?")


def visible_length(tex: str) -> int:
    r"""The number of characters ``tex`` shows: a command counts as one; ``\left``, ``\right``,
    ``\frac``, ``\dfrac``, ``\cdot``, braces, ``_``, ``^`` and spaces as none.
    """
    text = re.sub(r"\\(left|right|frac|dfrac|cdot)\b", "", tex)
    text = re.sub(r"\\[a-zA-Z]+", "m", text)
    return len(re.sub(r"[{}_^\s]", "", text))


def weight_tex(weight) -> str:
    """LaTeX of a weight; numbers (e.g. exact rationals) to 3 significant digits."""
    w = to_expr(weight, "weight")
    if w.is_number and w.is_real:
        return f"{float(w):.3g}"
    return latex(w)


def _self_tex(n: Neuron) -> str:
    r"""``\epsilon_{1} z^{-1}``, ``K_{1} z^{-1} + K_{2} z^{-2}``; empty without self-dynamics."""
    if not n.self_terms:
        return ""
    parts = []
    for s in sorted(n.self_terms, key=lambda s: s.delay):
        w = to_expr(s.weight, "weight")
        tex = weight_tex(w)
        if isinstance(w, sp.Add):
            tex = rf"\left({tex}\right)"
        parts.append(tex + (rf"\,z^{{-{s.delay}}}" if s.delay else ""))
    return " + ".join(parts).replace("+ -", "- ")


def display_text(tex: str) -> str:
    r"""The string matplotlib draws for ``tex``: a plain number as text (minus sign U+2212), else
    ``$tex$`` with ``\frac`` as ``\dfrac`` (mathtext sets a ``\frac``'s parts at 70 %).
    """
    if _NUMBER.fullmatch(tex):
        return tex.replace("-", "\N{MINUS SIGN}")
    return "$" + re.sub(r"\\frac\b", r"\\dfrac", tex) + "$"


@dataclass(frozen=True, eq=False)
class CircuitText:
    r"""What a circuit drawing writes (LaTeX without ``$``): ``weights`` each synapse's (and weighted
    or delayed output's) label, its weight or :math:`w_k` then :math:`z^{-d}` for a delay
    ``d > 1``; ``bodies`` each neuron's self-dynamics or :math:`\mathrm{self}_k`; ``key`` the
    ``(label, value)`` of each long value, the self-dynamics first.
    """

    weights: Mapping = field(default_factory=dict)
    bodies: Mapping[str, str] = field(default_factory=dict)
    key: tuple[tuple[str, str], ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "weights", MappingProxyType(dict(self.weights)))
        object.__setattr__(self, "bodies", MappingProxyType(dict(self.bodies)))

    def key_lines(self) -> list[str]:
        """The key as LaTeX lines, ``label = value``."""
        return [f"{label} = {value}" for label, value in self.key]


class _Labels:
    """Short labels ``stem_k`` for long values, one per distinct value."""

    def __init__(self, stem: str, limit: int):
        self.stem, self.limit, self.seen = stem, limit, {}

    def __call__(self, tex: str) -> str:
        if visible_length(tex) <= self.limit:
            return tex
        if tex not in self.seen:
            self.seen[tex] = f"{self.stem}_{{{len(self.seen) + 1}}}"
        return self.seen[tex]

    def key(self) -> list[tuple[str, str]]:
        return [(label, tex) for tex, label in self.seen.items()]


def circuit_text(c: Circuit) -> CircuitText:
    r"""The labels of the drawing of ``c``: weights, neuron bodies, and the key of long ones."""
    weight, body = _Labels("w", LONG_WEIGHT), _Labels(r"\mathrm{self}", LONG_SELF)
    bodies = {n.name: body(_self_tex(n)) for n in c.neurons}
    synapses: list[Synapse] = [s for n in c.neurons for s in n.synapses]
    synapses += [o for o in c.outputs if o.weight != 1 or o.delay]
    weights = {}
    for s in synapses:
        tex = weight(weight_tex(s.weight))
        if s.delay > 1:  # a weight 1 of k steps is z^-k alone
            tex = ("" if tex == "1" else tex + r"\,") + rf"z^{{-{s.delay}}}"
        weights[s] = tex
    return CircuitText(weights, bodies, (*body.key(), *weight.key()))
