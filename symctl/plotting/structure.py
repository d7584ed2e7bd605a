r"""Rendering of a structure's block diagram (the paper's style) from its layout.

:func:`draw_structure` asks :func:`symctl.plotting.structure_layout.structure_layout`
where everything goes (measuring text with :func:`symctl.plotting.common.text_size`)
and draws it: gains as boxes with their value, adders as circles with a plus,
one-step delays as dashed wires into the delayed signal (a small dot, named
when the paper names it, e.g. :math:`\gamma`). :meth:`Structure.draw
<symctl.compatibility.structure.Structure.draw>` delegates here.

>>> from symctl import ifp_structure
>>> from symctl.plotting.structure import draw_structure
>>> fig = draw_structure(ifp_structure(2))
>>> type(fig).__name__
'Figure'
"""

from __future__ import annotations

import math

from symctl.compatibility.structure import Structure
from symctl.errors import ParameterError, SymctlTypeError
from symctl.plotting.common import figure_and_axes, finish_figure, text_size
from symctl.plotting.structure_layout import (
    DOT_R,
    FONT,
    NAME_FONT,
    SUM_R,
    StructureLayout,
    Wire,
    structure_layout,
)
from symctl.plotting.structure_overview import draw_structure_overview

__all__ = ["draw_structure"]

_INK = "0.15"


def draw_structure(
    S: Structure,
    ax=None,
    *,
    title: str | None = None,
    max_signals: int = 400,
    overview: bool = False,
):
    """Draw the structure ``S`` in the style of the paper's block diagrams.

    Parameters
    ----------
    S : Structure
    ax : matplotlib Axes, optional
        Draw into these axes; by default a new figure sized to the drawing.
    title : str, optional
        The heading (default: the counts of gains, adders and delays).
    max_signals : int, default 400
        Refuse larger structures (their drawings are unreadable and slow).
    overview : bool, default False
        Draw the overview of the parts instead (:func:`draw_structure_overview`).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    SymctlTypeError
        ``S`` is not a Structure.
    ParameterError
        ``S`` has more than ``max_signals`` signals.

    Examples
    --------
    >>> from symctl import ifp_structure
    >>> from symctl.plotting.structure import draw_structure
    >>> draw_structure(ifp_structure(2), title="IFP").axes[0].texts[-2].get_text()
    'IFP'
    """
    if not isinstance(S, Structure):
        raise SymctlTypeError(f"S: expected a Structure, got {type(S).__name__}")
    if overview:
        return draw_structure_overview(S, ax, title=title)
    if len(S) > max_signals:
        raise ParameterError(
            f"max_signals: the structure has {len(S)} signals, more than {max_signals}; "
            "raise max_signals to draw it anyway"
        )
    layout = structure_layout(S, text_size)
    fig, ax, own = figure_and_axes(ax)
    _draw_wires(ax, layout.wires)
    _draw_blocks(ax, S, layout)
    for arrow in (*layout.arrows_in, *layout.arrows_out):
        _draw_wires(ax, [arrow])
    for part, x_left, x_right, y in layout.parts:
        ax.plot([x_left, x_right], [y, y], color="0.6", lw=0.8)
        ax.text(
            (x_left + x_right) / 2,
            y + 0.04,
            part,
            ha="center",
            va="bottom",
            fontsize=FONT,
            color="0.35",
        )
    axons = any(b.steps > 1 for b in S.blocks.values())
    word = "delay" if axons else "one-step delay"
    counts = ", ".join(
        f"{S.count(k)} {w}{'s' if S.count(k) != 1 else ''}"
        for k, w in (("gain", "gain"), ("sum", "adder"), ("delay", word))
    )
    heading = title or f"controller structure: {counts}"
    legend = (
        "boxes: gains (their values; long ones by block name)   circles: adders   "
        "dashed arrows: one-step delays   dots: signals"
        + ("   z^-k: an axon of k steps" if axons else "")
    )
    return finish_figure(fig, ax, own, layout.bounds, heading, legend, top=0.62)


def _draw_wires(ax, wires: list[Wire] | tuple[Wire, ...]) -> None:
    """Polylines ending in an arrow head; dashed for a delay, labelled z^-k for an axon of k steps."""
    from matplotlib.patches import FancyArrowPatch

    for wire in wires:
        pts = wire.points
        xs, ys = zip(*pts, strict=True)
        style = (0, (3.5, 2.2)) if wire.delay else "-"
        ax.plot(xs, ys, color=_INK, lw=1.0, linestyle=style, zorder=1, solid_capstyle="butt")
        if wire.delay > 1:
            k = max(range(len(pts) - 1), key=lambda i: math.dist(pts[i], pts[i + 1]))
            (xa, ya), (xb, yb) = pts[k], pts[k + 1]
            ax.text((xa + xb) / 2, (ya + yb) / 2 + 0.03, f"$z^{{-{wire.delay}}}$",
                    ha="center", va="bottom", fontsize=FONT, color=_INK, zorder=2,
                    bbox={"fc": "white", "ec": "none", "pad": 0.5})  # fmt: skip
        (x0, y0), (x1, y1) = pts[-2], pts[-1]
        length = math.hypot(x1 - x0, y1 - y0)
        if length == 0:
            continue
        back = min(0.08, length) / length
        ax.add_patch(
            FancyArrowPatch(
                (x1 - (x1 - x0) * back, y1 - (y1 - y0) * back),
                (x1, y1),
                arrowstyle="-|>,head_length=0.5,head_width=0.22",
                mutation_scale=11,
                color=_INK,
                lw=0.8,
                shrinkA=0,
                shrinkB=0,
                zorder=1.5,
            )
        )


def _draw_blocks(ax, S: Structure, layout: StructureLayout) -> None:
    """Gain boxes with their values, adders with a plus, dots and names for signals."""
    from matplotlib.patches import Circle, Rectangle

    for name, block in S.blocks.items():
        xc, yc = layout.positions[name]
        w, h = layout.sizes[name]
        if block.kind == "gain":
            ax.add_patch(
                Rectangle(
                    (xc - w / 2, yc - h / 2),
                    w,
                    h,
                    fc="white",
                    ec="black",
                    lw=1.0,
                    zorder=2,
                    gid=f"gain:{name}",
                )
            )
            ax.text(
                xc,
                yc,
                layout.labels[name],
                ha="center",
                va="center",
                fontsize=FONT,
                zorder=3,
                gid=f"gain:{name}",
            )
        elif block.kind == "sum":
            ax.add_patch(
                Circle((xc, yc), SUM_R, fc="white", ec="black", lw=1.0, zorder=2, gid=f"sum:{name}")
            )
            ax.text(xc, yc, "+", ha="center", va="center_baseline", fontsize=FONT + 1, zorder=3)
        else:
            ax.add_patch(Circle((xc, yc), DOT_R, fc="black", zorder=2, gid=f"signal:{name}"))
        if name in layout.names:
            ax.text(
                xc + w / 2 + 0.03,
                yc + 0.035,
                layout.names[name],
                ha="left",
                va="bottom",
                fontsize=NAME_FONT,
                color="0.3",
                zorder=3,
            )
