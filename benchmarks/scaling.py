"""Time and peak memory of every step of ``symctl paper`` against the net delay T, beside the previous method.

Each case runs in its own process (benchmarks/_scaling_case.py): ``derive_paper``
at net delay T (sensor_delay = T // 2, actuator_delay = T - T // 2), timed step
by step through its ``progress`` callback (plant, delays, LQR, G(z),
factorization, simulation, realizations, compatibility), then
``PaperResults.write`` (results.json, figures, documents, pdflatex): exactly
what ``symctl paper`` does. The same case runs on the previous method: the
package as of revision ``--baseline`` (default the last commit before the
derivation's scaling work), extracted from git into a temporary folder and put
first on ``PYTHONPATH``, with its T <= 8 limit lifted; a baseline case past
``--cap`` seconds is stopped and the larger T are not tried.

Also: the general realization of the order-n controller with a fully symbolic
n x n P (build and exact proof) against n, new and previous; the MIMO
controller against the number of inputs m is benchmarks/mimo.py (run last,
unless --no-mimo). Last, the fitted growth exponent of each step (least-squares
slope of log time against log T over the cases above 10 ms).

Run:  python benchmarks/scaling.py [--T 1-20] [--cap 300] [--max-n 6] [--baseline REV]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
BASELINE = "43dc9c6"  # main before the derivation's rewrite (T = 10: 106 s, 1.3 GB)
STEPS = (
    "plant",
    "delays",
    "LQR",
    "G(z)",
    "factorization",
    "simulation",
    "realizations",
    "compatibility",
    "json",
    "figures",
    "documents",
    "pdflatex",
)
SHORT = {
    "factorization": "factor",
    "simulation": "simul",
    "realizations": "realiz",
    "compatibility": "compat",
    "documents": "docs",
    "pdflatex": "pdf",
}
TARGETS = {2: 8.0, 6: 15.0, 10: 30.0, 20: 120.0}  # targets of symctl paper, seconds
MEMORY_TARGET_MB = 1024.0


def extract(rev: str, into: Path) -> Path | None:
    """The ``symctl`` package of revision ``rev`` under ``into`` (None without git or the rev)."""
    try:
        blob = subprocess.run(
            ["git", "-C", str(REPO), "archive", "--format=tar", rev, "symctl"],
            capture_output=True,
            check=True,
        ).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    into.mkdir(parents=True, exist_ok=True)
    path = into / "tar"
    path.write_bytes(blob)
    with tarfile.open(path) as tar:
        tar.extractall(into, filter="data")
    return into


def run(args: list[str], root: Path, cap: float) -> tuple[dict, float, bool]:
    """``({step: (s, MB)}, wall seconds, finished)`` of one case with ``root`` first on the path."""
    env = {**os.environ, "PYTHONPATH": f"{root}{os.pathsep}{os.environ.get('PYTHONPATH', '')}"}
    start = time.perf_counter()
    proc = subprocess.Popen(
        [sys.executable, str(HERE / "_scaling_case.py"), *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        env=env,
    )
    try:
        out, _ = proc.communicate(timeout=cap)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, _ = proc.communicate()
        finished = False
    else:
        finished = proc.returncode == 0
        if not finished:
            out += "\n" + json.dumps({"error": True})
    got: dict = {}
    for line in filter(None, out.splitlines()):
        item = json.loads(line)
        if "step" in item:
            got[item["step"]] = (item["s"], item["mb"])
        else:
            got.update(item)
    return got, time.perf_counter() - start, finished


def slope(points) -> float | None:
    pts = [(x, t) for x, t in points if t > 0.01]
    if len({x for x, _ in pts}) < 2:
        return None
    xs, ts = zip(*pts, strict=True)
    return float(np.polyfit(np.log(xs), np.log(ts), 1)[0])


def parse_range(text: str) -> list[int]:
    out: list[int] = []
    for part in text.split(","):
        lo, _, hi = part.partition("-")
        out += list(range(int(lo), int(hi or lo) + 1))
    return out


def paper_table(rows: dict, before: dict) -> None:
    names = [SHORT.get(s, s) for s in STEPS]
    w = 7
    head = " | ".join(f"{n:>{w}}" for n in names)
    print("symctl paper (derive_paper + write), seconds per step; total wall time and peak RSS")
    print(f"{'T':>3} | {head} | {'total':>7} | {'before':>7} | {'MB':>5} | {'before':>6} | pdf")
    print("-" * (6 + (w + 3) * len(names) + 46))
    for T, (got, wall, ok) in rows.items():
        cells = " | ".join(f"{got[s][0]:{w}.2f}" if s in got else f"{'-':>{w}}" for s in STEPS)
        mb = max((v[1] for k, v in got.items() if k in STEPS), default=float("nan"))
        b = before.get(T)
        if b is None:
            bt, bm = f"{'-':>7}", f"{'-':>6}"
        elif b[2]:
            bm_value = max(v[1] for k, v in b[0].items() if k in STEPS)
            bt, bm = f"{b[1]:7.1f}", f"{bm_value:6.0f}"
        else:
            bm_value = max((v[1] for k, v in b[0].items() if k in STEPS), default=float("nan"))
            bt = f"{'failed' if b[0].get('error') else '> cap':>7}"
            bm = f"{bm_value:6.0f}"
        total = f"{wall:7.1f}" if ok else f"{'failed' if got.get('error') else '> cap':>7}"
        pdf = "yes" if got.get("pdf") else "no"
        print(f"{T:>3} | {cells} | {total} | {bt} | {mb:5.0f} | {bm} | {pdf}", flush=True)
    fits = []
    for s in STEPS:
        k = slope([(T, got[s][0]) for T, (got, _, _) in rows.items() if s in got])
        fits.append(f"{'-':>{w}}" if k is None else f"{k:{w}.2f}")
    k = slope([(T, wall) for T, (_, wall, ok) in rows.items() if ok])
    kb = slope([(T, b[1]) for T, b in before.items() if b[2]])
    print(
        f"{'exp':>3} | {' | '.join(fits)} | {'-' if k is None else f'{k:7.2f}':>7} | "
        f"{'-' if kb is None else f'{kb:7.2f}':>7}"
    )
    last = max((T for T, (_, _, ok) in rows.items() if ok), default=None)
    if last is not None:
        got = rows[last][0]
        total = sum(got[s][0] for s in STEPS if s in got)
        ranked = sorted((s for s in STEPS if s in got), key=lambda s: -got[s][0])
        print(
            f"where the time goes at T = {last} ({total:.1f} s in the steps): "
            + ", ".join(f"{s} {100 * got[s][0] / total:.0f}%" for s in ranked[:5])
        )
    verdicts = []
    for T, target in TARGETS.items():
        if T in rows:
            got, wall, ok = rows[T]
            mb = max((v[1] for k, v in got.items() if k in STEPS), default=float("inf"))
            good = ok and wall < target and mb < MEMORY_TARGET_MB and got.get("pdf")
            verdicts.append(f"T = {T}: {wall:.1f} s < {target:g} s {'met' if good else 'NOT met'}")
    print("targets (time, peak < 1 GB, PDF): " + "; ".join(verdicts))


def before_table(before: dict, rev: str) -> None:
    """The previous method's seconds per step, where its case ran (the steps it finished)."""
    names = [SHORT.get(s, s) for s in STEPS]
    w = 7
    print(f"before ({rev}): seconds per step, and the peak RSS of the case")
    print(f"{'T':>3} | " + " | ".join(f"{n:>{w}}" for n in names) + f" | {'MB':>5}")
    print("-" * (6 + (w + 3) * len(names) + 8))
    for T, (got, _, _) in before.items():
        cells = " | ".join(f"{got[s][0]:{w}.2f}" if s in got else f"{'-':>{w}}" for s in STEPS)
        mb = max((v[1] for k, v in got.items() if k in STEPS), default=float("nan"))
        print(f"{T:>3} | {cells} | {mb:5.0f}")


