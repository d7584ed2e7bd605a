"""Stylized linear neurons and their synapses, the parts of a circuit; values (equal fields,
equal objects, equal hashes)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import sympy as sp

from symctl._util.validate import to_expr
from symctl.symbols import z

__all__ = ["Neuron", "Synapse"]


def _sign(weight: sp.Expr) -> str:
    if weight.is_zero:
        return "0"
    if weight.is_positive:
        return "+"
    if weight.is_negative:
        return "-"
    return "?"


class Synapse(NamedTuple):
    """One axon path from a neuron (or a circuit input) to a neuron (or a circuit output).

    Attributes
    ----------
    source, target : str
        The presynaptic neuron or input, and the postsynaptic neuron or output.
    weight : sympy expression
        The product of the gains on the path.
    delay : int
        The unit delays on the path, axon delays included.
    path : tuple of str
        The signals strictly between ``source`` and ``target``, in signal-flow order.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl import Synapse
    >>> s = Synapse("u", "x", sp.Integer(-2), 1)
    >>> s.sign, s.excitatory, s.inhibitory
    ('-', False, True)
    >>> s == Synapse("u", "x", -2, 1)   # a value: equal fields, equal synapses
    True
    """

    source: str
    target: str
    weight: sp.Expr
    delay: int
    path: tuple[str, ...] = ()

    @property
    def sign(self) -> str:
        """``"+"`` (excitatory), ``"-"`` (inhibitory), ``"0"``, or ``"?"`` when symbolic."""
        return _sign(to_expr(self.weight, "weight"))

    @property
    def excitatory(self) -> bool:
        """Whether the weight is known to be positive."""
        return self.sign == "+"

    @property
    def inhibitory(self) -> bool:
        """Whether the weight is known to be negative."""
        return self.sign == "-"


@dataclass(frozen=True)
class Neuron:
    r"""A stylized linear neuron, :math:`n(t) = \sum_k w_k\, n(t - d_k) + \sum_j v_j\, s_j(t - e_j)`.

    Attributes
    ----------
    name : str
        The adder's signal in the structure (e.g. ``"G2.x2"``).
    part : str
        The part of a series connection it belongs to (``"G1"``, ...; ``""`` if none).
    synapses, self_terms : tuple of Synapse
        Its inputs from other neurons and circuit inputs, and from its own output.
    axon : tuple of Synapse
        Its outgoing branches: synapses onto other neurons, then the circuit outputs it drives.
    vertex : int or None
        The delay-graph vertex of its signal, when an assignment was given.

    Examples
    --------
    >>> from symctl import Circuit, Structure, first_order_realization
    >>> from symctl.symbols import epsilon_1, C_1
    >>> c = Circuit.from_structure(Structure.from_realization(
    ...     first_order_realization(epsilon_1, C_1)))
    >>> n = c.neuron("x1")
    >>> n.self_weight, n.self_dynamics, [(s.source, s.weight, s.delay) for s in n.synapses]
    (epsilon_1, epsilon_1/z, [('u', C_1, 1)])
    """

    name: str
    part: str
    synapses: tuple[Synapse, ...]
    self_terms: tuple[Synapse, ...]
    axon: tuple[Synapse, ...]
    vertex: int | None = None

    @property
    def self_weight(self) -> sp.Expr:
        r"""The total weight of its own past outputs, :math:`\sum_k w_k`."""
        return sp.Add(*(to_expr(s.weight, "weight") for s in self.self_terms))

    @property
    def self_dynamics(self) -> sp.Expr:
        r"""The self-dynamics as a polynomial in :math:`z^{-1}`, :math:`\sum_k w_k z^{-d_k}`."""
        return sp.Add(*(to_expr(s.weight, "weight") * z ** (-s.delay) for s in self.self_terms))

    @property
    def branches(self) -> int:
        """The number of axon branches (outgoing synapses and circuit outputs)."""
        return len(self.axon)
