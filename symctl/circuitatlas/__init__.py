"""The circuit atlas: every minimal circuit of a controller, found, proved and ranked.

Modules, in the order data flows: :mod:`~symctl.circuitatlas.pattern` (supports
of realizations and their symmetries), :mod:`~symctl.circuitatlas.rank` (the
exact generic-rank filter), :mod:`~symctl.circuitatlas.certify` (certified real
roots), :mod:`~symctl.circuitatlas.fibre` (a pattern's equations over one
:math:`G_2` and their exact real solutions),
:mod:`~symctl.circuitatlas.screen` (the exact refutation screen),
:mod:`~symctl.circuitatlas.universality` (proofs and refutations),
:mod:`~symctl.circuitatlas.circuitclass` (circuits and their isomorphism classes),
:mod:`~symctl.circuitatlas.solve` (realizing one controller with a class),
:mod:`~symctl.circuitatlas.search` (enumeration, workers, checkpoints) and
:mod:`~symctl.circuitatlas.atlas` (:func:`symctl.atlas`).
"""
