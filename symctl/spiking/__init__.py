"""Stage 5b: symctl's circuits in other simulators, and as spiking neurons.

- ``connections``: a circuit as a numeric connection list, which every export reads;
  ``export_circuit``, the simulator-neutral JSON;
- ``nengo_export``: ``Circuit.to_nengo``, exact nodes or spiking populations (NEF);
- ``nest_export``: ``Circuit.to_nest``, NEST's linear rate neurons, retimed to be exact;
- ``nir_export``: ``Circuit.to_nir``, a NIR graph: exact delay-sum neurons or LIF populations;
- ``loop``: ``spiking_response``, the loop closed through spiking populations;
- ``cost``: ``spiking_cost``, the neurons and spikes each circuit needs to stay near the
  linear loop, swept on the dask path.

nengo, NEST and nir (``pip install symctl[spiking]``) are imported only when asked for, never
with ``import symctl``.
"""
