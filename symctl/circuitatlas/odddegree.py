r"""The odd-degree proof: a pattern whose generic fibre has odd degree is universal.

Take a pattern of :math:`3n` entries (:math:`2n` unknowns after the torus normalization,
:math:`2n` equations; :mod:`~symctl.circuitatlas.fibre`) over the field :math:`K = \mathbb{Q}(a,
c)` of the generic target. A lex Groebner basis over :math:`K` in **shape position**, :math:`x_i
- r_i(u)` for every unknown but one, :math:`u`, and :math:`f(u)` monic of degree :math:`D`, says
that for every target outside a proper algebraic set (where a coefficient's denominator
vanishes) the fibre is the :math:`D` points :math:`(r(u_j), u_j)` at the roots of :math:`f`.
Then, with :math:`D` odd:

1. **Simple points.** The discriminant of :math:`f` is nonzero at a rational target
   :math:`t_0` (checked), so almost every target has :math:`D` distinct roots.
2. **A real point.** A real polynomial of odd degree has a real root :math:`u^*`, and
   :math:`r(u^*)` is real at a real target.
3. **Every entry nonzero.** For each unknown the resultant of :math:`f` and :math:`r_i` (and
   :math:`f(0)` for :math:`u`) is nonzero at :math:`t_0` (checked), so almost every target has
   no root where an entry vanishes; the spanning-tree entries are 1.

So the pattern is universal. The variable order is chosen at :math:`t_0` (an unknown whose lex
basis over :math:`\mathbb{Q}` is in shape position); each basis element is checked to vanish on
the fibre at random rational points. An even :math:`D`, no shape position, or more than
:data:`CPU_SECONDS` of CPU (:data:`CPU_SECONDS_ABOVE_3` above order 3) proves nothing (the
proofs run in a child process that stops itself on a CPU timer: SymPy cannot be stopped from
another thread).

>>> from symctl.circuitatlas.pattern import Pattern
>>> from symctl.circuitatlas.odddegree import odd_degree_proof
>>> P = Pattern.from_matrices([[1, 0, 0], [1, 1, 1], [1, 1, 0]], [1, 0, 0], [1, 1, 0])
>>> proof = odd_degree_proof(P)
>>> proof["proved"], proof["degree"]
(True, 3)
"""

from __future__ import annotations

import atexit
import contextlib
import itertools
import json
import os
import random
import select
import signal
import subprocess
import sys
import threading
from pathlib import Path

import sympy as sp

from symctl._util.validate import bounded_number
from symctl.circuitatlas.fibre import _system, coefficient_symbols, solve_at
from symctl.circuitatlas.pattern import Pattern, slot_names

__all__ = ["CPU_SECONDS", "CPU_SECONDS_ABOVE_3", "odd_degree_proof", "proving", "slice_proof"]

CPU_SECONDS = 30  # CPU seconds of one pattern's Groebner bases over Q(a, c), up to order 3
# above order 3 about 50 odd patterns run out any budget: halving it keeps order 4 under 30
# minutes on 2 cores for 5 proofs fewer
CPU_SECONDS_ABOVE_3 = 15

ATTEMPTS = 3  # variable orders tried; choosing them and each try get an equal share of the CPU


def _rationals(rng: random.Random, k: int) -> list[sp.Rational]:
    return [sp.Rational(rng.randint(-(10**4), 10**4), rng.randint(1, 10**4)) for _ in range(k)]


def _draws(seed: int, mask: int) -> random.Random:
    """The random stream of one proof: the fixed values first, then the target and the checks."""
    return random.Random(seed * 7919 + mask)


def _fixed_values(fixed, rng: random.Random) -> dict[int, sp.Integer]:
    """Small nonzero integers for the slots ``fixed``, drawn first from ``rng``."""
    return {k: sp.Integer(rng.choice([-1, 1]) * rng.randint(1, 5)) for k in fixed}


def slice_proof(pattern: Pattern, *, seed: int = 0, tries: int = 8):
    """The odd-degree proof of a pattern above :math:`3n` entries through a slice (the first of
    ``tries`` choices of fixed entries with an odd-degree fibre that proves), or None."""
    n = pattern.n
    tree = set(pattern.tree_slots() or ())
    free = [k for k in pattern.indices if k not in tree]
    rng = random.Random(seed * 104729 + pattern.mask)
    choices = list(itertools.combinations(free, pattern.size - 3 * n))
    rng.shuffle(choices)
    for fixed in choices[:tries]:
        values = _fixed_values(fixed, _draws(seed, pattern.mask))
        a, c = _rationals(rng, n), _rationals(rng, n)
        sol = solve_at(pattern, a, c, fixed=values, rng=rng)
        if sol is not None and sol["degree"] % 2:
            proof = odd_degree_proof(pattern, fixed=fixed, seed=seed)
            if proof and proof["proved"]:
                return proof
    return None


