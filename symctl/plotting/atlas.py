"""Drawing an atlas: one circuit per class on a grid (the classes' own drawings are Circuit.draw)."""

from __future__ import annotations

import math

from matplotlib.figure import Figure

__all__ = ["draw_atlas", "draw_classes"]

CELL = (6.0, 3.4)
"""Width and height of one class's panel, in inches."""


def draw_atlas(atlas, *, universal_only: bool = True, columns: int = 3) -> Figure:
    """The circuits of an atlas's classes on a grid, each titled with its label and counts.

    Parameters
    ----------
    atlas : Atlas
    universal_only : bool
        Only the universal classes (default), or every class.
    columns : int
        Panels per row.

    Returns
    -------
    matplotlib.figure.Figure
    """
    classes = atlas.universal_classes if universal_only else atlas.classes
    return draw_classes(atlas, classes or atlas.classes, columns=columns)


def draw_classes(atlas, classes, *, columns: int = 3) -> Figure:
    """The circuits of the given classes of ``atlas`` on a grid."""
    columns = max(1, min(columns, len(classes)))
    rows = math.ceil(len(classes) / columns)
    fig = Figure(figsize=(CELL[0] * columns, CELL[1] * rows + 0.5))
    for i, c in enumerate(classes):
        ax = fig.add_subplot(rows, columns, i + 1)
        verdict = {True: "universal", False: "not universal", None: "not decided"}[c.universal]
        c.circuit.draw(
            ax, title=f"{c.label}: {c.n_neurons} neurons, {c.n_synapses} synapses, {verdict}"
        )
    fig.suptitle(
        f"Order-{atlas.order} circuit atlas: {len(classes)} of {len(atlas.classes)} classes "
        f"({len(atlas.universal_classes)} universal)",
        fontsize=12,
    )
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=0.93, wspace=0.05, hspace=0.15)
    return fig
