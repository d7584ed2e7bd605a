"""The paper's report: the whole derivation run once, and written as files.

Modules, lowest first (each imports only those above it in this list):

- ``spec``: the paper's parameters (defaults of ``MuscleModel`` and ``augment``)
  and the report's circuits;
- ``document``: blocks (headings, prose, equations, tables, graphics) written as
  LaTeX, Markdown and PDF;
- ``longform``: the page layout of long objects at any size (line breaking,
  patterns of large matrices, corners of dense ones), its thresholds named;
- ``shorthand``: the indexed forms of long objects (products over sections,
  G(z) as b(z)/a(z) with a coefficient table, entries as N c_k);
- ``story``: the derivation told as blocks;
- ``figures``: the report's figures by name, saved as PDF and PNG (SVG on request);
- ``output``: an output folder written all at once (checked, locked, staged
  beside its place, renamed into it when complete);
- ``results``: a :class:`~symctl.derivation.Derivation` written: ``results.json``,
  the documents and the figures (``Derivation.write`` / ``Derivation.figure``).

The report computes nothing: :mod:`symctl.derivation` derives. The names of the
former module ``symctl.report`` stay importable from here.

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
        "CIRCUITS": "symctl.report.spec",
        "CircuitRecord": "symctl.derivation.derivation",
        "PaperResults": "symctl.derivation.derivation",
        "RealizationRecord": "symctl.derivation.derivation",
        "derive_paper": "symctl.derivation.pipeline",
    },
)
