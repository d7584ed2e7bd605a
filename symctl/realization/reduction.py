r"""Whether the optimal delayed controller is minimal, decided exactly, and its reduction.

The controller :math:`G(z)` keeps the :math:`T` past intended actuations
:math:`\gamma_1, \dots, \gamma_T` of its :math:`m` inputs: :math:`T m` states,
:math:`\gamma_1(t+1) = K_0 x(t) + \sum_k K_k \gamma_k(t)`, :math:`u = \gamma_T`. Some plants
and costs make it provably non-minimal.

**Theorem.** Let :math:`\mathcal N` be the subspace of :math:`\chi` that the cost never sees
(the unobservable subspace of :math:`(\tilde A, \tilde Q)`, :math:`\tilde A`-invariant) and
:math:`\mathcal D = \{d : \tilde B d \in \mathcal N\}` the input directions that move only it.
With :math:`(\tilde A, \tilde B)` stabilizable and :math:`(\tilde A, \tilde Q)` detectable
(:func:`~symctl.design.lqr.lqr_gains` checks both), the optimal gain satisfies
:math:`K v = 0` for :math:`v \in \mathcal N` and :math:`(R d)^\top K = 0` for
:math:`d \in \mathcal D`. *Proof.* From :math:`\chi_0 \in \mathcal N` the input
:math:`\mu = 0` costs nothing and :math:`\chi \to 0` (detectability makes
:math:`\tilde A` Schur on :math:`\mathcal N`), so :math:`\chi_0^\top X \chi_0 = 0` and
:math:`X \chi_0 = 0` (:math:`X \succeq 0`); then :math:`K \chi_0 = -(R + \tilde B^\top X
\tilde B)^{-1} \tilde B^\top X \tilde A \chi_0 = 0`. For :math:`d \in \mathcal D`,
:math:`X \tilde B d = 0`, so :math:`d^\top (R + \tilde B^\top X \tilde B) = (R d)^\top` and
:math:`(R d)^\top K = -d^\top \tilde B^\top X \tilde A = 0`. :math:`\square`

So the :math:`T \dim \mathcal D` states :math:`w^\top \gamma_k`, :math:`w \in R\mathcal D`, are
never reached. The numeric gains satisfy these linear ties to rounding only, so
:func:`controller_reduction` computes the tied gains exactly from the free ones and decides
the minimal order with :func:`~symctl.realization.minimal.minimal_realization`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
import sympy as sp
from flint import fmpq_mat

from symctl._util.exact import from_fmpq, from_fmpq_mat
from symctl.design.augment import AugmentedSystem
from symctl.design.controller import ifp_state_space
from symctl.design.lqr import Gains, sorted_poles
from symctl.design.tf import DiscreteTF
from symctl.errors import SymctlTypeError
from symctl.proof import Verdict
from symctl.realization.minimal import MAX_ORDER, _mat, _pivots, minimal_realization
from symctl.realization.realization import Realization
from symctl.symbols import gain_matrix_symbols, z

__all__ = ["ControllerReduction", "controller_reduction"]


@dataclass(frozen=True)
class ControllerReduction(Verdict):
    r"""The verdict on the delayed controller's minimality: truthy when it is minimal.

    Attributes
    ----------
    order, minimal_order : int
        The controller's states (:math:`T m`) and its McMillan degree (exact).
    relations : mapping of Symbol to expression
        The gains the theorem ties, each in the free ones.
    never_driven, unseen : tuple of str
        The input combinations :math:`w^\top \mu` kept at 0 (:math:`w = R d`), and the
        plant-state combinations the cost never sees.
    reason, method : str
        Why it is not minimal ('' when it is), and how the McMillan degree was decided.
    """

    _verdict = "minimal"

    order: int
    minimal_order: int
    relations: Mapping[sp.Symbol, sp.Expr] = dataclasses.field(default_factory=dict)
    never_driven: tuple[str, ...] = ()
    unseen: tuple[str, ...] = ()
    reason: str = ""
    method: str = "the exact Kalman reduction of the delay chain, in rational arithmetic"

    def __post_init__(self) -> None:
        object.__setattr__(self, "relations", MappingProxyType(dict(self.relations)))

    def __hash__(self) -> int:
        return hash((self.order, self.minimal_order, tuple(self.relations.items())))

    @property
    def minimal(self) -> bool:
        return self.minimal_order == self.order

    @property
    def evidence(self) -> str:
        return f"McMillan degree {self.minimal_order} of {self.order} states"

    def reduce(self, G: DiscreteTF) -> DiscreteTF:
        r"""``G`` (in the gains' symbols) with the ties substituted and the common power of
        :math:`z` divided out."""
        if self.minimal:
            return G
        G = G.subs(self.relations)
        k = min(sp.Poly(e, z).monoms()[-1][0] for e in (G.den, *G.num_matrix) if e != 0)
        return DiscreteTF(
            G.num_matrix.applyfunc(lambda e: sp.expand(e / z**k)), sp.expand(G.den / z**k), G.dt
        )


def _numbers(M: sp.MatrixBase, name: str) -> fmpq_mat:
    """``M`` in rationals, an irrational number by its float (as the LQR)."""
    return _mat(M.applyfunc(lambda e: e if e.is_Rational else sp.Float(float(e))), name)


def _nullspace(M: fmpq_mat) -> list[list[sp.Rational]]:
    """A basis of the right null space of ``M``."""
    cols = M.ncols()
    R, rank = M.rref()
    pivots = _pivots(R) if rank else []
    out = []
    for f in (c for c in range(cols) if c not in pivots):
        v = [sp.Integer(0)] * cols
        v[f] = sp.Integer(1)
        for i, p in enumerate(pivots):
            v[p] = -from_fmpq(R[i, f])
        out.append(v)
    return out


def _unseen(A: fmpq_mat, Q: fmpq_mat) -> list[list[sp.Rational]]:
    """A basis of the unobservable subspace of ``(A, Q)``: the null space of ``[Q; QA; QA^2...]``."""
    n = A.nrows()
    blocks, block = [], Q
    for _ in range(n):
        blocks.append(block)
        block = block * A
    return _nullspace(
        fmpq_mat(n * n, n, [b[i, j] for b in blocks for i in range(n) for j in range(n)])
    )


def _combination(v, names) -> str:
    """``v`` scaled to a leading 1, as a signed sum of ``names`` without ``delta_``: ``u_1 + u_2``."""
    lead = abs(next(c for c in v if c != 0))
    terms = []
    for c, name in zip((c / lead for c in v), names, strict=True):
        if c == 0:
            continue
        sign = "-" if c < 0 else "+"
        mag = "" if abs(c) == 1 else f"{abs(c)} "
        terms.append(f"{sign} {mag}{name.removeprefix('delta_')}")
    text = " ".join(terms)
    return text[2:] if text.startswith("+ ") else "-" + text[2:]


def controller_reduction(
    system: AugmentedSystem, gains: Gains
) -> tuple[ControllerReduction, Gains]:
    r"""``(verdict, gains)``: whether the optimal delayed controller of the numeric ``system`` is
    minimal, and its ``gains`` with those the theorem ties computed exactly from the free ones
    (SymctlTypeError for other types)."""
    if not isinstance(system, AugmentedSystem) or not isinstance(gains, Gains):
        raise SymctlTypeError(
            "system, gains: expected an AugmentedSystem and its Gains, got "
            f"{type(system).__name__} and {type(gains).__name__}"
        )
    n, m, T = system.n, system.m, system.T
    if T == 0:
        return ControllerReduction(0, 0), gains
    size = n + T * m
    Qeq = sp.zeros(size, size)
    Qeq[:n, :n] = system.Q_plant
    A, B = _numbers(system.A, "A"), _numbers(system.B, "B")
    unseen = _unseen(A, _numbers(Qeq, "Q"))
    directions = _directions(B, unseen)
    K = sp.Matrix.hstack(*gain_matrix_symbols(T, m, n))
    Rm = sp.Matrix(from_fmpq_mat(_numbers(system.R, "R")))
    equations = [e for v in unseen for e in K * sp.Matrix(v)]
    equations += [e for d in directions for e in (Rm * sp.Matrix(d)).T * K]
    relations = _solve(equations, list(K))
    values = dict(zip(K, (sp.Rational(float(v)) for v in gains.K.ravel()), strict=True))
    values.update({s: e.xreplace(values) for s, e in relations.items()})
    exact = sp.Matrix(*K.shape, [values[s] for s in K])
    order, method = _chain_order(system, exact, len(directions))
    if order == T * m:
        return ControllerReduction(T * m, order, method=method), gains
    Kn = np.array(exact, dtype=float)
    poles = sorted_poles(np.array(system.A, dtype=float) + np.array(system.B, dtype=float) @ Kn)
    inputs = system.plant.input_names
    driven = tuple(_combination(Rm * sp.Matrix(d), inputs) for d in directions)
    blind = _unseen(_numbers(system.plant.A, "A"), _numbers(system.Q_plant, "Q"))
    blind = tuple(_combination(v, system.plant.state_names) for v in blind)
    reduction = ControllerReduction(
        T * m,
        order,
        relations,
        driven,
        blind,
        _reason(system, directions, blind, T * (m - len(directions)) - order),
        method,
    )
    return reduction, dataclasses.replace(gains, K=Kn, poles=poles)


def _directions(B: fmpq_mat, unseen: list) -> list[list[sp.Rational]]:
    """A basis of the input directions ``d`` with ``B d`` in the span of ``unseen``."""
    stacked = sp.Matrix.hstack(from_fmpq_mat(B), *(-sp.Matrix(v) for v in unseen))
    return [v[: B.ncols()] for v in _nullspace(_mat(stacked, "B"))]


def _solve(equations: list, symbols: list) -> dict:
    """The linear ``equations`` (each ``= 0``) solved for the latest ``symbols`` in the earliest."""
    if not equations:
        return {}
    order = symbols[::-1]  # rref's pivots are the leftmost: the latest symbols are solved for
    M, _ = sp.linear_eq_to_matrix(equations, order)
    R, rank = _mat(M, "equations").rref()
    pivots = _pivots(R) if rank else []
    free = [c for c in range(len(order)) if c not in pivots]
    solved = {
        order[p]: -sp.Add(*(from_fmpq(R[i, f]) * order[f] for f in free))
        for i, p in enumerate(pivots)
    }
    return {k: solved[k] for k in symbols if k in solved}


def _chain_order(system: AugmentedSystem, K: sp.Matrix, tied: int) -> tuple[int, str]:
    """The McMillan degree of the delay chain's controller with gains ``K``, and how it was found."""
    n, m, T = system.n, system.m, system.T
    if m == 1:  # K_0 / (z^T - K_1 z^(T-1) - ... - K_T): minimal unless K_0 = 0
        return (T if any(K[0, j] != 0 for j in range(n)) else 0), "K_0 != 0 (one input)"
    if T * m > MAX_ORDER:
        return T * (
            m - tied
        ), f"the theorem's count (the Kalman reduction takes {MAX_ORDER} states)"
    chain = Realization(*ifp_state_space(sp.Matrix(system.A), sp.Matrix(system.B), K, n, m, T))
    return minimal_realization(chain).n, ControllerReduction.method


def _reason(system: AugmentedSystem, directions, blind, unexplained: int) -> str:
    """Why the controller is not minimal, in words."""
    B = _numbers(system.plant.B, "B")
    reasons = []
    for d in directions:
        name = _combination(d, system.plant.input_names)
        if all(e == 0 for e in (B * _mat(sp.Matrix(d), "d")).entries()):
            how = "the same column" if sum(c != 0 for c in d) == 2 else "dependent columns"
            reasons.append(
                f"{name} moves no state: the inputs act on the plant through {how} of B (up to sign)"
            )
        else:
            reasons.append(
                f"{name} moves only {' and '.join(blind)}, which the cost never sees "
                "(Q weighs neither it nor any state it moves)"
            )
    if unexplained > 0:
        reasons.append(f"{unexplained} more states cancel between the poles and zeros of G(z)")
    return "; ".join(reasons)
