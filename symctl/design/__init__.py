"""Stages 1-2 of the paper: the plant, its delays, the optimal gains and the controller G(z).

- ``plant``: ``linearize``, ``discretize`` (exact ZOH), ``DiscretePlant``, ``MuscleModel``;
- ``augment``: sensor and actuator delays in the augmented state chi, the cost Q~;
- ``lqr``: ``lqr_gains`` (the paper's sign, mu = K chi);
- ``kalman``: ``kalman_gains`` (the delayed Kalman filter), ``lqg_tf`` and ``prove_lqg_tf``
  (the LQG compensator from measured outputs, K and L symbolic);
- ``tf``: ``DiscreteTF``, the transfer-function type (no SciPy);
- ``fraction``: ``MatrixFractionTF``, a MIMO DiscreteTF kept as D(z)^-1 N(z), expanded on request;
- ``controller``: ``controller_tf`` (G(z) with K symbolic), ``prove_controller_tf`` and
  the IFP controller's state space, built once.
"""
