"""Pages of the documentation site that are written from the code when the site is built.

When the configuration is read (before Sphinx looks for source files) this extension
writes into ``docs/generated/``:

- ``runs/<name>/``: the output of ``symctl paper`` for each entry of :data:`RUNS`
  (``derivation.tex``/``.pdf``, ``report.md``, ``results.json``, the figures); the runs
  go in parallel;
- ``derivation_<name>.md``: the run's ``report.md`` as a page, with its math, and
  links to the PDF, the LaTeX and ``results.json``;
- ``gallery_<name>.md``: every figure of the run with its caption (the captions of
  ``report.md``), with links to each format written;
- ``api.rst``: the API reference, one autosummary table per stage of the pipeline,
  listing every name of ``symctl.__all__`` (from the one table in ``symctl/__init__.py``);
- ``notebooks/``: copies of ``notebooks/*.ipynb``, which myst-nb executes;
- ``static/mathjax/``: MathJax 3 (from the ``django-static-mathjax`` package, which
  is only MathJax's files), served by the site itself.

A page is rewritten only when its text changes, so that Sphinx re-reads only what
changed. ``-D symctl_site_reuse=1`` keeps the runs of an earlier build (for editing
the site; ``make docs`` always runs them).
"""

from __future__ import annotations

import importlib
import json
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from sphinx.errors import ExtensionError
from sphinx.util import logging

logger = logging.getLogger(__name__)


@dataclass(frozen=True)
class Run:
    """One ``symctl`` run whose output becomes a derivation page and a gallery page."""

    name: str
    title: str
    args: tuple[str, ...]

    @property
    def command(self) -> str:
        return " ".join(("symctl", *self.args, "--out", "DIR"))


RUNS = (
    Run("paper", "the paper's case, T = 2", ("paper", "--formats", "pdf,png,svg")),
    Run(
        "paper_T6",
        "delays of three steps, T = 6",
        ("paper", "--sensor-delay", "3", "--actuator-delay", "3", "--formats", "pdf,png,svg"),
    ),
)
"""The derivations shown on the site: the paper's parameters at T = 2 and at T = 6."""

FORMATS = ("svg", "pdf", "png")
"""Formats of a figure, the first one found shown on the page (vector first)."""

IMAGE = re.compile(r"^!\[(?P<caption>.*)\]\((?P<file>[^)\s]+)\)\s*$")
"""A figure line of ``report.md``: ``![caption](name.png)``."""


def write_if_changed(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` unless it already holds exactly that."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def run_derivations(runs: tuple[Run, ...], folder: Path) -> None:
    """Run every ``symctl`` command of ``runs`` at once, each into ``folder/<name>``."""
    folder.mkdir(parents=True, exist_ok=True)
    started = []
    for run in runs:
        command = [sys.executable, "-m", "symctl.cli", *run.args, "--out", str(folder / run.name)]
        logger.info("symctl_site: %s", " ".join(command[2:]))
        started.append(
            (
                run,
                subprocess.Popen(
                    command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
                ),
            )
        )
    for run, process in started:
        output, _ = process.communicate()
        if process.returncode != 0:
            raise ExtensionError(
                f"{run.command} failed with exit code {process.returncode}:\n{output}"
            )


def figures(report: Path) -> list[tuple[str, str]]:
    """``(name, caption)`` of every figure of ``report`` (a ``report.md``), in its order."""
    found = []
    for line in report.read_text(encoding="utf-8").splitlines():
        match = IMAGE.match(line)
        if match:
            found.append((Path(match["file"]).stem, match["caption"]))
    return found


def _downloads(folder: str, files: list[tuple[str, Path]]) -> str:
    """``{download}`` links to the files that exist, by label."""
    return ", ".join(
        f"{{download}}`{label} <{folder}/{path.name}>`" for label, path in files if path.exists()
    )


def derivation_page(run: Run, out: Path) -> str:
    """The Markdown page of one run's derivation: links, then its ``report.md``."""
    rel = f"runs/{run.name}"
    pdf = out / "derivation.pdf"
    files = [
        ("derivation.pdf", pdf),
        ("derivation.tex", out / "derivation.tex"),
        ("results.json", out / "results.json"),
    ]
    missing = (
        ""
        if pdf.exists()
        else " (`derivation.pdf` was not made: `pdflatex` was not found when the site was built)"
    )
    return "\n".join(
        [
            f"# The derivation: {run.title}",
            "",
            f"Written by `{run.command}` when this site was built, from the code of this version.",
            f"The same derivation as a document to print and its data: {_downloads(rel, files)}{missing}.",
            f"Its figures, with their files, are in the [gallery](gallery_{run.name}.md).",
            "",
            f"```{{include}} {rel}/report.md",
            ":relative-images:",
            ":start-line: 1",
            "```",
            "",
        ]
    )


def gallery_page(run: Run, out: Path) -> str:
    """The Markdown page of one run's figures, each with its caption and its files."""
    rel = f"runs/{run.name}"
    lines = [
        f"# Gallery: {run.title}",
        "",
        f"Every figure of `{run.command}`, drawn when this site was built, with the caption it has in",
        f"the [derivation](derivation_{run.name}.md). Each is written as "
        + ", ".join(f.upper() for f in FORMATS)
        + " where the code writes that format.",
        "",
    ]
    for name, caption in figures(out / "report.md"):
        files = [(fmt.upper(), out / f"{name}.{fmt}") for fmt in FORMATS]
        shown = next((path for _, path in files if path.exists()), None)
        if shown is None:
            raise ExtensionError(f"{rel}/report.md shows {name!r}, but no file of it was written")
        lines += [
            f"## {name}",
            "",
            f"```{{figure}} {rel}/{shown.name}",
            f":name: {run.name}-{name}",
            f":alt: {_plain(caption)}",
            ":width: 100%",
            "",
            caption,
            "```",
            "",
            f"Files: {_downloads(rel, files)}.",
            "",
        ]
    return "\n".join(lines)


