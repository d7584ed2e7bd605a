"""Recorded firing-rate traces: the data :func:`symctl.fit` takes, read from CSV or NPZ (the
format: ``docs/fitting.md``; a time column ``t``, optionally ``disturbance``, one column per
recorded neuron, ``# key: value`` lines; nothing read is evaluated)."""

from __future__ import annotations

import csv
import io
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl._util.deprecate import rng_argument
from symctl._util.pickling import ArrayValue
from symctl._util.serial import DictMixin
from symctl._util.validate import bounded_int, read_only
from symctl.errors import DimensionError, ParameterError, SymctlTypeError

__all__ = ["Traces", "read_traces", "synthetic_traces"]

MAX_FILE_BYTES = 64 * 2**20  # largest data file read


@dataclass(frozen=True, eq=False)
class Traces(ArrayValue, DictMixin):
    r"""Recorded (or simulated) firing-rate traces of some neurons of one circuit.

    Attributes
    ----------
    t : (steps,) array
        Time of each sample.
    traces : mapping of str to (steps,) array
        Per neuron, its firing-rate change.
    disturbance : (steps,) array or None
        The force disturbance per step (None: the default unit pulse).
    meta, hidden : mapping
        The file's ``key: value`` lines; :func:`synthetic_traces`'s hidden parameters.

    Examples
    --------
    >>> import numpy as np
    >>> from symctl import Traces
    >>> tr = Traces(np.arange(3) * 0.01, {"G2.y": [0.0, 1.0, 0.5]})
    >>> tr.neurons, tr.steps
    (('G2.y',), 3)
    """

    t: np.ndarray
    traces: Mapping
    disturbance: np.ndarray | None = None
    meta: Mapping = field(default_factory=dict)
    hidden: Mapping = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "t", read_only(self.t, float))
        tr = {k: read_only(v, float) for k, v in self.traces.items()}
        object.__setattr__(self, "traces", MappingProxyType(tr))
        if self.disturbance is not None:
            object.__setattr__(self, "disturbance", read_only(self.disturbance, float))
        object.__setattr__(self, "meta", MappingProxyType(dict(self.meta)))
        object.__setattr__(self, "hidden", MappingProxyType(dict(self.hidden)))

    @property
    def neurons(self) -> tuple[str, ...]:
        return tuple(self.traces)

    @property
    def steps(self) -> int:
        return int(self.t.size)

    def select(self, neurons) -> Traces:
        """The same data with only ``neurons`` (e.g. the recorded ones)."""
        missing = [n for n in neurons if n not in self.traces]
        if missing:
            raise ParameterError(f"neurons: not in the data: {missing}; it has {self.neurons}")
        kept = {n: self.traces[n] for n in neurons}
        return Traces(self.t, kept, self.disturbance, self.meta, self.hidden)

    def to_csv(self, path) -> Path:
        """Write the CSV format (comment header, then ``t``, ``disturbance``, neurons)."""
        path = Path(path)
        buf = io.StringIO()
        for k, v in self.meta.items():
            buf.write(f"# {k}: {v}\n")
        cols = {"t": self.t}
        if self.disturbance is not None:
            cols["disturbance"] = self.disturbance
        cols.update(self.traces)
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(list(cols))
        for row in zip(*cols.values(), strict=True):
            w.writerow([repr(float(x)) for x in row])
        path.write_text(buf.getvalue(), encoding="utf-8")
        return path


