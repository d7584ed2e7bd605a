r"""The loop closed through a circuit of spiking populations, beside the linear loop.

The plant is a nengo node stepping once per sample (linear, or the ODE with ``nonlinear``),
reading the circuit's output at the sample's last simulator step; the populations' radii come
from the linear loop's traces.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.validate import bounded_int, read_only
from symctl.design.lqr import Gains
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.neural.circuit import Circuit
from symctl.neural.firing import _drive, _plant
from symctl.neural.nonlinear import ode_flow
from symctl.neural.simulate import _freeze, simulate_realization
from symctl.realization.realization import Realization
from symctl.spiking.connections import _edges, _require
from symctl.spiking.nengo_export import MAX_POPULATION, SUBSTEPS, _radii, to_nengo

__all__ = ["SpikingResponse", "spiking_response"]


@dataclass(frozen=True, eq=False)
class SpikingResponse(ArrayValue, DictMixin):
    r"""The loop through spiking populations and the linear loop, sample by sample
    (:func:`spiking_response`); read-only.

    Attributes
    ----------
    t : (steps,) array
        Time [s].
    delta_f, delta_f_linear : (steps, n) arrays
        Force change of the spiking loop and of the linear loop [N].
    delta_r, delta_r_linear : (steps, m) arrays
        Motor-neuron rate change of each loop [spikes/s].
    firing, firing_linear : mapping of str to (steps,) array
        Each neuron's rate change (decoded at the sample's last simulator step), and linear.
    spikes : mapping of str to (steps * SUBSTEPS, N) uint8 array
        Each population's spike trains.
    radius : mapping of str to float
        Each population's radius (1.2 times its linear peak).
    n_neurons : int
        Neurons per population (0: exact nodes).
    dt : float
        The simulator's step [s], ``Ts / SUBSTEPS`` (``Ts`` when exact).
    deviation : float
        :math:`\mathrm{RMS}(\delta_f - \delta_f^{lin}) / \mathrm{RMS}(\delta_f^{lin})`.

    Examples
    --------
    >>> import symctl
    >>> res = symctl.derive_paper()
    >>> c = res.circuits["controllable"].firing.circuits[0]
    >>> r = symctl.spiking_response(res.gains, c, n_neurons=None)
    >>> r.deviation < 1e-12, r.n_neurons
    (True, 0)
    """

    t: np.ndarray
    delta_f: np.ndarray
    delta_f_linear: np.ndarray
    delta_r: np.ndarray
    delta_r_linear: np.ndarray
    firing: Mapping[str, np.ndarray]
    firing_linear: Mapping[str, np.ndarray]
    spikes: Mapping[str, np.ndarray]
    radius: Mapping[str, float]
    n_neurons: int
    dt: float
    deviation: float

    def __post_init__(self) -> None:  # read-only arrays, mappings as proxies
        arrays = ("t", "delta_f", "delta_f_linear", "delta_r", "delta_r_linear")
        _freeze(self, arrays, ("firing", "firing_linear"))
        spikes = {k: read_only(v, np.uint8) for k, v in self.spikes.items()}
        object.__setattr__(self, "spikes", MappingProxyType(spikes))
        object.__setattr__(self, "radius", MappingProxyType(dict(self.radius)))

    @property
    def spikes_per_second(self) -> float:
        """Spikes of every population together per second of simulated time."""
        seconds = self.dt * max(1, len(self.t) * (SUBSTEPS if self.n_neurons else 1))
        return float(sum(int(s.sum()) for s in self.spikes.values())) / seconds

    def plot(self):
        """Force, rate changes and a spike raster: a Figure.

        Examples
        --------
        >>> import symctl
        >>> res = symctl.derive_paper()
        >>> c = res.circuits["ifp"].firing.circuits[0]
        >>> len(symctl.spiking_response(res.gains, c, n_neurons=10).plot().axes)
        3
        """
        from symctl.plotting.spiking import spiking_plot

        return spiking_plot(self)


def _rms_ratio(a: np.ndarray, ref: np.ndarray) -> float:
    """RMS of ``a - ref`` over RMS of ``ref`` (absolute when ``ref`` is zero)."""
    scale = float(np.sqrt(np.mean(ref**2)))
    return float(np.sqrt(np.mean((a - ref) ** 2))) / (scale if scale > 0 else 1.0)


def spiking_response(
    gains: Gains,
    circuit: Circuit,
    *,
    n_neurons: int | None = 100,
    rng=0,
    steps: int | None = None,
    disturbance=1.0,
    plant=None,
    neuron_type=None,
    nonlinear=None,
) -> SpikingResponse:
    r"""Close the loop through ``circuit`` as spiking populations, and beside it the linear loop.

    Parameters
    ----------
    gains : Gains
        The controller's gains (their plant the loop's unless ``plant`` is given).
    circuit : Circuit
        A numeric circuit of the whole controller, :math:`\delta_f \to \delta_r`.
    n_neurons : int or None
        Spiking neurons per population, in ``[1, MAX_POPULATION]``; ``None``: exact nodes.
    rng : int, numpy Generator or None, default 0
        Seeds the populations.
    steps, disturbance
        As in :func:`~symctl.simulate_realization`.
    plant : DiscretePlant, MuscleModel, (A, B) or python-control system, optional
        A discrete plant with the gains' ``dt`` (default the gains' plant).
    neuron_type : nengo.neurons.NeuronType, optional
        Default ``nengo.LIF()``.
    nonlinear : MuscleModel or ODEModel, optional
        Close the spiking loop around this ODE (the plant's ``dt`` and sizes): ``delta_f`` is
        then its deviation from the equilibrium.

    Returns
    -------
    SpikingResponse

    Raises
    ------
    MissingDependencyError
        nengo is not installed (``pip install symctl[spiking]``).
    ParameterError, DimensionError, SymctlTypeError
        Symbols left in the weights; ``n_neurons`` out of range; a plant without ``dt``; an
        unstable linear loop; a circuit not of the plant's sizes; arguments of the wrong type.

    Examples
    --------
    >>> import symctl
    >>> res = symctl.derive_paper()
    >>> c = res.circuits["observable"].firing.circuits[0]
    >>> r = symctl.spiking_response(res.gains, c, n_neurons=200, rng=1)
    >>> bool(r.deviation < 0.2), r.spikes["G2.x1"].shape
    (True, (500, 200))
    """
    if not isinstance(gains, Gains):
        raise SymctlTypeError(f"gains: expected Gains (lqr_gains), got {type(gains).__name__}")
    _edges(circuit)  # a symbolic circuit is refused before any work
    p = _plant(plant, gains)
    if p.dt is None:
        raise ParameterError("plant: needs a sampling time (a discrete plant with dt)")
    flow = None
    if nonlinear is not None:
        ode, flow = ode_flow(nonlinear)
        if (ode.n, ode.m) != (p.n, p.m) or abs(ode.dt - float(p.dt)) > 1e-12 * float(p.dt):
            raise ParameterError(
                f"nonlinear: {ode.n} states, {ode.m} inputs at Ts = {ode.dt:g}; the loop's "
                f"plant has {p.n}, {p.m} at Ts = {float(p.dt):g}"
            )
        x_bar, u_bar = ode.x_bar, ode.u_bar
    if (len(circuit.inputs), len(circuit.outputs)) != (p.n, p.m):
        raise DimensionError(
            f"circuit: has {len(circuit.inputs)} inputs and {len(circuit.outputs)} outputs; "
            f"the plant measures {p.n} states and takes {p.m} inputs"
        )
    if n_neurons is not None:
        n_neurons = bounded_int(n_neurons, "n_neurons", 1, MAX_POPULATION)
    nengo = _require("nengo")
    Ts = float(p.dt)
    sys = circuit.as_linear_system(numeric=True)
    k = len(circuit.neurons)
    R = Realization(sys.A, sys.B, sys.C[k:], sys.D[k:], p.dt)
    linear = simulate_realization(p, R, disturbance, steps=steps)
    firing_linear = _drive(circuit, linear.delta_f)
    radii = _radii(circuit, firing_linear)
    sub = SUBSTEPS if n_neurons else 1
    options = {"neuron_type": neuron_type, "radius": radii} if n_neurons else {}
    net = to_nengo(circuit, n_neurons, rng=rng, dt=Ts, **options)
    A, B = p.numeric()
    w = np.asarray(linear.w, dtype=float)
    count = w.shape[0]
    state = {"x": np.zeros(p.n)}

    def step(t, dr):  # the plant: a new sample at the first simulator step of each period
        j = round(t * sub / Ts)
        if j >= 2 and (j - 1) % sub == 0 and (j - 1) // sub <= count - 1:
            x = state["x"]
            moved = A @ x + B @ dr if flow is None else flow(x_bar + x, u_bar + dr) - x_bar
            state["x"] = moved + w[(j - 1) // sub - 1]
        return state["x"]

    with net:
        plant_node = nengo.Node(step, size_in=p.m, size_out=p.n, label="plant")
        for i, u in enumerate(circuit.inputs):
            nengo.Connection(plant_node[i], net.inputs[u], synapse=None)
        one_step = nengo.LinearFilter([1.0], [1.0, 0.0], analog=False)
        for i, o in enumerate(circuit.outputs):
            nengo.Connection(net.outputs[o.target], plant_node[i], synapse=one_step)
        p_force = nengo.Probe(plant_node)
        p_out = [nengo.Probe(net.outputs[o.target]) for o in circuit.outputs]
        p_axon = {name: nengo.Probe(node) for name, node in net.axons.items()}
        p_spikes = {name: nengo.Probe(e.neurons) for name, e in net.populations.items()}
    # no decoder cache: the seeds differ run by run, and parallel runs would fight for its lock
    model = nengo.builder.Model(dt=Ts / sub, decoder_cache=nengo.cache.NoDecoderCache())
    with nengo.Simulator(net, progress_bar=False, model=model) as sim:
        sim.run_steps(count * sub)
    first, last = np.arange(count) * sub, np.arange(1, count + 1) * sub - 1
    df = sim.data[p_force][first]
    dr = np.stack([sim.data[q][last, 0] for q in p_out], axis=1)
    spikes = {n: (sim.data[q] > 0).astype(np.uint8) for n, q in p_spikes.items()}
    return SpikingResponse(
        linear.t,
        df,
        linear.delta_f,
        dr,
        linear.delta_r,
        {n: sim.data[q][last, 0] for n, q in p_axon.items()},
        {n.name: firing_linear[n.name] for n in circuit.neurons},
        spikes,
        radii,
        n_neurons or 0,
        Ts / sub,
        _rms_ratio(df, np.asarray(linear.delta_f)),
    )
