r"""Realizers, the ways of realizing :math:`G_2` (after nengolib's ``signal/realizers.py``):
:data:`REALIZERS` is the one table of their names, titles and order; :func:`register` adds one
(docs/extending.md)."""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl._util.serial import DictMixin
from symctl._util.validate import as_generator, numeric_matrix, real_number
from symctl.design.controller import ifp_state_space
from symctl.design.lqr import Gains
from symctl.design.tf import DiscreteTF
from symctl.errors import ParameterError, SymctlTypeError
from symctl.realization.check import require_stable_sections
from symctl.realization.realization import (
    Realization,
    controllable_canonical,
    observable_canonical,
)

__all__ = [
    "REALIZERS",
    "Realizer",
    "RealizerResult",
    "circuit_names",
    "general_realization",
    "get_realizer",
    "ifp_realization",
    "random_full_rank",
    "random_realization",
    "register",
    "unregister",
]


@dataclass(frozen=True)
class RealizerResult(DictMixin):
    r"""What a realizer returns: the realization, its base and the transform between them.

    Attributes
    ----------
    sys : DiscreteTF
        The realized transfer function (after the realizer's substitutions).
    base, realization : Realization
        The canonical realization :math:`(F_0, H_0, M_0, N)` and ``base.similar(P)``.
    P, Pinv : sympy.ImmutableMatrix
        The transform; ``Pinv`` None for a symbolic ``P`` (never inverted).

    Examples
    --------
    >>> from symctl import z
    >>> from symctl.realization.realizers import get_realizer
    >>> result = get_realizer("controllable")(1 / (z - 2))
    >>> result.realization == result.base, result.P, result.Pinv
    (True, Matrix([[1]]), Matrix([[1]]))
    """

    sys: DiscreteTF
    base: Realization
    P: sp.ImmutableMatrix
    Pinv: sp.ImmutableMatrix | None
    realization: Realization


@dataclass(frozen=True)
class Realizer:
    """A way of realizing a proper :math:`G_2`, called for a :class:`RealizerResult`: subclass it,
    define ``__call__(self, G2, *, rng=None)`` and :func:`register` an instance.

    Attributes
    ----------
    name, title : str
        Its key in :data:`REALIZERS` (the word of model files and the CLI), a human title.
    canonical, takes_transform, keeps_symbols, circuit, paper, controller : bool
        A canonical form (a valid ``base``); accepts a transform ``P``; keeps free symbols;
        builds a circuit of its own; one of the paper's forms; realizes the whole controller
        from its :class:`~symctl.Gains`.
    form : str
        The words naming its :math:`G_2` in a circuit's title (default: the title).

    Examples
    --------
    >>> from symctl import Realizer, get_realizer, z
    >>> r = get_realizer("controllable")
    >>> isinstance(r, Realizer), r.canonical, r(1 / (z - 2)).realization.F
    (True, True, Matrix([[2]]))
    """

    name: str
    title: str
    canonical: bool = False
    takes_transform: bool = False
    keeps_symbols: bool = True
    form: str = ""
    circuit: bool = True
    paper: bool = False
    controller: bool = False

    def __post_init__(self):
        if not self.form:
            object.__setattr__(self, "form", self.title)

    def __call__(self, G2, **options) -> RealizerResult:  # pragma: no cover - abstract
        raise NotImplementedError


def _identity(R: Realization, tf: DiscreteTF) -> RealizerResult:
    eye = sp.ImmutableMatrix(sp.eye(R.n))
    return RealizerResult(tf, R, eye, eye, R)


@dataclass(frozen=True)
class _Canonical(Realizer):
    def __call__(self, G2, *, rng=None) -> RealizerResult:
        form = controllable_canonical if self.name == "controllable" else observable_canonical
        return _identity(form(G2), DiscreteTF.from_expr(G2))


def _transformed(base: Realization, tf: DiscreteTF, P) -> RealizerResult:
    R, Pinv = base._similar(P)
    P = R.params["P"]
    return RealizerResult(tf, base, P, None if P.free_symbols else Pinv, R)


