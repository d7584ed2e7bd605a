"""A structure's equations under their former function names (methods of :class:`Structure`)."""

from symctl.compatibility.structure import Structure

__all__ = ["structure_equations", "structure_latex"]

structure_equations = Structure.equations
structure_latex = Structure.latex
