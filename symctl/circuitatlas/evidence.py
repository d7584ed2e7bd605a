"""The verdict on one pattern's universality, with its method and evidence (plain data for JSON).

>>> from symctl.circuitatlas.evidence import CONJECTURED, Evidence
>>> ev = Evidence(None, CONJECTURED, False, "witnesses at sampled G2")
>>> bool(ev), ev.verdict, ev.status, ev.sort_rank
(False, None, 'conjectured', 1)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType

from symctl.proof import Verdict

__all__ = ["CONJECTURED", "ODD_DEGREE", "Evidence"]

CONJECTURED = "conjectured"
"""The method of a pattern with real realizations at sampled G2 in every region: not a proof."""

ODD_DEGREE = "odd degree"
"""The method of a pattern proved universal by its generic fibre's odd degree."""


@dataclass(frozen=True)
class Evidence(Verdict):
    """Why a pattern is (or is not) universal; truthy when it is proved universal.

    The verdict protocol (:class:`~symctl.proof.Verdict`): :attr:`verdict` is
    :attr:`universal` (True proved, False refuted, None a conjecture or undecided),
    :attr:`evidence` the details; :attr:`status` says it in words.

    Attributes
    ----------
    universal : bool or None
        True (proved), False (refuted), or None (a conjecture, or not decided).
    method : str
        One of the methods of :mod:`~symctl.circuitatlas.universality` (``"closed form"``,
        ``"odd degree"``, ``"lifted"``, ``"conjectured"``, ``"rank"``, ``"real eigenvalues"``,
        ``"real zeros"``, ``"counterexample"``, ``"not minimal"``, ``"not decided"``).
    proved : bool
        Whether the verdict is a proof (closed forms, odd degrees, lifts of proofs and the
        refutations) or not (conjectures and undecided patterns).
    text : str
        One sentence.
    details : mapping
        The formulas, witnesses or the counterexample (plain data, for JSON).

    Examples
    --------
    >>> from symctl.circuitatlas.pattern import Pattern
    >>> from symctl.circuitatlas.universality import decide
    >>> ev = decide(Pattern.from_matrices([[0, 1], [1, 1]], [0, 1], [1, 1]))
    >>> bool(ev), ev.proved, sorted(ev.details["entries"])
    (True, True, ['F[1,2]', 'F[2,1]', 'F[2,2]', 'H[2]', 'M[1]', 'M[2]'])
    """

    universal: bool | None
    method: str
    proved: bool
    text: str
    details: MappingProxyType = field(default_factory=lambda: MappingProxyType({}))

    _verdict = "universal"

    @property
    def evidence(self):
        """The witness or certificate: :attr:`details` (read-only)."""
        return self.details

    @property
    def conjectured(self) -> bool:
        """Whether the pattern is conjectured universal (real realizations at sampled G2 only)."""
        return self.method == CONJECTURED

    @property
    def status(self) -> str:
        """``"universal"``, ``"conjectured"``, ``"not universal"`` or ``"not decided"``."""
        if self.conjectured:
            return CONJECTURED
        return {True: "universal", False: "not universal", None: "not decided"}[self.universal]

    @property
    def sort_rank(self) -> int:
        """0 proved universal, 1 conjectured, 2 not decided, 3 refuted (atlases sort by it)."""
        return 1 if self.conjectured else {True: 0, None: 2, False: 3}[self.universal]

    @classmethod
    def from_dict(cls, data: dict) -> Evidence:
        """The evidence that :meth:`to_dict` wrote."""
        return cls(
            data["universal"],
            data["method"],
            data["proved"],
            data["text"],
            MappingProxyType(dict(data.get("details", {}))),
        )

    def to_dict(self) -> dict:
        """Plain data for JSON."""
        return {
            "universal": self.universal,
            "method": self.method,
            "proved": self.proved,
            "text": self.text,
            "details": dict(self.details),
        }


def _evidence(universal, method, proved, text, **details) -> Evidence:
    return Evidence(universal, method, proved, text, MappingProxyType(details))
