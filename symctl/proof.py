"""Verdicts: every checker's result is truthy when its claim holds, with its ``method`` and
``evidence`` (docs/conventions.md); :class:`Proof` is the result of an exact proof."""

from __future__ import annotations

from dataclasses import dataclass

from symctl._util.serial import DictMixin

__all__ = ["Proof", "Verdict"]


class Verdict(DictMixin):
    """The verdict protocol, mixed into every checker's and decision's result: ``bool(result)``,
    ``.verdict`` (None when undecided), ``.method``, ``.evidence``, ``to_dict()``/``from_dict()``.
    A subclass names the attribute holding its verdict in ``_verdict``.

    Examples
    --------
    >>> from symctl import DelayGraph, check_compatibility, ifp_structure
    >>> from symctl.proof import Verdict
    >>> r = check_compatibility(ifp_structure(2), DelayGraph.chain([0]))
    >>> isinstance(r, Verdict), bool(r), r.verdict, r.method
    (True, True, True, 'chain: bounds arc consistency')
    """

    __slots__ = ()
    _verdict: str = "verdict"

    @property
    def verdict(self) -> bool | None:
        """True when the claim holds, False when it fails, None when undecided."""
        return getattr(self, self._verdict)

    def __bool__(self) -> bool:
        return bool(self.verdict)


@dataclass(frozen=True, eq=False)
class Proof(Verdict):
    """An exact verdict on a claim; it equals its verdict's bool (``proof == True``).

    Parameters
    ----------
    holds : bool
        Whether the claim was proved.
    claim : str
        What was proved (or refuted).
    method : str
        How: the exact algebra used.
    evidence : str, optional
        For a refuted claim, a nonzero entry of the difference.

    Examples
    --------
    >>> from symctl.proof import Proof
    >>> p = Proof(True, "G3 G2 G1 = G", "cross-multiplication")
    >>> bool(p), p == True, p.verdict, p
    (True, True, True, Proof(True, claim='G3 G2 G1 = G', method='cross-multiplication'))
    >>> bool(Proof(False, "x = y", "expand", evidence="x - y"))
    False
    """

    _verdict = "holds"

    holds: bool
    claim: str
    method: str
    evidence: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "holds", bool(self.holds))

    def __eq__(self, other) -> bool:
        if isinstance(other, bool):
            return self.holds == other
        if isinstance(other, Proof):
            return vars(self) == vars(other)
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self.holds)  # equal to its verdict's bool, so the hash must be too

    def __repr__(self) -> str:
        tail = f", evidence={self.evidence!r}" if self.evidence else ""
        return f"Proof({self.holds}, claim={self.claim!r}, method={self.method!r}{tail})"
