"""Fitting: a circuit fitted to recorded firing rates, and what the recordings pin down.

Modules, in the order data flows: :mod:`~symctl.fitting.traces` (the data,
read from CSV or NPZ), :mod:`~symctl.fitting.fitmodel` (every neuron a linear
filter of the parameters), :mod:`~symctl.fitting.fitargs` (the arguments,
checked), :mod:`~symctl.fitting.fit` (:func:`symctl.fit`) and
:mod:`~symctl.fitting.identify` (:func:`symctl.identifiability`), with
:mod:`~symctl.fitting.uncertainty` (what these data, with their noise, determine).
"""
