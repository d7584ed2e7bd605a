"""Your own system in a file: :func:`load_model` reads a model file (TOML, ``docs/model-file.md``)
into a :class:`Model`, never evaluating it; every problem is one
:class:`~symctl.errors.ModelFileError` naming the file, the line and the field."""

from __future__ import annotations

import contextlib
import keyword
import math
import re
from pathlib import Path

import numpy as np
import sympy as sp

from symctl._util.parse import CONSTANTS, NAMES, parse_expr
from symctl._util.validate import MAX_DELAY, PAPER_MAX_DELAY, psd_matrix
from symctl.design.lqr import _pbh_defect
from symctl.design.ode import MAX_MODEL_STATES, ODEModel, exact_value, parameter_symbol
from symctl.design.plant import DiscretePlant
from symctl.design.tf import DiscreteTF
from symctl.errors import ModelFileError, SymctlError, SymctlTypeError
from symctl.model.graphsection import GraphSection, strip_argname
from symctl.model.measurement import MeasurementSection
from symctl.model.model import Model
from symctl.model.schema import FIELDS, SECTIONS
from symctl.model.source import Source
from symctl.model.units import Unit, check_rhs, parse_unit, unit_of
from symctl.realization.realization import controllable_canonical
from symctl.realization.realizers import circuit_names
from symctl.symbols import z

__all__ = ["Model", "load_model", "read_model"]

MAX_PARAMETERS = 200  # most parameters of a model file
MAX_SIM_STEPS = 5000  # longest simulation horizon of a model file
_IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_]{0,39}$")
_CONSTANT_NAMES = {"E": "e (Euler's number)", "pi": "pi"}
_RESERVED = NAMES | {"z", "T_s", "t"}  # the parser's own names, z, the sampling time, time


def load_model(source) -> Model:
    """Read a model file (a path, or TOML text) into a :class:`Model`.

    Parameters
    ----------
    source : str or pathlib.Path
        A path to a ``.toml`` file, or the TOML text (a string with a newline or ``[``).

    Returns
    -------
    Model

    Raises
    ------
    ModelFileError
        Any problem, in one line naming the file, the line and the field.
    SymctlTypeError
        ``source`` is neither text nor a path.

    Examples
    --------
    >>> from symctl.model.modelfile import load_model
    >>> m = load_model('''
    ... [model]
    ... name = "leaky"
    ... [parameters]
    ... k = { value = 2.0, unit = "1/s" }
    ... [[states]]
    ... name = "x"
    ... rhs = "-k*x + u"
    ... [[inputs]]
    ... name = "u"
    ... equilibrium = 1.0
    ... [sampling]
    ... Ts = 0.1
    ... ''')
    >>> m.ode.x_eq, m.sensor_delay, m.actuator_delay
    (Matrix([[1/k]]), 1, 1)
    >>> load_model('[model]\\nname = "x"\\n[sampling]\\nTz = 1\\n')
    Traceback (most recent call last):
    ...
    symctl.errors.ModelFileError: <text>:4: sampling.Tz: unknown key 'Tz'; did you mean 'Ts'?
    """
    if isinstance(source, Path) or (
        isinstance(source, str) and "\n" not in source and "[" not in source
    ):
        src = Source.from_path(source)
    elif isinstance(source, str):
        src = Source.from_text(source)
    else:
        raise SymctlTypeError(f"source: expected a path or TOML text, got {type(source).__name__}")
    return _Reader(src).model()


def read_model(text: str, path: str = "<text>") -> Model:
    """Read a model file's text, named ``path`` in messages (as :func:`load_model` reads a file)."""
    return _Reader(Source.from_text(text, path)).model()


