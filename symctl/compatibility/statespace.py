r"""The state-space form of a structure: every delay step is one state.

A delay block of :math:`k` steps is a shift register of :math:`k` states ``d@1, ..., d@(k-1),
d`` (``d@j`` holds :math:`a(t - j)`); each signal is a row of coefficients on :math:`[s \mid
u]`, read in delay-free order, giving :math:`s(t+1) = A s(t) + B u(t)`, :math:`y(t) = C s(t) + D
u(t)`.
"""

from __future__ import annotations

from collections.abc import Sequence

import networkx as nx
import sympy as sp

from symctl.compatibility.block import Block
from symctl.errors import ParameterError
from symctl.realization.realization import Realization

__all__ = ["MAX_STATES", "delay_states", "signal_rows", "structure_realization"]

MAX_STATES = 20_000
"""The most states (delay steps) of a structure's state-space form."""


def delay_states(S) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The states (every step of every delay block) and what each holds one step later."""
    states: list[str] = []
    feeds: list[str] = []
    for name, block in S.blocks.items():
        if block.kind != "delay":
            continue
        source = block.inputs[0]
        for j in range(1, block.steps):
            states.append(f"{name}@{j}")
            feeds.append(source)
            source = f"{name}@{j}"
        states.append(name)
        feeds.append(source)
        if len(states) > MAX_STATES:
            raise ParameterError(
                f"S: the state-space form has more than {MAX_STATES} states (delay steps)"
            )
    return tuple(states), tuple(feeds)


def signal_rows(S, states: Sequence[str], unit: list, zero, gain_value) -> dict:
    """Each signal as a row on ``[states | inputs]`` in delay-free order (SymPy or NumPy rows)."""
    row = dict(zip((*states, *S.inputs), unit, strict=True))
    free = nx.DiGraph()
    free.add_nodes_from(S.blocks)
    free.add_edges_from((a, b) for a, b, d in S.wires() if d == 0)
    for name in nx.topological_sort(free):
        block = S.blocks[name]
        if name in row:
            continue
        if block.kind == "gain":
            row[name] = gain_value(name, block_gain(block, name)) * row[block.inputs[0]]
        else:
            row[name] = sum((row[s] for s in block.inputs), zero)
    return row


def block_gain(block: Block, name: str) -> sp.Expr:
    """A gain block's value, or the symbol named after its signal when it has none."""
    return block.gain if block.gain is not None else sp.Symbol(name)


def structure_realization(S, outputs: Sequence[str] | None = None) -> Realization:
    """The structure as a realization :math:`(A, B, C, D)` from its inputs to ``outputs``.

    Parameters
    ----------
    S : Structure
    outputs : sequence of str, optional
        The signals read out (default: the structure's outputs).

    Returns
    -------
    Realization
        One state per delay step (:func:`delay_states`).

    Raises
    ------
    ParameterError
        An output that is not a signal; more than :data:`MAX_STATES` states.

    Examples
    --------
    >>> from symctl import Block, Structure, structure_realization
    >>> S = Structure({"u": ("input",), "d": Block("delay", ("u",), steps=3)}, "u", "d")
    >>> R = structure_realization(S)
    >>> R.n, R.to_tf().expr
    (3, z**(-3))
    """
    states, feeds = delay_states(S)
    outs = tuple(S.outputs if outputs is None else outputs)
    for name in outs:
        if name not in S.blocks:
            raise ParameterError(f"outputs: {name!r} is not a signal of the structure")
    k, m = len(states), len(S.inputs)
    unit = [sp.eye(k + m)[i, :] for i in range(k + m)]
    row = signal_rows(S, states, unit, sp.zeros(1, k + m), lambda name, g: g)
    nxt = sp.Matrix.vstack(*(row[f] for f in feeds)) if k else sp.zeros(0, k + m)
    obs = sp.Matrix.vstack(*(row[s] for s in outs)) if outs else sp.zeros(0, k + m)
    return Realization(
        nxt[:, :k].applyfunc(sp.expand), nxt[:, k:], obs[:, :k].applyfunc(sp.expand), obs[:, k:]
    )
