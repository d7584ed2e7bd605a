"""The result of an exact proof: truthy when the claim holds, with its method and evidence.

Checkers return results, not bare booleans (the house's rule): ``bool(proof)``
is the verdict, ``proof.claim`` what was proved, ``proof.method`` how, and
``proof.evidence`` a witness of failure (the first entry of the difference that
is not the zero polynomial). A proof also equals the boolean of its verdict, so
``prove_controller_tf(system) == True`` keeps working.

>>> from symctl._util.proof import Proof
>>> p = Proof(True, "G3 G2 G1 = G", "cross-multiplication")
>>> bool(p), p == True, p
(True, True, Proof(True, claim='G3 G2 G1 = G', method='cross-multiplication'))
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Proof"]


@dataclass(frozen=True, eq=False)
class Proof:
    """An exact verdict on a claim.

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
    >>> from symctl._util.proof import Proof
    >>> bool(Proof(False, "x = y", "expand", evidence="x - y"))
    False
    """

    holds: bool
    claim: str
    method: str
    evidence: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "holds", bool(self.holds))

    def __bool__(self) -> bool:
        return self.holds

    def __eq__(self, other) -> bool:
        if isinstance(other, bool):
            return self.holds == other
        if isinstance(other, Proof):
            return (self.holds, self.claim, self.method, self.evidence) == (
                other.holds,
                other.claim,
                other.method,
                other.evidence,
            )
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self.holds)  # equal to its verdict's bool, so the hash must be too

    def __repr__(self) -> str:
        tail = f", evidence={self.evidence!r}" if self.evidence else ""
        return f"Proof({self.holds}, claim={self.claim!r}, method={self.method!r}{tail})"
