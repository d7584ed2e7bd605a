r"""What spikes cost each circuit: the neurons per population that keep the force near the linear loop.

Per seed, the smallest :math:`N` within a tolerance, interpolated in :math:`\log N` against
:math:`\log` deviation between the bracketing sizes (:math:`\infty`: none), and its spikes per
second likewise; a circuit's cost is the median over seeds, times its populations.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from symctl._util.pickling import ArrayValue
from symctl._util.pool import Checkpoint, open_pool, pool_options
from symctl._util.serial import DictMixin
from symctl._util.validate import bounded_int
from symctl.design.lqr import Gains
from symctl.errors import ParameterError, SymctlTypeError
from symctl.neural.circuit import Circuit
from symctl.neural.firing import _plant
from symctl.neural.simulate import _freeze
from symctl.spiking.connections import _edges
from symctl.spiking.loop import spiking_response
from symctl.spiking.nengo_export import MAX_POPULATION, RADIUS_MARGIN

__all__ = ["NEURONS", "TOLERANCES", "SpikingCost", "spiking_cost"]

NEURONS = (10, 100, 1000)  # the population sizes of a sweep by default
TOLERANCES = (0.05, 0.01)  # the deviations from the linear loop a circuit is held to
FORMAT = 1  # version of the checkpoint format


@dataclass(frozen=True, eq=False)
class SpikingCost(ArrayValue, DictMixin):
    """The spiking sweep of a controller's circuits (:func:`spiking_cost`; module text); read-only.

    Attributes
    ----------
    circuits, atlas_classes : tuple of str
        The circuits' names (the named ones, then the atlas classes), and the atlas classes.
    populations, peak : tuple
        Each circuit's neurons (its populations), and its largest linear peak rate change.
    neurons : tuple of int
        The population sizes :math:`N`, increasing.
    seeds : int
        Seeds per size (``0 .. seeds - 1``).
    tolerances : tuple of float
    deviation, spikes : (circuits, neurons, seeds) arrays
        Each run's deviation from the linear loop, and its spikes per second.

    Examples
    --------
    >>> import symctl
    >>> res = symctl.derive_paper()
    >>> cost = symctl.spiking_cost(res, circuits=["ifp"], neurons=(10, 40), seeds=2)
    >>> cost.deviation.shape, cost.table()[0]["circuit"]
    ((1, 2, 2), 'ifp')
    """

    circuits: tuple
    populations: tuple
    peak: tuple
    neurons: tuple
    seeds: int
    tolerances: tuple
    deviation: np.ndarray
    spikes: np.ndarray
    atlas_classes: tuple = ()

    def __post_init__(self) -> None:
        _freeze(self, ("deviation", "spikes"))

    def needed(self, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
        """Per circuit and seed, the neurons per population within ``tolerance`` and the spikes
        per second there (``inf``: none): two ``(circuits, seeds)`` arrays."""
        logn = np.log(np.asarray(self.neurons, dtype=float))
        n_out = np.full((len(self.circuits), self.seeds), np.inf)
        s_out = np.full_like(n_out, np.inf)
        for c, s in np.ndindex(n_out.shape):
            d, sp = self.deviation[c, :, s], self.spikes[c, :, s]
            ok = np.flatnonzero(d <= tolerance)
            if not ok.size:
                continue
            i = ok[0]
            if i == 0:
                n_out[c, s], s_out[c, s] = self.neurons[0], sp[0]
                continue
            f = (np.log(tolerance) - np.log(d[i - 1])) / (np.log(d[i]) - np.log(d[i - 1]))
            n_out[c, s] = np.exp(logn[i - 1] + f * (logn[i] - logn[i - 1]))
            lo, hi = np.log(max(sp[i - 1], 1e-300)), np.log(max(sp[i], 1e-300))
            s_out[c, s] = np.exp(lo + f * (hi - lo))
        return n_out, s_out

    def table(self) -> list[dict]:
        """One dict per circuit, cheapest first: ``circuit``, ``populations``, ``peak``, and per
        tolerance ``t`` (as ``5%``) ``N@t`` (median neurons per population), ``N@t range``,
        ``neurons@t`` (times populations) and ``spikes@t`` (median spikes per second)."""
        needs = {f"{100 * t:g}%": self.needed(t) for t in self.tolerances}
        rows = []
        for c, name in enumerate(self.circuits):
            row = {"circuit": name, "populations": self.populations[c], "peak": self.peak[c]}
            for key, (n, s) in needs.items():
                row[f"N@{key}"] = float(np.median(n[c]))
                row[f"N@{key} range"] = (float(n[c].min()), float(n[c].max()))
                row[f"neurons@{key}"] = row[f"N@{key}"] * self.populations[c]
                row[f"spikes@{key}"] = float(np.median(s[c]))
            rows.append(row)
        return self._sorted(rows, "neurons", "spikes")

    def _sorted(self, rows: list[dict], first: str, then: str) -> list[dict]:
        key = f"{100 * self.tolerances[0]:g}%"
        return sorted(rows, key=lambda r: (r[f"{first}@{key}"], r[f"{then}@{key}"]))

    def ranking(self, by: str = "neurons") -> tuple[str, ...]:
        """The circuits, cheapest first at the first tolerance, ``by`` ``"neurons"`` or ``"spikes"``."""
        if by not in ("neurons", "spikes"):
            raise ParameterError(f"by: expected 'neurons' or 'spikes', got {by!r}")
        then = "spikes" if by == "neurons" else "neurons"
        return tuple(r["circuit"] for r in self._sorted(self.table(), by, then))

    def fewest_neurons_cheapest(self, among=None) -> bool:
        """Whether a fewest-neuron circuit (among ``among``) is also the cheapest in spikes."""
        names = self._among(among)
        return self._cheapest(names) in self._fewest(names)

    def _among(self, among) -> list[str]:
        names = list(self.circuits if among is None else among)
        if not names or any(n not in self.circuits for n in names):
            raise ParameterError(f"among: expected some of {list(self.circuits)}, got {among!r}")
        return names

    def _fewest(self, names) -> list[str]:
        k = min(self.populations[self.circuits.index(n)] for n in names)
        return [n for n in names if self.populations[self.circuits.index(n)] == k]

    def _cheapest(self, names) -> str:
        return next(n for n in self.ranking("spikes") if n in names)

    def finding(self, among=None) -> str:
        """The answer in a sentence: is the fewest-neuron circuit (among ``among``) the cheapest in spikes?"""
        names = self._among(among)
        rows = {r["circuit"]: r for r in self.table()}
        key = f"{100 * self.tolerances[0]:g}%"
        fewest, best = self._fewest(names), self._cheapest(names)
        k = self.populations[self.circuits.index(fewest[0])]
        spikes = rows[best][f"spikes@{key}"]
        if not np.isfinite(spikes):
            return (
                f"No circuit stays within {key} of the linear loop at up to "
                f"{self.neurons[-1]:,} neurons per population."
            )
        verb = "is" if best in fewest else "is not"
        which = (
            f"The fewest-neuron linear circuit, {fewest[0]} ({k} neuron{'s' * (k > 1)}),"
            if len(fewest) == 1
            else f"A fewest-neuron linear circuit (of {', '.join(fewest)}: {k} neurons each)"
        )
        text = (
            f"{which} {verb} the cheapest in spikes: within {key} of the linear loop, {best} "
            f"fires the fewest, {spikes:,.0f} spikes per second with "
            f"{rows[best][f'neurons@{key}']:,.0f} neurons in all"
        )
        others = [n for n in fewest if n != best]
        if others:
            times = ", ".join(f"{n} {rows[n][f'spikes@{key}'] / spikes:.1f}" for n in others)
            text += f"; the other fewest-neuron ones fire this many times as many: {times}"
        return text + "."

    def peak_correlation(self) -> float:
        """Spearman's correlation of ``peak`` with the median neurons per population (or nan)."""
        from scipy.stats import spearmanr

        n = np.median(self.needed(self.tolerances[0])[0], axis=1)
        n = np.where(np.isfinite(n), n, 10.0 * self.neurons[-1])  # above every finite one
        if len(n) < 3 or np.ptp(n) == 0 or np.ptp(self.peak) == 0:
            return float("nan")
        return float(spearmanr(self.peak, n).statistic)

    def summary(self) -> dict:
        """The sweep as plain JSON types (``inf`` as ``null``): ``symctl spiking``'s ``spiking.json``."""

        def num(x):
            return None if not np.isfinite(x) else float(x)

        rows = []
        for r in self.table():
            c = self.circuits.index(r["circuit"])
            cost = {
                key: {
                    "neurons_per_population": num(r[f"N@{key}"]),
                    "range": [num(x) for x in r[f"N@{key} range"]],
                    "neurons": num(r[f"neurons@{key}"]),
                    "spikes_per_second": num(r[f"spikes@{key}"]),
                }
                for key in (f"{100 * t:g}%" for t in self.tolerances)
            }
            rows.append(
                {
                    **{k: r[k] for k in ("circuit", "populations", "peak")},
                    "deviation": self.deviation[c].tolist(),
                    "spikes_per_second": self.spikes[c].tolist(),
                    "cost": cost,
                }
            )
        rho = self.peak_correlation()
        out = {
            "neurons": list(self.neurons),
            "seeds": self.seeds,
            "tolerances": list(self.tolerances),
            "circuits": rows,
            "ranking": {"neurons": list(self.ranking()), "spikes": list(self.ranking("spikes"))},
            "peak_correlation": num(rho),
            "fewest_neurons_cheapest": self.fewest_neurons_cheapest(),
            "finding": self.finding(),
            "atlas_classes": list(self.atlas_classes),
        }
        if self.atlas_classes:
            out["atlas_fewest_neurons_cheapest"] = self.fewest_neurons_cheapest(self.atlas_classes)
            out["atlas_finding"] = self.finding(self.atlas_classes)
        return out

    def plot(self):
        """Deviation against population size, and spikes against neurons: a Figure."""
        from symctl.plotting.spiking import spiking_cost_plot

        return spiking_cost_plot(self)


