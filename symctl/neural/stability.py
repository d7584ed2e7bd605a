r"""Internal stability of the whole loop: every state, not only the transfer function
(:math:`G_3 G_2 G_1` cancels poles at :math:`\epsilon_1, \epsilon_3` with zeros of :math:`G_2`,
so with :math:`|\epsilon| \ge 1` a hidden mode grows while the transfer function is right)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from symctl.neural.circuit import Circuit
from symctl.neural.simulate import (
    UNIT_CIRCLE,
    _closed_loop_matrices,
    _controller_realization,
    _eig_text,
    _is_hidden,
    _numeric_realization,
    _plant,
)
from symctl.proof import Verdict

__all__ = ["LoopStability", "loop_stability"]


@dataclass(frozen=True)
class LoopStability(Verdict):
    """The verdict of :func:`loop_stability`: truthy when every state of the loop decays.

    Attributes
    ----------
    stable : bool
        Spectral radius of :math:`A_{cl}` below 1 - 1e-9 (a marginal mode is unstable).
    spectral_radius : float
    eigenvalues, unstable, hidden : tuple of complex
        The eigenvalues of :math:`A_{cl}`, those of modulus :math:`\\ge 1 - 10^{-9}`, and of
        these the controller's own (its :math:`F`'s, relative 1e-8): hidden from its transfer function.

    Examples
    --------
    >>> from symctl import MuscleModel, Realization, loop_stability
    >>> result = loop_stability(MuscleModel(), Realization([[0]], [[-1]], [[1]], 0))
    >>> bool(result), result.hidden
    (False, ())
    """

    stable: bool
    spectral_radius: float
    eigenvalues: tuple[complex, ...]
    unstable: tuple[complex, ...]
    hidden: tuple[complex, ...]

    _verdict = "stable"
    method = "eigenvalues of the closed loop's state matrix"

    @property
    def evidence(self):
        """The :attr:`unstable` eigenvalues when unstable, else the :attr:`spectral_radius` (< 1)."""
        return self.spectral_radius if self.stable else self.unstable

    def __str__(self) -> str:
        if self.stable:
            return f"internally stable: spectral radius {self.spectral_radius:.6g} < 1"
        text = (
            f"internally unstable: spectral radius {self.spectral_radius:.6g} >= 1, "
            f"unstable eigenvalues {', '.join(_eig_text(x) for x in self.unstable)}"
        )
        if self.hidden:
            text += (
                f"; hidden modes of the controller (its own F) at "
                f"{', '.join(_eig_text(x) for x in self.hidden)}"
            )
        return text


def loop_stability(plant, controller) -> LoopStability:
    r"""Whether every state of the plant in closed loop with ``controller`` decays.

    Parameters
    ----------
    plant : DiscretePlant, MuscleModel, (A, B) or python-control system (as_plant)
    controller : Realization, DiscreteTF, Gains or Circuit
        Numeric (a transfer function in controllable canonical form, gains by IFP).

    Returns
    -------
    LoopStability

    Raises
    ------
    SymctlTypeError, DimensionError, ParameterError
        ``controller`` of another type or shape, with symbols left, or of another ``dt``.

    Examples
    --------
    >>> from symctl import MuscleModel, Realization, loop_stability
    >>> hidden = Realization([[0, 0], [0, 1.5]], [[-0.05], [1]], [[1, 0]], 0)
    >>> result = loop_stability(MuscleModel(), hidden)
    >>> bool(result), result.hidden
    (False, ((1.5+0j),))
    """
    p, A, B = _plant(plant)
    if isinstance(controller, Circuit):
        sys = controller.as_linear_system(numeric=True)
        k = controller.n_neurons
        mats = (sys.A[None], sys.B[None], sys.C[None, k:], sys.D[None, k:])
    else:
        mats = _numeric_realization(
            _controller_realization(controller, p, ", a Circuit"), p, "controller"
        )
    Acl, _ = _closed_loop_matrices(A, B, *mats)
    Acl = Acl[:, :, 0]
    eigs = np.linalg.eigvals(Acl) if Acl.shape[0] else np.zeros(0)
    rho = float(np.max(np.abs(eigs))) if eigs.size else 0.0
    unstable = tuple(complex(x) for x in eigs if abs(x) >= UNIT_CIRCLE)
    hidden = tuple(x for x in unstable if _is_hidden(Acl, x, p.n))
    return LoopStability(rho < UNIT_CIRCLE, rho, tuple(complex(x) for x in eigs), unstable, hidden)
