r"""The factorization of a MIMO controller :math:`G = N(z)/d(z)`: one chain of sections per channel.

Measured signal :math:`j` gets :math:`g_{1,j} = \prod_{k \le d_s} C_{1,j,k}/(z - \epsilon_{1,j,k})`,
input :math:`i` likewise :math:`g_{3,i}`; :math:`G_1 = \operatorname{diag}_j g_{1,j}`, :math:`G_3 =
\operatorname{diag}_i g_{3,i}` and :math:`(G_2)_{ij} = G_{ij}/(g_{3,i} g_{1,j}) = N_{ij} Z_{3,i}
Z_{1,j}/(C_{3,i} C_{1,j} d)` (:math:`Z` the sections' zeros, :math:`C` their gains' product), so
:math:`G_3 G_2 G_1 = G` entry by entry; :math:`G_2` keeps :math:`d`.
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from symctl import symbols as S
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, ParameterError
from symctl.symbols import z

__all__ = ["MAX_CHANNELS", "channel_sections", "channel_symbols", "mimo_G2", "section_symbols"]

MAX_CHANNELS = 50
"""Most measured signals (and most inputs) of a MIMO factorization."""


@cache
def section_symbols(side: int, count: int, channel: int | None = None) -> tuple[tuple, tuple]:
    """The ``(epsilons, Cs)`` of the ``count`` first-order sections on side 1 or 3, of one ``channel``
    of a MIMO factorization (``epsilon_{side,channel,k}``) or not (``epsilon_{side,k}``; one
    section: ``epsilon_1``, ``epsilon_3``)."""
    if side not in (1, 3):
        raise ParameterError(f"side: must be 1 (sensor) or 3 (actuator), got {side!r}")
    if count == 1 and channel is None:
        return ((S.epsilon_1,), (S.C_1,)) if side == 1 else ((S.epsilon_3,), (S.C_3,))
    at = f"{side}," if channel is None else f"{side},{channel},"
    return tuple(
        tuple(sp.Symbol(f"{stem}_{{{at}{k}}}", real=True) for k in range(1, count + 1))
        for stem in ("epsilon", "C")
    )


def channel_symbols(side: int, channel: int, count: int) -> tuple[tuple, tuple]:
    """:func:`section_symbols` of one ``channel``: ``epsilon_{side,channel,k}``, ``C_{side,channel,k}``."""
    return section_symbols(side, count, channel)


def _check_shape(tf: DiscreteTF) -> tuple[int, int]:
    p, m = tf.shape
    if p > MAX_CHANNELS or m > MAX_CHANNELS:
        raise DimensionError(
            f"G: at most {MAX_CHANNELS} inputs and {MAX_CHANNELS} outputs, got shape {tf.shape}"
        )
    return p, m


def channel_sections(values: tuple, count: int, channels: int) -> tuple[tuple, ...]:
    """``values`` (channel-major) cut into one tuple of ``count`` per channel."""
    return tuple(values[j * count : (j + 1) * count] for j in range(channels))


def mimo_G2(
    tf: DiscreteTF, sens_eps, sens_C, act_eps, act_C, ds: int, da: int, zeros=None
) -> DiscreteTF:
    r""":math:`(G_2)_{ij} = N_{ij} Z_{3,i} Z_{1,j} / (C_{3,i} C_{1,j} d)` from channel-major
    sections; ``zeros(i, j)``, when given, is written for :math:`Z_{3,i} Z_{1,j}` (from 0)."""
    p, m = _check_shape(tf)
    e1, c1 = channel_sections(sens_eps, ds, m), channel_sections(sens_C, ds, m)
    e3, c3 = channel_sections(act_eps, da, p), channel_sections(act_C, da, p)
    Z1 = [sp.Mul(*(z - e for e in e1[j])) for j in range(m)]
    Z3 = [sp.Mul(*(z - e for e in e3[i])) for i in range(p)]
    C1 = [sp.Mul(*c1[j]) for j in range(m)]
    C3 = [sp.Mul(*c3[i]) for i in range(p)]
    num = tf.num_matrix
    zeros = zeros or (lambda i, j: Z3[i] * Z1[j])
    entries = sp.Matrix(p, m, lambda i, j: sp.expand(num[i, j] * zeros(i, j)) / (C3[i] * C1[j]))
    return DiscreteTF(entries, tf.den, tf.dt)


def diagonal(sections: tuple[DiscreteTF, ...], dt) -> DiscreteTF:
    """The diagonal matrix of SISO transfer functions, over one common denominator."""
    k = len(sections)
    if k == 1:
        return sections[0]
    den = sp.Mul(*(s.den for s in sections))
    num = sp.zeros(k, k)
    for j, s in enumerate(sections):
        num[j, j] = s.num * sp.Mul(*(t.den for i, t in enumerate(sections) if i != j))
    return DiscreteTF(num, den, dt)


def verify_entries(G: DiscreteTF, G2: DiscreteTF, g1, g3, products_equal) -> bool:
    """Whether :math:`g_{3,i} (G_2)_{ij} g_{1,j} = G_{ij}` for every entry, exactly."""
    p, m = G.shape
    n, n2 = G.num_matrix, G2.num_matrix
    for i in range(p):
        for j in range(m):
            left = [g3[i].num, n2[i, j], g1[j].num, G.den]
            right = [n[i, j], g3[i].den, G2.den, g1[j].den]
            if not products_equal(left, right):
                return False
    return True
