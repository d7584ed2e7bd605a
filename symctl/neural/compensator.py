"""The LQG compensator as a numeric realization, to close around the plant it measures."""

from __future__ import annotations

import numpy as np

from symctl._util.validate import numeric_matrix
from symctl.design.kalman import KalmanGains, lqg_state_space
from symctl.design.lqr import Gains
from symctl.errors import ParameterError, SymctlTypeError
from symctl.realization.realization import Realization

__all__ = ["lqg_realization"]


def lqg_realization(gains: Gains, kalman: KalmanGains) -> Realization:
    r"""The delayed LQG compensator (predictor form) from the outputs to :math:`\delta_r`, in numbers.

    Its transfer function is :func:`~symctl.lqg_tf` with :math:`K` and :math:`L` substituted;
    close it with ``closed_loop_response(R, plant, outputs=kalman.C)``.

    Parameters
    ----------
    gains : Gains
        The LQR gains (:func:`~symctl.lqr_gains`).
    kalman : KalmanGains
        The filter (:func:`~symctl.kalman_gains`) of the same system.

    Returns
    -------
    Realization
        ``m x p``, with :math:`n + Tm` states: the estimate :math:`\hat\chi`.

    Raises
    ------
    SymctlTypeError, ParameterError
        ``gains`` or ``kalman`` of another type; ``kalman`` of another system.

    Examples
    --------
    >>> import numpy as np
    >>> from symctl import MuscleModel, augment, kalman_gains, lqg_realization, lqg_tf, lqr_gains
    >>> s = augment(MuscleModel(), 1, 1)
    >>> gains, kf = lqr_gains(s), kalman_gains(s, C=[[1]], W=1, V=1)
    >>> R = lqg_realization(gains, kf)
    >>> R.n, R.shape
    (3, (1, 1))
    >>> G = lqg_tf(s, None, gains, kf)
    >>> bool(np.allclose(G.impulse_response(8).ravel(), [float(h[0]) for h in R.markov(8)]))
    True
    """
    if not isinstance(gains, Gains):
        raise SymctlTypeError(f"gains: expected Gains, got {type(gains).__name__}")
    if not isinstance(kalman, KalmanGains):
        raise SymctlTypeError(f"kalman: expected KalmanGains, got {type(kalman).__name__}")
    s = gains.system
    if kalman.system != s:
        raise ParameterError("kalman: designed for another system than the gains")
    A, B = numeric_matrix(s.A, "gains"), numeric_matrix(s.B, "gains")
    C = numeric_matrix(kalman.C, "kalman")
    F, H, M, N = lqg_state_space(A, B, C, np.asarray(gains.K), kalman.L[: s.n], s.n, s.m, s.T)
    return Realization(F, H, M, N, s.plant.dt)
