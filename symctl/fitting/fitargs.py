"""The arguments of :func:`symctl.fit`, validated, and the closed loop the traces answer.

>>> from symctl.fitting.fitargs import _circuit_arg
>>> _circuit_arg("general")
['general']
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import sympy as sp

from symctl._util.validate import bounded_int
from symctl.compatibility.structure import Structure
from symctl.design.lqr import Gains
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.fitting.fitmodel import TraceModel
from symctl.neural.circuit import Circuit
from symctl.neural.simulate import closed_loop_response
from symctl.realization.realizers import circuit_names

__all__: list[str] = []

MAX_NEURONS = 64  # most recorded neurons of one fit
MAX_FIT_STEPS = 100_000  # most samples per trace


def _loop(G, plant, disturbance, window, outputs=None) -> tuple[DiscreteTF, np.ndarray, np.ndarray]:
    """``(exact G, its input trace, t)`` of the closed loop under ``disturbance``."""
    if outputs is not None and not isinstance(G, DiscreteTF):
        raise SymctlTypeError("outputs: a controller fed by outputs is a DiscreteTF G (lqg_tf)")
    if isinstance(G, Gains):
        s = G.system
        if (s.n, s.m) != (1, 1):
            raise DimensionError(f"G: fit takes a SISO controller, got {s.m} inputs, {s.n} states")
        from symctl.design.controller import controller_tf

        tf = controller_tf(s).subs(G.substitutions(exact=True))
        res = closed_loop_response(G, plant, disturbance=disturbance, **window)
    elif isinstance(G, DiscreteTF):
        if G.free_symbols:
            raise ParameterError(
                f"G: must be numeric, has the symbols {sorted(map(str, G.free_symbols))}"
            )
        if G.shape != (1, 1):
            raise DimensionError(f"G: fit takes a SISO controller, got shape {G.shape}")
        tf = _rational_tf(G)
        res = closed_loop_response(tf, plant, disturbance=disturbance, outputs=outputs, **window)
        if outputs is not None:
            C = np.atleast_2d(np.array(outputs, dtype=float))
            y = np.asarray(res.delta_f, dtype=float).reshape(len(res.t), -1) @ C.T
            return tf, y[:, 0], np.asarray(res.t, dtype=float)
    else:
        raise SymctlTypeError(
            f"G: expected Gains or a numeric SISO DiscreteTF, got {type(G).__name__}"
        )
    return tf, np.asarray(res.delta_f[:, 0], dtype=float), np.asarray(res.t, dtype=float)


def _rational_tf(G: DiscreteTF) -> DiscreteTF:
    """``G`` with every float coefficient replaced by the exact rational it is."""
    floats = {f: sp.Rational(f) for f in G.expr.atoms(sp.Float)}
    return G.subs(floats) if floats else G


def _traces(traces, steps: int) -> dict:
    if not isinstance(traces, Mapping):
        raise SymctlTypeError(
            f"traces: expected a mapping of neuron names to arrays, got {type(traces).__name__}"
        )
    if not traces:
        raise ParameterError("traces: no recorded neuron given")
    if steps > MAX_FIT_STEPS:
        raise ParameterError(
            f"disturbance: {steps} steps; a fit takes at most {MAX_FIT_STEPS} per trace"
        )
    if len(traces) > MAX_NEURONS:
        raise ParameterError(f"traces: at most {MAX_NEURONS} neurons, got {len(traces)}")
    out = {}
    for name, v in traces.items():
        if not isinstance(name, str):
            raise SymctlTypeError(f"traces: keys are neuron names (str), got {name!r}")
        if isinstance(v, str | bytes) or v is None:
            raise SymctlTypeError(f"traces[{name!r}]: expected an array of numbers, got {v!r}")
        try:
            arr = np.asarray(v, dtype=float)
        except (TypeError, ValueError):
            raise SymctlTypeError(f"traces[{name!r}]: expected an array of numbers") from None
        if arr.ndim != 1:
            raise DimensionError(
                f"traces[{name!r}]: expected one sample per step, got shape {arr.shape}"
            )
        if arr.size != steps:
            raise DimensionError(
                f"traces[{name!r}]: has {arr.size} samples, the closed loop under the "
                f"disturbance has {steps} steps"
            )
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            raise ParameterError(
                f"traces[{name!r}]: not finite (NaN or inf) at step {int(bad[0])}"
                + (f" and {bad.size - 1} more" if bad.size > 1 else "")
            )
        out[name] = arr
    return out


def _circuit_arg(circuit) -> list:
    """The classes to fit: names and atlas classes (labels resolved)."""
    from symctl.circuitatlas.atlas import atlas
    from symctl.circuitatlas.circuitclass import CircuitClass

    if circuit == "all":  # the registry's classes and the atlas's closed-form classes
        closed = [k for k in atlas(2, workers=1).classes if k.evidence.method == "closed form"]
        return [*circuit_names(whole=False), *closed]
    items = list(circuit) if isinstance(circuit, list | tuple) else [circuit]
    if not items or len(items) > 100:
        raise ParameterError(f"circuit: expected 1 to 100 classes, got {len(items)}")
    out = []
    for c in items:
        if isinstance(c, CircuitClass) or c in circuit_names(whole=False):
            out.append(c)
        elif isinstance(c, str) and c[:1] == "A" and c[1:].isdigit():
            classes = {k.label: k for k in atlas(2, workers=1).classes}
            if c not in classes:
                raise ParameterError(
                    f"circuit: no atlas class {c!r} of order 2 (A1..A{len(classes)})"
                )
            out.append(classes[c])
        elif isinstance(c, str):
            raise ParameterError(
                f"circuit: expected {', '.join(map(repr, circuit_names(whole=False)))} or an "
                f"atlas label such as 'A1', got {c!r}"
            )
        else:
            raise SymctlTypeError(f"circuit: expected a class name or CircuitClass, got {c!r}")
    return out


def _one_class(circuit, what: str):
    """The one class of ``circuit`` (a list or ``"all"`` is refused for ``what``)."""
    classes = _circuit_arg(circuit)
    if len(classes) != 1 or isinstance(circuit, list | tuple):
        raise ParameterError(f"circuit: {what} takes one class, got {circuit!r}")
    return classes[0]


def _label(circuit) -> str:
    return circuit if isinstance(circuit, str) else circuit.label


def _signs(signs, neurons) -> tuple:
    if signs is None:
        return ()
    if not isinstance(signs, Mapping):
        raise SymctlTypeError(
            f"signs: expected a mapping of neuron names to '+' or '-', got {signs!r}"
        )
    out = []
    for name, s in signs.items():
        if name not in neurons:
            raise ParameterError(
                f"signs[{name!r}]: no such neuron; the circuit's neurons are {neurons}"
            )
        if s not in ("+", "-"):
            raise ParameterError(f"signs[{name!r}]: expected '+' or '-', got {s!r}")
        out.append((name, 1.0 if s == "+" else -1.0))
    return tuple(out)


def _circuit_neurons(model: TraceModel) -> tuple[str, ...]:
    """The neurons of the class's circuit (canonical forms merge pure-delay states)."""
    k = model.n_sections
    eps = [sp.Rational(3 + 2 * i, 17 + i) * (-1) ** i for i in range(k)]  # generic values
    cs = [1] * k if model.C is not None else [sp.Rational(7 + i, 6) for i in range(k)]
    fs = model.factorization(eps, cs)
    Q = sp.Matrix(model.order, model.order, lambda i, j: 2 if i == j else sp.Rational(1, 3 + i + j))
    R2 = model.realize(fs, Q)
    return tuple(
        n.name for n in Circuit.from_structure(Structure.from_factorization(fs, R2)).neurons
    )


def _window(steps, start, length) -> dict:
    if steps is not None:
        steps = bounded_int(steps, "steps", 1, MAX_FIT_STEPS)
    return {"steps": steps, "start": start, "length": length}
