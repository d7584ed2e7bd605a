"""Every export, run in its simulator, reproduces symctl's own simulation of the circuit.

The JSON connection list is run by a reader written here from its documented schema only.
"""

from __future__ import annotations

import graphlib
import importlib
import json

import numpy as np
import pytest
import sympy as sp
from helpers import need_spiking

from symctl import (
    Circuit,
    Structure,
    circuits_for,
    controllable_canonical,
    controller_tf,
    export_circuit,
    factor,
    pulse,
)
from symctl.neural.firing import _drive

SIMULATORS = {
    "nengo": ("nengo", "symctl.spiking.nengo_export", "nengo_response"),
    "nest": ("nest", "symctl.spiking.nest_export", "nest_response"),
    "nir": ("nir", "test_nir_export", "nir_response"),
    "json": (None, __name__, "_json_response"),
}


@pytest.fixture(params=sorted(SIMULATORS))
def response(request):
    """``(circuit, u) -> traces`` of one simulator (skipped without it, as need_spiking)."""
    package, module, name = SIMULATORS[request.param]
    if package:
        need_spiking(package)
    return getattr(importlib.import_module(module), name)


def _json_response(circuit: Circuit, u: np.ndarray) -> dict[str, np.ndarray]:
    """export_circuit's JSON, read back from disk and run by the schema's rule alone."""
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "circuit.json"
        export_circuit(circuit, path, dt=0.01)
        data = json.loads(path.read_text(encoding="utf-8"))
    assert (data["format"], data["version"]) == ("symctl-circuit", 1)
    u = u[:, None] if u.ndim == 1 else u
    steps = u.shape[0]
    signal = {name: u[:, j] for j, name in enumerate(data["inputs"])}
    terms = {}
    for n in data["neurons"]:
        signal[n["name"]] = np.zeros(steps)
        terms[n["name"]] = [(n["name"], t["weight"], t["delay_steps"]) for t in n["self_dynamics"]]
        for t in n["self_dynamics"]:
            assert t["delay_s"] == pytest.approx(0.01 * t["delay_steps"])
    for s in data["synapses"]:
        terms[s["target"]].append((s["source"], s["weight"], s["delay_steps"]))
    now = {n: {s for s, _, d in ts if d == 0 and s in terms} for n, ts in terms.items()}
    order = list(graphlib.TopologicalSorter(now).static_order())  # delay-free inputs first
    for t in range(steps):
        for n in order:
            signal[n][t] = sum(w * signal[s][t - d] for s, w, d in terms[n] if t >= d)
    traces = {n["name"]: signal[n["name"]] for n in data["neurons"]}
    outs = []
    for o in data["outputs"]:
        out = np.zeros(steps)
        if o["source"] is not None:
            d = o["delay_steps"]
            out[d:] = o["weight"] * signal[o["source"]][: steps - d]
        outs.append(out)
    traces["output"] = outs[0] if len(outs) == 1 else np.stack(outs, axis=1)
    return traces


def _same_traces(response, circuit: Circuit, u: np.ndarray) -> None:
    """The simulator's traces equal symctl's to 1e-9 relative to their peak, neuron by neuron."""
    ref, got = _drive(circuit, u), response(circuit, u)
    assert set(got) == set(ref)
    for name, trace in ref.items():
        scale = max(1.0, float(np.max(np.abs(trace))))
        np.testing.assert_allclose(got[name], trace, rtol=0, atol=1e-9 * scale, err_msg=name)


def _input(circuit: Circuit, steps: int = 40) -> np.ndarray:
    """A pulse on the first input and a shorter one of another height on each further input."""
    u = pulse(steps, 1.0, 3, 10, size=len(circuit.inputs))
    for j in range(1, u.shape[1]):
        u[:, j] = pulse(steps, -0.5 * j, 5 + j, 4)[:, 0]
    return u


@pytest.mark.parametrize("name", ["ifp", "general", "controllable", "observable"])
def test_every_paper_circuit_runs_as_symctls_simulation(response, derived_T2, name):
    firing = derived_T2.circuits[name].firing
    for circuit in firing.circuits:
        _same_traces(response, circuit, _input(circuit))


def test_every_order_2_atlas_class_runs_as_symctls_simulation(response, derived_T2):
    candidates = circuits_for(derived_T2.G)
    assert len({c.circuit_class.label for c in candidates}) == len(candidates) > 3
    for cand in candidates:
        _same_traces(response, cand.circuit, _input(cand.circuit))


def test_a_mimo_circuit_runs_as_symctls_simulation(response, derived_oculomotor):
    for record in derived_oculomotor.circuits.values():
        if record.firing is not None:
            circuit = record.firing.circuits[0]
            break
    assert len(circuit.inputs) > 1 or len(circuit.outputs) > 1
    _same_traces(response, circuit, _input(circuit))


def test_multi_step_axons_are_delays_of_as_many_steps(response):
    T = 3
    G = controller_tf(T).subs({f"K_{k}": sp.Rational(k + 1, 5 * (k + 2)) for k in range(T + 1)})
    f = factor(G, 1, 0 + 2, eps=[sp.Rational(1, 3), sp.Rational(-1, 4), sp.Rational(1, 5)], C=1)
    R = controllable_canonical(f.G2)
    circuit = Circuit.from_structure(Structure.from_realization(R))
    assert max(s.delay for s in (*circuit.synapses, *circuit.outputs)) >= 2
    _same_traces(response, circuit, _input(circuit))


def test_the_spiking_guide_runs_as_written(tmp_path, monkeypatch):
    """docs/guide/spiking.md's Python blocks, in order, in one fresh namespace."""
    import re
    from pathlib import Path

    need_spiking("nengo")
    need_spiking("nest")
    need_spiking("nir")
    page = Path(__file__).resolve().parents[2] / "docs" / "guide" / "spiking.md"
    namespace: dict = {"__name__": "__main__"}
    blocks = re.findall(r"```python\n(.*?)```", page.read_text(), re.S)
    assert len(blocks) == 6
    monkeypatch.chdir(tmp_path)  # the page writes circuit.json, sweep.jsonl, circuit.nir
    for k, code in enumerate(blocks):
        exec(compile(code, f"spiking.md python block {k + 1}", "exec"), namespace)
    np.testing.assert_allclose(
        namespace["traces"]["G2.x1"], _drive(namespace["circuit"], pulse(50))["G2.x1"], atol=1e-9
    )
