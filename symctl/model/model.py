"""A model, read and checked: what :func:`~symctl.model.modelfile.load_model` returns."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl._util.deprecate import renamed_attribute, renamed_keywords
from symctl._util.validate import (
    MAX_CIRCUITS,
    PAPER_MAX_DELAY,
    bounded_int,
    nonneg_int,
    positive_number,
    psd_matrix,
    to_matrix,
)
from symctl.compatibility.delaygraph import DelayGraph
from symctl.design.ode import ODEModel, exact_value, parameter_symbol
from symctl.design.plant import DiscretePlant
from symctl.errors import ModelFileError, ParameterError
from symctl.realization.realizers import circuit_names

__all__ = ["Model", "chain_graph"]

MAX_SEED = 2**32 - 1  # the largest ``[circuits] seed``
# the fields Model.replace takes, besides the plant's parameters by name
_FIELDS_REPLACED = ("dt", "sensor_delay", "actuator_delay", "Q", "R", "seed", "realizations")


def chain_graph(sensor_delay: int, actuator_delay: int) -> tuple[DelayGraph, tuple, tuple]:
    """``(graph, vertices, edges)`` of a model file without a delay graph: the chain of the
    delays, one vertex per step (a side without delay keeps an edge of 0 steps).

    >>> from symctl.model.model import chain_graph
    >>> graph, vertices, edges = chain_graph(1, 1)
    >>> vertices, edges
    (('v1', 'v2', 'v3'), (('v1', 'v2', 1), ('v2', 'v3', 1)))
    """
    steps = ([1] * sensor_delay or [0]) + ([1] * actuator_delay or [0])
    names = tuple(f"v{i + 1}" for i in range(len(steps) + 1))
    edges = tuple((names[i], names[i + 1], d) for i, d in enumerate(steps))
    return DelayGraph.chain(steps), names, edges


def _key_value(value):
    return tuple(value.items()) if isinstance(value, Mapping) else value


@dataclass(frozen=True, eq=False)
class Model:
    r"""A model file, read and checked: the plant, its delays, cost, delay graph and what to build.

    Made by :func:`load_model`; equal when every field is (the file's text included), so
    :func:`~symctl.derivation.derive` runs once per model.

    Attributes
    ----------
    name, title, description : str
        From ``[model]``.
    ode : ODEModel or None
        The nonlinear plant (None for a discrete plant given directly).
    plant, plant_symbolic : DiscretePlant
        The discrete linear plant, and its closed form in the parameters' symbols (SISO; else None).
    units, descriptions : mapping of str to str
        Of the states, inputs, outputs and parameters, by name.
    outputs : tuple of (str, str)
        The measured outputs: (name, state), or (name, expression).
    dt : float
        The sampling time [s] (the file's ``[sampling] Ts``; ``Ts``: deprecated).
    sensor_delay, actuator_delay : int
        The delays in steps.
    Q, R : sympy.ImmutableMatrix
        The cost weights (exact).
    graph, vertices, edges : DelayGraph, tuple of str, tuple of (str, str, int)
        The delay graph (sensor first, actuator last), its vertices' names in that
        order and its direct edges with their delays in steps.
    graph_given, max_wire_delay, vertex_descriptions : bool, int or None, mapping
        Whether the file gave the graph (else the chain of the delays); the most steps of
        one wire (None: any); the vertices' descriptions.
    circuits : tuple of str
        The circuits to build, of :func:`~symctl.realization.realizers.circuit_names`.
    realizations, seed, steps : int
        Random realizations per circuit, their seed, and the simulation horizon.
    disturbance, longest_delay : tuple, tuple or None
        ``(states, amplitude, start, length)`` of the pulse; ``(max, tolerance)`` of the
        longest-delay search, when asked for.
    notes, path : tuple of str, str
        What the reader changed and says so (delays in seconds rounded up); the file.
    C : sympy.ImmutableMatrix or None
        The outputs' matrix (``p x n``, linearized) when the controller estimates the
        state; None for full-state feedback.
    noise : mapping of str to sympy.ImmutableMatrix
        ``process``, ``sensor`` (and ``motor``) covariances of ``[noise]``.
    replaced : mapping of str to value
        The values :meth:`replace` set: with the file's text they re-create the model.

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
    replaced: Mapping = field(default_factory=dict)
    C: sp.ImmutableMatrix | None = None
    noise: Mapping = field(default_factory=dict)

    def __post_init__(self) -> None:
        units = {k: str(v) for k, v in self.units.items()}
        object.__setattr__(self, "units", MappingProxyType(units))
        for name in ("descriptions", "lines", "vertex_descriptions", "replaced", "noise"):
            object.__setattr__(self, name, MappingProxyType(dict(getattr(self, name))))

    def _key(self) -> tuple:
        return tuple(  # the values replaced: in any order, the same model
            tuple(sorted(self.replaced.items()))
            if f.name == "replaced"
            else _key_value(getattr(self, f.name))
            for f in dataclasses.fields(self)
        )

    def __eq__(self, other) -> bool:
        if not isinstance(other, Model):
            return NotImplemented
        return self is other or self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    @renamed_keywords(Ts="dt")
    def replace(self, **values) -> Model:
        r"""A new model with some values replaced (the plant and the chain graph derived again).

        Parameters
        ----------
        **values
            Any of ``dt`` [s] (``Ts``: deprecated), ``sensor_delay``, ``actuator_delay``,
            ``Q``, ``R``, ``seed``, ``realizations``, and the plant's parameters by name.

        Returns
        -------
        Model
            Its :attr:`replaced` records the values that differ; with none, this model.

        Raises
        ------
        ParameterError
            An unknown name, a value out of range, ``dt`` of a discrete plant, a net delay
            outside ``[1, PAPER_MAX_DELAY]``, or parameters at which there is no equilibrium.
        SymctlTypeError
            A value of the wrong type.
        DimensionError
            ``Q`` or ``R`` of the wrong shape.

        Examples
        --------
        >>> from symctl.model.presets import muscle
        >>> m = muscle()
        >>> slow = m.replace(tau=0.05, sensor_delay=2)
        >>> slow.T, [float(v) for v in slow.ode.params.values()], m.T
        (3, [0.05, 60.0, 1.0], 2)
        >>> slow == m.replace(sensor_delay=2).replace(tau=0.05), slow == m
        (True, False)
        >>> m.replace(taus=1)
        Traceback (most recent call last):
        ...
        symctl.errors.ParameterError: taus: not a value of the model; replace takes dt, ...
        """
        params = {p.name: p for p in self.ode.params} if self.ode is not None else {}
        for name in values:
            if name not in _FIELDS_REPLACED and name not in params:
                taken = ", ".join((*_FIELDS_REPLACED, *params))
                raise ParameterError(f"{name}: not a value of the model; replace takes {taken}")
        new = {k: v for k, v in values.items() if k in _FIELDS_REPLACED}
        given = {k: v for k, v in values.items() if k in params}
        current = dict(self.ode.params.items()) if self.ode is not None else {}
        given = {k: v for k, v in given.items() if exact_value(v, k) != current[params[k]]}
        if self.ode is None and "dt" in new:
            raise ParameterError(
                "dt: the discrete plant's matrices hold numbers for its own sampling time; "
                "give a model file with the new one"
            )
        changes: dict = {}
        if "dt" in new and positive_number(new["dt"], "dt") != self.dt:
            changes["dt"] = positive_number(new["dt"], "dt")
        else:
            new.pop("dt", None)
        if given or "dt" in changes:  # the plant derived again: only for a new value
            changes.update(self._replot(given, changes.get("dt", self.dt)))
            # the file's note on a bare Ts was on the file's Ts and time constants
            changes["notes"] = tuple(n for n in self.notes if not n.startswith("sampling.Ts:"))
        ds = nonneg_int(new.get("sensor_delay", self.sensor_delay), "sensor_delay")
        da = nonneg_int(new.get("actuator_delay", self.actuator_delay), "actuator_delay")
        if not 1 <= ds + da <= PAPER_MAX_DELAY:
            raise ParameterError(
                f"sensor_delay, actuator_delay: the derivation takes a net delay of 1 to "
                f"{PAPER_MAX_DELAY} steps, got {ds} + {da} = {ds + da}"
            )
        changes.update(sensor_delay=ds, actuator_delay=da)
        if not self.graph_given and (ds, da) != (self.sensor_delay, self.actuator_delay):
            changes["graph"], changes["vertices"], changes["edges"] = chain_graph(ds, da)
        for name, size, definite in (("Q", self.plant.n, False), ("R", self.plant.m, True)):
            if name in new:
                M = to_matrix(new[name], name)
                psd_matrix(M, name, size, definite=definite)
                changes[name] = sp.ImmutableMatrix(M)
        for name, low, high in (("seed", 0, MAX_SEED), ("realizations", 1, MAX_CIRCUITS)):
            if name in new:
                changes[name] = bounded_int(new[name], name, low, high)
        recorded = {k: changes[k] for k in new if changes[k] != getattr(self, k)}
        recorded.update({k: exact_value(v, k) for k, v in given.items()})
        if not recorded:  # every value is the one the model has: it stays as it is
            return self
        return dataclasses.replace(self, **changes, replaced={**self.replaced, **recorded})

    def _replot(self, given: dict, Ts: float) -> dict:
        """The ODE and plants at new parameter values or sampling time."""
        ode = self.ode
        rename, values = {}, {}
        for symbol, value in ode.params.items():
            value = exact_value(given.get(symbol.name, value), symbol.name)
            new = parameter_symbol(symbol.name, value)  # positive when the value is
            rename[symbol] = new
            values[new] = value
        x_eq = ode.x_eq.xreplace(rename) if ode.equilibrium_method == "given" else None
        rhs, u_eq = ode.rhs.xreplace(rename), ode.u_eq.xreplace(rename)
        ode = dataclasses.replace(ode, rhs=rhs, params=values, x_eq=x_eq, u_eq=u_eq, dt=Ts)
        return {"ode": ode, "plant": ode.plant(), "plant_symbolic": ode.discrete_symbolic()}

    def to_dict(self) -> dict:
        """The model as JSON data: ``source`` (the file's text), ``path`` and ``replaced``.

        Raises
        ------
        ParameterError
            A model not read from a model file (it has no text).

        Examples
        --------
        >>> from symctl.model.saved import model_from_dict
        >>> from symctl.model.presets import muscle
        >>> d = muscle().replace(tau=0.05).to_dict()
        >>> d["replaced"], model_from_dict(d) == muscle().replace(tau=0.05)
        ({'tau': '1/20'}, True)
        """
        if not self.source:
            raise ParameterError("model: made without a model file, so it has no text to save")
        return {
            "source": self.source,
            "path": self.path,
            "replaced": {k: _text(v) for k, v in self.replaced.items()},
        }

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
        """The states' and inputs' names as the file gives them (the plant's are ``delta_``...)."""
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


def _text(value):
    """A replaced value for JSON: numbers as numbers, exact ones as text, matrices as rows."""
    if isinstance(value, sp.MatrixBase):
        return [[_text(e) for e in row] for row in value.tolist()]
    if isinstance(value, int | float) and not isinstance(value, bool):
        return value
    if isinstance(value, sp.Float):
        return float(value)
    return sp.sstr(value)