def _plain(caption: str) -> str:
    """A caption as alt text: math and emphasis marks left out."""
    return re.sub(r"[$*`\\]", "", caption).replace("{", "").replace("}", "")


def api_page() -> str:
    """The reST page of the API reference: every public name, grouped by stage."""
    import symctl

    table: dict[str, str] = symctl._PUBLIC  # the one table the lazy __all__ is built from
    if set(table) != set(symctl.__all__):
        raise ExtensionError("symctl._PUBLIC and symctl.__all__ disagree")
    groups: dict[str, list[str]] = {}
    for name, module in table.items():
        groups.setdefault(".".join(module.split(".")[:2]), []).append(name)
    title = "API reference"
    lines = [
        title,
        "=" * len(title),
        "",
        "Every public name of symctl (``symctl.__all__``), in the order of the paper's pipeline,",
        "with its documentation (numpydoc) and a self-contained example. Import each name from",
        "``symctl``; the modules named below are where it is defined.",
        "",
        ".. currentmodule:: symctl",
        "",
    ]
    for package, names in groups.items():
        doc = (importlib.import_module(package).__doc__ or "").strip().splitlines()
        heading = f"``{package}``"
        lines += [heading, "-" * len(heading), ""]
        if doc:
            lines += [doc[0], ""]
        documented = []
        for name in names:
            obj = getattr(symctl, name)
            if isinstance(obj, type) or callable(obj):
                documented.append(name)
            else:  # a value (the symbol z): its docstring would be its type's
                kind = f"{type(obj).__module__}.{type(obj).__qualname__}"
                lines += [f"``symctl.{name}``: ``{obj!r}``, an instance of ``{kind}``.", ""]
        if documented:
            lines += [".. autosummary::", "   :toctree: api", "   :nosignatures:", ""]
            lines += [f"   {name}" for name in documented]
            lines.append("")
    return "\n".join(lines)


def copy_notebooks(source: Path, target: Path) -> None:
    """Copy ``source/*.ipynb`` into ``target`` (removing notebooks no longer there)."""
    target.mkdir(parents=True, exist_ok=True)
    wanted = {p.name: p for p in sorted(source.glob("*.ipynb"))}
    for old in target.glob("*.ipynb"):
        if old.name not in wanted:
            old.unlink()
    for name, path in wanted.items():
        write_if_changed(target / name, path.read_text(encoding="utf-8"))


def copy_mathjax(target: Path) -> None:
    """MathJax 3's browser files (``es5/``) into ``target``, from the installed package."""
    import mathjax  # the django-static-mathjax package: MathJax's files, no code

    source = Path(mathjax.__file__).parent / "static" / "mathjax"
    version = json.loads((source / "package.json").read_text(encoding="utf-8"))["version"]
    stamp = target / ".version"
    if stamp.exists() and stamp.read_text(encoding="utf-8") == version:
        return
    shutil.rmtree(target, ignore_errors=True)
    shutil.copytree(source / "es5", target)
    shutil.copy(source / "LICENSE", target / "LICENSE")
    stamp.write_text(version, encoding="utf-8")


def generate(app, config) -> None:
    """Write every generated page (the ``config-inited`` handler, before Sphinx looks for
    source files)."""
    docs = Path(app.confdir)
    gen = docs / "generated"
    runs = gen / "runs"
    copy_mathjax(gen / "static" / "mathjax")
    shutil.rmtree(gen / "api", ignore_errors=True)  # autosummary writes a page per name anew
    write_if_changed(gen / "api.rst", api_page())
    copy_notebooks(docs.parent / "notebooks", gen / "notebooks")
    reuse = str(config.symctl_site_reuse).lower() in ("1", "true", "yes")
    todo = tuple(r for r in RUNS if not (reuse and (runs / r.name / "report.md").exists()))
    if todo:
        run_derivations(todo, runs)
    for run in RUNS:
        write_if_changed(gen / f"derivation_{run.name}.md", derivation_page(run, runs / run.name))
        write_if_changed(gen / f"gallery_{run.name}.md", gallery_page(run, runs / run.name))


TAG = re.compile(r"\\tag\*?\{")
"""An equation number that a display gives itself (``report.md`` numbers its displays)."""


def keep_own_tags(app, doctree) -> None:
    """Displays that number themselves with ``\\tag`` go to MathJax as they are.

    Sphinx wraps a display holding a line break (``\\\\``) in ``split``, where a
    ``\\tag`` is an error; such a display already holds its own environment
    (``aligned``), so it is only delimited, not wrapped (the ``doctree-read`` handler).
    """
    from docutils import nodes

    start, end = app.config.mathjax_display
    for node in doctree.findall(nodes.math_block):
        text = node.astext()
        if TAG.search(text) and not node.get("nowrap"):
            node["nowrap"] = True
            node.children = [nodes.Text(f"{start}{text}{end}")]


def setup(app):
    app.add_config_value("symctl_site_reuse", False, "env", types=frozenset({bool, int, str}))
    app.connect("config-inited", generate)
    app.connect("doctree-read", keep_own_tags)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
