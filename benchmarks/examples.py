"""`symctl derive` on every shipped model file, against `symctl paper` in the same run.

For each ``examples/*.toml``: reading and checking the file (``load_model``), the whole
derivation (``derive``), and writing its files without figures or PDF; best of
``--repeat`` runs, in one process after a warm-up (the pipeline's caches, e.g. the
order-2 atlas, are filled once per process, as in a long Jupyter session). Then the
antagonist pair's files once more with its 13 figures (PNG and SVG, drawn in parallel
processes) and the PDF, as ``symctl derive`` writes them.
Baseline in the same run: ``derive_paper()``, the muscle through the paper's API,
which ``examples/muscle.toml`` must match in time (it is the same pipeline) and in
bytes (checked here too). Targets: reading a file under 0.1 s; every SISO example under
10 s; the antagonist pair's derivation and files under 30 s, with the figures and the
PDF too.

Run: ``python benchmarks/examples.py`` (options: ``--repeat``).
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from symctl import derive, derive_paper, load_model

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def best(fn, repeat: int) -> tuple[float, object]:
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return min(times), out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    derive_paper()  # warm-up: the caches of the process
    # derive keeps one derivation per model: emptied before each run, so that it is computed
    t_paper, paper = best(lambda: (derive.cache_clear(), derive_paper())[1], args.repeat)
    rows, full = [], None
    for path in sorted(EXAMPLES.glob("*.toml")):
        t_load, model = best(lambda p=path: load_model(p), args.repeat)
        t_derive, res = best(lambda m=model: (derive.cache_clear(), derive(m))[1], args.repeat)
        with tempfile.TemporaryDirectory() as tmp:
            t_write, _ = best(
                lambda r=res, t=tmp: r.write(Path(t) / "out", figures=False, pdf=False),
                args.repeat,
            )
        if path.stem == "antagonist":
            with tempfile.TemporaryDirectory() as tmp:
                t_full, _ = best(lambda r=res, t=tmp: r.write(Path(t) / "out"), 1)
            full = (t_derive, t_full)
        stages = "all" if res.skipped is None else "no IFP"
        rows.append((path.name, model.plant.n, model.plant.m, stages, t_load, t_derive, t_write))
        if path.stem == "muscle":
            a, b = res.to_dict(), paper.to_dict()
            a["model"]["file"].pop("path"), b["model"]["file"].pop("path")  # the file's name
            same = a == b
    print(
        f"{'model file':<26} {'n':>2} {'m':>2} {'stages':>8} {'read [s]':>9} "
        f"{'derive [s]':>11} {'write [s]':>10}"
    )
    print("-" * 74)
    for name, n, m, stages, a, b, c in rows:
        print(f"{name:<26} {n:>2} {m:>2} {stages:>8} {a:9.3f} {b:11.2f} {c:10.2f}")
    print(f"{'derive_paper() (baseline)':<26} {1:>2} {1:>2} {'all':>8} {'-':>9} {t_paper:11.2f}")
    print(f"examples/muscle.toml results == derive_paper() results: {same}")
    worst_read = max(r[4] for r in rows)
    siso = max(r[5] for r in rows if r[1] == r[2] == 1)
    mimo = max((r[5] + r[6] for r in rows if r[0] == "antagonist.toml"), default=0.0)
    print(
        f"targets: reading < 0.1 s: {worst_read:.3f} s {'met' if worst_read < 0.1 else 'MISSED'}"
        f"; SISO examples < 10 s: {siso:.1f} s {'met' if siso < 10 else 'MISSED'}"
        f"; antagonist derive + write < 30 s: {mimo:.1f} s {'met' if mimo < 30 else 'MISSED'}"
    )
    if full is not None:
        total = sum(full)
        print(
            f"antagonist derive + write with figures and PDF: {full[0]:.1f} + {full[1]:.1f} s"
            f" = {total:.1f} s, < 30 s {'met' if total < 30 else 'MISSED'}"
        )


if __name__ == "__main__":
    main()
