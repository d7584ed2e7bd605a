"""The ``[delay_graph]`` table of a model file (a mixin of its reader); without it, the graph
is the chain of the delays, one vertex per step."""

from __future__ import annotations

import math
import re

from symctl.compatibility.delaygraph import DelayGraph
from symctl.errors import SymctlError
from symctl.model.model import chain_graph

__all__ = ["MAX_VERTICES", "GraphSection", "strip_argname"]

MAX_VERTICES = 50  # the most vertices of a model file's delay graph


class GraphSection:
    """Reads ``[delay_graph]`` with the reader's field checks."""

    def graph(self, data, delays: tuple[int, int], Ts: float):
        if data is None:
            return (*chain_graph(*delays), False, {})
        table = self.table(data, "delay_graph", "delay_graph")
        vertices = self.need(table, "vertices", "delay_graph", " ([[delay_graph.vertices]])")
        vs = self.items(vertices, "delay_graph.vertices", "vertex", limit=MAX_VERTICES)
        names, about = [], {}
        for i, v in enumerate(vs):
            n = self.need(v, "name", f"delay_graph.vertices[{i}]")
            n = self.text(n, f"delay_graph.vertices[{i}].name", ident=True)
            if n in names:
                raise self.fail(f"delay_graph.vertices[{i}].name", f"{n!r} appears twice")
            names.append(n)
            if "description" in v:
                about[n] = self.text(v["description"], f"delay_graph.vertices[{i}].description")
        if len(names) < 2:
            raise self.fail("delay_graph.vertices", "needs at least 2 vertices")
        sensors = self.ends(table.get("sensor", names[0]), "delay_graph.sensor", names)
        actuators = self.ends(table.get("actuator", names[-1]), "delay_graph.actuator", names)
        both = set(sensors) & set(actuators)
        if both:
            raise self.fail(
                "delay_graph.actuator",
                f"{sorted(both)[0]!r} is both a sensor and an actuator vertex",
            )
        ends = (*sensors, *actuators)
        order = [*sensors, *[n for n in names if n not in ends], *actuators]
        es = self.items(table.get("edges", []), "delay_graph.edges", "edge", limit=MAX_VERTICES**2)
        edges = []
        for i, e in enumerate(es):
            where = f"delay_graph.edges[{i}]"
            for key in ("from", "to"):
                if self.text(self.need(e, key, where), f"{where}.{key}") not in names:
                    raise self.fail(f"{where}.{key}", f"{e[key]!r} is not a vertex")
            if ("steps" in e) == ("seconds" in e):
                raise self.fail(where, "give one of steps or seconds")
            d = self.delay({k: e[k] for k in ("steps", "seconds") if k in e}, where, Ts)
            if e["from"] == e["to"]:
                raise self.fail(where, "an edge from a vertex to itself")
            edges.append((e["from"], e["to"], d))
        index = {n: k + 1 for k, n in enumerate(order)}
        n = len(order)
        try:
            graph = DelayGraph.from_edges(
                n,
                [(index[a], index[b], d) for a, b, d in edges],
                sensors=[index[v] for v in sensors],
                actuators=[index[v] for v in actuators],
            )
        except SymctlError as exc:
            problem = re.sub(
                r"\bv(\d+)\b",
                lambda m: repr(order[int(m.group(1)) - 1]),
                strip_argname(str(exc), "E"),
            )
            raise self.fail("delay_graph.edges", problem) from None
        for a in sensors:
            for b in actuators:
                if math.isinf(graph.E[index[a] - 1, index[b] - 1]):
                    raise self.fail(
                        "delay_graph.edges", f"no path from the sensor {a!r} to the actuator {b!r}"
                    )
        return graph, tuple(order), tuple(edges), True, about

    def wire_bound(self, data) -> int | None:
        """``[delay_graph] max_wire_delay``: the most steps of one wire (None: any)."""
        if not isinstance(data, dict) or "max_wire_delay" not in data:
            return None
        return self.integer(data["max_wire_delay"], "delay_graph.max_wire_delay", 1, 100_000)

    def ends(self, value, where: str, names: list) -> tuple[str, ...]:
        """A sensor or actuator entry: one vertex name, or a list of them (one per channel)."""
        values = value if isinstance(value, list) else [value]
        if not values:
            raise self.fail(where, "expected a vertex or a list of vertices, got an empty list")
        out = []
        for k, v in enumerate(values):
            at = where if not isinstance(value, list) else f"{where}[{k}]"
            v = self.text(v, at)
            if v not in names:
                raise self.fail(at, f"{v!r} is not a vertex; the vertices are {', '.join(names)}")
            if v in out:
                raise self.fail(at, f"{v!r} appears twice")
            out.append(v)
        return tuple(out)


def strip_argname(message: str, where: str) -> str:
    """A symctl error's message without a leading ``argname:`` (the field is named already)."""
    head, sep, rest = message.partition(": ")
    return rest if sep and (head == where or " " not in head) else message
