"""Stage 3: G = G3 G2 G1 along the delays, realizations of G2, and the exact checker.

Modules: ``factorization`` (and ``channels`` for MIMO), ``realization`` (the type, canonical
forms, series), ``realizers`` (the one registry), ``check``, ``minimal``, ``reduction``.
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
