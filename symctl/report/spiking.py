"""What spikes cost each circuit: ``symctl spiking``'s files, ``symctl paper --spiking``'s section."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from symctl.report.document import Graphic, Heading, Table, Text, write_markdown
from symctl.report.output import write_json

__all__ = ["paper_blocks", "write_spiking"]


def _n(x: float, top: int = 0) -> str:
    """``x`` rounded; ``> top`` for infinity (no size reached the tolerance)."""
    return f"> {top:,}" if np.isinf(x) else f"{x:,.0f}"


def _table(cost) -> Table:
    """The cost table, cheapest first (the other tolerances: N alone, so that it fits a page)."""
    first, *rest = (f"{100 * t:g}%" for t in cost.tolerances)
    head = ["circuit", "populations", "peak [spikes/s]", f"N within {first}", "range"]
    head += ["neurons", "spikes/s", *(f"N within {key}" for key in rest)]
    top = cost.neurons[-1]
    rows = []
    for r in cost.table():
        lo, hi = r[f"N@{first} range"]
        rows.append(
            (
                r["circuit"],
                str(r["populations"]),
                f"{r['peak']:.3g}",
                _n(r[f"N@{first}"], top),
                f"{_n(lo, top)} - {_n(hi, top)}",
                "-" if np.isinf(r[f"neurons@{first}"]) else _n(r[f"neurons@{first}"]),
                "-" if np.isinf(r[f"spikes@{first}"]) else _n(r[f"spikes@{first}"]),
                *(_n(r[f"N@{key}"], top) for key in rest),
            )
        )
    return Table(tuple(head), tuple(rows))


def _prose(cost) -> list:
    """What the sweep was, and what it found (every number computed from ``cost``)."""
    sizes = ", ".join(f"{n:,}" for n in cost.neurons)
    rho = cost.peak_correlation()
    blocks = [
        Text(
            f"Each circuit ran as spiking LIF populations (nengo) in the closed loop at {sizes} "
            f"neurons per population, {cost.seeds} seeds each. N is the population size that "
            "keeps the RMS deviation of the plant's state (the force, for the muscle) from the "
            "linear loop within the tolerance "
            "(interpolated in log N between the sizes; the median over seeds and its range; "
            f"'> {cost.neurons[-1]:,}': no size reached it), neurons = N times the populations, "
            "spikes/s at that N; peak is the largest rate change of the circuit's neurons in "
            "the linear loop. Cheapest first:"
        ),
        _table(cost),
        Text(cost.finding()),
    ]
    if cost.atlas_classes:
        blocks.append(Text("Among the atlas classes alone: " + cost.finding(cost.atlas_classes)))
    key = f"{100 * cost.tolerances[0]:g}%"
    rates = [r[f"spikes@{key}"] / r[f"neurons@{key}"] for r in cost.table()]
    rates = [x for x in rates if np.isfinite(x)]
    if np.isfinite(rho) and rates:
        blocks.append(
            Text(
                f"Firing amplitude and cost: Spearman's rank correlation of the peak with N within "
                f"{key} is {rho:.2f}. A spiking neuron fires {min(rates):.0f} to "
                f"{max(rates):.0f} spikes/s on average whatever its circuit (each population's "
                "radius follows its neuron's peak), so spikes follow neurons: ranked by neurons "
                f"in all, {', '.join(cost.ranking())}; by spikes, "
                f"{', '.join(cost.ranking('spikes'))}."
            )
        )
    return blocks


def write_spiking(cost, folder: Path, *, figures: bool = True, formats=("pdf", "png")) -> list:
    """Write ``spiking.json`` (:meth:`~symctl.spiking.cost.SpikingCost.summary`), ``spiking.md``
    and the figure ``spiking_cost`` into ``folder``; return the paths."""
    folder = Path(folder)
    out = [write_json(folder / "spiking.json", cost.summary(), indent=1, allow_nan=False)]
    blocks = [Heading("What spikes cost each circuit"), *_prose(cost)]
    if figures:
        from symctl.report.figures import save

        out += save(cost.plot(), folder, "spiking_cost", formats=formats)
        blocks.append(Graphic("spiking_cost", _CAPTION))
    return [*out, write_markdown(blocks, folder / "spiking.md", title="symctl spiking")]


_CAPTION = (
    "Left: median deviation of the force from the linear loop against neurons per "
    "population, the tolerances dotted. Right: neurons in all against spikes per second "
    "within the first tolerance; the marker's area is the circuit's firing amplitude."
)


def paper_blocks(res, shown) -> list:
    """The section of ``symctl paper --spiking``: the sweep of this controller's circuits."""
    blocks = [Heading("What spikes cost each circuit"), *_prose(res.spiking_cost)]
    if "spiking_cost" in shown:
        blocks.append(Graphic("spiking_cost", _CAPTION))
    return blocks