def _circuits(source, circuits) -> tuple[Gains, dict[str, Circuit], list[str]]:
    """The gains, the named circuits of ``source`` and which of them are atlas classes."""
    if isinstance(source, Gains):
        if not isinstance(circuits, Mapping) or not circuits:
            raise ParameterError("circuits: with gains, give a dict of circuits by name")
        return source, dict(circuits), []
    gains = getattr(source, "gains", None)
    if not isinstance(gains, Gains) or not hasattr(source, "circuits"):
        raise SymctlTypeError(
            f"source: expected a Derivation (derive_paper(), derive(model)) or Gains, got "
            f"{type(source).__name__}"
        )
    found = {k: r.firing.circuits[0] for k, r in source.circuits.items() if r.firing is not None}
    atlas = [c.circuit_class.label for c in source.candidates or ()]
    found.update((c.circuit_class.label, c.circuit) for c in source.candidates or ())
    if circuits is None:
        return gains, found, atlas
    names = [circuits] if isinstance(circuits, str) else list(circuits)
    bad = [n for n in names if n not in found]
    if bad or not names:
        raise ParameterError(f"circuits: expected some of {list(found)}, got {bad or names}")
    return gains, {n: found[n] for n in names}, [n for n in atlas if n in names]


def _runs(gains, circuit, name, n, seeds, steps, disturbance) -> list[dict]:
    """Every seed of one circuit at one size (a worker's task)."""
    out = []
    for seed in seeds:
        r = spiking_response(
            gains, circuit, n_neurons=n, rng=seed, steps=steps, disturbance=disturbance
        )
        out.append(
            {
                "circuit": name,
                "n": n,
                "seed": seed,
                "deviation": r.deviation,
                "spikes": r.spikes_per_second,
                "peak": max(r.radius.values()) / RADIUS_MARGIN,
            }
        )
    return out


