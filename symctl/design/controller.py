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

For several inputs, :math:`\operatorname{adj} D` and :math:`\det D` are computed
fraction-free (memoized Laplace minors, no division) in :math:`\mathbb{Z}[z, K]`
for symbolic gains, or exactly in :math:`\mathbb{Q}[z]` from the floats of numeric
gains (rounded once at the end), and the proof multiplies out in the same ring
instead of inverting.

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
    dt = system.plant.Ts if system is not None else None
    if m > 1 and gains is not None and _same_sizes(gains, T, m, n):
        return _numeric_mimo(gains, T, m, n, dt)
    if m == 1:
        num, den = blocks[0], D[0, 0]
        relative_degree = None
    else:
        num, den, relative_degree = _symbolic_mimo(blocks, T, m)
    G = DiscreteTF(num, den, dt)
    if relative_degree is None:
        relative_degree = G.relative_degree
    if relative_degree != T and any(e != 0 for e in num):
        raise AssertionError(f"internal: relative degree {G.relative_degree} != T = {T}")
    if gains is not None:
        G = G.subs(gains.substitutions())
    return G


def _same_sizes(gains: Gains, T: int, m: int, n: int) -> bool:
    s = gains.system
    return (s.T, s.m, s.n) == (T, m, n)


def _adj_det(D: list[list], zero) -> tuple[list[list], object]:
    """Adjugate and determinant of a square matrix over a polynomial ring, fraction-free.

    Laplace expansion with every minor memoized on its (rows, columns): no division,
    so the entries stay polynomials; zero entries are skipped.
    """
    m = len(D)
    memo: dict[tuple[tuple, tuple], object] = {}

    def minor(rows: tuple, cols: tuple):
        if not rows:
            return zero + 1
        key = (rows, cols)
        if key not in memo:
            r, rest = rows[0], rows[1:]
            acc = zero
            for idx, c in enumerate(cols):
                if D[r][c]:
                    term = D[r][c] * minor(rest, cols[:idx] + cols[idx + 1 :])
                    acc = acc - term if idx % 2 else acc + term
            memo[key] = acc
        return memo[key]

    every = tuple(range(m))
    adj = [
        [
            (-1) ** (i + j) * minor(every[:j] + every[j + 1 :], every[:i] + every[i + 1 :])
            for j in range(m)
        ]
        for i in range(m)
    ]
    det = zero
    for c in range(m):  # first row against its cofactors (already in adj's column 0)
        if D[0][c]:
            det += D[0][c] * adj[c][0]
    return adj, det


def _chain_matrix(ring, blocks, T: int, m: int, convert) -> list[list]:
    """``D(z) = z^T I - K_1 z^{T-1} - ... - K_T`` as a list of ring elements."""
    zz = ring.gens[0]
    return [
        [
            (zz**T if i == j else ring.zero)
            - sum((convert(blocks[k][i, j]) * zz ** (T - k) for k in range(1, T + 1)), ring.zero)
            for j in range(m)
        ]
        for i in range(m)
    ]


def _filled(rows: int, cols: int, entry) -> sp.Matrix:
    """A matrix of ring results (SymPy expressions, never text: no sympify on the way)."""
    out = sp.zeros(rows, cols)
    for i in range(rows):
        for j in range(cols):
            out[i, j] = entry(i, j)
    return out


def _symbolic_mimo(blocks, T: int, m: int):
    """``adj D(z) K_0`` and ``det D(z)`` for symbolic gain blocks, in ZZ[z, K]."""
    gens = [z, *(s for b in blocks for s in b)]
    R = sp.polys.rings.ring(gens, sp.ZZ)[0]
    sym = dict(zip(gens, R.gens, strict=True))
    D = _chain_matrix(R, blocks, T, m, sym.__getitem__)
    adj, det = _adj_det(D, R.zero)
    K0 = blocks[0]
    num_r = [
        [sum((adj[i][k] * sym[K0[k, j]] for k in range(m)), R.zero) for j in range(K0.shape[1])]
        for i in range(m)
    ]
    top = max(
        (p.degree(R.gens[0]) for row in num_r for p in row if p), default=det.degree(R.gens[0])
    )
    num = _filled(m, K0.shape[1], lambda i, j: num_r[i][j].as_expr())
    return num, det.as_expr(), det.degree(R.gens[0]) - top


