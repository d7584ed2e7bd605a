"""Pieces shared by every drawing: a figure (pyplot-free), text measure, heading and key.

This is the only place besides the rest of :mod:`symctl.plotting` that imports matplotlib.
"""

from __future__ import annotations

from functools import lru_cache

__all__ = [
    "figure_and_axes",
    "finish_figure",
    "fit_to_drawing",
    "text_outline",
    "text_size",
    "wrap_key",
]


@lru_cache(maxsize=4096)
def text_size(text: str, size: float) -> tuple[float, float]:
    """Width and height in inches of ``text`` set at ``size`` points (mathtext allowed).

    The box of its glyph outlines (:func:`text_outline`). Cached: every drawing
    measures the same keys and headings again (an atlas overview measured its key
    nine times, two thirds of its drawing time).
    """
    _, (x0, y0, x1, y1) = text_outline(text, size)
    return (x1 - x0) / 72, (y1 - y0) / 72


def text_outline(text: str, size: float):
    """``(path, (x0, y0, x1, y1))``: the glyph outlines of ``text`` at ``size`` points and their box.

    The path is in points, its origin on the baseline at the left (``None`` for text
    without ink). The box is that of the outlines' vertices: TrueType outlines have
    their on- and off-curve points at the curves' extrema, so it is the outlines' box
    (to a thousandth of a point) without ``Path.get_extents``, which walks every
    Bezier segment in Python (three quarters of the drawing time of a circuit with a
    key of long weights).
    """
    from matplotlib.font_manager import FontProperties
    from matplotlib.path import Path
    from matplotlib.textpath import TextPath

    if not text.strip():  # no ink (TextPath cannot make an empty path)
        return None, (0.0, 0.0, 0.0, 0.0)
    path = TextPath((0, 0), text, size=size, prop=FontProperties(size=size))
    points = path.vertices if path.codes is None else path.vertices[path.codes != Path.CLOSEPOLY]
    if not len(points):
        return None, (0.0, 0.0, 0.0, 0.0)
    (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
    return path, (float(x0), float(y0), float(x1), float(y1))


def figure_and_axes(ax):
    """``(fig, ax, own)``: a new pyplot-free figure filling one axes, or the caller's axes."""
    from matplotlib.figure import Figure

    if ax is None:
        fig = Figure()
        return fig, fig.add_axes((0, 0, 1, 1)), True
    return ax.figure, ax, False


def fit_to_drawing(fig, ax, own: bool, x_lo: float, x_hi: float, y_lo: float, y_hi: float):
    """The axes show ``[x_lo, x_hi] x [y_lo, y_hi]`` at one inch per data unit, without frame;
    a figure of the drawing's own (``own``) is sized to it. Returns ``fig``."""
    ax.set_xlim(x_lo, x_hi)
    ax.set_ylim(y_lo, y_hi)
    ax.set_aspect("equal")
    ax.axis("off")
    if own:
        fig.set_size_inches(x_hi - x_lo, y_hi - y_lo)
    return fig


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
    ax.text(
        x_lo + 0.1,
        y_hi + 0.1,
        "\n".join(lines),
        ha="left",
        va="bottom",
        fontsize=7.5,
        color="0.35",
        linespacing=1.3,
    )
    width = 1.08 * max(text_size(t, s)[0] for t, s in [(heading, 10), *((ln, 7.5) for ln in lines)])
    x_hi = max(x_hi, x_lo + width + 0.3)
    y_hi += top + extra
    return fit_to_drawing(fig, ax, own, x_lo, x_hi, y_lo, y_hi)


def wrap_key(items: list[str], room: float, size: float) -> list[str]:
    """Pack the key's items into lines no wider than ``room`` inches (one item may overflow)."""
    lines: list[str] = []
    for item in items:
        if lines and 1.08 * text_size(lines[-1] + "   " + item, size)[0] <= room:
            lines[-1] += "   " + item
        else:
            lines.append(item)
    return lines
