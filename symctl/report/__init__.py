"""The report: a derivation written as ``results.json``, documents and figures (it computes
nothing: :mod:`symctl.derivation` derives)."""

from symctl._util.lazy import attach

__getattr__, __dir__, __all__ = attach(
    __name__,
    {
        "CIRCUITS": "symctl.report.spec",
        "CircuitRecord": "symctl.derivation.derivation",
        "PaperResults": "symctl.derivation.derivation",
        "RealizationRecord": "symctl.derivation.derivation",
        "derive_paper": "symctl.derivation.pipeline",
    },
)
