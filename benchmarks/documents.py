"""The documents of ``symctl paper`` at growing delay: do they compile and fit the page?

For each net delay T (split as sensor = ceil(T/2), actuator = floor(T/2)) this runs
``derive_paper``, writes every output with ``PaperResults.write`` (results.json, the
figures, derivation.tex, report.md, derivation.pdf), then runs pdflatex once more on
derivation.tex into a scratch folder to read its log (``write`` keeps only the PDF), and
prints one row:

    T | pages | overfull hboxes | shrunk displays | LaTeX errors | longest report.md line | derive s | write s

"shrunk displays" counts the displays the LaTeX safety net scaled down to the line
(``symctl: shrunk`` in the log); the layout aims at none. Slow (minutes at large T) and
not part of ``make test``:

    python benchmarks/documents.py              # T = 2 4 6 8 10
    python benchmarks/documents.py 2 6 10 20 --no-figures --out /tmp/docs

A T above ``derive_paper``'s limit (``symctl.derivation.pipeline.PAPER_MAX_DELAY``) is run
with the limit raised for this script, and the row says so.
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import symctl.derivation.pipeline as pipeline
from symctl import derive_paper


def _log(out: Path) -> str:
    """The pdflatex log of ``out/derivation.tex`` (one pass, into a scratch folder)."""
    with tempfile.TemporaryDirectory() as scratch:
        subprocess.run(
            [
                "pdflatex",
                "-interaction=nonstopmode",
                f"-output-directory={scratch}",
                "derivation.tex",
            ],
            cwd=out,
            capture_output=True,
            text=True,
            errors="replace",
            timeout=600,
        )
        path = Path(scratch) / "derivation.log"
        return path.read_text(errors="replace") if path.exists() else ""


def run(T: int, out: Path, figures: bool) -> dict:
    raised = T > pipeline.PAPER_MAX_DELAY
    limit = pipeline.PAPER_MAX_DELAY
    if raised:
        pipeline.PAPER_MAX_DELAY = T
    try:
        t0 = time.perf_counter()
        res = derive_paper(sensor_delay=(T + 1) // 2, actuator_delay=T // 2)
        t1 = time.perf_counter()
        error = ""
        try:
            res.write(out, figures=figures)
        except Exception as exc:  # the row reports it
            error = f"{type(exc).__name__}: {exc}"[:70]
            if figures:  # the documents alone, so that the row still measures them
                error = "with figures: " + error + "; written without figures"
                res.write(out, figures=False)
        t2 = time.perf_counter()
    finally:
        pipeline.PAPER_MAX_DELAY = limit
    log = _log(out) if (out / "derivation.tex").exists() else ""
    pages = re.search(r"Output written on .*?\((\d+) pages?", log)
    md = out / "report.md"
    errors = [line for line in log.splitlines() if line.startswith("!")]
    return {
        "T": T,
        "pages": int(pages.group(1)) if pages else 0,
        "overfull": len(re.findall(r"Overfull \\hbox", log)),
        "shrunk": log.count("symctl: shrunk"),
        "errors": len(errors),
        "md": max((len(x) for x in md.read_text().splitlines()), default=0) if md.exists() else 0,
        "derive": t1 - t0,
        "write": t2 - t1,
        "note": (error or (errors[0] if errors else "")) + (" (limit raised)" if raised else ""),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("T", nargs="*", type=int, default=[2, 4, 6, 8, 10])
    ap.add_argument("--no-figures", action="store_true", help="skip the figures (faster)")
    ap.add_argument("--out", type=Path, help="keep the outputs in OUT/T<T> (default: scratch)")
    args = ap.parse_args()
    if shutil.which("pdflatex") is None:
        raise SystemExit("pdflatex is not installed (Debian: apt-get install texlive-latex-base)")
    root = args.out or Path(tempfile.mkdtemp(prefix="symctl-documents-"))
    print(f"outputs in {root}; figures {'off' if args.no_figures else 'on'}")
    head = (
        "T",
        "pages",
        "overfull hboxes",
        "shrunk",
        "errors",
        "max md line",
        "derive s",
        "write s",
        "note",
    )
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for T in args.T:
        r = run(T, root / f"T{T}", figures=not args.no_figures)
        print(
            f"| {r['T']} | {r['pages']} | {r['overfull']} | {r['shrunk']} | {r['errors']} | "
            f"{r['md']} | {r['derive']:.1f} | {r['write']:.1f} | {r['note']} |",
            flush=True,
        )
    if args.out is None:
        shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    main()
