"""Drawing: the only package that imports matplotlib. The layouts (``layered`` and the
``*_layout`` modules) return numbers and never import it; the other modules render on
pyplot-free ``Figure`` objects, reached through one-line delegations (``Structure.draw``, ...).
"""
