"""One case of benchmarks/scaling.py, run in its own process (not a benchmark by itself).

    python benchmarks/_scaling_case.py paper T OUT   derive_paper at net delay T, then write OUT
    python benchmarks/_scaling_case.py checker n     general realization, symbolic n x n P, proof

It imports whichever symctl is first on ``PYTHONPATH`` (the working tree, or
the baseline revision scaling.py extracted), and prints one JSON line per step
as it finishes: ``{"step": name, "s": seconds, "mb": peak RSS during the step}``,
the peak reset before each step (Linux ``/proc/self/clear_refs``).
"""

from __future__ import annotations

import json
import sys
import time


def _reset_peak() -> None:
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:  # not Linux: the peak stays the process's overall peak
        pass


def _peak_mb() -> float:
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


class Steps:
    """A progress callback that times the step it names until the next one starts."""

    def __init__(self) -> None:
        self.name: str | None = None
        self.start = 0.0

    def __call__(self, name: str | None) -> None:
        now = time.perf_counter()
        if self.name is not None:
            print(json.dumps({"step": self.name, "s": now - self.start, "mb": _peak_mb()}))
            sys.stdout.flush()
        _reset_peak()
        self.name, self.start = name, time.perf_counter()


def paper(T: int, out: str) -> None:
    import symctl.derivation.pipeline as pipeline

    pipeline.PAPER_MAX_DELAY = max(pipeline.PAPER_MAX_DELAY, T)  # the baseline stops at 8
    steps = Steps()
    res = pipeline.derive_paper(sensor_delay=T // 2, actuator_delay=T - T // 2, progress=steps)
    steps("json")  # write() names its later steps; the first is results.json
    written = res.write(out, progress=steps)
    steps(None)
    pdf = any(p.name == "derivation.pdf" for p in written)
    print(json.dumps({"pdf": pdf}))


def checker(n: int) -> None:
    import sympy as sp

    from symctl import check_realization, controller_tf, general_realization

    G = controller_tf(n)
    P = sp.Matrix(n, n, sp.symbols(f"p_1:{n + 1}(1:{n + 1})"))
    steps = Steps()
    steps("build")
    R = general_realization(G, P)
    steps("prove")
    assert check_realization(R, G)
    steps(None)


if __name__ == "__main__":
    kind, *rest = sys.argv[1:]
    if kind == "paper":
        paper(int(rest[0]), rest[1])
    elif kind == "checker":
        checker(int(rest[0]))
    else:
        raise SystemExit(f"unknown case {kind!r}")
