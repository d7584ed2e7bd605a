"""Stage 4: structures, delay graphs, delay assignments and the exact compatibility checker.

- ``signalgraph``: the compiled signal graph, 0-1 BFS and the one DFS for back edges;
- ``structure``: ``Structure`` (the paper's branch-delay signal-flow graphs), ``Block``;
- ``delaygraph``: ``DelayGraph`` (NumPy only);
- ``assignment``: ``DelayAssignment`` and its E~;
- ``csp``: the constraint model, the chain and search solvers and their certificates;
- ``check``: ``check_compatibility``, ``brute_force_compatibility``, ``CompatibilityResult``;
- ``controller``: ``controller_compatibility``, the chain theorem and its construction.

The names of the former module ``symctl.compatibility`` stay importable from here.
"""

from symctl._util.lazy import attach

__getattr__, __dir__, __all__ = attach(
    __name__,
    {
        "METHODS": "symctl.compatibility.check",
        "CompatibilityResult": "symctl.compatibility.check",
        "brute_force_compatibility": "symctl.compatibility.check",
        "check_compatibility": "symctl.compatibility.check",
        "ControllerCompatibility": "symctl.compatibility.controller",
        "controller_compatibility": "symctl.compatibility.controller",
    },
)