def _valid(rec) -> bool:
    """A record as :func:`_runs` writes it (the file may have been edited or cut)."""
    if not isinstance(rec, dict) or not isinstance(rec.get("circuit"), str):
        return False
    ints = all(isinstance(rec.get(k), int) and not isinstance(rec[k], bool) for k in ("n", "seed"))
    floats = all(isinstance(rec.get(k), float) for k in ("deviation", "spikes", "peak"))
    return ints and floats


def _key(rec) -> str:
    return f"{rec['circuit']}|{rec['n']}|{rec['seed']}"


def _header(gains, circuits, steps, disturbance) -> dict:
    """Names the sweep: a digest of the plant, the circuits' edges and the loop's input."""
    A, B = (np.asarray(m, dtype=float).tolist() for m in _plant(None, gains).numeric())
    text = json.dumps(
        [A, B, {k: [list(e) for e in _edges(c)] for k, c in circuits.items()}, steps],
        sort_keys=True,
    ) + repr(np.asarray(disturbance, dtype=float).tolist())
    return {
        "format": FORMAT,
        "sweep": "spiking_cost",
        "digest": hashlib.sha256(text.encode()).hexdigest(),
    }


def spiking_cost(
    source,
    *,
    circuits=None,
    neurons=NEURONS,
    seeds: int = 10,
    tolerances=TOLERANCES,
    steps: int | None = None,
    disturbance=1.0,
    workers: int = 1,
    scheduler: str | None = None,
    checkpoint=None,
    progress: Callable[[int, int], None] | None = None,
) -> SpikingCost:
    """What spikes cost each circuit of a controller: a sweep of population sizes and seeds.

    Each circuit runs through :func:`~symctl.spiking_response` at every size and seed.

    Parameters
    ----------
    source : Derivation or Gains
        A derivation: its named circuits (the first realization of each) and every class
        ``circuits_for`` lists; or gains, with ``circuits`` a dict.
    circuits : list of str or dict of str to Circuit, optional
        The names to run (default all), or with gains the circuits by name.
    neurons : sequence of int
        Population sizes, each in ``[1, MAX_POPULATION]``.
    seeds : int
        Seeds per size, ``0 .. seeds - 1``.
    tolerances : sequence of float
        Deviations in ``(0, 1)`` the cost is read at.
    steps, disturbance
        As in :func:`~symctl.spiking_response`.
    workers, scheduler : int, str
        Local worker processes (1: this process), or a dask scheduler's address.
    checkpoint : path, optional
        A JSON-lines file of finished runs to resume from (one of another sweep is refused).
    progress : callable, optional
        Called with ``(done, total)`` runs.

    Returns
    -------
    SpikingCost

    Raises
    ------
    MissingDependencyError
        nengo is not installed (``pip install symctl[spiking]``).
    ParameterError, SymctlTypeError
        A size out of range or repeated, ``seeds < 1``, a tolerance outside ``(0, 1)``, an
        unknown circuit, another sweep's checkpoint, another ``source``; as ``spiking_response``.

    Examples
    --------
    >>> import symctl
    >>> cost = symctl.spiking_cost(symctl.derive_paper(), circuits=["ifp", "A16"],
    ...                            neurons=(10, 100), seeds=2)
    >>> sorted(cost.ranking()), cost.populations
    (['A16', 'ifp'], (1, 4))
    """
    gains, found, atlas = _circuits(source, circuits)
    if isinstance(neurons, int | str) or not len(neurons):
        raise ParameterError(f"neurons: expected a list of population sizes, got {neurons!r}")
    sizes = sorted(bounded_int(n, "neurons", 1, MAX_POPULATION) for n in neurons)
    if len(set(sizes)) < len(sizes):
        raise ParameterError(f"neurons: sizes repeat in {list(neurons)}")
    seeds = bounded_int(seeds, "seeds", 1, 10_000)
    tols = tuple(float(t) for t in tolerances)
    if not tols or not all(0 < t < 1 for t in tols):
        raise ParameterError(f"tolerances: expected numbers in (0, 1), got {list(tolerances)}")
    workers, scheduler = pool_options(workers, scheduler)
    header = _header(gains, found, steps, disturbance)  # refuses symbolic weights (_edges)
    pool = open_pool(workers, scheduler)
    try:
        store = Checkpoint(checkpoint, header, _key, _valid)
        total = len(found) * len(sizes) * seeds
        tasks = []
        for name, c in found.items():
            for n in sizes:
                todo = [s for s in range(seeds) if f"{name}|{n}|{s}" not in store.done]
                if todo:
                    tasks.append((gains, c, name, n, todo, steps, disturbance))
        done = total - sum(len(t[4]) for t in tasks)
        if progress:
            progress(done, total)
        for records in pool.map(_runs, tasks):
            store.add(records)
            done += len(records)
            if progress:
                progress(done, total)
    finally:
        pool.close()
    names = list(found)
    shape = (len(names), len(sizes), seeds)
    runs = [store.done[f"{c}|{n}|{s}"] for c in names for n in sizes for s in range(seeds)]
    return SpikingCost(
        tuple(names),
        tuple(found[c].n_neurons for c in names),
        tuple(store.done[f"{c}|{sizes[0]}|0"]["peak"] for c in names),
        tuple(sizes),
        seeds,
        tols,
        np.array([r["deviation"] for r in runs]).reshape(shape),
        np.array([r["spikes"] for r in runs]).reshape(shape),
        tuple(atlas),
    )
