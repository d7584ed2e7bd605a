"""Fitting: a circuit fitted to recorded firing rates, and what the recordings pin down.

``traces`` (the data), ``fitmodel`` (each neuron a linear filter of the parameters),
``fitargs``, ``fit``, ``identify`` (structural) and ``uncertainty`` (with noise).
"""
