r"""The optimal delayed controller :math:`G(z)` in closed form, its proof, and its state space.

:func:`controller_tf` derives the controller of the paper's section
"Optimal delayed controller" from the augmented system: with
:math:`\mu(t) = K_0 x(t) + \sum_{k=1}^T K_k \gamma_k(t)` and
:math:`\gamma_k = z^{-k} \mu`, eliminating the chain gives

.. math::
    G(z) = \frac{\Delta_r(z)}{X(z)} = D(z)^{-1} K_0,\qquad
    D(z) = z^T I - K_1 z^{T-1} - \dots - K_T,

which for a scalar plant is the paper's eq. (transfer_fn),
:math:`K_0/(z^T - K_1 z^{T-1} - \dots - K_T)`. The derivation is proved, not
trusted: :func:`prove_controller_tf` checks the polynomial identity
:math:`(zI - F_c)\,W(z) = H_c \det D(z)` against the controller's own
state-space matrices read off the augmented system.

Those matrices, the paper's IFP controller (eqs. augmented_states,
ifp_controller), are built in ONE place, :func:`ifp_state_space`, for symbolic
gain blocks (here) and for numeric gains
(:func:`symctl.ifp_realization`) alike.

>>> from symctl import controller_tf
>>> G = controller_tf(2)
>>> G.expr
K_0/(-K_1*z - K_2 + z**2)
>>> G.relative_degree
2
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from symctl._util.proof import Proof
from symctl._util.validate import MAX_DELAY, bounded_int
from symctl.design.augment import AugmentedSystem
from symctl.design.lqr import Gains
from symctl.design.tf import DiscreteTF
from symctl.errors import SymctlTypeError
from symctl.symbols import gain_matrix_symbols, z

__all__ = ["controller_tf", "ifp_state_space", "prove_controller_tf"]


def _system_of(source) -> tuple[AugmentedSystem | None, int, int, int]:
    if isinstance(source, Gains):
        source = source.system
    if isinstance(source, AugmentedSystem):
        return source, source.T, source.m, source.n
    return None, bounded_int(source, "T", 0, MAX_DELAY), 1, 1


def controller_tf(source, gains: Gains | None = None) -> DiscreteTF:
    r"""The optimal delayed controller :math:`G(z) = \Delta_r(z)/X(z)` in closed form.

    Parameters
    ----------
    source : int, AugmentedSystem or Gains
        An integer ``T`` gives the scalar controller with symbolic gains
        :math:`K_0 \dots K_T`; an :class:`~symctl.AugmentedSystem` gives the
        (possibly MIMO) controller for its sizes and delay with symbolic gain
        blocks and the plant's ``Ts``; :class:`~symctl.Gains` give the numeric controller.
    gains : Gains, optional
        Substitute these gain values.

    Returns
    -------
    DiscreteTF
        ``m x n`` (plant inputs by plant states), relative degree ``T``.

    Raises
    ------
    SymctlTypeError
        ``source`` is neither an integer, an AugmentedSystem nor Gains, or
        ``gains`` is not Gains.
    ParameterError
        ``source`` is an integer outside ``[0, MAX_DELAY]`` (500).

    Examples
    --------
    >>> from symctl import controller_tf
    >>> controller_tf(3).den
    -K_1*z**2 - K_2*z - K_3 + z**3
    >>> controller_tf(2) == controller_tf(2)
    True
    >>> from symctl import MuscleModel, augment, lqr_gains
    >>> G = controller_tf(lqr_gains(augment(MuscleModel(), 1, 1)))
    >>> [round(float(c), 6) for c in G.den_coeffs()]
    [1.0, 0.580041, 0.351813]
    """
    if gains is not None and not isinstance(gains, Gains):
        raise SymctlTypeError(f"gains: expected Gains (from symctl.lqr_gains), got {gains!r}")
    if isinstance(source, Gains) and gains is None:
        gains = source
    system, T, m, n = _system_of(source)
    blocks = gain_matrix_symbols(T, m, n)
    D = z**T * sp.eye(m)
    for k in range(1, T + 1):
        D = D - blocks[k] * z ** (T - k)
    if m == 1:
        num, den = blocks[0], D[0, 0]
    else:
        num, den = (D.adjugate() * blocks[0]).applyfunc(sp.expand), sp.expand(D.det())
    dt = system.plant.Ts if system is not None else None
    G = DiscreteTF(num, den, dt)
    if G.relative_degree != T and any(e != 0 for e in num):
        raise AssertionError(f"internal: relative degree {G.relative_degree} != T = {T}")
    if gains is not None:
        G = G.subs(gains.substitutions())
    return G


def ifp_state_space(A, B, K, n: int, m: int, T: int):
    r"""``(F, H, M, N)`` of the IFP controller, read off the augmented matrices.

    Controller state: the chain :math:`[\gamma_1; \dots; \gamma_{T-1}; \delta_r]`;
    input: the plant state :math:`x`; output: :math:`\delta_r`. With
    :math:`\tilde A_c, \tilde B_c` the chain's rows of the augmented system,
    :math:`F = \tilde A_c + \tilde B_c [K_1 \dots K_T]`,
    :math:`H = \tilde B_c K_0`, :math:`M = [0 \dots 0\ I]`, :math:`N = 0` (for
    :math:`T = 0`: a static gain, :math:`N = K_0`). The same code runs on SymPy
    matrices (symbolic gain blocks) and on NumPy arrays (numeric gains):
    ``A``, ``B`` are the augmented matrices and ``K = [K_0, K_1, ..., K_T]``
    the gain, of one kind. ``M`` and ``N`` (for ``T > 0``) are integer arrays.

    >>> import sympy as sp
    >>> from symctl import MuscleModel, augment
    >>> from symctl.design.controller import ifp_state_space
    >>> from symctl.symbols import gain_matrix_symbols
    >>> s = augment(MuscleModel(), 1, 1)
    >>> K = sp.Matrix.hstack(*gain_matrix_symbols(s.T, s.m, s.n))
    >>> F, H, M, N = ifp_state_space(s.A, s.B, K, s.n, s.m, s.T)
    >>> F, H.T, M
    (Matrix([
    [K_1, K_2],
    [  1,   0]]), Matrix([[K_0, 0]]), array([[0, 1]]))
    """
    if T == 0:
        return np.zeros((0, 0)), np.zeros((0, n)), np.zeros((m, 0)), K
    A_c, B_c = A[n:, n:], B[n:, :]
    F = A_c + B_c @ K[:, n:]
    H = B_c @ K[:, :n]
    M = np.zeros((m, T * m), dtype=int)
    M[:, -m:] = np.eye(m, dtype=int)
    return F, H, M, np.zeros((m, n), dtype=int)


def prove_controller_tf(system: AugmentedSystem, G: DiscreteTF | None = None) -> Proof:
    r"""Prove that ``G`` (default: :func:`controller_tf`) is the controller of ``system``.

    With the controller's state-space matrices :math:`(F_c, H_c, M_c)` of
    :func:`ifp_state_space` for symbolic gains, and the candidate state
    numerators :math:`W = [z^{T-1}; \dots; 1] \otimes \operatorname{adj} D(z) K_0`,
    checks the polynomial identities :math:`(zI - F_c) W = H_c \det D` and
    :math:`M_c W = N_G` exactly. Together they give :math:`M_c (zI-F_c)^{-1} H_c = G`.

    Parameters
    ----------
    system : AugmentedSystem
        The plant with its delays.
    G : DiscreteTF, optional
        The candidate controller; default :func:`controller_tf` of ``system``.

    Returns
    -------
    Proof
        Truthy when both identities hold (``G`` is the controller), with the
        method and, when they do not, the first entry that is not zero.

    Raises
    ------
    SymctlTypeError
        ``system`` is not an AugmentedSystem, or ``G`` not a DiscreteTF.

    Examples
    --------
    >>> from symctl import MuscleModel, augment, controller_tf, prove_controller_tf
    >>> system = augment(MuscleModel(), 2, 3)
    >>> bool(prove_controller_tf(system))
    True
    >>> proof = prove_controller_tf(system, 2 * controller_tf(system))
    >>> bool(proof), proof.method
    (False, 'polynomial identities (zI - F_c) W = H_c det D and M_c W = N_G, expanded')
    """
    if not isinstance(system, AugmentedSystem):
        raise SymctlTypeError(f"system: expected an AugmentedSystem, got {type(system).__name__}")
    if G is not None and not isinstance(G, DiscreteTF):
        raise SymctlTypeError(f"G: expected a DiscreteTF, got {G!r}")
    G = controller_tf(system) if G is None else G
    T = system.T
    claim = "G(z) is the transfer function of the delayed LQR controller"
    if T == 0:
        K0 = gain_matrix_symbols(0, system.m, system.n)[0]
        return Proof(G.equals(K0), claim, "G == K_0 (no delay)", "" if G.equals(K0) else "G - K_0")
    K = sp.Matrix.hstack(*gain_matrix_symbols(T, system.m, system.n))
    F, H, M, _ = ifp_state_space(sp.Matrix(system.A), sp.Matrix(system.B), K, system.n, system.m, T)
    M = sp.Matrix(M)
    N = G.num_matrix
    W = sp.Matrix.vstack(*(N * z ** (T - k) for k in range(1, T + 1)))
    lhs = (z * sp.eye(F.shape[0]) - F) * W - H * G.den
    method = "polynomial identities (zI - F_c) W = H_c det D and M_c W = N_G, expanded"
    for e in (*lhs, *(M * W - N)):
        e = sp.expand(e)
        if e != 0:
            return Proof(False, claim, method, str(e))
    return Proof(True, claim, method)
