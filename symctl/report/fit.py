"""The files of ``symctl fit``: fit.json, predictions.csv, report.md and the figure."""

from __future__ import annotations

from pathlib import Path

from symctl.fitting.traces import Traces
from symctl.report.output import write_json

__all__ = ["write_fit"]


def report_text(result, source: str = "") -> str:
    """The short Markdown report: what was fitted, how well, what is pinned down."""
    lines = [
        "# symctl fit",
        "",
        f"Data: {source}" if source else "",
        f"Circuit class: **{result.circuit_class}** ({result.starts} starts). The fitted "
        "realization implements the controller G exactly "
        f"(check_realization, method {getattr(result.proof, 'method', 'exact')}: "
        f"{result.exact}), so the force and motor-neuron rate are the optimal controller's: "
        "the behaviour did not move while the neurons were fitted.",
        "",
        "```",
        result.table(),
        "```",
        "",
        f"Intervals and bands: {result.uncertainty.method}; a band's half-width is shown as "
        "its RMS over the trace's RMS, the bands step by step are in fit.json (uncertainty). "
        "A neuron whose band is wider than its trace is *not determined by these data*, even "
        "when the recorded neurons pin it down in principle (identifiable).",
    ]
    if len(result.alternatives) > 1:
        lines += ["", "| class | cost |", "|---|---|"]
        lines += [f"| {c} | {cost:.4g} |" for c, cost in result.alternatives]
    lines += ["", f"Circuit:\n\n```\n{result.circuit}\n```", ""]
    return "\n".join(x for x in lines if x is not None) + "\n"


def write_fit(result, folder: Path, *, figures: bool = True, source: str = "") -> list[Path]:
    """Write the fit's files into ``folder``; return their paths."""
    folder = Path(folder)
    out = [write_json(folder / "fit.json", result.to_dict())]
    meta = {"circuit": result.circuit_class, "content": "predicted traces of every neuron"}
    pred = Traces(result.t, result.predict(), meta=meta)
    out.append(pred.to_csv(folder / "predictions.csv"))
    path = folder / "report.md"
    path.write_text(report_text(result, source), encoding="utf-8")
    out.append(path)
    if figures:  # fit.pdf, fit.svg and fit.png, as every figure of a report
        from symctl.report.figures import save

        out += save(result.plot(), folder, "fit")
    return out
