"""Dale's law: can a circuit carry the controller with every neuron excitatory or inhibitory?

Modules, in the order data flows: :mod:`~symctl.dalelaw.signs` (the sign
problem of a template, decided by z3), :mod:`~symctl.dalelaw.witness` (the
general circuit's numeric search, made exact), :mod:`~symctl.dalelaw.dale`
(:func:`symctl.dale`), :mod:`~symctl.dalelaw.interneurons`
(:func:`symctl.ei_circuit`) and :mod:`~symctl.dalelaw.dale_atlas`
(:func:`symctl.dale_atlas`, the E/I table across the atlas).
"""
