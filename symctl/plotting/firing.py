r"""The firing-pattern figure: one panel per neuron of :math:`G_2`, one line per realization.

The rendering of :meth:`FiringPatterns.plot <symctl.neural.firing.FiringPatterns.plot>`
(the paper's Figs. full_diagram, ccr_diagram, ocr_diagram): the force of every
realization on top (identical), each neuron's change of firing rate below.

>>> from symctl import MuscleModel, augment, circuit_firing, lqr_gains
>>> from symctl.plotting.firing import firing_plot
>>> fp = circuit_firing("controllable", lqr_gains(augment(MuscleModel(), 1, 1)), count=2)
>>> [ax.get_title() for ax in firing_plot(fp).axes][1:]
['neuron $x_{2}$', 'neuron $y$']
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from matplotlib.figure import Figure

from symctl._util.texnames import signal_tex
from symctl._util.validate import positive_int
from symctl.neural.firing import _TITLES

if TYPE_CHECKING:
    from symctl.neural.firing import FiringPatterns

__all__ = ["firing_plot"]

_RATE_LABEL = "change in firing rate [spikes/s]"


def _tex(name: str, *, part: bool = True) -> str:
    return f"${signal_tex(name, part=part)}$"


def _names(fp, labels, which: str = "state") -> tuple[str, str, str]:
    """(axis label, unit, short name) of the plant's state or input."""
    if labels is None:
        return (
            ("force f", "N", "force")
            if which == "state"
            else ("rate r", "spikes/s", "motor-neuron rate")
        )
    ref = fp.reference
    name = (ref.state_names if which == "state" else ref.input_names)[0]
    raw = name.removeprefix("delta_")
    what, unit = labels.get(raw, ("", ""))
    return (f"{what} {raw}" if what else raw), unit or "units", what or raw


def firing_plot(fp: FiringPatterns, ncols: int = 3, labels=None) -> Figure:
    """One panel per neuron of :math:`G_2` (one line per realization), the plant's state on top.

    Parameters
    ----------
    fp : FiringPatterns
        The result of :func:`~symctl.neural.firing.circuit_firing`.
    ncols : int
        Neuron panels per row.
    labels : mapping of str to (str, str), optional
        ``name -> (description, unit)`` of the plant's state and input (their
        names without ``delta_``); default the muscle's (force f [N], rate r).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ParameterError
        ``ncols`` is not an integer >= 1.

    Examples
    --------
    >>> from symctl import MuscleModel, augment, circuit_firing, lqr_gains
    >>> from symctl.plotting.firing import firing_plot
    >>> fp = circuit_firing("observable", lqr_gains(augment(MuscleModel(), 1, 1)), count=2)
    >>> [ax.get_title() for ax in firing_plot(fp, ncols=2).axes][1:]
    ['neuron $x_{1}$', 'neuron $x_{2}$', 'neuron $y$']
    """
    ncols = positive_int(ncols, "ncols")
    names = fp.neurons
    cols = max(1, min(int(ncols), len(names)))
    rows = -(-len(names) // cols)
    fig = Figure(figsize=(max(3.6 * cols + 1.2, 8.0), 2.2 + 2.7 * rows), layout="constrained")
    grid = fig.add_gridspec(1 + rows, cols, height_ratios=[0.55] + [1.0] * rows)
    top = fig.add_subplot(grid[0, :])
    for i in range(fp.count):
        top.plot(fp.t, fp.f_bar + fp.delta_f[i], color=f"C{i % 10}", lw=1.2,
                 drawstyle="steps-post")  # fmt: skip
    top.plot(fp.t, fp.f_bar + fp.reference.delta_f[:, 0], "k:", lw=1.2,
             label="optimal controller (identical)", drawstyle="steps-post")  # fmt: skip
    state = _names(fp, labels)
    top.set_ylabel(f"{state[0]} [{state[1]}]")
    top.set_title(f"{state[2]}, every realization (identical)", fontsize="medium")
    top.legend(loc="upper right", fontsize="small")
    top.grid(alpha=0.3)
    axes = []
    for k, name in enumerate(names):
        ax = fig.add_subplot(grid[1 + k // cols, k % cols], sharex=top)
        for i in range(fp.count):
            ax.plot(fp.t, fp.firing[name][i], marker=".", ms=3, lw=1.3, drawstyle="steps-post",
                    color=f"C{i % 10}", label=fp.legend_label(i))  # fmt: skip
        ax.axhline(0, color="black", lw=0.5)
        part = name.rpartition(".")[0]  # "P1.G2" for a part of a parallel decomposition
        where = f" ({part.partition('.')[0]})" if "." in part else ""
        ax.set_title(f"neuron {_tex(name, part=False)}{where}")
        ax.set_xlabel(f"time [{fp.reference.time_unit}]")
        if k % cols == 0:
            ax.set_ylabel(_RATE_LABEL)
        ax.grid(alpha=0.3)
        axes.append(ax)
    if axes:
        handles, texts = axes[0].get_legend_handles_labels()
        wide = max((len(t) for t in texts), default=0) > 48  # long labels: two per row
        fig.legend(handles, texts, loc="outside lower center", fontsize="small",
                   ncols=min(fp.count, 2 if wide or cols <= 2 else 4), title="realization")  # fmt: skip
    what = "the neuron of the" if fp.kind == "ifp" else "the neurons of $G_2$,"
    fig.suptitle(
        f"Firing of {what} {_TITLES.get(fp.kind, fp.kind)}\n"
        + (
            "one realization: the optimal controller's delay chain"
            if fp.kind == "ifp"
            else f"same {state[2]} (top) and {_names(fp, labels, 'input')[2]} in every realization"
            f"\n(the rate checked to {max(fp.max_deviation, 1e-16):.0e}, relative); different firing"
        )
    )
    return fig
