"""The key under a drawing: ``name = value`` lines of the values too long to write in place.

A circuit drawing writes a long synapse weight as :math:`w_k` and a structure drawing
a long gain as its matrix entry (:math:`F_{12}`); both list the values under the
drawing, in as many columns as fit the page (:func:`key_columns`). Numbers only.

>>> from symctl.plotting.key import key_columns
>>> key_columns([1.0, 1.0, 1.0], room=2.5, gap=0.3)
[[0, 1], [2]]
>>> key_columns([3.0, 1.0], room=2.5, gap=0.3)
[[0, 1]]
"""

from __future__ import annotations

from collections.abc import Sequence

__all__ = ["key_columns"]


def key_columns(widths: Sequence[float], room: float, gap: float) -> list[list[int]]:
    """The key's lines (indices) in columns, top to bottom: the most columns that fit ``room``.

    Each column is as wide as its widest line, columns ``gap`` apart; with ``n`` columns
    the first ones hold ``ceil(len / n)`` lines. One column when even two do not fit.

    Parameters
    ----------
    widths : sequence of float
        The width of each line [in].
    room : float
        The width the key may take [in].
    gap : float
        The space between two columns [in].

    Returns
    -------
    list of list of int
    """
    for n in range(len(widths), 1, -1):
        rows = -(-len(widths) // n)
        columns = [list(range(k, min(k + rows, len(widths)))) for k in range(0, len(widths), rows)]
        total = sum(max(widths[k] for k in col) for col in columns) + gap * (len(columns) - 1)
        if total <= room:
            return columns
    return [list(range(len(widths)))]
