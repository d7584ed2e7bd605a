r"""The optimal delayed controller :math:`G(z)` in closed form, its proof, and its state space.

With :math:`\mu(t) = K_0 x(t) + \sum_{k=1}^T K_k \gamma_k(t)` and :math:`\gamma_k = z^{-k}
\mu`, eliminating the chain gives (the paper's section "Optimal delayed controller")

.. math::
    G(z) = \frac{\Delta_r(z)}{X(z)} = D(z)^{-1} K_0,\qquad
    D(z) = z^T I - K_1 z^{T-1} - \dots - K_T,

for a scalar plant the paper's eq. (transfer_fn). For several inputs it is kept as the
left fraction (:class:`~symctl.design.fraction.MatrixFractionTF`), expanded only within
``MAX_EXPANDED_TERMS``.

**Proof** (:func:`prove_controller_tf`, by multiplying, never inverting). With the IFP
controller's matrices :math:`(F_c, H_c, M_c)` (:func:`ifp_state_space`) and
:math:`V = [z^{T-1} I; \dots; z I; I]`, the identities
:math:`(zI - F_c) V = B_c D(z)`, :math:`H_c = B_c K_0` and :math:`M_c V = I` give
:math:`(zI - F_c) V D^{-1} K_0 = B_c K_0 = H_c`, so
:math:`M_c (zI - F_c)^{-1} H_c = M_c V D^{-1} K_0 = D(z)^{-1} K_0`; then :math:`G = D^{-1} K_0` is
checked as :math:`D(z) N_G = K_0 d_G` for an expanded :math:`G = N_G/d_G`, or as
:math:`D_G = D,\ N_G = K_0` for a fraction: polynomial identities checked exactly, of
degree :math:`T` in :math:`z` and linear in the gains but the last.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from sympy.polys.rings import ring

from symctl._util.exact import NotRational, RingFractions, fold
from symctl._util.validate import MAX_DELAY, MAX_EXPANDED_TERMS, bounded_int
from symctl.design.augment import AugmentedSystem
from symctl.design.fraction import MatrixFractionTF
from symctl.design.lqr import Gains
from symctl.design.tf import DiscreteTF
from symctl.errors import SymctlTypeError
from symctl.proof import Proof
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
        ``T`` (scalar, symbolic gains), a system (symbolic gain blocks) or Gains (numeric).
    gains : Gains, optional
        Substitute these gain values.

    Returns
    -------
    DiscreteTF
        ``m x n``, relative degree ``T``; beyond ``MAX_EXPANDED_TERMS`` (50,000) a
        :class:`~symctl.design.fraction.MatrixFractionTF`.

    Raises
    ------
    SymctlTypeError, ParameterError
        ``source`` or ``gains`` of another type; an integer ``source`` outside ``[0, MAX_DELAY]``.

    Examples
    --------
    >>> from symctl import controller_tf, prove_controller_tf
    >>> controller_tf(3).den
    -K_1*z**2 - K_2*z - K_3 + z**3
    >>> from symctl import MuscleModel, augment, lqr_gains
    >>> G = controller_tf(lqr_gains(augment(MuscleModel(), 1, 1)))
    >>> [round(float(c), 6) for c in G.den_coeffs()]
    [1.0, 0.580041, 0.351813]
    >>> import numpy as np
    >>> six_inputs = augment((np.eye(2) / 2, np.ones((2, 6))), 1, 2)
    >>> G = controller_tf(six_inputs)
    >>> type(G).__name__, G.shape, G.order, G.relative_degree
    ('MatrixFractionTF', (6, 2), 18, 3)
    >>> bool(prove_controller_tf(six_inputs, G))
    True
    """
    if gains is not None and not isinstance(gains, Gains):
        raise SymctlTypeError(f"gains: expected Gains (from symctl.lqr_gains), got {gains!r}")
    if isinstance(source, Gains) and gains is None:
        gains = source
    system, T, m, n = _system_of(source)
    blocks = gain_matrix_symbols(T, m, n)
    dt = system.plant.dt if system is not None else None
    if m > 1:
        return _mimo(blocks, gains, T, m, n, dt)
    G = DiscreteTF(blocks[0], _chain(T, m, lambda k, i, j: blocks[k][i, j])[0, 0], dt)
    if G.relative_degree != T and any(e != 0 for e in G.num_matrix):
        raise AssertionError(f"internal: relative degree {G.relative_degree} != T = {T}")
    if gains is not None:
        G = G.subs(gains.substitutions())
    return G


