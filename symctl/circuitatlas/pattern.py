r"""Patterns of realizations: which entries of :math:`(F, H, M)` are nonzero.

A pattern is a bit mask over the :math:`n^2 + 2n` *slots* ``F[1,1], .., F[n,n], H[1], .., H[n],
M[1], .., M[n]`` (bit ``k`` is slot ``k``); :math:`N \ne 0` always. Two symmetries act:

* **state permutations** (:math:`F \mapsto \Pi F \Pi^\top`, :math:`H \mapsto \Pi H`,
  :math:`M \mapsto M \Pi^\top`) rename the circuit's neurons; :meth:`Pattern.canonical` picks
  the smallest mask of the orbit;
* the **torus** of diagonal similarities :math:`D` keeps the pattern and :math:`G_2`
  (:math:`F_{ij} \mapsto F_{ij} d_j / d_i`, :math:`H_i \mapsto H_i / d_i`, :math:`M_j \mapsto
  M_j d_j`): on the graph of the states and one node ``o`` for input and output, with an edge
  per off-diagonal entry, a real :math:`D` sets a spanning tree's entries to 1
  (:meth:`Pattern.tree_slots`).

>>> from symctl.circuitatlas.pattern import Pattern
>>> P = Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1])
>>> P.size, P.text, P.canonical().text
(6, '01 11 | 01 | 11', '11 10 | 10 | 11')
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from functools import cache

import networkx as nx
import sympy as sp

from symctl.errors import DimensionError, ParameterError, SymctlTypeError

__all__ = ["MAX_ORDER", "Pattern", "slot_names"]

MAX_ORDER = 6  # largest order a pattern may have (the exhaustive atlas stops far lower)


@cache
def _slot_of(n: int) -> tuple[tuple, ...]:
    """Each slot as (matrix, row, column)."""
    F = [("F", i, j) for i in range(n) for j in range(n)]
    return (*F, *(("H", i, 0) for i in range(n)), *(("M", 0, j) for j in range(n)))


@cache
def slot_names(n: int) -> tuple[str, ...]:
    """The names of the ``n**2 + 2n`` slots, in bit order (``"F[1,2]"``, ``"H[1]"``, ``"M[2]"``)."""
    return tuple(
        f"F[{i + 1},{j + 1}]" if m == "F" else f"{m}[{i + j + 1}]" for m, i, j in _slot_of(n)
    )


@cache
def _permutation_maps(n: int) -> tuple[tuple[int, ...], ...]:
    """For each state permutation, the image slot of each slot."""
    maps = []
    for p in itertools.permutations(range(n)):
        F = [p[i] * n + p[j] for i in range(n) for j in range(n)]
        maps.append((*F, *(n * n + p[i] for i in range(n)), *(n * n + n + p[j] for j in range(n))))
    return tuple(maps)


def _permute(mask: int, image: tuple[int, ...]) -> int:
    return sum(1 << target for k, target in enumerate(image) if mask >> k & 1)


@dataclass(frozen=True, order=True)
class Pattern:
    """The support of :math:`(F, H, M)` of an order-``n`` SISO realization (a value ordered and
    hashed by ``(n, mask)``).

    Parameters
    ----------
    n : int
        The order, 1 to :data:`MAX_ORDER`.
    mask : int
        Bit ``k`` set when slot ``k`` (:func:`slot_names`) is nonzero.

    Examples
    --------
    >>> from symctl.circuitatlas.pattern import Pattern
    >>> Pattern(2, 0b11101110).slots
    ('F[1,2]', 'F[2,1]', 'F[2,2]', 'H[2]', 'M[1]', 'M[2]')
    """

    n: int
    mask: int

    def __post_init__(self):
        if isinstance(self.n, bool) or not isinstance(self.n, int):
            raise SymctlTypeError(f"n: expected an int, got {self.n!r}")
        if not 1 <= self.n <= MAX_ORDER:
            raise ParameterError(f"n: must be between 1 and {MAX_ORDER}, got {self.n}")
        if isinstance(self.mask, bool) or not isinstance(self.mask, int):
            raise SymctlTypeError(f"mask: expected an int, got {self.mask!r}")
        if not 0 <= self.mask < 1 << len(slot_names(self.n)):
            raise ParameterError(f"mask: must fit {len(slot_names(self.n))} bits, got {self.mask}")

    @classmethod
    def from_matrices(cls, F, H, M) -> Pattern:
        """The pattern of zero/nonzero arrays ``F`` (n x n), ``H`` (n), ``M`` (n).

        >>> from symctl.circuitatlas.pattern import Pattern
        >>> Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1]).mask
        238
        """
        try:
            Fr = [list(r) for r in F]
            Hr = list(itertools.chain.from_iterable(h if hasattr(h, "__len__") else [h] for h in H))
            Mr = list(itertools.chain.from_iterable(m if hasattr(m, "__len__") else [m] for m in M))
        except TypeError as exc:
            raise SymctlTypeError(f"F, H, M: expected nested sequences ({exc})") from None
        n = len(Fr)
        if any(len(r) != n for r in Fr) or len(Hr) != n or len(Mr) != n:
            raise DimensionError(
                f"F, H, M: expected shapes ({n}, {n}), ({n},), ({n},), got "
                f"{[len(r) for r in Fr]}, {len(Hr)}, {len(Mr)}"
            )
        values = [v for r in Fr for v in r] + Hr + Mr
        return cls(n, sum(1 << k for k, v in enumerate(values) if v != 0))

    @classmethod
    def of(cls, R) -> Pattern:
        """The pattern of a SISO realization: its entries that are not identically zero.

        >>> from symctl import controllable_canonical, z
        >>> from symctl.circuitatlas.pattern import Pattern
        >>> Pattern.of(controllable_canonical(1 + 1 / (z**2 - z / 2 - 1))).text
        '01 11 | 01 | 10'
        """
        from symctl.realization.realization import Realization

        if not isinstance(R, Realization):
            raise SymctlTypeError(f"R: expected a Realization, got {type(R).__name__}")
        if R.shape != (1, 1):
            raise DimensionError(f"R: expected a SISO realization, got shape {R.shape}")
        nonzero = (
            [[sp.cancel(v) != 0 for v in row] for row in m.tolist()] for m in (R.F, R.H, R.M)
        )
        return cls.from_matrices(*nonzero)

    @property
    def size(self) -> int:
        """The number of nonzero entries."""
        return self.mask.bit_count()

    @property
    def indices(self) -> tuple[int, ...]:
        """The nonzero slots, by index."""
        return tuple(k for k in range(len(slot_names(self.n))) if self.mask >> k & 1)

    @property
    def slots(self) -> tuple[str, ...]:
        """The nonzero slots, by name."""
        names = slot_names(self.n)
        return tuple(names[k] for k in self.indices)

    @property
    def n_neurons(self) -> int:
        """Neurons of its circuit: rows of ``[F H]`` with two or more entries, and the output."""
        F, H, _M = self.arrays()
        return 1 + sum(sum(row) + h >= 2 for row, h in zip(F, H, strict=True))

    def where(self, k: int) -> tuple[str, int, int]:
        """Slot ``k`` as (matrix letter, row, column), 0-based."""
        return _slot_of(self.n)[k]

    def arrays(self) -> tuple[list[list[int]], list[int], list[int]]:
        """``F`` (rows), ``H`` and ``M`` as 0/1 lists."""
        n = self.n
        bits = [self.mask >> k & 1 for k in range(n * n + 2 * n)]
        return (
            [bits[i * n : (i + 1) * n] for i in range(n)],
            bits[n * n : n * n + n],
            bits[n * n + n :],
        )

    @property
    def F(self) -> sp.ImmutableMatrix:
        """The support of ``F`` as a 0/1 matrix (``H``, ``M``: a column and a row).

        >>> from symctl.circuitatlas.pattern import Pattern
        >>> P = Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1])
        >>> P.F.tolist(), P.H.T.tolist(), P.M.tolist()
        ([[0, 1], [1, 1]], [[0, 1]], [[1, 1]])
        """
        return sp.ImmutableMatrix(self.arrays()[0])

    @property
    def H(self) -> sp.ImmutableMatrix:
        """The support of ``H`` as a 0/1 column."""
        return sp.ImmutableMatrix(self.n, 1, self.arrays()[1])

    @property
    def M(self) -> sp.ImmutableMatrix:
        """The support of ``M`` as a 0/1 row."""
        return sp.ImmutableMatrix(1, self.n, self.arrays()[2])

    @property
    def text(self) -> str:
        """One line: the rows of ``F``, then ``H`` and ``M``, as 0/1 digits."""
        F, H, M = self.arrays()
        return " | ".join(
            [" ".join("".join(map(str, r)) for r in F), *("".join(map(str, v)) for v in (H, M))]
        )

    def __repr__(self) -> str:
        return f"Pattern({self.n}, {self.text!r})"

    def permuted(self, perm) -> Pattern:
        """The pattern after renaming state ``i`` to ``perm[i]`` (0-based)."""
        perm = tuple(perm)
        if sorted(perm) != list(range(self.n)):
            raise ParameterError(f"perm: must be a permutation of 0..{self.n - 1}, got {perm}")
        index = list(itertools.permutations(range(self.n))).index(perm)
        return Pattern(self.n, _permute(self.mask, _permutation_maps(self.n)[index]))

    def canonical(self) -> Pattern:
        """The representative of the state-permutation orbit: the smallest mask."""
        return Pattern(self.n, canonical_mask(self.n, self.mask))

    def orbit(self) -> frozenset[Pattern]:
        """Every pattern that a state permutation gives."""
        return frozenset(Pattern(self.n, _permute(self.mask, m)) for m in _permutation_maps(self.n))

    def contains(self, other: Pattern) -> bool:
        """``other``'s nonzero slots are all nonzero here."""
        return self.n == other.n and other.mask & ~self.mask == 0

    def tree_slots(self) -> tuple[int, ...] | None:
        """Slots of a spanning tree of the torus graph (module text); None when it is not
        connected (no realization with this pattern is then minimal)."""
        graph = nx.Graph()
        graph.add_nodes_from(["o", *range(self.n)])
        for k in self.indices:
            kind, i, j = self.where(k)
            a, b = {"F": (i, j), "H": ("o", i), "M": ("o", j)}[kind]
            if a != b and not graph.has_edge(a, b):
                graph.add_edge(a, b, slot=k)
        if not nx.is_connected(graph):
            return None
        tree = nx.minimum_spanning_tree(graph, weight="slot")
        return tuple(sorted(d["slot"] for _, _, d in tree.edges(data=True)))

    def component_sizes(self) -> tuple[int, ...]:
        """Sizes of the strongly connected components of ``F``'s graph."""
        graph = nx.DiGraph()
        graph.add_nodes_from(range(self.n))
        for k in self.indices:
            kind, i, j = self.where(k)
            if kind == "F":
                graph.add_edge(j, i)
        return tuple(sorted(len(c) for c in nx.strongly_connected_components(graph)))

    def symbols(self) -> dict[int, sp.Symbol]:
        """One symbol per nonzero slot, named like the slot (``F_12`` for ``F[1,2]``)."""
        out = {}
        for k in self.indices:
            kind, i, j = self.where(k)
            sub = f"{i + 1}{j + 1}" if kind == "F" else str(i + j + 1)
            out[k] = sp.Symbol(f"{kind}_{sub}")
        return out

    def matrices(self, values) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
        """``F``, ``H``, ``M`` with ``values[k]`` in each nonzero slot ``k`` (a mapping)."""
        n = self.n
        mats = {"F": sp.zeros(n, n), "H": sp.zeros(n, 1), "M": sp.zeros(1, n)}
        for k in self.indices:
            kind, i, j = self.where(k)
            mats[kind][i, j] = values[k]
        return mats["F"], mats["H"], mats["M"]


def canonical_mask(n: int, mask: int) -> int:
    """The smallest mask in the state-permutation orbit of ``mask``."""
    return min(_permute(mask, m) for m in _permutation_maps(n))


def orbit_size(n: int, mask: int) -> int:
    """How many patterns the state permutations give from ``mask``."""
    return len({_permute(mask, m) for m in _permutation_maps(n)})
