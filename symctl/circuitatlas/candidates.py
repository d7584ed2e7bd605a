r"""Every circuit class that realizes one controller :math:`G`, with its compatibility, ranked.

:func:`circuits_for` factors :math:`G = G_3 G_2 G_1` along the delays and asks, class by class
of the order-:math:`n` atlas, whether the class realizes :math:`G_2` for *some* section poles
:math:`\epsilon` and gains :math:`C`: at generic (seeded random) :math:`\epsilon`, or, for a
**degenerate** class (generic rank below :math:`2n`), on a special set. With :math:`G = \nu /
\delta`, :math:`Z = \prod (z - \epsilon_i)`, the unknowns are the pattern's entries and the
:math:`\epsilon_i`, and the equations are :math:`\det(zI - F) = \delta` and :math:`M
\operatorname{adj}(zI - F) H = \nu Z - \nu_{\mathrm{lead}} \delta` (the gain :math:`\mu =
1/\prod C_i` set to 1 loses nothing: scaling :math:`M` keeps the pattern). A real point with
every entry nonzero and no cancellation between :math:`Z` and :math:`\delta` is found by
Gauss-Newton and proved by the Krawczyk test
(:func:`~symctl.circuitatlas.certify.certified_point`). Only section poles inside :data:`STABLE`
are accepted: an unstable section cancelled by a zero of :math:`G_2` would hide an unstable
mode. The paper's simplified circuits come out here, e.g. the controllable canonical circuit
without :math:`M_1` at :math:`K_2 + \epsilon_1 \epsilon_3 = 0`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import sympy as sp

from symctl._util.deprecate import rng_argument
from symctl._util.serial import DictMixin
from symctl.circuitatlas.certify import certified_point
from symctl.circuitatlas.circuitclass import CircuitClass
from symctl.circuitatlas.fibre import _system, binary_rationals
from symctl.compatibility.check import CompatibilityResult, check_compatibility
from symctl.compatibility.delaygraph import DelayGraph
from symctl.compatibility.structure import Structure
from symctl.design.tf import DiscreteTF
from symctl.errors import NotRealizableError, ParameterError, SymctlTypeError
from symctl.neural.circuit import Circuit
from symctl.realization.check import check_realization
from symctl.realization.factorization import Factorization, factor
from symctl.realization.realization import Realization, split_proper
from symctl.symbols import z

__all__ = ["CandidateCircuit", "circuits_for"]

MAX_ORDER = 3  # largest order of G2 (the exhaustive atlas)

STABLE = 0.999
"""Section poles lie inside this radius (an internally stable controller: module text)."""


@dataclass(frozen=True)
class CandidateCircuit(DictMixin):
    """One circuit class realizing a given controller, at given section values.

    Attributes
    ----------
    circuit_class : CircuitClass
    degenerate : bool
        True when the class needs special section poles (generic rank below :math:`2n`).
    eps, C : tuple
        The section poles and gains used (sensor sections first).
    factorization : Factorization
        :math:`G = G_3 G_2 G_1` at those values.
    realization : Realization
        The realization of :math:`G_2` with the class's pattern.
    check : RealizationCheck
        Its check against :math:`G_2` (exact, or numeric for floats).
    structure, circuit : Structure, Circuit
        The whole controller's (neurons placed when compatible).
    compatibility : CompatibilityResult or None
        The verdict on the delay graph (None without one).
    method : str
        How the realization was found.

    Examples
    --------
    >>> import symctl
    >>> G = -0.046 / (symctl.z**2 + 0.58 * symctl.z + 0.352)
    >>> best = symctl.circuits_for(G, symctl.DelayGraph.chain([1, 1]))[0]
    >>> best.degenerate, best.n_neurons, bool(best.check), best.compatible
    (True, 4, True, True)
    """

    circuit_class: CircuitClass
    degenerate: bool
    eps: tuple
    C: tuple
    factorization: Factorization
    realization: Realization
    check: object
    structure: Structure
    circuit: Circuit
    compatibility: CompatibilityResult | None
    method: str

    @property
    def n_neurons(self) -> int:
        """Neurons of the whole controller's circuit."""
        return self.circuit.n_neurons

    @property
    def n_synapses(self) -> int:
        """Synapses of the whole controller's circuit."""
        return len(self.circuit.synapses)

    @property
    def compatible(self) -> bool | None:
        """The compatibility verdict (None without a delay graph)."""
        return None if self.compatibility is None else bool(self.compatibility)

    def __repr__(self) -> str:
        kind = "degenerate" if self.degenerate else "generic"
        eps = ", ".join(f"{float(e):.4g}" for e in self.eps)
        return (
            f"CandidateCircuit({self.circuit_class.label}, {kind}, eps=({eps}), "
            f"{self.n_neurons} neurons, {self.n_synapses} synapses, compatible={self.compatible})"
        )


