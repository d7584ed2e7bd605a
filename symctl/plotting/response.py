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

import numpy as np
from matplotlib.figure import Figure

if TYPE_CHECKING:
    from symctl.neural.nonlinear import NonlinearCheck
    from symctl.neural.simulate import Response

__all__ = ["MAX_PANELS", "nonlinear_plot", "response_plot"]

MAX_PANELS = 6
"""Most panels of signals in :func:`response_plot` (beyond, the rest share the last)."""


_MUSCLE = {"f": ("force", "N"), "r": ("rate", "spikes/s")}


def _label(name: str, labels) -> tuple[str, str, str]:
    """(change label, absolute label, unit) of a signal ``delta_<x>`` (or ``<x>``)."""
    raw = name.removeprefix("delta_")
    table = _MUSCLE if labels is None else labels
    what, unit = table.get(raw, ("", ""))
    if labels is None and raw == "r":
        return "rate change δr", "motor-neuron rate r", "spikes/s"
    what = what or raw
    unit = unit or "units"
    head = f"{what} change δ{raw}" if what != raw else f"change δ{raw}"
    return head, f"{what} {raw}" if what != raw else raw, unit


def _state_tex(name: str) -> str:
    """A controller state's name as mathtext: ``gamma_1`` -> γ₁, ``delta_r[2]`` -> δ_r[2]."""
    base, _, index = name.partition("[")
    head, _, sub = base.partition("_")
    head = {"gamma": r"\gamma", "delta": r"\delta"}.get(head, head)
    tex = f"${head}_{{{sub}}}$" if sub else f"${head}$"
    return tex + (f"[{index}" if index else "")


def response_plot(res: Response, states: bool | None = None, labels=None) -> Figure:
    """Each state and input against time (absolute values on the right axes), and the controller.

    Parameters
    ----------
    res : Response
        An open- or closed-loop simulation.
    states : bool, optional
        Add a panel with the controller's internal states (default: when there
        are any).
    labels : mapping of str to (str, str), optional
        ``name -> (description, unit)`` of the states and inputs (their names
        without ``delta_``); default the muscle's (force f [N], rate r [spikes/s]).

    Returns
    -------
    matplotlib.figure.Figure
        One panel per state and per input (at most ``MAX_PANELS``; beyond, the
        rest share the last one), then the controller's states, on one time axis.

    Examples
    --------
    >>> from symctl import open_loop_response
    >>> from symctl.plotting.response import response_plot
    >>> len(response_plot(open_loop_response()).axes)   # open loop: no controller states
    2
    """
    states = res.states.shape[1] > 0 if states is None else states
    signals = [(res.delta_f, res.f_bar, res.state_names, i, True)
               for i in range(res.delta_f.shape[1])]  # fmt: skip
    signals += [(res.delta_r, res.r_bar, res.input_names, i, False)
                for i in range(res.delta_r.shape[1])]  # fmt: skip
    groups = [[s] for s in signals[: MAX_PANELS - 1]]
    if len(signals) >= MAX_PANELS:
        groups.append(signals[MAX_PANELS - 1 :])
    rows = len(groups) + (1 if states else 0)
    fig = Figure(figsize=(7.5, min(2.4 * rows + 0.6, 16)), layout="constrained")
    axes = fig.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]
    for ax, group in zip(axes, groups, strict=False):
        for trace, _bar, names, i, is_state in group:
            change, absolute, unit = _label(names[i], labels)
            ax.plot(res.t, trace[:, i], marker=".", lw=1.5, label=change, drawstyle="steps-post")
            if is_state and res.kind == "closed loop" and res.w.shape[1] > i and res.w[:, i].any():
                ax.step(res.t, res.w[:, i], where="post", ls="--", color="gray",
                        label=f"disturbance w [{unit}/step]")  # fmt: skip
        ax.axhline(0, color="black", lw=0.5)
        if len(group) == 1:
            _, bar, names, i, _ = group[0]
            raw = names[i].removeprefix("delta_")
            ax.set_ylabel(f"{change} [{unit}]" if labels is None else f"δ{raw} [{unit}]")
            absolute = absolute if labels is None else raw
            offset = float(bar[i])
            sec = ax.secondary_yaxis(
                "right", functions=(lambda x, o=offset: x + o, lambda x, o=offset: x - o)
            )
            sec.set_ylabel(f"{absolute} [{unit}]")
        else:
            ax.set_ylabel("change from equilibrium")
        ax.legend(loc="best", fontsize="small")
        ax.grid(alpha=0.3)
    if states:
        ax = axes[-1]
        count = res.states.shape[1]
        names = res.controller_state_names or tuple(f"x_{i + 1}" for i in range(count))
        for i, name in enumerate(names):
            ax.plot(res.t, res.states[:, i], marker=".", lw=1.2, label=_state_tex(name),
                    drawstyle="steps-post")  # fmt: skip
        if res.delta_r.shape[1] == 1:
            change, _, unit = _label(res.input_names[0], labels)
            what = change.replace(" change", "").split(" δ")[0]
            ax.set_ylabel(
                f"controller state\n({what} change) [{unit}]"
                if labels is None
                else f"controller state [{unit}]"
            )
        else:
            ax.set_ylabel("controller state")
        ax.legend(loc="best", fontsize="small", ncol=min(4, res.states.shape[1]))
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(f"time [{res.time_unit}]")
    if res.kind == "open loop":
        what = "pulse in " + ", ".join(_label(n, labels)[1] for n in res.input_names)
        if labels is None:
            what = "pulse in firing rate"
    else:
        hit = [n for i, n in enumerate(res.state_names) if res.w[:, i].any()]
        what = "pulse disturbance on " + ", ".join(_label(n, labels)[1] for n in hit)
        if labels is None:
            what = "pulse disturbance on force"
    fig.suptitle(f"{res.kind.capitalize()} response to a {what}")
    return fig