def checker_table(rows: dict, before: dict) -> None:
    print("general realization of the order-n controller with a fully symbolic n x n P")
    print(
        f"{'n':>3} | {'build':>8} | {'prove':>8} | {'MB':>5} | {'before build':>12} | {'prove':>8}"
    )
    print("-" * 60)

    def cells(entry, w1, w2):
        if entry is None:
            return f"{'-':>{w1}} | {'-':>{w2}}"
        got, _, ok = entry
        b = f"{got['build'][0]:{w1}.3f}" if "build" in got else f"{'> cap':>{w1}}"
        p = f"{got['prove'][0]:{w2}.3f}" if ok and "prove" in got else f"{'> cap':>{w2}}"
        return f"{b} | {p}"

    for n, entry in rows.items():
        mb = max((v[1] for v in entry[0].values() if isinstance(v, tuple)), default=float("nan"))
        print(f"{n:>3} | {cells(entry, 8, 8)} | {mb:5.0f} | {cells(before.get(n), 12, 8)}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--T", default="1-20", help="net delays, e.g. 1-20 or 2,6,10,20")
    parser.add_argument("--cap", type=float, default=300.0, help="time cap of one case [s]")
    parser.add_argument("--baseline-cap", type=float, default=150.0, help="cap of a baseline case")
    parser.add_argument("--max-n", type=int, default=6, help="the symbolic-P realization")
    parser.add_argument("--baseline", default=BASELINE, help="git revision of the previous method")
    parser.add_argument("--no-mimo", action="store_true", help="skip benchmarks/mimo.py")
    args = parser.parse_args()
    load = os.getloadavg()
    start = time.perf_counter()
    print(
        f"{os.cpu_count()} cores, load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}; "
        f"cap {args.cap:g} s per case (baseline {args.baseline_cap:g} s)\n"
    )
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        old = extract(args.baseline, tmp / "before")
        if old is None:
            print(f"(no baseline: git revision {args.baseline} not available)\n")
        rows, before = {}, {}
        for T in parse_range(args.T):
            rows[T] = run(["paper", str(T), str(tmp / f"new{T}")], REPO, args.cap)
            capped = any(not b[2] and not b[0].get("error") for b in before.values())
            if old is not None and not capped:  # an error (its pdflatex) still times the steps
                before[T] = run(["paper", str(T), str(tmp / f"old{T}")], old, args.baseline_cap)
        paper_table(rows, before)
        print()
        if before:
            before_table(before, args.baseline)
            print()
        n_rows, n_before = {}, {}
        for n in range(2, args.max_n + 1):
            n_rows[n] = run(["checker", str(n)], REPO, args.cap)
            if old is not None and (not n_before or all(b[2] for b in n_before.values())):
                n_before[n] = run(["checker", str(n)], old, args.baseline_cap)
        checker_table(n_rows, n_before)
    print(
        "\nwall time and peak RSS of a fresh process per case (imports included in 'total');\n"
        "a step's MB is the peak RSS while it ran; figures are drawn in worker processes,\n"
        "whose memory is not counted; '> cap': stopped at the cap; 'failed': an error (the\n"
        "baseline's pdflatex from T = 8: 'Dimension too large'); 'before': the same case\n"
        f"on revision {args.baseline}. exp: slope of log time against log T (or n).\n"
        f"total {time.perf_counter() - start:.0f} s"
    )
    if not args.no_mimo:
        print()
        subprocess.run([sys.executable, str(HERE / "mimo.py")], check=False)


if __name__ == "__main__":
    main()