@rng_argument("random")
def circuits_for(
    G,
    graph: DelayGraph | None = None,
    *,
    sensor_delay: int = 1,
    actuator_delay: int = 1,
    atlas=None,
    rng=0,
) -> tuple[CandidateCircuit, ...]:
    """Every circuit class of the atlas that realizes the controller ``G``, ranked (module text).

    Parameters
    ----------
    G : DiscreteTF or sympy expression in ``z``
        A SISO controller with numeric coefficients (floats taken as the exact rationals they are).
    graph : DelayGraph, optional
        The delay graph each candidate is checked against.
    sensor_delay, actuator_delay : int
        The sections of :math:`G_1` and :math:`G_3`.
    atlas : Atlas, optional
        The atlas of :math:`G_2`'s order (built when not given).
    rng : int, numpy Generator or None, default 0
        Seeds the generic section poles and the numeric searches (``seed=`` is deprecated).

    Returns
    -------
    tuple of CandidateCircuit
        Ranked by neurons, then synapses.

    Raises
    ------
    ParameterError
        ``G`` with symbolic coefficients, or a :math:`G_2` of order 0 or above
        :data:`MAX_ORDER`, or with :math:`N = 0`.
    NotRealizableError
        No class of the atlas realizes ``G``.

    Examples
    --------
    >>> import symctl
    >>> G = -0.046 / (symctl.z**2 + 0.58 * symctl.z + 0.352)
    >>> [c.degenerate for c in symctl.circuits_for(G)][:3]
    [True, True, False]
    """
    from symctl.circuitatlas.atlas import Atlas
    from symctl.circuitatlas.atlas import atlas as build_atlas

    tf = DiscreteTF.from_expr(G)
    if tf.free_symbols - {z}:
        raise ParameterError(
            f"G: give numeric coefficients (substitute the gains), got the symbols "
            f"{sorted(map(str, tf.free_symbols - {z}))}"
        )
    if graph is not None and not isinstance(graph, DelayGraph):
        raise SymctlTypeError(f"graph: expected a DelayGraph, got {type(graph).__name__}")
    T = sensor_delay + actuator_delay
    generic = factor(tf, sensor_delay, actuator_delay)
    n = generic.G2.order
    if not 1 <= n <= MAX_ORDER:
        raise ParameterError(
            f"G: its G2 has order {n}; circuits_for handles orders 1 to {MAX_ORDER}"
        )
    if atlas is None:
        atlas = build_atlas(n, workers=1 if n <= 2 else None)
    elif not isinstance(atlas, Atlas) or atlas.order != n:
        raise ParameterError(f"atlas: expected the order-{n} atlas, got {atlas!r}")
    eps = _generic_eps(T, tf, rng)
    at_eps = factor(tf, sensor_delay, actuator_delay, eps=eps, C=1)
    found = []
    for cls in atlas.classes:
        if cls.evidence.method in ("rank", "not minimal"):
            hit = _degenerate(cls, tf, sensor_delay, actuator_delay, rng)
        else:
            hit = _generic(cls, at_eps, eps)
        if hit is not None:
            found.append(_candidate(cls, *hit, graph))
    if not found:
        raise NotRealizableError(
            f"G: no circuit class of the order-{n} atlas realizes this controller (its G2 = "
            f"{at_eps.G2.expr})"
        )
    found.sort(key=lambda c: (c.n_neurons, c.n_synapses, c.degenerate, c.circuit_class.label))
    return tuple(found)


def _generic_eps(T: int, tf: DiscreteTF, rng) -> list:
    poles = set(sp.Poly(tf.den, z).nroots()) if tf.order else set()
    out = []
    while len(out) < T:
        e = sp.Rational(rng.choice([-1, 1]) * rng.randint(1, 9), 10)
        if e not in out and all(abs(complex(e - p)) > 1e-6 for p in poles):
            out.append(e)
    return out