def _chain(T: int, m: int, gain) -> sp.Matrix:
    """``D(z) = z^T I - K_1 z^{T-1} - ... - K_T``, with ``gain(k, i, j)`` the entry of ``K_k``."""
    D = z**T * sp.eye(m)
    for k in range(1, T + 1):
        for i in range(m):
            for j in range(m):
                D[i, j] -= gain(k, i, j) * z ** (T - k)
    return D


def _mimo(blocks, gains: Gains | None, T: int, m: int, n: int, dt) -> DiscreteTF:
    """The MIMO controller as ``D(z)^-1 K_0``: expanded up to the size limit, or kept."""
    s = None if gains is None else gains.system
    if s is not None and (s.T, s.m, s.n) == (T, m, n):  # numbers: exact, rounded once
        vals = [np.asarray(b, dtype=float).reshape(m, -1) for b in gains.blocks]
        D = _chain(T, m, lambda k, i, j: sp.Float(float(vals[k][i, j])))
        K0 = sp.Matrix(m, n, lambda i, j: sp.Float(float(vals[0][i, j])))
        return MatrixFractionTF(D, K0, dt).expanded()
    G = MatrixFractionTF(_chain(T, m, lambda k, i, j: blocks[k][i, j]), blocks[0], dt)
    if G.relative_degree != T:
        raise AssertionError(f"internal: relative degree {G.relative_degree} != T = {T}")
    if G.terms_bound() <= MAX_EXPANDED_TERMS:
        G = G.expanded()
    return G if gains is None else G.subs(gains.substitutions())


_RING_METHOD = (
    "polynomial identities (zI - F_c) V = B_c D, H_c = B_c K_0, M_c V = I "
    "(V = [z^(T-1) I; ...; I]) and {}, multiplied out in Q[z, K]"
)


def _ring_of(K) -> tuple[object, object]:
    """``QQ[z, K]`` and an exact converter of SymPy expressions into it (floats exactly)."""
    gens = [z, *K]
    R = ring(gens, sp.QQ)[0]
    algebra, memo = RingFractions(R, gens), {}

    def convert(e):
        num, den = fold(e, algebra, memo)
        if not den.is_ground:
            raise NotRational(e)
        return num.quo(den)

    return R, convert


def _mat(convert, M) -> list[list]:
    return [[convert(e) for e in M.row(i)] for i in range(M.rows)]


def _mul(R, X, Y) -> list[list]:
    return [
        [sum((a * Y[k][j] for k, a in enumerate(row) if a), R.zero) for j in range(len(Y[0]))]
        for row in X
    ]


