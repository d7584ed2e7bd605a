"""The ``[[outputs]]`` and ``[noise]`` tables of a model file: a mixin of its reader.

An ``expr`` output is linearized at the equilibrium; the outputs' matrix ``C`` is None
when every state is measured without noise (the paper's full-state design).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from symctl._util.validate import numeric_matrix, psd_matrix
from symctl.design.lqr import _pbh_defect
from symctl.design.ode import MAX_MODEL_STATES, exact_value
from symctl.design.plant import DiscretePlant
from symctl.model.units import unit_of

__all__ = ["MeasurementSection"]


class MeasurementSection:
    """Reads ``[[outputs]]`` and ``[noise]`` with the reader's field checks."""

    def outputs(self, data, ode, params, units, descr) -> tuple:
        """The outputs ``(name, state or expr)`` and their matrix ``C`` (None: every state)."""
        if data is None:
            return tuple((s, s) for s in self.names), None
        items = self.items(data, "outputs", "outputs", limit=MAX_MODEL_STATES)
        if ode is not None:
            xs, us, values = list(ode.states), list(ode.inputs), ode.values
            point = dict(zip((*xs, *us), (*ode.x_eq, *ode.u_eq), strict=True))
        else:
            xs, us, point = [sp.Symbol(s, real=True) for s in self.names], [], {}
            values = {p: exact_value(v, p.name) for p, v in params.items()}
        names = {**{p.name: p for p in params}, **{x.name: x for x in (*xs, *us)}}
        sym_units = {v: units[k] for k, v in names.items() if k in units}
        out, rows = [], []
        for i, item in enumerate(items):
            where = f"outputs[{i}]"
            name = self.text(self.need(item, "name", where), f"{where}.name", ident=True)
            u = self.unit(item.get("unit"), f"{where}.unit")
            if "expr" in item:
                if "state" in item:
                    raise self.fail(where, "give state or expr, not both")
                what = self.text(item["expr"], f"{where}.expr")
                e = self.expr(what, f"{where}.expr", names)
                with self.named(f"{where}.expr"):
                    got = unit_of(e, sym_units)
                if u is not None and got is not None and got != u:
                    raise self.fail(
                        f"{where}.unit", f"[{u}] contradicts the unit [{got}] of {what}"
                    )
                row, through = (
                    [sp.diff(e, v).subs(point).subs(values) for v in group] for group in (xs, us)
                )
                if any(c != 0 for c in through):
                    raise self.fail(
                        f"{where}.expr",
                        "moves with an input at the equilibrium (a direct feedthrough); "
                        "measure states only",
                    )
            else:
                what = self.text(item.get("state", name), f"{where}.state")
                if what not in self.names:
                    raise self.fail(
                        f"{where}.state",
                        f"{what!r} is not a state; the states are {', '.join(self.names)}",
                    )
                if u is not None and what in units and units[what] != u:
                    raise self.fail(
                        f"{where}.unit",
                        f"[{u}] contradicts the unit [{units[what]}] of state {what}",
                    )
                row = [int(s == what) for s in self.names]
            descr.setdefault(name, self.text(item.get("description", ""), f"{where}.description"))
            out.append((name, what))
            rows.append(row)
        measured = {w for (_, w), i in zip(out, items, strict=True) if "expr" not in i}
        full = measured >= set(self.names) and not any("expr" in i for i in items)
        return tuple(out), None if full else sp.ImmutableMatrix(rows)

    def noise(self, table, plant, params, p: int) -> dict:
        """The covariances ``process`` (default I, or 0 with ``motor``), ``sensor`` (default I)
        and ``motor``; ``{}`` without [noise]."""
        if table is None:
            return {}
        table = self.table(table, "noise", "noise")
        psyms = {q.name: q for q in params}
        values = {q: exact_value(v, q.name) for q, v in params.items()}
        sizes = {"process": plant.n, "motor": plant.m, "sensor": p}
        out = {}
        for key, size in sizes.items():
            if key not in table:
                continue
            where, value = f"noise.{key}", table[key]
            if isinstance(value, list) and value and all(isinstance(r, list) for r in value):
                M = self.matrix(value, where, psyms)
            elif isinstance(value, list):
                if len(value) != size:
                    raise self.fail(where, f"a diagonal of {size} entries, got {len(value)}")
                M = sp.diag(*[self.expr(e, f"{where}[{i}]", psyms) for i, e in enumerate(value)])
            else:
                M = sp.eye(size) * self.expr(value, where, psyms)
            if M.shape != (size, size):
                raise self.fail(where, f"must be {size} x {size}, got {M.shape[0]} x {M.shape[1]}")
            M = M.subs(values)
            with self.named(where):
                arr = psd_matrix(M, where, size)
            if key == "sensor" and np.min(np.linalg.eigvalsh(arr)) <= 1e-12 * max(
                1, np.abs(arr).max()
            ):
                raise self.fail(
                    where,
                    "singular: the Kalman filter divides by the sensor covariance, so every "
                    "output needs noise of its own",
                )
            out[key] = sp.ImmutableMatrix(M)
        out.setdefault("process", sp.zeros(plant.n) if "motor" in out else sp.eye(plant.n))
        out.setdefault("sensor", sp.eye(p))
        return {k: sp.ImmutableMatrix(v) for k, v in out.items()}

    def detectable(self, plant: DiscretePlant, C) -> None:
        """Refuse outputs that leave an unstable mode unseen (PBH test)."""
        mode = _pbh_defect(*(numeric_matrix(M, "outputs") for M in (plant.A, C)), stack="v")
        if mode is not None:
            raise self.fail(
                "outputs",
                f"the outputs leave the plant undetectable: its mode {mode:.6g} (|lambda| >= 1) "
                "is seen by no output; measure a signal that it moves",
            )