def _generic(cls: CircuitClass, f: Factorization, eps):
    try:
        R = cls.realize(f.G2)
    except NotRealizableError:
        return None
    return False, tuple(eps), (1,) * len(eps), f, R, R.params.get("method", "")


@functools.lru_cache(maxsize=8)
def _targets(tf: DiscreteTF, T: int):
    """What every degenerate class of one controller solves for: the sections' poles ``e``,
    the coefficients (lowest first) of G's monic denominator and of ``nu Z - lead delta``, and
    G's poles."""
    e = sp.symbols(f"e_0:{T}")
    Z = sp.Mul(*(z - ei for ei in e))
    num = sp.Poly(tf.num, z)
    den = sp.Poly(tf.den, z)
    lead_den = den.LC()
    nu = num.as_expr() / lead_den
    delta = den.as_expr() / lead_den
    lead = sp.Poly(nu, z).LC()
    monic = sp.Poly(delta, z)
    target_b = sp.Poly(sp.expand(nu * Z - lead * delta), z).all_coeffs()[::-1]
    return e, monic.all_coeffs()[::-1], target_b, monic.nroots()


def _degenerate(cls: CircuitClass, tf: DiscreteTF, ds: int, da: int, rng):
    pattern = cls.representatives[0]
    n = pattern.n
    T = ds + da
    unknowns, _slots, values, charpoly, numer = _system(pattern)
    e, target_a, target_b, poles = _targets(tf, T)
    target_a = target_a[:n]
    target_b = target_b + [sp.Integer(0)] * (n - len(target_b))
    eqs = [sp.expand(p - binary_rationals(t)) for p, t in zip(charpoly, target_a, strict=True)]
    eqs += [sp.expand(p - binary_rationals(t)) for p, t in zip(numer, target_b[:n], strict=True)]
    gens = [*unknowns, *e]
    if len(gens) < len(eqs):
        return None

    def accept(v):  # stable sections (an internally stable controller), nonzero entries
        return all(abs(v[ei]) < STABLE for ei in e) and all(abs(v[x]) > 1e-6 for x in unknowns)

    point = certified_point(
        eqs, gens, seed=rng.randrange(2**32), starts=12, scale=0.6, accept=accept
    )
    if point is None:
        return None
    vals = point["values"]
    if any(abs(vals[x]) < 1e-9 for x in unknowns) or any(abs(vals[ei]) >= 1 for ei in e):
        return None
    eps_vals = tuple(sp.Float(vals[ei], 15) for ei in e)
    if any(abs(complex(p) - float(ev)) < 1e-7 for p in poles for ev in eps_vals):
        return None  # a pole-zero cancellation: G2 would lose order
    C = (sp.Integer(1),) * T
    f = factor(tf, ds, da, eps=list(eps_vals), C=list(C))
    entries = {
        k: sp.Float(vals[values[k]], 15) if values[k] in vals else values[k]
        for k in pattern.indices
    }
    F, H, M = pattern.matrices(entries)
    R = Realization(F, H, M, split_proper(f.G2)[0])
    return True, eps_vals, C, f, R, "special eps: Gauss-Newton, Krawczyk-certified"


def _floats(R: Realization) -> Realization:
    """R with algebraic entries as 30-digit floats, for checks and drawings."""
    if all(v.is_Rational or not v.is_number for m in (R.F, R.H, R.M, R.N) for v in m):
        return R
    F, H, M, N = (m.evalf(30) for m in (R.F, R.H, R.M, R.N))
    return Realization(F, H, M, N, params=R.params)


def _candidate(cls, degenerate, eps, C, f, R, method, graph):
    shown = _floats(R)  # exact algebraic entries were proved in CircuitClass.realize
    check = check_realization(shown, f.G2, "auto", rng=0)
    S = Structure.from_factorization(f, shown)
    result = None if graph is None else check_compatibility(S, graph)
    circuit = Circuit.from_structure(S, result if result is not None and result.ok else None)
    return CandidateCircuit(cls, degenerate, eps, C, f, R, check, S, circuit, result, method)
