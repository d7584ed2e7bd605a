"""A model, read and checked: what :func:`~symctl.model.modelfile.load_model` returns.

:class:`Model` holds the plant (nonlinear or discrete), the delays, the cost,
the delay graph and what to build and simulate, as values; the pipeline
(:func:`~symctl.report.pipeline.derive`) reads it and nothing else.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl._util.deprecate import renamed_attribute, renamed_keywords
from symctl.compatibility.delaygraph import DelayGraph
from symctl.design.ode import ODEModel
from symctl.design.plant import DiscretePlant
from symctl.errors import ModelFileError
from symctl.realization.realizers import circuit_names

__all__ = ["Model"]


@dataclass(frozen=True, eq=False)
class Model:
    r"""A model file, read and checked: the plant, its delays, cost, delay graph and what to build.

    Made by :func:`load_model`; the pipeline (:func:`~symctl.report.pipeline.derive`)
    reads it.

    Attributes
    ----------
    name, title, description : str
        From ``[model]``.
    ode : ODEModel or None
        The nonlinear plant (None for a discrete plant given directly).
    plant : DiscretePlant
        The discrete linear plant (exact where it can be).
    plant_symbolic : DiscretePlant or None
        The closed-form discrete plant in the parameters' symbols (one state
        and one input), else None.
    units, descriptions : mapping of str to str
        Units and descriptions of the states, inputs, outputs and parameters, by name.
    outputs : tuple of (str, str)
        The measured outputs: (name, state).
    dt : float
        The sampling time in seconds (the file's ``[sampling] Ts``; ``Ts`` is
        the deprecated name of the attribute and keyword).
    sensor_delay, actuator_delay : int
        The delays in steps.
    Q, R : sympy.ImmutableMatrix
        The cost weights (exact).
    graph : DelayGraph
        The delay graph, vertices ordered sensor first and actuator last.
    vertices : tuple of str
        The names of the graph's vertices in that order.
    edges : tuple of (str, str, int)
        Its direct edges by name, with their delays in steps.
    graph_given : bool
        Whether the file gave the delay graph (else the chain of the delays).
    max_wire_delay : int or None
        The most steps one wire of a circuit may carry (``[delay_graph]
        max_wire_delay``; None: axons of any length).
    vertex_descriptions : mapping of str to str
        The descriptions of the graph's vertices the file gives, by name.
    circuits : tuple of str
        The circuits to build, of :func:`~symctl.realization.realizers.circuit_names`.
    realizations, seed : int
        Random realizations per circuit and their seed.
    steps : int
        Simulation horizon.
    disturbance : tuple
        ``(states, amplitude, start, length)``: the indices of the states the
        pulse is added to, its size per step, first step and length.
    longest_delay : tuple or None
        ``(max, tolerance)`` of the longest-delay search, when asked for.
    notes : tuple of str
        What the reader changed and says so (delays in seconds rounded up).
    path : str
        The file.

    Examples
    --------
    >>> from symctl.model.modelfile import load_model
    >>> m = load_model('''
    ... [model]
    ... name = "d"
    ... [discrete]
    ... A = [[1.0, 0.1], [0.0, 1.0]]
    ... B = [[0.0], [0.1]]
    ... [sampling]
    ... Ts = 0.1
    ... [delays]
    ... sensor = { seconds = 0.15 }
    ... ''')
    >>> m.plant.n, m.sensor_delay, m.notes[0][:40]
    (2, 2, 'delays.sensor: 0.15 s is 1.5 steps of Ts')
    """

    name: str
    title: str
    description: str
    ode: ODEModel | None
    plant: DiscretePlant
    plant_symbolic: DiscretePlant | None
    units: Mapping
    descriptions: Mapping
    outputs: tuple
    dt: float
    sensor_delay: int
    actuator_delay: int
    Q: sp.ImmutableMatrix
    R: sp.ImmutableMatrix
    graph: DelayGraph
    vertices: tuple
    edges: tuple
    graph_given: bool
    circuits: tuple = field(default_factory=circuit_names)
    realizations: int = 4
    seed: int = 0
    steps: int = 50
    disturbance: tuple = ((0,), 1.0, 5, 10)
    longest_delay: tuple | None = None
    notes: tuple = ()
    path: str = "<text>"
    source: str = field(default="", repr=False)
    lines: Mapping = field(default_factory=dict, repr=False)
    vertex_descriptions: Mapping = field(default_factory=dict)
    max_wire_delay: int | None = None

    def __post_init__(self) -> None:
        units = {k: str(v) for k, v in self.units.items()}
        object.__setattr__(self, "units", MappingProxyType(units))
        for name in ("descriptions", "lines", "vertex_descriptions"):
            object.__setattr__(self, name, MappingProxyType(dict(getattr(self, name))))

    def error(self, dotted: str, problem: str) -> ModelFileError:
        """An error about one field of the file this model came from (with its line)."""
        parts = dotted.split(".")
        line = None
        while parts and line is None:
            line = self.lines.get(".".join(parts))
            parts.pop()
        return ModelFileError(problem, path=self.path, line=line, field=dotted)

    @property
    def signal_names(self) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """The names of the states and inputs as the file gives them (the plant's are ``delta_``...)."""
        if self.ode is not None:
            return tuple(s.name for s in self.ode.states), tuple(s.name for s in self.ode.inputs)
        return self.plant.state_names, self.plant.input_names

    @property
    def T(self) -> int:
        """The net delay ``sensor_delay + actuator_delay``."""
        return self.sensor_delay + self.actuator_delay

    @property
    def state_names(self) -> tuple[str, ...]:
        """The states' names."""
        return self.plant.state_names

    @property
    def input_names(self) -> tuple[str, ...]:
        """The inputs' names."""
        return self.plant.input_names

    def unit(self, name: str) -> str:
        """The unit of a state, input or parameter ('' when not given)."""
        return self.units.get(name, "")

    def disturbance_signal(self, steps: int | None = None) -> np.ndarray:
        """The disturbance as an array ``(steps, n)``: the pulse on the chosen states."""
        states, amplitude, start, length = self.disturbance
        n_steps = self.steps if steps is None else steps
        w = np.zeros((n_steps, self.plant.n))
        w[start : start + length, list(states)] = amplitude
        return w

    Ts = renamed_attribute("Ts", "dt")


Model.__init__ = renamed_keywords(Ts="dt")(Model.__init__)
