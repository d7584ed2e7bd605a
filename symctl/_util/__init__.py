"""Internal helpers every stage uses; nothing here is public API.

- ``validate``: every argument check (types, shapes, numbers, seeds, read-only arrays);
- ``parse``: the safe parser for user text (never ``eval``);
- ``exact``: the one fold of a SymPy expression into fraction-free polynomials;
- ``display``: LaTeX and text printing with the paper's symbol names (``LatexMixin``);
- ``texnames``: the one spelling of a signal name in LaTeX;
- ``evaluate``: symbolic matrices lambdified once for vectorised NumPy evaluation;
- ``lazy``: public names from one table, loaded on first use.
"""
