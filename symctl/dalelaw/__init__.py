"""Dale's law: can a circuit carry the controller with every neuron excitatory or inhibitory?

``signs`` (the sign problem, for z3), ``witness`` (a numeric search, made exact), ``dale``,
``interneurons`` (:func:`symctl.ei_circuit`) and ``dale_atlas`` (the E/I table of an atlas).
"""