class _Reader(GraphSection, MeasurementSection):
    """Reads one :class:`Source` into a :class:`Model`, field by field."""

    def __init__(self, src: Source):
        self.src = src
        self.notes: list[str] = []

    def fail(self, where: str, problem: str) -> ModelFileError:
        return self.src.error(where, problem)

    @contextlib.contextmanager
    def named(self, where: str, argname: str | None = None):
        """A symctl error in the block as this file's error at ``where`` (its argname dropped)."""
        try:
            yield
        except ModelFileError:
            raise
        except SymctlError as exc:
            raise self.fail(where, strip_argname(str(exc), argname or where)) from None

    def need(self, table: dict, key: str, where: str, hint: str = ""):
        """``table[key]``, or the error that ``where`` misses it."""
        if key not in table:
            raise self.fail(where, f"missing {key}{hint}")
        return table[key]

    def table(self, data, where: str, allowed: str | None = None) -> dict:
        if not isinstance(data, dict):
            raise self.fail(where, f"expected a table, got {_kind(data)}")
        if allowed is not None:
            self.src.check_keys(data, FIELDS[allowed], where)
        return data

    def text(self, value, where: str, *, ident: bool = False) -> str:
        if not isinstance(value, str):
            raise self.fail(where, f"expected text, got {_kind(value)}")
        if ident and value in CONSTANTS:
            raise self.fail(
                where,
                f"{value!r} is the constant {_CONSTANT_NAMES[value]} = "
                f"{float(CONSTANTS[value]):.6g}, which every expression may use undeclared; "
                "give this another name",
            )
        if ident and (not _IDENT.match(value) or value in _RESERVED or keyword.iskeyword(value)):
            raise self.fail(
                where,
                f"{value!r} is not a valid name (a letter, then letters, digits or _, "
                "at most 40; not a Python keyword, a function name or z, t, T_s)",
            )
        return value

    def number(self, value, where: str, *, positive: bool = False) -> float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.fail(where, f"expected a number, got {_kind(value)}")
        if not math.isfinite(value) or abs(value) > 1e100:
            raise self.fail(where, f"expected a finite number, got {value!r}")
        if positive and value <= 0:
            raise self.fail(where, f"must be > 0, got {value!r}")
        return value

    def integer(self, value, where: str, low: int, high: int) -> int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(where, f"expected an integer, got {_kind(value)}")
        if not low <= value <= high:
            raise self.fail(where, f"must be an integer in [{low}, {high}], got {value}")
        return value

    def expr(self, value, where: str, names: dict) -> sp.Expr:
        if isinstance(value, bool):
            raise self.fail(where, f"expected a number or text, got {_kind(value)}")
        if isinstance(value, int | float):
            return exact_value(self.number(value, where), where)
        if not isinstance(value, str):
            raise self.fail(where, f"expected a number or text, got {_kind(value)}")
        with self.named(where):
            expr = parse_expr(value, names, argname=where)
        if re.search(r"(?<![\w.])E(?!\w)", value):
            self.notes.append(
                f"{where}: E is Euler's number e = 2.71828 (a constant; a parameter cannot be named E)"
            )
        return expr

    def unit(self, value, where: str) -> Unit | None:
        if value is None:
            return None
        with self.named(where):
            return parse_unit(self.text(value, where), where)

    def items(self, data, where: str, allowed: str, *, limit: int) -> list[dict]:
        if not isinstance(data, list):
            raise self.fail(where, f"expected an array of tables ([[{where}]]), got {_kind(data)}")
        if len(data) > limit:
            raise self.fail(where, f"at most {limit} entries, got {len(data)}")
        return [self.table(d, f"{where}[{i}]", allowed) for i, d in enumerate(data)]

    def model(self) -> Model:
        d = self.src.data
        self.src.check_keys(d, SECTIONS, "")
        meta = self.table(d.get("model", {}), "model", "model")
        if "name" not in meta:
            raise self.fail("model", 'missing the model\'s name; give name = "..."')
        name = self.text(meta["name"], "model.name")
        if not re.match(r"^[A-Za-z0-9_-]{1,60}$", name):
            raise self.fail("model.name", f"{name!r}: letters, digits, _ and - only (at most 60)")
        title = self.text(meta.get("title", name), "model.title")
        description = self.text(meta.get("description", ""), "model.description")
        if "sampling" not in d:
            raise self.fail("sampling", "missing; give [sampling] Ts")
        Ts = self.sampling(self.table(d["sampling"], "sampling", "sampling"))
        params, units, descr = self.parameters(d.get("parameters", {}))
        ode, plant, plant_symbolic = self.plant(d, params, units, descr, Ts, name)
        if ode is not None and not isinstance(d["sampling"]["Ts"], dict):
            self.bare_ts(ode, Ts)
        self.names = tuple(s.name for s in ode.states) if ode is not None else plant.state_names
        self.stabilizable(plant, "states" if ode is not None else "discrete")
        outputs, C = self.outputs(d.get("outputs"), ode, params, units, descr)
        noise = self.noise(d.get("noise"), plant, params, len(outputs))
        if noise and C is None:  # every state measured, through noise
            C = sp.ImmutableMatrix([[int(s == st) for s in self.names] for _, st in outputs])
        if C is not None:
            self.detectable(plant, C)
        delays = self.table(d.get("delays", {}), "delays", "delays")
        ds = self.delay(delays.get("sensor", 1), "delays.sensor", Ts)
        da = self.delay(delays.get("actuator", 1), "delays.actuator", Ts)
        if ds + da > PAPER_MAX_DELAY:
            raise self.fail(
                "delays",
                f"the derivation takes a net delay of at most {PAPER_MAX_DELAY} steps, "
                f"got {ds} + {da} = {ds + da}",
            )
        if ds + da == 0:
            raise self.fail("delays", "the net delay sensor + actuator must be at least 1 step")
        cost = self.table(d.get("cost", {}), "cost", "cost")
        Q = self.weight(cost.get("Q", "identity"), "cost.Q", plant.n)
        R = self.weight(cost.get("R", "identity"), "cost.R", plant.m, definite=True)
        graph, vertices, edges, given, about = self.graph(d.get("delay_graph"), (ds, da), Ts)
        sensed = (plant.n, "measured state") if C is None else (C.rows, "measured output")
        for key, ends, count, what in (
            ("sensor", graph.sensors, *sensed),
            ("actuator", graph.actuators, plant.m, "input"),
        ):
            if len(ends) not in (1, count):
                raise self.fail(
                    f"delay_graph.{key}",
                    f"{len(ends)} {key} vertices for {count} "
                    f"{what}s; give one vertex for all, or one per {what}",
                )
        circuits = self.table(d.get("circuits", {}), "circuits", "circuits")
        build = self.build(circuits.get("build", list(circuit_names())))
        realizations = self.integer(
            circuits.get("realizations", 4), "circuits.realizations", 1, 1000
        )
        seed = self.integer(circuits.get("seed", 0), "circuits.seed", 0, 2**32 - 1)
        sim = self.table(d.get("simulation", {}), "simulation", "simulation")
        steps = self.integer(sim.get("steps", 50), "simulation.steps", 2, MAX_SIM_STEPS)
        disturbance = self.disturbance(sim.get("disturbance", {}), plant, steps)
        longest = self.analysis(d.get("analysis", {}))
        plant_part = (name, title, description, ode, plant, plant_symbolic, units, descr, outputs)
        design = (Ts, ds, da, Q, R, graph, vertices, edges, given, build, realizations, seed)
        run = (steps, disturbance, longest, tuple(self.notes))
        src, wires = self.src, self.wire_bound(d.get("delay_graph"))
        return Model(
            *plant_part, *design, *run, src.path, src.text, src.lines, about, wires, {}, C, noise
        )

    def sampling(self, table: dict) -> float:
        value = self.need(table, "Ts", "sampling", ", the sampling time")
        if isinstance(value, dict):
            self.table(value, "sampling.Ts", "parameter")
            ts = self.number(
                self.need(value, "value", "sampling.Ts"), "sampling.Ts.value", positive=True
            )
            unit = self.unit(value.get("unit", "s"), "sampling.Ts.unit")
            if not unit.is_time():
                raise self.fail("sampling.Ts.unit", f"{unit} is not a unit of time")
            return ts * unit.scale
        return float(self.number(value, "sampling.Ts", positive=True))

    def bare_ts(self, ode, Ts: float) -> None:
        """A note when a bare Ts (seconds) is off the plant's fastest time constant: a unit was meant."""
        a = ode.jacobian_numeric(ode.x_bar, ode.u_bar)
        rate = np.abs(np.linalg.eigvals(a)).max() if np.isfinite(a).all() else 0.0
        if rate == 0:  # integrators only: no time constant
            return
        fastest = 1 / rate
        if 1e-4 * fastest <= Ts <= fastest:
            return
        where, unit = ("longer than", "ms") if Ts > fastest else ("under 1e-4 of", "s")
        self.notes.append(
            f"sampling.Ts: a number without a unit is in seconds, and Ts = {Ts:g} s is {where} "
            f"the plant's fastest time constant ({fastest:.3g} s); if another unit was meant, "
            f'say so: Ts = {{ value = {Ts:g}, unit = "{unit}" }}'
        )

    def parameters(self, table) -> tuple[dict, dict, dict]:
        table = self.table(table, "parameters")
        if len(table) > MAX_PARAMETERS:
            raise self.fail("parameters", f"at most {MAX_PARAMETERS} parameters")
        params, units, descr = {}, {}, {}
        for key, value in table.items():
            where = f"parameters.{key}"
            self.text(key, where, ident=True)
            if isinstance(value, dict):
                self.table(value, where, "parameter")
                number = self.number(self.need(value, "value", where), f"{where}.value")
                if "unit" in value:
                    units[key] = self.unit(value["unit"], f"{where}.unit")
                descr[key] = self.text(value.get("description", ""), f"{where}.description")
            else:
                number = self.number(value, where)
            params[parameter_symbol(key, number)] = number
        return params, units, descr

    def signals(self, d, section, allowed, *, required: bool) -> list[dict]:
        if section not in d:
            if required:
                raise self.fail(section, f"missing; give at least one [[{section}]] with a name")
            return []
        items = self.items(d[section], section, allowed, limit=MAX_MODEL_STATES)
        for i, item in enumerate(items):
            self.text(
                self.need(item, "name", f"{section}[{i}]"), f"{section}[{i}].name", ident=True
            )
        return items

    def plant(self, d, params, units, descr, Ts, name):
        if "discrete" in d:
            return self.discrete(d, params, units, descr, Ts)
        states = self.signals(d, "states", "states", required=True)
        inputs = self.signals(d, "inputs", "inputs", required=True)
        names = [s["name"] for s in states] + [u["name"] for u in inputs]
        pnames = {str(p) for p in params}
        for i, n in enumerate(names):
            kind, k = ("states", i) if i < len(states) else ("inputs", i - len(states))
            if n in pnames or names.index(n) != i:
                raise self.fail(
                    f"{kind}[{k}].name", f"{n!r} is already a state, input or parameter"
                )
        xs = [sp.Symbol(s["name"], real=True) for s in states]
        us = [sp.Symbol(u["name"], real=True) for u in inputs]
        psyms = {p.name: p for p in params}
        allnames = {**psyms, **{s.name: s for s in (*xs, *us)}}
        sym_units = {psyms[k]: v for k, v in units.items()}
        for kind, items, syms in (("states", states, xs), ("inputs", inputs, us)):
            for i, (item, s) in enumerate(zip(items, syms, strict=True)):
                u = self.signal_about(item, f"{kind}[{i}]", units, descr)
                if u is not None:
                    sym_units[s] = u
        rhs = []
        for i, item in enumerate(states):
            rhs_text = self.need(item, "rhs", f"states[{i}]", ", d(state)/dt as text")
            e = self.expr(rhs_text, f"states[{i}].rhs", allnames)
            with self.named(f"states[{i}].rhs"):
                check_rhs(e, sym_units.get(xs[i]), sym_units, f"states[{i}].rhs")
            rhs.append(e)
        u_eq = [sp.Integer(0)] * len(inputs)
        for i, u in enumerate(inputs):
            if "equilibrium" in u:
                u_eq[i] = self.equilibrium(
                    u, f"inputs[{i}]", psyms, sym_units.get(us[i]), sym_units
                )
        given = [("equilibrium" in s) for s in states]
        if any(given) and not all(given):
            raise self.fail(
                f"states[{given.index(False)}]",
                "give the equilibrium of every state, or of none (then it is solved)",
            )
        x_eq = guess = None
        if all(given):
            x_eq = [
                self.equilibrium(s, f"states[{i}]", psyms, sym_units.get(xs[i]), sym_units)
                for i, s in enumerate(states)
            ]
        if any("guess" in s for s in states):
            guess = [
                self.number(s.get("guess", 0.0), f"states[{i}].guess") for i, s in enumerate(states)
            ]
        where = "states" if x_eq is None else "states[0].equilibrium"
        with self.named(where):
            texts = {k: str(v) for k, v in units.items()}
            ode = ODEModel(xs, us, rhs, params, x_eq, u_eq, Ts, guess, name, texts)
            plant = ode.plant()
            plant_symbolic = ode.discrete_symbolic()
        return ode, plant, plant_symbolic

    def signal_about(self, item: dict, where: str, units: dict, descr: dict) -> Unit | None:
        """A state's or input's unit (recorded in ``units``, and returned) and description."""
        u = self.unit(item.get("unit"), f"{where}.unit")
        if u is not None:
            units[item["name"]] = u
        descr[item["name"]] = self.text(item.get("description", ""), f"{where}.description")
        return u

    def stabilizable(self, plant: DiscretePlant, where: str) -> None:
        """Refuse a plant with an unstable mode the inputs cannot reach (delays keep that)."""
        lam = _pbh_defect(*plant.numeric(), stack="h")
        if lam is not None:
            shown = f"{lam.real:.6g}" if abs(lam.imag) < 1e-12 else f"{lam:.6g}"
            raise self.fail(
                where,
                f"the plant cannot be stabilized with any delays: its mode {shown} (|lambda| "
                ">= 1) is not reachable from the inputs (to 1e-9 of the plant's scale)",
            )

    def equilibrium(self, item, where, psyms, unit, sym_units) -> sp.Expr:
        e = self.expr(item["equilibrium"], f"{where}.equilibrium", psyms)
        with self.named(f"{where}.equilibrium", where):
            got = unit_of(e, sym_units)
        if unit is not None and got is not None and not e.is_Number and got != unit:
            raise self.fail(
                f"{where}.equilibrium", f"has unit [{got}] but the signal is in [{unit}]"
            )
        return e

    def discrete(self, d, params, units, descr, Ts):
        table = self.table(d["discrete"], "discrete", "discrete")
        psyms = {p.name: p for p in params}
        values = {p: exact_value(v, p.name) for p, v in params.items()}
        has_ab = "A" in table or "B" in table
        has_tf = "numerator" in table or "denominator" in table
        if has_ab == has_tf:
            raise self.fail("discrete", "give either A and B, or numerator and denominator")
        with self.named("discrete"):
            if has_ab:
                if "A" not in table or "B" not in table:
                    raise self.fail("discrete", "give both A and B")
                A = self.matrix(table["A"], "discrete.A", psyms).subs(values)
                B = self.matrix(table["B"], "discrete.B", psyms).subs(values)
            else:
                if "numerator" not in table or "denominator" not in table:
                    raise self.fail("discrete", "give both numerator and denominator")
                num = self.row(table["numerator"], "discrete.numerator", psyms)
                den = self.row(table["denominator"], "discrete.denominator", psyms)
                G = DiscreteTF(*(sp.Poly(p, z).as_expr().subs(values) for p in (num, den)), dt=Ts)
                if G.relative_degree is None or G.relative_degree < 1:
                    raise self.fail(
                        "discrete.numerator",
                        "the plant's transfer function must be strictly "
                        "proper (x(t+1) = A x(t) + B u(t) has no direct feedthrough)",
                    )
                Rz = controllable_canonical(G)
                A, B = Rz.F, Rz.H
        n, m = A.shape[0], B.shape[1] if B.shape[0] else 0
        states = self.signals(d, "states", "states", required=False)
        inputs = self.signals(d, "inputs", "inputs", required=False)
        for kind, items, size in (("states", states, n), ("inputs", inputs, m)):
            if items and len(items) != size:
                raise self.fail(
                    kind, f"the discrete plant has {size} {kind}, got {len(items)} names"
                )
            for i, item in enumerate(items):
                where = f"{kind}[{i}]"
                if "rhs" in item or "equilibrium" in item or "guess" in item:
                    raise self.fail(
                        where,
                        "a discrete plant takes names, units and descriptions only (no rhs or "
                        "equilibrium)",
                    )
                self.signal_about(item, where, units, descr)
        with self.named("discrete"):
            names = (tuple(s["name"] for s in states), tuple(u["name"] for u in inputs))
            by_name = {str(k): v for k, v in params.items()}
            plant = DiscretePlant(A, B, exact_value(Ts, "Ts"), *names, params=by_name)
            plant.numeric()
        return None, plant, None

    def matrix(self, value, where, names) -> sp.Matrix:
        if not isinstance(value, list) or not value or not all(isinstance(r, list) for r in value):
            raise self.fail(where, "expected rows of entries, like [[1, 0], [0, 1]]")
        if len(value) > MAX_MODEL_STATES or len({len(r) for r in value}) != 1:
            raise self.fail(where, f"rows of one length, at most {MAX_MODEL_STATES} of them")
        if len(value[0]) > MAX_MODEL_STATES or not value[0]:
            raise self.fail(where, f"1 to {MAX_MODEL_STATES} columns")
        return sp.Matrix(
            [
                [self.expr(e, f"{where}[{i}][{j}]", names) for j, e in enumerate(r)]
                for i, r in enumerate(value)
            ]
        )

    def row(self, value, where, names) -> list:
        if not isinstance(value, list) or not 1 <= len(value) <= MAX_MODEL_STATES + 1:
            raise self.fail(where, f"expected a list of 1 to {MAX_MODEL_STATES + 1} coefficients")
        return [self.expr(e, f"{where}[{i}]", names) for i, e in enumerate(value)]

    def delay(self, value, where: str, Ts: float) -> int:
        if isinstance(value, dict):
            self.src.check_keys(value, ("steps", "seconds"), where)
            if len(value) != 1:
                raise self.fail(where, "give one of steps or seconds")
            if "steps" in value:
                return self.integer(value["steps"], f"{where}.steps", 0, MAX_DELAY)
            seconds = self.number(value["seconds"], f"{where}.seconds")
            if seconds < 0:
                raise self.fail(f"{where}.seconds", f"must be >= 0, got {seconds}")
            exact = seconds / Ts
            steps = math.ceil(exact - 1e-9)
            if abs(exact - round(exact)) > 1e-6:
                self.notes.append(
                    f"{where}: {seconds:g} s is {exact:.4g} steps of Ts = {Ts:g} s, not a "
                    f"multiple; rounded up to {steps} steps ({steps * Ts:g} s)"
                )
            if steps > MAX_DELAY:
                raise self.fail(f"{where}.seconds", f"{steps} steps, above {MAX_DELAY}")
            return int(steps)
        return self.integer(value, where, 0, MAX_DELAY)

    def weight(self, value, where: str, size: int, *, definite: bool = False) -> sp.ImmutableMatrix:
        if value == "identity":
            return sp.ImmutableMatrix(sp.eye(size))
        if isinstance(value, int | float) and not isinstance(value, bool):
            M = sp.eye(size) * exact_value(self.number(value, where), where)
        elif isinstance(value, list):
            M = self.matrix(value, where, {})
            if M.shape != (size, size):
                raise self.fail(where, f"must be {size} x {size}, got {M.shape[0]} x {M.shape[1]}")
        else:
            raise self.fail(where, f"expected a number, a matrix or 'identity', got {_kind(value)}")
        with self.named(where):
            psd_matrix(M, where, size, definite=definite)
        return sp.ImmutableMatrix(M)

    def build(self, value) -> tuple:
        kinds = circuit_names()
        if not isinstance(value, list) or not value:
            raise self.fail("circuits.build", f"expected a list of {', '.join(kinds)}")
        for i, k in enumerate(value):
            if k not in kinds:
                raise self.fail(f"circuits.build[{i}]", f"{k!r} is not one of {', '.join(kinds)}")
        return tuple(k for k in kinds if k in value)

    def disturbance(self, table, plant, steps: int) -> tuple:
        table = self.table(table, "simulation.disturbance", "disturbance")
        where = "simulation.disturbance"
        chosen = table.get("state", list(self.names))
        chosen = [chosen] if isinstance(chosen, str) else chosen
        if not isinstance(chosen, list) or not chosen:
            raise self.fail(f"{where}.state", "expected a state or a list of states")
        for s in chosen:
            if not isinstance(s, str) or s not in self.names:
                raise self.fail(
                    f"{where}.state",
                    f"{s!r} is not a state; the states are {', '.join(self.names)}",
                )
        amplitude = float(self.number(table.get("amplitude", 1.0), f"{where}.amplitude"))
        start = self.integer(table.get("start", 5), f"{where}.start", 0, steps - 1)
        length = self.integer(table.get("length", 10), f"{where}.length", 1, steps - start)
        idx = tuple(self.names.index(s) for s in dict.fromkeys(chosen))
        return idx, amplitude, start, length

    def analysis(self, table):
        table = self.table(table, "analysis", "analysis")
        value = table.get("longest_delay", False)
        if value is False:
            return None
        if value is True:
            value = {}
        where = "analysis.longest_delay"
        value = self.table(value, where, "longest_delay")
        top = self.integer(value.get("max", PAPER_MAX_DELAY), f"{where}.max", 1, 200)
        tol = self.number(value.get("tolerance", 0.01), f"{where}.tolerance", positive=True)
        return top, float(tol)


def _kind(value) -> str:
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return "an array"
    if isinstance(value, str):
        return f"text {value!r}" if len(value) <= 40 else "text"
    return f"{type(value).__name__} {value!r}"