@dataclass(frozen=True)
class _General(Realizer):
    def __call__(self, G2, P=None, *, base: str = "controllable", rng=None) -> RealizerResult:
        """The ``base`` form transformed by ``P`` (``None``: drawn from ``rng``)."""
        start = get_realizer(base, "base", where=_canonical)(G2).realization
        tf = DiscreteTF.from_expr(G2)
        if start.n == 0:
            return _identity(start, tf)
        if P is None:
            P = random_full_rank(start.n, as_generator(rng, "rng"))
        return _transformed(start, tf, P)


@dataclass(frozen=True)
class _Random(Realizer):
    def __call__(
        self,
        G2,
        rng=None,
        *,
        base: str = "controllable",
        eps_range: tuple[float, float] = (-0.9, 0.9),
        values: dict | None = None,
    ) -> RealizerResult:
        """The paper's recipe (:func:`random_realization`)."""
        gen = as_generator(rng, "rng")
        low, high = _eps_range(eps_range)
        tf = DiscreteTF.from_expr(G2)
        if values is not None and not isinstance(values, Mapping):
            raise SymctlTypeError(
                f"values: expected a mapping of symbols (or names) to values, got {values!r}"
            )
        if values:
            tf = tf.subs(values)  # checked by subs_rule: text goes to the safe parser
        eps = sorted(
            (s for s in tf.free_symbols if s.name.startswith("epsilon")), key=lambda s: s.name
        )
        chosen = {
            s: sp.Rational(int(gen.integers(round(low * 1000), round(high * 1000) + 1)), 1000)
            for s in eps
        }
        tf = tf.subs(chosen)
        start = get_realizer(base, "base", where=_canonical)(tf).realization
        out = _transformed(start, tf, random_full_rank(start.n, gen))
        R = replace(out.realization, params={**chosen, **out.realization.params})
        return replace(out, realization=R)


def _eps_range(value) -> tuple[float, float]:
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise SymctlTypeError(f"eps_range: expected a pair (low, high), got {value!r}")
    low, high = (real_number(v, "eps_range") for v in value)
    if low > high:
        raise ParameterError(f"eps_range: needs low <= high, got {value!r}")
    if max(abs(low), abs(high)) > 1e6:
        raise ParameterError(f"eps_range: bounds must lie in [-1e6, 1e6], got {value!r}")
    require_stable_sections((low, high), "eps_range")  # |eps| >= 1 is a hidden unstable mode
    return low, high


@dataclass(frozen=True)
class _IFP(Realizer):
    def __call__(self, gains, *, rng=None) -> RealizerResult:
        R = ifp_realization(gains)
        return _identity(R, R.to_tf())


_REGISTRY: dict[str, Realizer] = {
    r.name: r
    for r in (
        _IFP("ifp", "IFP controller", keeps_symbols=False, paper=True, controller=True),
        _General(
            "general",
            "general (similarity transform)",
            takes_transform=True,
            form="general",
            paper=True,
        ),
        _Canonical("controllable", "controllable canonical", canonical=True, paper=True),
        _Canonical("observable", "observable canonical", canonical=True, paper=True),
        _Random("random", "random (the paper's recipe)", keeps_symbols=False, circuit=False),
    )
}
_BUILTIN = frozenset(_REGISTRY)
_RESERVED = ("all", "pathways")  # the fits' classes, the report's graph-built circuit
_NAME = re.compile(r"[a-z][a-z0-9_]{0,31}")

REALIZERS: Mapping[str, Realizer] = MappingProxyType(_REGISTRY)
"""Every realizer, by name, in the report's order (a read-only view; :func:`register` adds one)."""


def _canonical(realizer: Realizer) -> bool:
    return realizer.canonical


