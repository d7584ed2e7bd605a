r"""Compatibility of a controller (a transfer function) with a delay graph: the chain theorem.

A controller is compatible with a delay graph when one of its realizations has
a compatible structure (the paper's section "Structure, delay graphs, and
compatibility"). :func:`controller_compatibility` decides it for chain graphs by
a theorem (proved in its docstring) and a construction checked by
:func:`symctl.check_compatibility`; for other graphs it searches the family of
structures symctl builds and says so.

>>> from symctl import DelayGraph, controller_compatibility, controller_tf
>>> r = controller_compatibility(controller_tf(2), DelayGraph.chain([1, 1]))
>>> r.ok, r.scope
(True, 'all realizations')
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from symctl._util.display import LatexMixin
from symctl.compatibility.check import CompatibilityResult, check_compatibility
from symctl.compatibility.delaygraph import DelayGraph
from symctl.compatibility.structure import Structure
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.realization.factorization import factor
from symctl.realization.realization import controller_realization
from symctl.realization.realizers import REALIZERS, get_realizer

__all__ = ["ControllerCompatibility", "controller_compatibility"]


@dataclass(frozen=True)
class ControllerCompatibility(LatexMixin):
    r"""Whether some realization of a controller has a structure compatible with a delay graph.

    The verdict of :func:`controller_compatibility`; truthy exactly when
    compatible (``bool(r) == r.ok``), compared and hashed by its fields.

    Parameters
    ----------
    ok : bool
        Whether a compatible realization exists (within ``scope``).
    realization : Realization or None
        The whole controller's realization (series of the parts) when found.
    structure : Structure or None
        Its compatible structure (the series of the parts' structures).
    check : CompatibilityResult or None
        The structure-level result with the witness assignment.
    reason : str
        The argument: the theorem's condition that fails, or the construction.
    scope : str
        ``"all realizations"`` when the verdict is a theorem about every
        realization, ``"family"`` when it only covers the structures searched.
    method : str
        ``"theorem (chain graphs)"``, ``"necessary condition"``, or the search.

    Examples
    --------
    >>> from symctl import DelayGraph, controller_compatibility, controller_tf
    >>> r = controller_compatibility(controller_tf(2), DelayGraph.chain([1, 1]))
    >>> bool(r), r.scope, bool(r.check)
    (True, 'all realizations', True)
    >>> no = controller_compatibility(controller_tf(2), DelayGraph.chain([2]))
    >>> bool(no), no.realization is None
    (False, True)
    """

    ok: bool
    realization: object
    structure: Structure | None
    check: CompatibilityResult | None
    reason: str
    scope: str
    method: str

    def __bool__(self) -> bool:
        return self.ok

    def latex(self) -> str:
        return (
            r"\text{" + ("compatible" if self.ok else "not compatible") + f" ({self.scope})" + "}"
        )

    def __repr__(self) -> str:
        return (
            f"ControllerCompatibility(ok={self.ok}, scope={self.scope!r}, method={self.method!r})"
        )


def _build(G: DiscreteTF, ds: int, da: int, base: str, delays: str):
    f = factor(G, ds, da)
    realizer = get_realizer(base, "base", where=lambda r: r.keeps_symbols)
    n = f.G2.order  # a transform is dense and fixed: I + 1 1^T (det n + 1)
    options = {"P": sp.eye(n) + sp.ones(n, n)} if realizer.takes_transform else {}
    R2 = realizer(f.G2, **options).realization
    return controller_realization(f, R2), Structure.from_factorization(f, R2, delays)


def controller_compatibility(
    G, graph: DelayGraph, *, base: str = "controllable", delays: str = "branch"
) -> ControllerCompatibility:
    r"""Decide whether a SISO controller :math:`G` has a realization compatible with a delay graph.

    **Theorem (chain graphs).** Let the chain :math:`v_1 \to \dots \to v_N` have
    step delays :math:`d_1, \dots, d_{N-1}` and total :math:`D = \sum_k d_k`,
    and let :math:`G \ne 0` be proper with relative degree :math:`r`. Some
    structure of some realization of :math:`G` is compatible with the chain iff
    :math:`r \ge D` and every :math:`d_k \le 1`.

    *Proof.* Necessity: in a compatible assignment every wire
    :math:`a \xrightarrow{w} b` has :math:`E_{v(a) v(b)} \le w \le 1` (wires of
    a realization's structure carry at most one unit delay), so :math:`v(a)`
    comes no later than :math:`v(b)` on the chain and a wire that crosses step
    :math:`k` needs :math:`d_k \le 1`. As :math:`G \ne 0` some path runs from the
    input (at :math:`v_1`) to the output (at :math:`v_N`); it crosses every step,
    and the delays of its wires add up to at least :math:`D`. Every path from
    input to output thus has at least :math:`D` delays, so
    :math:`y(t)` depends on :math:`u(t-D), u(t-D-1), \dots` only: the first
    :math:`D` Markov parameters vanish and :math:`r \ge D`. Sufficiency: factor
    :math:`G = G_3 G_2 G_1` with one first-order section
    :math:`C/(z - \epsilon)` per unit step (:func:`symctl.factor`,
    :math:`G_2` proper as :math:`r \ge D`), give the sections the branch
    structure and :math:`G_2` any realization; put each section's output at the
    vertex after its step and :math:`G_2` at the vertex where the sensor-side
    steps end, as the paper does for :math:`T = 2`. The checker confirms the
    constructed structure with a witness. :math:`G = 0` is always compatible.
    :math:`\square`

    A chain step of 2 or more delays can therefore never be crossed by a
    structure built from unit delays (a signal must sit at a vertex after every
    unit delay); split such a step with relay vertices if that is what it means.

    **Other graphs.** The necessary condition :math:`r \ge E_{1N}` holds for any
    graph (same argument). Beyond it, symctl searches the structures it can
    build: every split :math:`d_s + d_a \le r` into first-order sections, with
    :math:`G_2` in controllable, observable or general (dense) form and branch or
    state delays. A negative answer then covers **only that family**
    (``scope == "family"``); another realization may still be compatible.

    Parameters
    ----------
    G : DiscreteTF or sympy expression in z
        The controller, SISO and proper.
    graph : DelayGraph
    base : {"controllable", "observable", "general"}
        The realization of :math:`G_2` in the chain construction.
    delays : {"branch", "state"}
        The structure of :math:`G_2` in the chain construction.

    Returns
    -------
    ControllerCompatibility
        Truthy when compatible, with the realization, its structure and the
        witness, or the reason and its ``scope``.

    Raises
    ------
    SymctlTypeError
        ``graph`` is not a DelayGraph.
    DimensionError
        ``G`` is not SISO.
    ParameterError
        ``G`` is improper, or an unknown ``base`` or ``delays``.

    Examples
    --------
    >>> from symctl import DelayGraph, controller_compatibility, controller_tf
    >>> r = controller_compatibility(controller_tf(2), DelayGraph.chain([1, 1, 1]))
    >>> r.ok, r.scope
    (False, 'all realizations')
    >>> print(r.reason)  # doctest: +ELLIPSIS
    Not compatible: the relative degree 2 of G is below the chain's total delay 3 ...
    """
    tf = DiscreteTF.from_expr(G)
    if not isinstance(graph, DelayGraph):
        raise SymctlTypeError(f"graph: expected a DelayGraph, got {type(graph).__name__}")
    if not tf.is_siso:
        raise DimensionError(
            f"G: controller compatibility is decided for SISO G, got shape {tf.shape}"
        )
    get_realizer(base, "base", where=lambda r: r.keeps_symbols)
    if delays not in ("branch", "state"):
        raise ParameterError(f"delays: must be 'branch' or 'state', got {delays!r}")
    r = tf.relative_degree
    if r < 0:
        raise ParameterError("G: improper (numerator degree above denominator degree)")
    zero = tf.num == 0
    total = graph.E[0, graph.n - 1]
    steps = graph.chain_delays
    theorem = "theorem (chain graphs)" if steps is not None else "necessary condition"
    if not zero and r < total:
        return ControllerCompatibility(
            False,
            None,
            None,
            None,
            f"Not compatible: the relative degree {r} of G is below the "
            f"{'chain' if steps is not None else 'graph'}'s total delay {int(total)} = E[1,{graph.n}]; "
            "every path from the input to the output of any compatible structure has at least "
            "that many delays, so the first Markov parameters of G would vanish.",
            "all realizations",
            theorem,
        )
    if steps is not None and not zero and max(steps) > 1:
        k = next(i for i, d in enumerate(steps) if d > 1)
        return ControllerCompatibility(
            False,
            None,
            None,
            None,
            f"Not compatible: step {k + 1} of the chain has delay {steps[k]} > 1; a wire of a "
            "realization's structure carries at most one unit delay, so no signal path from the "
            "input to the output can cross that step.",
            "all realizations",
            theorem,
        )
    if steps is not None:
        ds = int(total) // 2
        da = int(total) - ds
        realization, structure = _build(tf, ds, da, base, delays)
        check = check_compatibility(structure, graph)
        if not check.ok:  # pragma: no cover - contradicts the theorem
            raise RuntimeError("the chain construction is not compatible:\n" + check.reason)
        return ControllerCompatibility(
            True,
            realization,
            structure,
            check,
            f"Compatible (theorem for chain graphs): G = G3 G2 G1 with {ds} sensor-side and {da} "
            f"actuator-side first-order sections, G2 {base} with {delays} delays. " + check.reason,
            "all realizations",
            "theorem (chain graphs) + construction",
        )
    tried = 0
    for ds in range(r + 1 if not zero else 1):
        for da in range(r - ds + 1 if not zero else 1):
            for b in (k for k, r in REALIZERS.items() if r.keeps_symbols):
                for d in ("branch", "state"):
                    realization, structure = _build(tf, ds, da, b, d)
                    check = check_compatibility(structure, graph)
                    tried += 1
                    if check.ok:
                        return ControllerCompatibility(
                            True,
                            realization,
                            structure,
                            check,
                            f"Compatible: G = G3 G2 G1 with {ds} sensor-side and {da} actuator-side "
                            f"sections, G2 {b} with {d} delays. " + check.reason,
                            "all realizations",
                            f"family search ({tried} structures)",
                        )
    return ControllerCompatibility(
        False,
        None,
        None,
        None,
        f"None of the {tried} structures symctl builds for G (first-order sections d_s + d_a <= "
        f"{r}, G2 controllable / observable / general, branch / state delays) is compatible. "
        "This answer covers only that family: another realization or structure of G may still "
        "be compatible.",
        "family",
        f"family search ({tried} structures)",
    )
