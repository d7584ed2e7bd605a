"""Pieces shared by every drawing: a figure (pyplot-free), text measure, heading and key.

This is the only place besides the rest of :mod:`symctl.plotting` that imports matplotlib.
"""

from __future__ import annotations

from functools import lru_cache

__all__ = ["figure_and_axes", "finish_figure", "text_size", "wrap_key"]


@lru_cache(maxsize=4096)
def text_size(text: str, size: float) -> tuple[float, float]:
    """Width and height in inches of ``text`` set at ``size`` points (mathtext allowed).

    Cached: every drawing measures the same keys and headings again (an atlas overview
    measured its key nine times, two thirds of its drawing time).
    """
    from matplotlib.font_manager import FontProperties
    from matplotlib.textpath import TextPath

    box = TextPath((0, 0), text, size=size, prop=FontProperties(size=size)).get_extents()
    return box.width / 72, box.height / 72


def figure_and_axes(ax):
    """``(fig, ax, own)``: a new pyplot-free figure filling one axes, or the caller's axes."""
    from matplotlib.figure import Figure

    if ax is None:
        fig = Figure()
        return fig, fig.add_axes((0, 0, 1, 1)), True
    return ax.figure, ax, False


def finish_figure(fig, ax, own: bool, bounds, heading: str, key: str, top: float):
    """Heading and key above the drawing, equal axes without frame, size in inches.

    Shared by structure and circuit drawings (one data unit is one inch).
    """
    x_lo, x_hi, y_lo, y_hi = bounds
    # TextPath measures the glyph outlines; rendered text runs a few percent wider
    room = max(x_hi - x_lo, 4.0) - 0.3
    lines = wrap_key(key.split("   "), room, 7.5)
    extra = 0.14 * (len(lines) - 1)
    ax.text(x_lo + 0.1, y_hi + 0.3 + extra, heading, ha="left", va="bottom", fontsize=10)
    ax.text(x_lo + 0.1, y_hi + 0.1, "\n".join(lines), ha="left", va="bottom", fontsize=7.5,
            color="0.35", linespacing=1.3)  # fmt: skip
    width = 1.08 * max(text_size(t, s)[0] for t, s in [(heading, 10), *((ln, 7.5) for ln in lines)])
    x_hi = max(x_hi, x_lo + width + 0.3)
    y_hi += top + extra
    ax.set_xlim(x_lo, x_hi)
    ax.set_ylim(y_lo, y_hi)
    ax.set_aspect("equal")
    ax.axis("off")
    if own:
        fig.set_size_inches(x_hi - x_lo, y_hi - y_lo)
    return fig


def wrap_key(items: list[str], room: float, size: float) -> list[str]:
    """Pack the key's items into lines no wider than ``room`` inches (one item may overflow)."""
    lines: list[str] = []
    for item in items:
        if lines and 1.08 * text_size(lines[-1] + "   " + item, size)[0] <= room:
            lines[-1] += "   " + item
        else:
            lines.append(item)
    return lines