def nonlinear_plot(chk: NonlinearCheck, labels=None) -> Figure:
    """The first state's traces (nonlinear solid, linear dashed) and the deviation against amplitude.

    Parameters
    ----------
    chk : NonlinearCheck
        The result of :func:`~symctl.neural.nonlinear.nonlinear_check`.
    labels : mapping of str to (str, str), optional
        ``name -> (description, unit)``, as in :func:`response_plot`.

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
    x0 = chk.state_names[0]
    _, absolute, unit = _label(x0, labels)
    if labels is None:
        absolute, unit = "force f", "N"
    plant = "muscle" if labels is None else "plant"
    ok = np.isfinite(chk.max_deviation)
    colors = [f"C{i % 10}" for i in range(len(chk.amplitudes))]
    for a, lin, nl, c in zip(chk.amplitudes, chk.f_linear, chk.f_nonlinear, colors, strict=True):
        ax1.plot(chk.t, nl, color=c, lw=1.6, label=f"w = {a:g} per step")
        ax1.plot(chk.t, lin, color=c, lw=1.2, ls="--")
    ax1.plot([], [], color="gray", lw=1.6, label=f"nonlinear {plant} (solid)")
    ax1.plot([], [], color="gray", lw=1.2, ls="--", label="linear model (dashed)")
    ax1.set_xlabel("time [s]")
    ax1.set_ylabel(f"{absolute} [{unit}]")
    ax1.set_title(f"Linear controller around the nonlinear {plant}")
    ax1.legend(fontsize="small", loc="best")
    ax1.grid(alpha=0.3)
    amps = np.abs(chk.amplitudes[ok])
    ax2.loglog(amps, chk.max_deviation[ok], "o-", label=f"max |{x0}_nl - {x0}_lin| [{unit}]")
    ax2.loglog(amps, chk.relative_deviation[ok], "s--", label="relative to the peak")
    ax2.set_xlabel("disturbance pulse amplitude (per step)")
    ax2.set_ylabel(f"deviation [{unit}] / relative [1]")
    ax2.set_title("Departure from the linear prediction")
    ax2.legend(fontsize="small")
    ax2.grid(alpha=0.3, which="both")
    return fig
