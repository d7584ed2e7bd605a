"""Stage 4: structures, delay graphs, delay assignments and the exact compatibility checker."""

from symctl._util.lazy import attach

__getattr__, __dir__, __all__ = attach(
    __name__,
    {
        "METHODS": "symctl.compatibility.check",
        "CompatibilityResult": "symctl.compatibility.check",
        "brute_force_compatibility": "symctl.compatibility.check",
        "check_compatibility": "symctl.compatibility.check",
        "PathPart": "symctl.compatibility.construction",
        "markov_split": "symctl.compatibility.construction",
        "structure_realization": "symctl.compatibility.statespace",
        "ControllerCompatibility": "symctl.compatibility.controller",
        "controller_compatibility": "symctl.compatibility.controller",
    },
)
