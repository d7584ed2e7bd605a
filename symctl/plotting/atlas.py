"""An atlas drawn: one circuit per class on a grid at the printed size, one key for all."""

from __future__ import annotations

from matplotlib.figure import Figure

from symctl.plotting import style
from symctl.plotting.circuit import SMALL, draw_circuit, drawn
from symctl.plotting.circuit_key import Key, draw_key_items, key_items

__all__ = ["draw_atlas", "draw_classes"]


def _cell(columns: int) -> float:
    """The width of a panel in a grid of ``columns`` panels across the text [in]."""
    return (style.TEXT_WIDTH - GAP * (columns - 1)) / columns


def _panel(fig, circuit, head: str, width: float, ax=None):
    """``(axes, width, height, head)``: the circuit drawn into an axes of ``fig`` [in]."""
    if ax is None:
        ax = fig.add_axes((0, 0, 1, 1))
    else:
        ax.clear()
    draw_circuit(circuit, ax, title=head, width=width, key=False)
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    return ax, x1 - x0, y1 - y0, head


GAP = 0.08  # between two panels [in]
_SQUEEZE = 1.1  # a drawing this much wider than its column is redrawn to fit it
_VERDICT = {True: "universal", False: "not universal", None: "not decided"}


def _verdict(c) -> str:
    """A class's verdict: universal, conjectured, not universal or not decided."""
    return getattr(c, "verdict", None) or _VERDICT[c.universal]


def draw_atlas(
    atlas, *, universal_only: bool = True, columns: int = 3, title: str | None = None
) -> Figure:
    """The circuits of an atlas's classes (``universal_only``: the proved universal ones) on a
    grid of at most ``columns``, each titled with its label and counts, ``title`` above."""
    classes = atlas.universal_classes if universal_only else atlas.classes
    return draw_classes(atlas, classes or atlas.classes, columns=columns, title=title)


def draw_classes(atlas, classes, *, columns: int = 3, title: str | None = None) -> Figure:
    """The circuits of the given classes of ``atlas`` on a grid no wider than the text width.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from symctl import Circuit, ifp_structure
    >>> from symctl.plotting.atlas import draw_classes
    >>> one = SimpleNamespace(circuit=Circuit.from_structure(ifp_structure(2)), label="I1",
    ...                       n_neurons=1, n_synapses=1, universal=True)
    >>> fig = draw_classes(SimpleNamespace(order=2), [one])
    >>> fig.axes[0].texts[-1].get_text()
    'I1: 1 neuron, 1 synapse, universal'
    """
    width = style.TEXT_WIDTH
    fig = Figure()
    panels = []
    for c in classes:  # each at its natural size first
        head = (
            f"{c.label}: {c.n_neurons} neuron{'s' if c.n_neurons != 1 else ''}, "
            f"{c.n_synapses} synapse{'s' if c.n_synapses != 1 else ''}, {_verdict(c)}"
        )
        panels.append(_panel(fig, c.circuit, head, width))
    # as many columns as asked for, or as fit the widest drawing (one a little wider is
    # drawn again at the column's width, more tightly spaced)
    columns = max(1, min(columns, len(classes)))
    while columns > 1 and max(w for _, w, _, _ in panels) > _SQUEEZE * _cell(columns):
        columns -= 1
    cell = _cell(columns)
    panels = [
        p if p[1] <= cell else _panel(fig, c.circuit, p[3], cell, p[0])
        for p, c in zip(panels, classes, strict=True)
    ]
    rows = [panels[k : k + columns] for k in range(0, len(panels), columns)]
    heights = [max(h for _, _, h, _ in row) for row in rows]
    # the shared key, drawn in an axes of its own under the grid
    said = [drawn(ax).key for ax, _, _, _ in panels]
    union = Key(
        signs=frozenset().union(*(k.signs for k in said)),
        delays=frozenset().union(*(k.delays for k in said)),
        labelled=all(k.labelled for k in said),
        bodies=any(k.bodies for k in said),
        empty=any(k.empty for k in said),
        # said only of panels without weights: the largest of their counts
        synapses=max((k.synapses for k in said if not k.labelled), default=0),
    )
    kax = fig.add_axes((0, 0, 1, 1))
    bottom, _ = draw_key_items(kax, key_items(union), 0.0, 0.0, width, SMALL)
    key_height = -bottom + 0.04
    kax.set_xlim(0, width)
    kax.set_ylim(bottom - 0.02, 0.02)
    kax.axis("off")
    head = 0.0
    if title:
        head = style.TITLE / 72 * 1.6
        fig.text(0.0, 1.0, title, ha="left", va="top", fontsize=style.TITLE)
    total = head + sum(heights) + GAP * len(rows) + key_height
    fig.set_size_inches(width, total)
    top = total - head
    for row, h in zip(rows, heights, strict=True):
        for k, (ax, w, hh, _) in enumerate(row):
            left = k * (cell + GAP)
            ax.set_position((left / width, (top - hh) / total, w / width, hh / total))
        top -= h + GAP
    kax.set_position((0, 0, 1, (key_height + 0.02) / total))
    return fig