def read_traces(path) -> Traces:
    r"""Read recorded traces from a CSV or NPZ file (format: ``docs/fitting.md``).

    Parameters
    ----------
    path : str or Path
        A ``.csv`` or ``.npz`` file (at most 64 MiB).

    Returns
    -------
    Traces

    Raises
    ------
    ParameterError
        An unreadable file or suffix, no ``t`` or neuron column, a non-number, NaN,
        uneven time steps.
    DimensionError
        Columns of different lengths.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from symctl import read_traces
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "a.csv"
    >>> _ = p.write_text("# circuit: general\nt,G2.y\n0,0\n0.01,1.5\n")
    >>> tr = read_traces(p)
    >>> tr.meta["circuit"], tr.traces["G2.y"].tolist()
    ('general', [0.0, 1.5])
    """
    if not isinstance(path, str | Path):
        raise SymctlTypeError(f"path: expected a file name, got {type(path).__name__}")
    p = Path(path)
    if not p.is_file():
        raise ParameterError(f"path: no such file {str(p)!r}")
    if p.stat().st_size > MAX_FILE_BYTES:
        raise ParameterError(f"path: {str(p)!r} is larger than {MAX_FILE_BYTES} bytes")
    suffix = p.suffix.lower()
    if suffix == ".csv":
        cols, meta = _read_csv(p)
    elif suffix == ".npz":
        cols, meta = _read_npz(p)
    else:
        raise ParameterError(f"path: expected a .csv or .npz file, got {str(p)!r}")
    from symctl.fitting.fitargs import MAX_FIT_STEPS, MAX_NEURONS

    if "t" not in cols:
        raise ParameterError(f"path: {p.name} has no time column 't'")
    t = cols.pop("t")
    disturbance = cols.pop("disturbance", None)
    if not cols:
        raise ParameterError(f"path: {p.name} has no neuron column")
    if len(cols) > MAX_NEURONS or t.size > MAX_FIT_STEPS:
        raise ParameterError(
            f"path: {p.name} has {len(cols)} neurons and {t.size} steps; at most {MAX_NEURONS} "
            f"and {MAX_FIT_STEPS}"
        )
    source = f"path: {p.name}"
    if t.ndim != 1 or t.size < 2:
        raise DimensionError(f"{source}: column 't' needs at least 2 samples, got {t.size}")
    dt = np.diff(t)
    if not np.all(np.isfinite(t)) or dt[0] <= 0 or not np.allclose(dt, dt[0], rtol=1e-6, atol=0):
        raise ParameterError(f"{source}: column 't' must increase in equal steps")
    for name, v in (cols if disturbance is None else {**cols, "disturbance": disturbance}).items():
        if v.shape != t.shape:
            raise DimensionError(
                f"{source}: column {name!r} has {v.size} samples, 't' has {t.size}"
            )
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise ParameterError(
                f"{source}: column {name!r} is not finite (NaN or inf) at row {int(bad[0])}"
            )
    return Traces(t, cols, disturbance, meta)


def _read_csv(p: Path) -> tuple[dict, dict]:
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise ParameterError(f"path: cannot read {p.name}: {exc}") from None
    meta, body = {}, []
    for line in text.splitlines():
        if line.startswith("#"):
            key, sep, value = line[1:].partition(":")
            if sep and key.strip():
                meta[key.strip()] = value.strip()
        elif line.strip():
            body.append(line)
    if not body:
        raise ParameterError(f"path: {p.name} has no header row")
    rows = list(csv.reader(body))
    head = [h.strip() for h in rows[0]]
    if len(set(head)) != len(head):
        raise ParameterError(f"path: {p.name} repeats a column name: {head}")
    values = np.empty((len(rows) - 1, len(head)))
    for i, row in enumerate(rows[1:]):
        if len(row) != len(head):
            raise DimensionError(
                f"path: {p.name} row {i + 1} has {len(row)} values, the header {len(head)}"
            )
        for j, cell in enumerate(row):
            try:
                values[i, j] = float(cell)
            except ValueError:
                raise ParameterError(
                    f"path: {p.name} row {i + 1}, column {head[j]!r}: not a number: {cell[:40]!r}"
                ) from None
    return {h: values[:, j] for j, h in enumerate(head)}, meta


def _read_npz(p: Path) -> tuple[dict, dict]:
    try:
        with np.load(p, allow_pickle=False) as z:
            arrays = {k: np.asarray(z[k]) for k in z.files}
    except (OSError, ValueError) as exc:
        raise ParameterError(f"path: cannot read {p.name}: {exc}") from None
    cols, meta = {}, {}
    for k, a in arrays.items():
        if a.dtype.kind in "US":
            meta[k] = str(a.item()) if a.ndim == 0 else str(a)
        elif a.dtype.kind in "fiu":
            cols[k] = a.astype(float)
        else:
            raise ParameterError(f"path: {p.name} array {k!r} is neither numbers nor text")
    for k, a in cols.items():
        if a.ndim != 1:
            raise DimensionError(f"path: {p.name} array {k!r} has shape {a.shape}; expected 1-d")
    return cols, meta


