"""Discovery: the circuit atlas, every minimal circuit of a controller, found, proved and ranked.

Modules, in the order data flows: :mod:`~symctl.discovery.pattern` (supports
of realizations and their symmetries), :mod:`~symctl.discovery.rank` (the
exact generic-rank filter), :mod:`~symctl.discovery.certify` (certified real
roots), :mod:`~symctl.discovery.fibre` (a pattern's equations over one
:math:`G_2` and their exact real solutions), :mod:`~symctl.discovery.universality` (proofs and refutations),
:mod:`~symctl.discovery.circuitclass` (circuits and their isomorphism classes),
:mod:`~symctl.discovery.solve` (realizing one controller with a class),
:mod:`~symctl.discovery.search` (enumeration, workers, checkpoints) and
:mod:`~symctl.discovery.atlas` (:func:`symctl.atlas`).
"""
