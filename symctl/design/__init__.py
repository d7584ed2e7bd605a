"""Stages 1-2 of the paper: the plant (``plant``, ``ode``), its delays (``augment``), the optimal
gains (``lqr``, ``kalman``), the transfer-function types (``tf``, ``fraction``) and the
controller G(z) with its proof (``controller``)."""