@rng_argument()
def synthetic_traces(
    G,
    *,
    sensor_delay: int,
    actuator_delay: int,
    circuit="general",
    disturbance=1.0,
    plant=None,
    C=1,
    noise: float = 0.0,
    rng=0,
    steps: int | None = None,
) -> Traces:
    r"""Every neuron's trace in a hidden random realization of ``G``, with noise.

    :math:`\epsilon` on the grid :math:`k/1000` in :math:`(-0.9, 0.9)`, every :math:`C` =
    ``C``, a random rational :math:`P` for the general class; seeded Gaussian noise of
    ``noise`` times each trace's RMS.

    Parameters
    ----------
    G, sensor_delay, actuator_delay, circuit, disturbance, plant, steps
        As in :func:`~symctl.fitting.fit.fit` (one class).
    C : number
        The section gains of the hidden circuit (default 1).
    noise : float
        Relative noise level, in ``[0, 10]``.
    rng : int, numpy Generator or None, default 0
        Seeds the sections, ``P`` and the noise (``seed=`` is its deprecated name).

    Returns
    -------
    Traces
        ``hidden`` holds the hidden parameters, exact; ``meta`` the circuit and delays.

    Examples
    --------
    >>> from symctl import MuscleModel, augment, lqr_gains, synthetic_traces
    >>> gains = lqr_gains(augment(MuscleModel(), 1, 1))
    >>> data = synthetic_traces(gains, sensor_delay=1, actuator_delay=1, rng=1)
    >>> sorted(data.hidden)[:2], data.meta["circuit"]
    (['C_1', 'C_3'], 'general')
    """
    from symctl.fitting.fitargs import _circuit_neurons, _label, _loop, _one_class, _window
    from symctl.fitting.fitmodel import TraceModel, transformed
    from symctl.neural.simulate import DEFAULT_LENGTH, DEFAULT_START, _signal
    from symctl.realization.realizers import random_full_rank

    cls = _one_class(circuit, "synthetic_traces")
    sensor_delay = bounded_int(sensor_delay, "sensor_delay", 1, 50)
    actuator_delay = bounded_int(actuator_delay, "actuator_delay", 1, 50)
    if isinstance(C, bool) or not isinstance(C, int | float) or C == 0 or not np.isfinite(C):
        raise ParameterError(f"C: expected a finite nonzero number, got {C!r}")
    if isinstance(noise, bool) or not isinstance(noise, int | float) or not 0 <= noise <= 10:
        raise ParameterError(f"noise: expected a number in [0, 10], got {noise!r}")
    window = _window(steps, DEFAULT_START, DEFAULT_LENGTH)
    tf, u, t = _loop(G, plant, disturbance, window)
    model = TraceModel.build(tf, sensor_delay, actuator_delay, cls, None)
    k = model.n_sections
    eps = [sp.Rational(int(rng.integers(-899, 900)), 1000) for _ in range(k)]
    values = [*eps, *[sp.Rational(C)] * k]
    if transformed(model.circuit):
        values += list(random_full_rank(model.order, rng).inv())  # the entries of P^-1
    hidden = dict(zip(model.names, values, strict=True))
    vals, _ = model.traces(np.array([float(v) for v in values]), u)
    traces = {}
    for n in _circuit_neurons(model):
        rms = float(np.sqrt(np.mean(vals[n] ** 2)))
        traces[n] = vals[n] + noise * rms * rng.normal(size=vals[n].size)
    w = _signal(disturbance, "disturbance", window["steps"], 1, DEFAULT_START, DEFAULT_LENGTH)[:, 0]
    meta = {
        "circuit": _label(cls),
        "sensor_delay": str(sensor_delay),
        "actuator_delay": str(actuator_delay),
        "noise": f"{noise:g}",
        "hidden": ", ".join(f"{n}={v}" for n, v in hidden.items()),
    }
    return Traces(t, traces, w, meta, hidden)