def circuit_names(*, whole: bool = True) -> tuple[str, ...]:
    """The circuits a model builds, in the report's order (registered ones included); ``whole``:
    with those of the whole controller (IFP), else only :math:`G_3 G_2 G_1`'s.

    >>> from symctl.realization.realizers import circuit_names
    >>> circuit_names()
    ('ifp', 'general', 'controllable', 'observable')
    >>> circuit_names(whole=False)
    ('general', 'controllable', 'observable')
    """
    return tuple(k for k, r in _REGISTRY.items() if r.circuit and (whole or not r.controller))


def register(realizer: Realizer) -> Realizer:
    """Add ``realizer`` (an instance of a subclass defining ``__call__(G2, *, rng=None)``) to
    :data:`REALIZERS` after the others, and return it (docs/extending.md). Raises
    SymctlTypeError for another type, ParameterError for a name taken, reserved (``"all"``,
    ``"pathways"``) or not a lower-case identifier of at most 32 characters."""
    if not isinstance(realizer, Realizer):
        raise SymctlTypeError(f"realizer: expected a Realizer, got {type(realizer).__name__}")
    name = realizer.name
    if not isinstance(name, str) or not _NAME.fullmatch(name):
        raise ParameterError(
            f"realizer: its name must be a lower-case identifier (a-z, 0-9, _; at most 32), "
            f"got {name!r}"
        )
    if name in _REGISTRY or name in _RESERVED:
        raise ParameterError(f"realizer: the name {name!r} is taken")
    if not isinstance(realizer.title, str) or not realizer.title:
        raise ParameterError(
            f"realizer: its title must be a nonempty string, got {realizer.title!r}"
        )
    _REGISTRY[name] = realizer
    return realizer


def unregister(name: str) -> Realizer:
    """Remove the realizer :func:`register` ed as ``name`` and return it (ParameterError for a
    built-in or unknown one)."""
    if name in _BUILTIN:
        raise ParameterError(f"name: {name!r} is built in and cannot be removed")
    added = [k for k in _REGISTRY if k not in _BUILTIN]
    if name not in added:
        raise ParameterError(f"name: {name!r} is not a registered realizer (registered: {added})")
    return _REGISTRY.pop(name)


def get_realizer(name: str, argname: str = "name", *, where=None) -> Realizer:
    """The realizer registered as ``name``.

    Parameters
    ----------
    name : str
        A key of :data:`REALIZERS`.
    argname : str
        The caller's argument, named in the error.
    where : callable, optional
        Admit only the realizers for which ``where(realizer)`` is true.

    Returns
    -------
    Realizer

    Raises
    ------
    ParameterError
        Not an admitted realizer (naming ``argname``, the value and the choices).

    Examples
    --------
    >>> from symctl.realization.realizers import get_realizer
    >>> get_realizer("observable").title
    'observable canonical'
    >>> get_realizer("diagonal", "base")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: base: must be 'ifp', ... or 'random', got 'diagonal'
    """
    names = [k for k, r in REALIZERS.items() if where is None or where(r)]
    if not isinstance(name, str) or name not in names:
        choices = ", ".join(map(repr, names[:-1])) + f" or {names[-1]!r}"
        raise ParameterError(f"{argname}: must be {choices}, got {name!r}")
    return REALIZERS[name]


def general_realization(G2, P, base: str = "controllable") -> Realization:
    r"""A general realization: the similarity transform by ``P`` of a canonical one.

    Parameters
    ----------
    G2 : DiscreteTF or sympy expression in z
        A proper transfer function.
    P : (n, n) matrix-like
        Invertible; symbolic or numeric.
    base : {"controllable", "observable"}
        The canonical realization transformed.

    Returns
    -------
    Realization
        :math:`(P^{-1} F_0 P,\ P^{-1} H_0,\ M_0 P,\ N)`, with ``params == {"P": P}``.

    Raises
    ------
    ParameterError, DimensionError
        Unknown ``base``; ``P`` singular; ``G2`` improper; ``P`` not ``n x n``.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl import general_realization, z
    >>> R = general_realization(1 / (z - sp.Rational(1, 2)), [[2]])
    >>> R.F, R.H, R.M
    (Matrix([[1/2]]), Matrix([[1/2]]), Matrix([[2]]))
    """
    start = get_realizer(base, "base", where=_canonical)(G2).realization
    return start.similar(P)


