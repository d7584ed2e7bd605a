"""Stage 3: G = G3 G2 G1 along the delays, realizations of G2, and the exact checker.

- ``factorization``: ``factor`` and ``Factorization``;
- ``realization``: the ``Realization`` type (F, H, M, N), canonical forms, sections, series;
- ``realizers``: one registry of realizers (controllable, observable, general, random)
  returning a ``RealizerResult`` with the transform; ``ifp_realization``;
- ``check``: ``check_realization``, an exact proof or a randomized test with its bound;
- ``channels``: MIMO factorization channel by channel;
- ``minimal``: ``minimal_realization``, the exact Kalman reduction (MIMO too);
- ``reduction``: ``controller_reduction``, whether the delayed controller is minimal and why not.

The names of the former module ``symctl.realization`` stay importable from here.
"""

from symctl._util.lazy import attach

__getattr__, __dir__, __all__ = attach(
    __name__,
    {
        "Realization": "symctl.realization.realization",
        "controllable_canonical": "symctl.realization.realization",
        "controller_realization": "symctl.realization.realization",
        "first_order_realization": "symctl.realization.realization",
        "observable_canonical": "symctl.realization.realization",
        "split_proper": "symctl.realization.realization",
        "minimal_realization": "symctl.realization.minimal",
        "controller_reduction": "symctl.realization.reduction",
        "general_realization": "symctl.realization.realizers",
        "random_realization": "symctl.realization.realizers",
    },
)
