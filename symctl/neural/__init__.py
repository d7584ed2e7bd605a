"""Stage 5: circuits of stylized linear neurons, and their simulation.

- ``neuron``: ``Neuron`` and ``Synapse``;
- ``circuit``: ``Circuit.from_structure`` (the paper's neuron rule), its linear system;
- ``simulate``: the one time-stepping core, open and closed loop, any realization;
- ``batch``: ``simulate_batch``, many realizations at once (chunks on threads);
- ``nonlinear``: the loop closed around the nonlinear muscle;
- ``firing``: ``circuit_firing``, the paper's firing-pattern figures' data.
"""