def _shape(basis, unknowns, u):
    """``(f, {x: r(u)})`` when ``basis`` (lex, ``u`` last) is in shape position, else None."""
    if len(basis) != len(unknowns):
        return None
    *rest, f = basis
    if f.free_symbols & set(unknowns) - {u}:
        return None
    r = {}
    for g, x in zip(rest, [v for v in unknowns if v != u], strict=True):
        tail = sp.expand(x - g)
        if tail.free_symbols & set(unknowns) - {u}:
            return None
        r[x] = tail
    return f, r


class _OutOfCPU(Exception):
    pass


@contextlib.contextmanager
def _cpu_limit(seconds: float):
    """Raise :class:`_OutOfCPU` once the block has used ``seconds`` of CPU time."""

    def stop(*_):
        raise _OutOfCPU

    signal.signal(signal.SIGVTALRM, stop)
    signal.setitimer(signal.ITIMER_VIRTUAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_VIRTUAL, 0)


def _orders(unknowns, eqs, t0: dict, seconds: float) -> list[tuple[list, int]]:
    """Lex orders (each unknown last) in shape position at ``t0`` with their degree, smallest
    basis first, found within ``seconds`` of CPU."""
    at = [sp.expand(e.xreplace(t0)) for e in eqs]
    found = []
    try:
        with _cpu_limit(seconds):
            for u in reversed(unknowns):
                rest = [v for v in unknowns if v != u]
                for order in {(*rest, u), (*rest[::-1], u)}:
                    basis = sp.groebner(at, *order, order="lex").exprs
                    shape = _shape(basis, order, u)
                    if shape is not None:
                        size = sum(len(str(g)) for g in basis)
                        degree = int(sp.degree(shape[0], u))
                        found.append((size, str(order), list(order), degree))
    except _OutOfCPU:
        pass
    return [(order, degree) for *_, order, degree in sorted(found)]


def _generic_basis(eqs, orders, params, seconds: float):
    """The lex basis over Q(a, c) in the first of ``orders`` that ends within its CPU time."""
    for order in orders[:ATTEMPTS]:
        try:
            with _cpu_limit(seconds / ATTEMPTS):
                basis = sp.groebner(eqs, *order, order="lex", domain=sp.QQ.frac_field(*params))
        except _OutOfCPU:
            continue
        return order, basis.exprs
    return None


def _prove(
    n: int, mask: int, seed: int, fixed: tuple[int, ...] = (), seconds: float = CPU_SECONDS
) -> dict:
    """The proof of one pattern (module text) as plain data; slots ``fixed`` set from ``seed``."""
    pattern = Pattern(n, mask)
    unknowns, _, values, charpoly, numer = _system(pattern)
    rng = _draws(seed, mask)
    rule = {values[k]: v for k, v in _fixed_values(fixed, rng).items()}
    unknowns = tuple(x for x in unknowns if x not in rule)
    charpoly, numer = ([sp.expand(e.xreplace(rule)) for e in part] for part in (charpoly, numer))
    a, c = coefficient_symbols(n)
    params = (*a, *c)
    eqs = [sp.expand(p - v) for p, v in zip((*charpoly, *numer), params, strict=True)]
    t0 = dict(zip(params, _rationals(rng, 2 * n), strict=True))
    orders = _orders(list(unknowns), eqs, t0, seconds / (ATTEMPTS + 1))
    if not orders:
        return {
            "proved": False,
            "why": "no unknown put the fibre in shape position within its CPU time",
        }
    degree = orders[0][1]
    if degree % 2 == 0:
        return {"proved": False, "why": f"the fibre has even degree {degree}", "degree": degree}
    computed = _generic_basis(
        eqs, [order for order, _ in orders], params, seconds * ATTEMPTS / (ATTEMPTS + 1)
    )
    if computed is None:
        return {"proved": False, "why": f"no basis over Q(a, c) within {seconds:g} CPU s"}
    order, basis = computed
    u = order[-1]
    found = _shape(basis, order, u)
    if found is None or sp.degree(found[0], u) != degree:
        return {"proved": False, "why": "the generic basis is not in shape position"}
    f, r = found
    # every basis element vanishes on the fibre: checked at random points of the unknowns
    for _ in range(2):
        x0 = dict(zip(unknowns, _rationals(rng, len(unknowns)), strict=True))
        at = {p: e.xreplace(x0) for p, e in zip(params, (*charpoly, *numer), strict=True)}
        for g in (f, *(x - ri for x, ri in r.items())):
            if sp.cancel(g.xreplace(x0).xreplace(at)) != 0:
                return {"proved": False, "why": "a basis element failed its check"}
    f0 = sp.Poly(sp.cancel(f.xreplace(t0)), u)
    if sp.discriminant(f0) == 0:
        return {"proved": False, "why": "the eliminant is not squarefree at the rational target"}
    entries = [f0.eval(0)] + [sp.resultant(f0, sp.Poly(ri.xreplace(t0), u)) for ri in r.values()]
    if any(v == 0 for v in entries):
        return {"proved": False, "why": "an entry vanishes at a root at the rational target"}
    return {
        "proved": True,
        "degree": degree,
        "variable": str(u),
        "eliminant": str(f),
        "fixed": {slot_names(n)[k]: int(rule[values[k]]) for k in fixed},
        "target": {str(k): str(v) for k, v in t0.items()},
    }


