"""Stage 5b: symctl's circuits in other simulators (nengo, NEST, NIR) and as spiking neurons.

nengo, NEST and nir (``pip install symctl[spiking]``) are imported only when asked for.
"""