def _numeric_mimo(gains: Gains, T: int, m: int, n: int, dt) -> DiscreteTF:
    """The controller for numeric gains: exact in QQ[z] from the gains' floats, rounded once."""
    R = sp.polys.rings.ring([z], sp.QQ)[0]
    vals = [np.asarray(b, dtype=float).reshape(m, -1) for b in gains.blocks]

    def q(x):
        return R(sp.QQ.from_sympy(sp.Rational(float(x))))

    D = _chain_matrix(R, vals, T, m, q)
    adj, det = _adj_det(D, R.zero)

    def floats(p) -> sp.Expr:
        return sp.Add(*(sp.Float(sp.QQ.to_sympy(c)) * z**k for (k,), c in p.terms()))

    num = _filled(
        m, n, lambda i, j: floats(sum((adj[i][k] * q(vals[0][k, j]) for k in range(m)), R.zero))
    )
    return DiscreteTF(num, floats(det), dt)


_RING_METHOD = (
    "polynomial identities (zI - F_c) W = H_c det D and M_c W = N_G, multiplied out in Z[z, K]"
)


def _prove_in_ring(F, H, M, N, den, T: int, K) -> tuple[bool, str] | None:
    """Both identities of :func:`prove_controller_tf` in ``ZZ[z, K]``; None if not expressible.

    ``W = [z^{T-1} N; ...; N]`` is never formed: block ``k`` of ``(zI - F) W`` is
    ``z^{T-k} z N - sum_l F_{kl} z^{T-l} N`` with the sparse ``F`` (an entry at a time).
    """
    gens = [z, *K]
    R = sp.polys.rings.ring(gens, sp.ZZ)[0]
    try:
        Nr = [[R.from_expr(e) for e in N.row(i)] for i in range(N.rows)]
        den_r = R.from_expr(den)
        Fr = {
            (i, j): R.from_expr(F[i, j])
            for i in range(F.rows)
            for j in range(F.cols)
            if F[i, j] != 0
        }
        Hr = {
            (i, j): R.from_expr(H[i, j])
            for i in range(H.rows)
            for j in range(H.cols)
            if H[i, j] != 0
        }
    except (sp.polys.polyerrors.CoercionFailed, ValueError, TypeError):
        return None
    zz = R.gens[0]
    m, cols = N.rows, N.cols
    zpow = [zz**p for p in range(T + 1)]

    def w(row: int, col: int):  # entry of W: block row // m is z^{T-1-block} N
        block, r = divmod(row, m)
        return Nr[r][col] * zpow[T - 1 - block]

    by_row: dict[int, list[tuple[int, object]]] = {}
    for (i, j), f in Fr.items():
        by_row.setdefault(i, []).append((j, f))
    for i in range(F.rows):
        for c in range(cols):
            e = zz * w(i, c) - sum((f * w(j, c) for j, f in by_row.get(i, ())), R.zero)
            e -= Hr.get((i, c), R.zero) * den_r
            if e:
                return False, str(e.as_expr())
    for i in range(M.rows):
        for c in range(cols):
            e = sum((int(M[i, j]) * w(j, c) for j in range(M.cols) if M[i, j]), R.zero)
            e -= Nr[i][c]
            if e:
                return False, str(e.as_expr())
    return True, ""


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
    ring_proof = _prove_in_ring(F, H, M, N, G.den, T, K) if system.m > 1 else None
    if ring_proof is not None:
        ok, first = ring_proof
        return Proof(ok, claim, _RING_METHOD, first)
    W = sp.Matrix.vstack(*(N * z ** (T - k) for k in range(1, T + 1)))
    lhs = (z * sp.eye(F.shape[0]) - F) * W - H * G.den
    method = "polynomial identities (zI - F_c) W = H_c det D and M_c W = N_G, expanded"
    for e in (*lhs, *(M * W - N)):
        e = sp.expand(e)
        if e != 0:
            return Proof(False, claim, method, str(e))
    return Proof(True, claim, method)