def _prove_in_ring(system: AugmentedSystem, G: DiscreteTF, K) -> tuple[bool, str, str] | None:
    """``(holds, evidence, method)`` of the module's identities in ``QQ[z, K]`` (None: not there)."""
    T, m, n = system.T, system.m, system.n
    F, H, M, _ = ifp_state_space(sp.Matrix(system.A), sp.Matrix(system.B), K, n, m, T)
    B_c = sp.Matrix(system.B)[n:, :]
    blocks = gain_matrix_symbols(T, m, n)
    R, convert = _ring_of(K)
    zz = R.gens[0]
    try:
        Fr = {
            (i, j): convert(F[i, j]) for i in range(F.rows) for j in range(F.cols) if F[i, j] != 0
        }
        Hr, Br = _mat(convert, H), _mat(convert, B_c)
        D = _mat(convert, _chain(T, m, lambda k, i, j: blocks[k][i, j]))
        K0 = _mat(convert, blocks[0])
        if isinstance(G, MatrixFractionTF):
            D_G, N_G = _mat(convert, G.D), _mat(convert, G.N)
        else:
            N_G, d_G = _mat(convert, G.num_matrix), convert(G.den)
    except (NotRational, KeyError):
        return None

    def v(row: int, col: int):  # V = [z^(T-1) I; ...; z I; I]
        block, r = divmod(row, m)
        return zz ** (T - 1 - block) if r == col else R.zero

    def first_nonzero(entries):
        return next((str(e.as_expr()) for e in entries if e), "")

    def lhs_rows():  # (zI - F) V - B_c D, H - B_c K_0 and M V - I, an entry at a time
        for i in range(T * m):
            for c in range(m):
                e = zz * v(i, c) - sum(
                    (Fr[i, j] * v(j, c) for j in range(c, T * m, m) if (i, j) in Fr), R.zero
                )
                yield e - sum((Br[i][k] * D[k][c] for k in range(m) if Br[i][k]), R.zero)
            for c in range(n):
                yield Hr[i][c] - sum((Br[i][k] * K0[k][c] for k in range(m) if Br[i][k]), R.zero)
        for r in range(m):
            for c in range(m):
                e = sum((int(M[r, j]) * v(j, c) for j in range(T * m) if M[r, j]), R.zero)
                yield e - (R.one if r == c else R.zero)

    evidence = first_nonzero(lhs_rows())
    if isinstance(G, MatrixFractionTF):
        method = _RING_METHOD.format("D_G = D, N_G = K_0")
        if evidence:
            return False, evidence, method
        if D_G != D:  # another left fraction: compared by expansion (within its size limit)
            return _prove_in_ring(system, G.expanded(), K)
        evidence = first_nonzero(
            a - b for ra, rb in zip(N_G, K0, strict=True) for a, b in zip(ra, rb, strict=True)
        )
        return not evidence, evidence, method
    method = _RING_METHOD.format("D N_G = K_0 d_G")
    if not evidence:
        evidence = first_nonzero(
            sum((D[i][k] * N_G[k][j] for k in range(m) if N_G[k][j]), R.zero) - K0[i][j] * d_G
            for i in range(m)
            for j in range(n)
        )
    return not evidence, evidence, method


def ifp_state_space(A, B, K, n: int, m: int, T: int):
    r"""``(F, H, M, N)`` of the IFP controller read off the augmented matrices: state
    :math:`[\gamma_1; \dots; \delta_r]`, input :math:`x`, output :math:`\delta_r`; :math:`F =
    \tilde A_c + \tilde B_c [K_1 \dots K_T]`, :math:`H = \tilde B_c K_0`, :math:`M = [0 \dots 0\
    I]`, :math:`N = 0` (:math:`T = 0`: :math:`N = K_0`). SymPy or NumPy (``M``, ``N`` integer)."""
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

    Scalar plant: :math:`(zI - F_c) W = H_c d_G` and :math:`M_c W = N_G`, :math:`W =
    [z^{T-1}; \dots; 1] N_G`; several inputs: the module's identities in :math:`\mathbb{Q}[z, K]`.

    Parameters
    ----------
    system : AugmentedSystem
    G : DiscreteTF, optional

    Returns
    -------
    Proof
        Truthy when the identities hold (else with the first nonzero entry).

    Raises
    ------
    SymctlTypeError, ParameterError
        ``system`` or ``G`` of another type; a left fraction with another ``D`` too large to expand.

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
    m, n = system.m, system.n
    if G.shape != (m, n):
        return Proof(False, claim, "shapes", f"G has shape {G.shape}, the controller ({m}, {n})")
    K = sp.Matrix.hstack(*gain_matrix_symbols(T, m, n))
    ring_proof = _prove_in_ring(system, G, K) if m > 1 else None
    if ring_proof is not None:
        ok, first, method = ring_proof
        return Proof(ok, claim, method, first)
    F, H, M, _ = ifp_state_space(sp.Matrix(system.A), sp.Matrix(system.B), K, n, m, T)
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
