r"""The fit figure: data against fit for the recorded neurons, predictions for the others.

The rendering of :meth:`FitResult.plot <symctl.discovery.fit.FitResult.plot>`: one
panel per neuron of the fitted circuit. A recorded neuron shows its data (dots)
and the fitted trace; an unrecorded one its predicted trace with one standard
error as a band, or a note that the data do not pin it down.

>>> from symctl import MuscleModel, augment, fit, lqr_gains, synthetic_traces
>>> from symctl.plotting.fit import fit_plot
>>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
>>> data = synthetic_traces(gains, sensor_delay=1, actuator_delay=1, seed=3)
>>> res = fit(data.select(["G2.x1", "G2.x2", "G2.y"]).traces, gains, sensor_delay=1,
...           actuator_delay=1, C=1, starts=2)
>>> [ax.get_title() for ax in fit_plot(res).axes][:2]
['G1.x1 (predicted)', 'G2.x1 (recorded)']
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.figure import Figure

if TYPE_CHECKING:
    from symctl.discovery.fit import FitResult

__all__ = ["fit_plot"]


def fit_plot(result: FitResult, ncols: int = 3) -> Figure:
    """One panel per neuron: data and fit (recorded), prediction and its band (unrecorded).

    Parameters
    ----------
    result : FitResult
    ncols : int
        Panels per row.

    Returns
    -------
    matplotlib.figure.Figure
    """
    pred, band = result.predict(), result.band()
    names = list(pred)
    rows = -(-len(names) // ncols)
    fig = Figure(figsize=(4.0 * min(ncols, len(names)), 2.8 * rows), layout="constrained")
    t = result.t
    for i, name in enumerate(names):
        ax = fig.add_subplot(rows, min(ncols, len(names)), i + 1)
        if name in result.data:
            ax.plot(t, result.data[name], ".", ms=3, color="0.55", label="data")
            ax.plot(t, pred[name], color="C0", label="fit", drawstyle="steps-post")
            ax.set_title(f"{name} (recorded)")
        else:
            ok = result.neuron_identifiable[name]
            ax.plot(t, pred[name], color="C1" if ok else "C3", label="prediction",
                    drawstyle="steps-post")  # fmt: skip
            if ok and np.all(np.isfinite(band[name])):
                ax.fill_between(t, pred[name] - band[name], pred[name] + band[name], color="C1",
                                alpha=0.3, lw=0, label="1 s.e.")  # fmt: skip
            else:
                ax.text(0.5, 0.9, "not identifiable: one of many", transform=ax.transAxes,
                        ha="center", fontsize=8, color="C3")  # fmt: skip
            ax.set_title(f"{name} (predicted)")
        ax.set_xlabel("t [s]")
        ax.set_ylabel("change in firing rate [spikes/s]")
        ax.legend(fontsize=7, loc="lower right")
    fig.suptitle(
        f"fit: {result.circuit_class} circuit, realizes G exactly: {result.exact}", fontsize=10
    )
    return fig
