"""Drawing: the only package that imports matplotlib.

Layout apart from rendering, as networkx's ``drawing/layout.py`` and ``nx_pylab.py``: one
layered layout core (:mod:`~symctl.plotting.layered`) and each drawing's layout
(``structure_layout``, ``circuit_layout``, ``delaygraph_layout``) return numbers and never
import matplotlib; ``structure``, ``circuit``, ``delaygraph``, ``response``, ``firing``,
``fit`` and ``atlas`` render on pyplot-free ``Figure`` objects. Objects reach this package
through one-line delegations (``Structure.draw``, ``Circuit.draw``, ``Response.plot``, ...).
"""
