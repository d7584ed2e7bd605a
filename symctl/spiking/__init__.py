"""Stage 5b: symctl's circuits in the simulators neuroscientists use (``pip install symctl[spiking]``).

- ``connections``: a circuit as a numeric connection list, the one reading every export shares;
- ``nengo_export``: ``Circuit.to_nengo``, a nengo network of the circuit;
- ``nest_export``: ``Circuit.to_nest``, the circuit in NEST's linear rate neurons.

nengo and NEST are imported only when an export is asked for, never with ``import symctl``.
"""
