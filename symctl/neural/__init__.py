"""Stage 5: circuits of stylized linear neurons (``neuron``, ``circuit``), and the simulation of
the loop they close (``simulate``, ``batch``, ``noise``, ``montecarlo``, ``nonlinear``, ``firing``)."""
