"""The verdict on one pattern's universality, with its method and evidence (plain data for JSON)."""

from __future__ import annotations

from dataclasses import dataclass, field, fields
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

    Attributes
    ----------
    universal : bool or None
        The verdict: True (proved), False (refuted), or None (a conjecture, or not decided).
    method : str
        ``"closed form"``, ``"odd degree"``, ``"lifted"``, ``"conjectured"``, ``"rank"``,
        ``"real eigenvalues"``, ``"real zeros"``, ``"counterexample"``, ``"not minimal"`` or
        ``"not decided"`` (:mod:`~symctl.circuitatlas.universality`).
    proved : bool
        Whether the verdict is a proof (not for conjectures and undecided patterns).
    text : str
        One sentence.
    details : mapping
        The formulas, witnesses or counterexample (plain data, also :attr:`evidence`).

    Examples
    --------
    >>> from symctl.circuitatlas.evidence import CONJECTURED, Evidence
    >>> ev = Evidence(None, CONJECTURED, False, "witnesses at sampled G2")
    >>> bool(ev), ev.verdict, ev.status, ev.sort_rank
    (False, None, 'conjectured', 1)
    """

    universal: bool | None
    method: str
    proved: bool
    text: str
    details: MappingProxyType = field(default_factory=lambda: MappingProxyType({}))

    _verdict = "universal"

    @property
    def evidence(self):
        """The witness or certificate: :attr:`details`."""
        return self.details

    @property
    def conjectured(self) -> bool:
        """Whether the pattern is conjectured universal."""
        return self.method == CONJECTURED

    @property
    def status(self) -> str:
        """``"universal"``, ``"conjectured"``, ``"not universal"`` or ``"not decided"``."""
        if self.conjectured:
            return CONJECTURED
        return {True: "universal", False: "not universal", None: "not decided"}[self.universal]

    @property
    def sort_rank(self) -> int:
        """0 proved universal, 1 conjectured, 2 not decided, 3 refuted."""
        return 1 if self.conjectured else {True: 0, None: 2, False: 3}[self.universal]

    @classmethod
    def from_dict(cls, data: dict) -> Evidence:
        """The evidence that :meth:`to_dict` wrote."""
        head = (data[k] for k in ("universal", "method", "proved", "text"))
        return cls(*head, MappingProxyType(dict(data.get("details", {}))))

    def to_dict(self) -> dict:
        """Plain data for JSON."""
        return {f.name: getattr(self, f.name) for f in fields(self)} | {
            "details": dict(self.details)
        }


def _evidence(universal, method, proved, text, **details) -> Evidence:
    return Evidence(universal, method, proved, text, MappingProxyType(details))
