"""Drawing: the only package that imports matplotlib.

Layout apart from rendering, as networkx's ``drawing/layout.py`` and ``nx_pylab.py``:
``structure_layout``, ``circuit_layout`` and ``delaygraph_layout`` return numbers
(positions, routes, sizes) and never import matplotlib, on one layered core ``layered``
(layers, bends, crossing reduction, rows, Bézier curves); ``structure``, ``circuit``,
``delaygraph``, ``response`` and ``firing`` render them on pyplot-free ``Figure``
objects; ``common`` holds the figure, heading, key and text measure they share;
``circuit_labels`` chooses a circuit drawing's text (long weights as :math:`w_k`, with a
key) without matplotlib; ``png`` writes a figure's PNG without the alpha channel, ``vector``
its PDF and SVG without a date; ``style`` is the house style and ``legibility`` measures a
drawn figure as it is printed.
Objects reach this package through one-line delegations (``Structure.draw``,
``Circuit.draw``, ``DelayGraph.draw``, ``Response.plot``, ...).
"""
