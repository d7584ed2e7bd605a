"""The pipeline: a model derived, plant to circuits, into one :class:`Derivation` (above the
algorithms and model files, below the report, which writes it)."""

from symctl._util.lazy import attach

__getattr__, __dir__, __all__ = attach(
    __name__,
    {
        "CircuitRecord": "symctl.derivation.derivation",
        "Derivation": "symctl.derivation.derivation",
        "PaperResults": "symctl.derivation.derivation",
        "RealizationRecord": "symctl.derivation.derivation",
        "derive": "symctl.derivation.pipeline",
        "derive_paper": "symctl.derivation.pipeline",
        "SavedDerivation": "symctl.derivation.load",
        "load_results": "symctl.derivation.load",
    },
)
