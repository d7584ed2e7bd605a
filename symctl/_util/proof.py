"""The old home of :class:`symctl.proof.Proof`, kept so that its import path keeps working."""

from symctl.proof import Proof

__all__ = ["Proof"]