def odd_degree_proof(
    pattern: Pattern, *, fixed=(), seed: int = 0, cpu_seconds: float | None = None
):
    """The odd-degree proof of ``pattern``'s universality (module text), or None.

    ``fixed``: slots of a bigger pattern set to small nonzero integers (drawn from ``seed``,
    which also draws the rational target and the checks) so that :math:`2n` unknowns remain.
    ``cpu_seconds`` defaults to :data:`CPU_SECONDS` up to order 3, :data:`CPU_SECONDS_ABOVE_3`
    above. Returns ``{"proved": True, "degree", "variable", "eliminant", "target"}``,
    ``{"proved": False, "why"}``, or None when it ran out of time or failed.
    """
    if cpu_seconds is None:
        cpu_seconds = CPU_SECONDS if pattern.n <= 3 else CPU_SECONDS_ABOVE_3
    cpu_seconds = bounded_number(cpu_seconds, "cpu_seconds", 1e-6, 3600)
    request = [pattern.n, pattern.mask, seed, list(fixed), cpu_seconds]
    with proving():
        return _PROVER.ask(request, timeout=10 * cpu_seconds + 60)


@contextlib.contextmanager
def proving():
    """Keep the proving child process for the block's proofs (stopped at the outermost end).

    >>> from symctl.circuitatlas.odddegree import proving
    >>> with proving():
    ...     pass
    """
    with _LOCK:
        _PROVER.holds += 1
    try:
        yield
    finally:
        with _LOCK:
            _PROVER.holds -= 1
            if _PROVER.holds == 0:
                _PROVER.stop()


class _Prover:
    """A child process proving patterns (a JSON line in, one out); killed past its time."""

    def __init__(self):
        self.child = None
        self.holds = 0
        atexit.register(self.stop)

    def _start(self):
        root = str(Path(__file__).resolve().parents[2])
        path = os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")]))
        self.child = subprocess.Popen(
            [sys.executable, "-m", "symctl.circuitatlas.odddegree"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
            env={**os.environ, "PYTHONPATH": path},
        )

    def ask(self, request: list, timeout: float):
        with _LOCK:
            if self.child is None or self.child.poll() is not None:
                self._start()
            try:
                self.child.stdin.write(json.dumps(request) + "\n")
                self.child.stdin.flush()
                ready, _, _ = select.select([self.child.stdout], [], [], timeout)
                line = self.child.stdout.readline() if ready else ""
            except (BrokenPipeError, OSError):
                line = ""
            if not line:
                self.stop()
                return None
            return json.loads(line)

    def stop(self):
        if self.child is not None:
            self.child.kill()
            self.child.wait()
            self.child.stdin.close()
            self.child.stdout.close()
            self.child = None


_PROVER = _Prover()
_LOCK = threading.RLock()


def _serve() -> None:
    """The child: one JSON line out per request line in."""
    sys.setrecursionlimit(10_000)
    for line in sys.stdin:
        n, mask, seed, fixed, seconds = json.loads(line)
        try:
            out = _prove(n, mask, seed, tuple(fixed), seconds)
        except Exception as exc:  # a failure of SymPy's is no proof, and the child goes on
            out = {"proved": False, "why": f"the proof failed: {type(exc).__name__}"}
        print(json.dumps(out), flush=True)


if __name__ == "__main__":
    _serve()
