"""Every figure of the report: time to make and save it, its printed size and smallest font.

For the paper at T = 2 and T = 6 (``derive_paper``) and for ``examples/antagonist.toml``
(``derive``): the derivation once, then each figure of the report made
(``PaperResults.figure``) and saved as the report saves it (``symctl.report.figures.save``:
PDF, SVG and PNG, into a scratch folder), one after the other in this process, the
text-measure cache (``symctl.plotting.common.text_size``) emptied before each, as a figure
worker starts. Times are CPU seconds of this process, which does all the drawing. The
machine this runs on is shared: its wall times (printed per case) vary two- or threefold
from run to run; CPU times vary less, but a busy machine (shared cores and caches) still
makes them up to twice as long, so compare methods within one run, not across runs.

For each figure as ``derivation.pdf`` prints it (at its natural size, or scaled down to fit
when wider than the text or taller than the text less four lines, as its ``\fitgraphic``
does):
its printed width [in] and scale, its smallest font [pt], and whether
``symctl.plotting.legibility.legibility()`` passes at that scale (else what fails).

Baseline in the same run: each structure figure made once more by the previous method,
which laid every structure out with its text, in one piece and in rows of parts, before it
decided on the overview (the antagonist's 128- and 138-signal block forms): the same
``PaperResults.figure`` with the text-free bound (``page_bound``, which now decides the
overview before any text is measured) letting every structure through; both methods draw
the same figure, so its save time is counted once for both. The baseline runs second, on
a warmer process, so it errs on the fast side. Not in it: the report also printed the
LaTeX of every gain of the general structure to choose which realization to draw (the
antagonist's 372 rational gains: 1.5 s of CPU on a quiet machine, 6 s on a busy one), and
now stops at the first long one.

Run: ``python benchmarks/figures.py`` (2.5 min on 2 quiet cores, 5 min on busy ones;
``--cases T2 T6`` for the paper only).
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path
from unittest import mock

from symctl import derive, derive_paper, load_model
from symctl.plotting import structure
from symctl.plotting.common import text_size
from symctl.plotting.legibility import legibility
from symctl.plotting.style import TEXT_WIDTH
from symctl.report.figures import save

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
TEXT_HEIGHT = 9.43
"""The text height of derivation.tex [in] (letter, 2 cm margins)."""
FIGURE_HEIGHT = TEXT_HEIGHT - 4 * 13.6 / 72
"""\\fitgraphic scales down a figure taller than this [in]: the text less four 11-pt lines."""
CASES = {
    "T2": ("paper T=2", lambda: derive_paper()),
    "T6": ("paper T=6", lambda: derive_paper(sensor_delay=3, actuator_delay=3)),
    "antagonist": ("antagonist", lambda: derive(load_model(EXAMPLES / "antagonist.toml"))),
}


def made_and_saved(res, name: str, out: str | None):
    """``(figure, make s, save s, wall s)``: CPU seconds, then wall, the text measures not cached.

    ``out=None``: the figure is made, not saved.
    """
    text_size.cache_clear()
    w0, t0 = time.perf_counter(), time.process_time()
    fig = res.figure(name)
    t1 = time.process_time()
    if out is not None:
        save(fig, out, name)
    return fig, t1 - t0, time.process_time() - t1, time.perf_counter() - w0


def smallest_font(fig) -> float:
    from matplotlib.text import Text

    sizes = [
        t.get_fontsize() for t in fig.findobj(Text) if t.get_visible() and t.get_text().strip()
    ]
    return min(sizes, default=float("nan"))


def verdict(check) -> str:
    if check:
        return "yes"
    found = (("small", check.small), ("overlaps", check.overlaps), ("clipped", check.clipped))
    fails = [f"{len(v)} {k}" for k, v in found if v]
    if check.too_wide:
        fails.append("too wide")
    return "no: " + ", ".join(fails)


def run(key: str, out: str) -> tuple[list[tuple], str]:
    label, make = CASES[key]
    c0, w0 = time.process_time(), time.perf_counter()
    res = make()
    derive_cpu, derive_wall = time.process_time() - c0, time.perf_counter() - w0
    rows, total, wall, structures, previous = [], 0.0, 0.0, 0.0, 0.0
    for name in res.figure_names():
        fig, t_make, t_save, t_wall = made_and_saved(res, name, out)
        wall += t_wall
        width, height = (float(v) for v in fig.get_size_inches())
        scale = min(1.0, TEXT_WIDTH / width, FIGURE_HEIGHT / height)
        font = smallest_font(fig) * scale
        check = verdict(legibility(fig, scale=scale))
        before = None
        if name.startswith("structure_"):
            with mock.patch.object(structure, "page_bound", lambda *a, **k: True):
                _, b_make, _, _ = made_and_saved(res, name, None)
            before = b_make + t_save  # the same figure (the same bytes): the same save
            structures += t_make + t_save
            previous += before
        total += t_make + t_save
        rows.append((label, name, t_make, t_save, before, width * scale, scale, font, check))
    summary = (
        f"{label}: derivation {derive_cpu:.1f} s (wall {derive_wall:.0f} s); "
        f"{len(rows)} figures {total:.1f} s "
        f"(wall {wall:.0f} s); structure figures "
        f"{structures:.1f} s, by the previous method {previous:.1f} s "
        f"(figures stage by the previous method {total - structures + previous:.1f} s)"
    )
    return rows, summary


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", choices=sorted(CASES), default=list(CASES))
    args = parser.parse_args()
    rows, summaries = [], []
    with tempfile.TemporaryDirectory() as out:
        for key in args.cases:
            case_rows, summary = run(key, out)
            rows += case_rows
            summaries.append(summary)
    head = (
        f"{'case':<11} {'figure':<23} {'make':>5} {'save':>5} {'prev.':>5} {'width':>5} "
        f"{'scale':>5} {'font':>4}  legible"
    )
    print("make, save: CPU s; prev.: make + save by the previous method (structure figures)")
    print("as printed in derivation.pdf: width [in], scale (1: natural size), smallest font [pt]")
    print(head)
    print("-" * len(head))
    for label, name, t_make, t_save, before, width, scale, font, check in rows:
        prev = f"{before:5.2f}" if before is not None else f"{'-':>5}"
        print(
            f"{label:<11} {name:<23} {t_make:5.2f} {t_save:5.2f} {prev} {width:5.2f} "
            f"{scale:5.2f} {font:4.1f}  {check}"
        )
    print()
    for line in summaries:
        print(line)


if __name__ == "__main__":
    main()
