"""The paper's report: the whole derivation run once, and written as files.

Modules: ``spec`` (the paper's parameters and circuits), ``document`` (blocks written
as LaTeX, Markdown and PDF), ``longform``, ``matrixview`` and ``shorthand`` (the page
layout of long objects), ``story``, ``model_story`` and ``mimo_story`` (the derivation
told as blocks), ``figures``, ``output`` (an output folder written all at once) and
``results`` (``results.json``, the documents and the figures of a derivation).
The report computes nothing: :mod:`symctl.derivation` derives.
"""

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
