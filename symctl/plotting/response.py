r"""Figures of simulations: a loop's force and rate traces, the nonlinear muscle's departure.

The rendering of :meth:`Response.plot <symctl.neural.simulate.Response.plot>` and
:meth:`NonlinearCheck.plot <symctl.neural.nonlinear.NonlinearCheck.plot>` (the methods
hand their object over). Figures are pyplot-free :class:`matplotlib.figure.Figure`
objects, saved by the caller.

>>> from symctl import MuscleModel, augment, closed_loop_response, lqr_gains
>>> from symctl.plotting.response import response_plot
>>> fig = response_plot(closed_loop_response(lqr_gains(augment(MuscleModel(), 1, 1))))
>>> [ax.get_ylabel() for ax in fig.axes]
['force change δf [N]', 'rate change δr [spikes/s]', 'controller state\n(rate change) [spikes/s]']
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from matplotlib.figure import Figure

if TYPE_CHECKING:
    from symctl.neural.nonlinear import NonlinearCheck
    from symctl.neural.simulate import Response

__all__ = ["nonlinear_plot", "response_plot"]


def _labels(p_names: tuple[str, ...], kind: str) -> tuple[str, str, str]:
    """(change label, absolute label, unit) for the muscle; neutral names otherwise."""
    muscle = {"delta_f": ("force change δf", "force f", "N"),
              "delta_r": ("rate change δr", "motor-neuron rate r", "spikes/s")}  # fmt: skip
    if p_names == (kind,) and kind in muscle:
        return muscle[kind]
    return ("change from equilibrium", "absolute value", "units")


def response_plot(res: Response, states: bool | None = None) -> Figure:
    """Force and motor-neuron rate against time, absolute values on the right axes.

    Parameters
    ----------
    res : Response
        An open- or closed-loop simulation.
    states : bool, optional
        Add a panel with the controller's internal states (default: when there
        are any).

    Returns
    -------
    matplotlib.figure.Figure
        Two or three panels sharing the time axis.

    Examples
    --------
    >>> from symctl import open_loop_response
    >>> from symctl.plotting.response import response_plot
    >>> len(response_plot(open_loop_response()).axes)   # open loop: no controller states
    2
    """
    states = res.states.shape[1] > 0 if states is None else states
    rows = 3 if states else 2
    fig = Figure(figsize=(7.5, 2.4 * rows + 0.6), layout="constrained")
    axes = fig.subplots(rows, 1, sharex=True)
    panels = [
        (axes[0], res.delta_f, res.f_bar, res.state_names, "delta_f"),
        (axes[1], res.delta_r, res.r_bar, res.input_names, "delta_r"),
    ]
    for ax, trace, bar, names, kind in panels:
        change, absolute, unit = _labels(names, kind)
        for i in range(trace.shape[1]):
            label = change if trace.shape[1] == 1 else f"{change} ({names[i]})"
            ax.plot(res.t, trace[:, i], marker=".", lw=1.5, label=label)
        if kind == "delta_f" and res.kind == "closed loop":
            for i in range(res.w.shape[1]):
                ax.step(res.t, res.w[:, i], where="post", ls="--", color="gray",
                        label=f"disturbance w [{unit}/step]")  # fmt: skip
        ax.axhline(0, color="black", lw=0.5)
        ax.set_ylabel(f"{change} [{unit}]")
        if trace.shape[1] == 1:
            offset = float(bar[0])
            sec = ax.secondary_yaxis(
                "right", functions=(lambda x, o=offset: x + o, lambda x, o=offset: x - o)
            )
            sec.set_ylabel(f"{absolute} [{unit}]")
        ax.legend(loc="best", fontsize="small")
        ax.grid(alpha=0.3)
    if states:
        ax = axes[2]
        for i in range(res.states.shape[1]):
            ax.plot(res.t, res.states[:, i], marker=".", lw=1.2, label=f"x_{i + 1}")
        ax.set_ylabel("controller state\n(rate change) [spikes/s]")
        ax.legend(loc="best", fontsize="small", ncol=min(4, res.states.shape[1]))
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(f"time [{res.time_unit}]")
    what = "pulse in firing rate" if res.kind == "open loop" else "pulse disturbance on force"
    fig.suptitle(f"{res.kind.capitalize()} response to a {what}")
    return fig


def nonlinear_plot(chk: NonlinearCheck) -> Figure:
    """Force traces (nonlinear solid, linear dashed) and the deviation against amplitude.

    Parameters
    ----------
    chk : NonlinearCheck
        The result of :func:`~symctl.neural.nonlinear.nonlinear_check`.

    Returns
    -------
    matplotlib.figure.Figure
        The traces on the left, the deviations (log-log) on the right.

    Examples
    --------
    >>> from symctl import nonlinear_check
    >>> from symctl.plotting.response import nonlinear_plot
    >>> fig = nonlinear_plot(nonlinear_check(amplitudes=[0.1, 1.0], steps=20))
    >>> [ax.get_title() for ax in fig.axes]
    ['Linear controller around the nonlinear muscle', 'Departure from the linear prediction']
    """
    fig = Figure(figsize=(11, 4.2), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2, width_ratios=[1.6, 1])
    colors = [f"C{i % 10}" for i in range(len(chk.amplitudes))]
    for a, lin, nl, c in zip(chk.amplitudes, chk.f_linear, chk.f_nonlinear, colors, strict=True):
        ax1.plot(chk.t, nl, color=c, lw=1.6, label=f"w = {a:g} N per step")
        ax1.plot(chk.t, lin, color=c, lw=1.2, ls="--")
    ax1.plot([], [], color="gray", lw=1.6, label="nonlinear muscle (solid)")
    ax1.plot([], [], color="gray", lw=1.2, ls="--", label="linear model (dashed)")
    ax1.set_xlabel("time [s]")
    ax1.set_ylabel("force f [N]")
    ax1.set_title("Linear controller around the nonlinear muscle")
    ax1.legend(fontsize="small", loc="best")
    ax1.grid(alpha=0.3)
    ax2.loglog(chk.amplitudes, chk.max_deviation, "o-", label="max |f_nl - f_lin| [N]")
    ax2.loglog(chk.amplitudes, chk.relative_deviation, "s--", label="relative to peak |δf|")
    ax2.set_xlabel("disturbance pulse amplitude [N per step]")
    ax2.set_ylabel("deviation [N] / relative [1]")
    ax2.set_title("Departure from the linear prediction")
    ax2.legend(fontsize="small")
    ax2.grid(alpha=0.3, which="both")
    return fig
