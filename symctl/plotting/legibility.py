"""Is a figure legible in print? Its text measured as drawn: size, overlaps, clipping, width."""

from __future__ import annotations

import itertools
from dataclasses import dataclass

from symctl.plotting.style import MIN_FONT, TEXT_WIDTH

__all__ = ["Legibility", "legibility", "missing_units"]


@dataclass(frozen=True)
class Legibility:
    """What :func:`legibility` found, truthy when legible: texts ``small`` ``(text, size [pt])``,
    pairs that ``overlaps``, texts ``clipped`` off the figure; the printed ``width`` [in] and
    whether it is ``too_wide``.
    """

    small: tuple = ()
    overlaps: tuple = ()
    clipped: tuple = ()
    width: float = 0.0
    too_wide: bool = False

    def __bool__(self) -> bool:
        return not (self.small or self.overlaps or self.clipped or self.too_wide)

    def __str__(self) -> str:
        if self:
            return f"legible ({self.width:.2f} in wide)"
        parts = []
        if self.small:
            parts.append("small text: " + ", ".join(f"{t!r} {s:.1f} pt" for t, s in self.small))
        if self.overlaps:
            parts.append("overlaps: " + ", ".join(f"{a!r}/{b!r}" for a, b in self.overlaps))
        if self.clipped:
            parts.append("clipped: " + ", ".join(repr(t) for t in self.clipped))
        if self.too_wide:
            parts.append(f"{self.width:.2f} in wide")
        return "not legible: " + "; ".join(parts)


def _hidden_ticks(fig) -> set[int]:
    """Tick labels outside their axis's view (kept but never drawn), as matplotlib compares."""
    hidden = set()
    for ax in fig.get_axes():
        for axis in (ax.xaxis, ax.yaxis):
            scale = axis.get_transform()
            lo, hi = sorted(scale.transform(list(axis.get_view_interval())))
            slack = 1e-9 * abs(hi - lo)
            for tick in (*axis.get_major_ticks(), *axis.get_minor_ticks()):
                loc = scale.transform([tick.get_loc()])[0]
                if not lo - slack <= loc <= hi + slack:
                    hidden.update((id(tick.label1), id(tick.label2)))
    return hidden


def _texts(fig):
    """Every drawn, non-empty text artist of ``fig`` (titles, labels, ticks, legends)."""
    from matplotlib.text import Text

    hidden = _hidden_ticks(fig)
    for t in fig.findobj(Text):
        if t.get_visible() and t.get_text().strip() and id(t) not in hidden:
            yield t


def legibility(
    fig,
    *,
    scale: float = 1.0,
    min_font: float = MIN_FONT,
    page_width: float | None = TEXT_WIDTH,
    overlap_tolerance: float = 0.5,
) -> Legibility:
    """Check that ``fig`` is legible printed at ``scale`` times its size: no text under
    ``min_font`` [pt], no overlap of more than ``overlap_tolerance`` [pt] either way, none
    clipped, no wider than ``page_width`` [in] (None: not checked).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = fig.canvas
    try:
        renderer = FigureCanvasAgg(fig).get_renderer()
        fig.draw(renderer)
        W, H = fig.bbox.width, fig.bbox.height
        tol = overlap_tolerance * (fig.dpi / 72.0)  # [px]
        small, boxes, clipped = [], [], []
        for t in _texts(fig):
            size = t.get_fontsize() * scale
            if size < min_font - 1e-9:
                small.append((t.get_text(), round(float(size), 2)))
            box = t.get_window_extent(renderer)
            if box.x0 < -tol or box.y0 < -tol or box.x1 > W + tol or box.y1 > H + tol:
                clipped.append(t.get_text())
            boxes.append((t.get_text(), box))
        overlaps = []
        for (a, ba), (b, bb) in itertools.combinations(boxes, 2):
            dx = min(ba.x1, bb.x1) - max(ba.x0, bb.x0)
            dy = min(ba.y1, bb.y1) - max(ba.y0, bb.y0)
            if dx > tol and dy > tol:
                overlaps.append((a, b))
    finally:
        fig.set_canvas(canvas)
    printed = float(fig.get_size_inches()[0]) * scale
    too_wide = page_width is not None and printed > page_width + 1e-6
    return Legibility(tuple(small), tuple(overlaps), tuple(clipped), printed, too_wide)


def missing_units(fig) -> tuple[str, ...]:
    """The axes of ``fig`` (drawn: tick labels get their text when drawn) showing numbers but
    naming no unit ``[unit]`` in their label or one their (sub)figure shares, as
    ``"axes <k> y: '<label>'"``.
    """

    def shared(ax, which: str) -> str:
        texts, parent = [], ax.figure
        while parent is not None:  # the (sub)figure, then its parents up to the figure
            label = getattr(parent, f"_sup{which}label", None)
            texts.append(label.get_text() if label is not None else "")
            parent = getattr(parent, "_parent", None)
        return " ".join(texts)

    missing = []
    for k, ax in enumerate(fig.get_axes()):
        if not ax.get_visible() or not ax.axison:
            continue
        for which, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
            shown = any(
                t.label1.get_visible() and t.label1.get_text().strip()
                for t in axis.get_major_ticks()
            )
            label = axis.get_label().get_text()
            if shown and "[" not in label and "[" not in shared(ax, which):
                missing.append(f"axes {k} {which}: {label!r}")
    return tuple(missing)
