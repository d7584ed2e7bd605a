"""Stage 4: structures, delay graphs, delay assignments and the exact compatibility checker.

- ``signalgraph``: the compiled signal graph, 0-1 BFS and the one DFS for back edges;
- ``block``: ``Block``, the blocks of a structure (delays of one step or an axon of k steps);
- ``structure``: ``Structure`` (the paper's branch-delay signal-flow graphs; series, parallel);
- ``statespace``: a structure's state-space form, one state per delay step;
- ``delaygraph``: ``DelayGraph`` (NumPy only);
- ``assignment``: ``DelayAssignment`` and its E~;
- ``csp``: the constraint model, the chain and search solvers and their certificates;
- ``check``: ``check_compatibility``, ``brute_force_compatibility``, ``CompatibilityResult``;
- ``construction``: compatible structures built along paths, the parallel decomposition;
- ``controller``: ``controller_compatibility``, the theorems (any delay graph) and their proofs.

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
        "PathPart": "symctl.compatibility.construction",
        "markov_split": "symctl.compatibility.construction",
        "structure_realization": "symctl.compatibility.statespace",
        "ControllerCompatibility": "symctl.compatibility.controller",
        "controller_compatibility": "symctl.compatibility.controller",
    },
)
