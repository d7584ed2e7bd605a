"""The pipeline: a model derived, plant to circuits, into one :class:`Derivation`.

This stage sits above the algorithms (design, realization, compatibility, neural,
circuitatlas, dalelaw, fitting) and the model files, and below the report, which writes a derivation
and computes nothing.

- ``pipeline``: :func:`derive` (a model) and :func:`derive_paper` (the muscle preset
  with values replaced), each computed once per model;
- ``derivation``: :class:`Derivation` (its inputs, every stage's result, what was
  skipped and why) and its records;
- ``paper``: :data:`PAPER`, the paper's inputs;
- ``load``: :func:`load_results`, a derivation's ``results.json`` read back
  (numbers, exact symbolic objects, the figures' data, the model).

Examples
--------
>>> from symctl import derive_paper
>>> derive_paper().circuits["general"].compatibility.ok
True
"""

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