def random_full_rank(n: int, rng=None, *, max_cond: float | None = None) -> sp.Matrix:
    """A random ``n x n`` matrix of hundredths, entries about N(0, 1), redrawn until its
    condition number is below ``max_cond`` (default ``max(10, 5 n)``: two draws in three pass)."""
    gen = as_generator(rng, "rng")
    max_cond = max(10.0, 5.0 * n) if max_cond is None else max_cond
    for _ in range(10_000):
        P = sp.Matrix(n, n, lambda i, j: sp.Rational(round(gen.normal() * 100), 100))
        if n == 0 or np.linalg.cond(np.array(P, dtype=float)) < max_cond:
            return P
    raise ParameterError(
        f"n: no well-conditioned random matrix found for n = {n}"
    )  # pragma: no cover


def random_realization(
    G2,
    rng=None,
    *,
    base: str = "controllable",
    eps_range: tuple[float, float] = (-0.9, 0.9),
    values: dict | None = None,
) -> Realization:
    r"""The paper's recipe for its figures: random epsilons, then a random full-rank ``P``.

    Every free symbol ``epsilon...`` of ``G2`` gets a random multiple of 1/1000 in
    ``eps_range``; the ``base`` realization is then transformed by a random rational ``P``
    (:func:`random_full_rank`). Other symbols stay unless given in ``values``.

    Parameters
    ----------
    G2 : DiscreteTF or sympy expression in z
        A proper transfer function.
    rng : None, int or numpy.random.Generator, optional
    base : {"controllable", "observable"}
        The canonical realization transformed.
    eps_range : (float, float)
        Inside (-1, 1) (:func:`~symctl.realization.check.require_stable_sections`).
    values : dict, optional
        Values substituted first.

    Returns
    -------
    Realization
        With the epsilons and ``P`` used in ``.params``.

    Raises
    ------
    ParameterError
        Unknown ``base``; ``G2`` improper; a bad ``rng`` or ``eps_range``.

    Examples
    --------
    >>> from symctl import controller_tf, factor, random_realization
    >>> R = random_realization(factor(controller_tf(2)).G2, rng=1)
    >>> sorted(str(k) for k in R.params)
    ['P', 'epsilon_1', 'epsilon_3']
    """
    return REALIZERS["random"](G2, rng, base=base, eps_range=eps_range, values=values).realization


def ifp_realization(gains: Gains) -> Realization:
    r"""The optimal controller as the paper's IFP structure: the delay chain with :math:`\mu = K\chi`
    (:func:`symctl.design.controller.ifp_state_space`).

    Parameters
    ----------
    gains : Gains
        The optimal gains (:func:`symctl.lqr_gains`) of a numeric system.

    Returns
    -------
    Realization
        Numeric, with the plant's sampling time (SymctlTypeError for other ``gains``).

    Examples
    --------
    >>> from symctl import MuscleModel, augment, ifp_realization, lqr_gains
    >>> R = ifp_realization(lqr_gains(augment(MuscleModel(), 1, 1)))
    >>> [round(float(v), 4) for v in R.F], R.M
    ([-0.58, -0.3518, 1.0, 0.0], Matrix([[0, 1]]))
    """
    if not isinstance(gains, Gains):
        raise SymctlTypeError(
            f"gains: expected Gains (from symctl.lqr_gains), got {type(gains).__name__}"
        )
    s = gains.system
    A, B = numeric_matrix(s.A, "gains"), numeric_matrix(s.B, "gains")
    K = np.asarray(gains.K, dtype=float)
    return Realization(*ifp_state_space(A, B, K, s.n, s.m, s.T), s.plant.dt)
