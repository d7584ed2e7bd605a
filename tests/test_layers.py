"""The house's rules, read from the code: one-way imports, drawing apart, small modules.

Every ``import`` in ``symctl/`` is read, at module level or inside a function. The
stages are ranked in the order data flows (the README's Layout section); an
import may go to the same or a lower stage only. The one exception is a
delegation: a method such as ``.draw()``, ``.plot()`` or ``.to_control()`` whose
body is one import of the plotting package (or interop) and one call that hands
the object over (python-control's ``TimeResponseData.plot`` is the model).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import networkx as nx
import pytest

ROOT = Path(__file__).resolve().parent.parent / "symctl"

# lowest first; a module may import from its own rank or below
STAGES = (
    ("symctl.errors", "symctl.symbols"),
    ("symctl._util", "symctl.proof"),
    ("symctl.design",),
    ("symctl.realization",),
    ("symctl.compatibility",),
    ("symctl.neural",),
    ("symctl.spiking",),
    ("symctl.circuitatlas",),
    ("symctl.dalelaw",),
    ("symctl.fitting",),
    ("symctl.latex", "symctl.interop"),
    ("symctl.model",),
    ("symctl.derivation",),
    ("symctl.plotting",),
    ("symctl.report",),
    ("symctl.cli",),
)
DELEGATIONS = {
    "draw",
    "plot",
    "to_control",
    "from_control",
    "to_sympy",
    "from_sympy",
    "to_scipy",
    "from_scipy",
    "to_nengo",
    "to_nest",
    "to_nir",
    # a derivation handed to the report stage, which writes it
    "to_dict",
    "parameters",
    "figure",
    "figure_names",
    "write",
}
DELEGATION_TARGETS = ("symctl.plotting", "symctl.interop", "symctl.report", "symctl.spiking")
MAX_LINES = 720  # "about 700"


def _module_name(path: Path) -> str:
    parts = path.relative_to(ROOT.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {_module_name(p): p for p in sorted(ROOT.rglob("*.py"))}


def _rank(module: str) -> int | None:
    for rank, prefixes in enumerate(STAGES):
        if any(module == p or module.startswith(p + ".") for p in prefixes):
            return rank
    return None


def _resolve(name: str) -> str:
    """The symctl module that ``name`` (a module or ``module.attribute``) lives in."""
    while name not in MODULES and "." in name:
        name = name.rpartition(".")[0]
    return name


class _Imports(ast.NodeVisitor):
    """Every import of a module: ``(target, function or None, delegation?, line)``."""

    def __init__(self, module: str):
        self.module = module
        self.found: list[tuple[str, str | None, bool, int]] = []
        self.stack: list[ast.FunctionDef | ast.AsyncFunctionDef] = []

    def visit_FunctionDef(self, node):
        self.stack.append(node)
        self.generic_visit(node)
        self.stack.pop()

    visit_AsyncFunctionDef = visit_FunctionDef

    def _add(self, target: str, node: ast.AST) -> None:
        func = self.stack[-1] if self.stack else None
        self.found.append(
            (target, func.name if func else None, self._delegation(func), node.lineno)
        )

    @staticmethod
    def _delegation(func) -> bool:
        if func is None or func.name not in DELEGATIONS:
            return False
        body = list(func.body)
        if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
            body = body[1:]  # the docstring
        return len(body) == 2 and isinstance(body[0], ast.Import | ast.ImportFrom)

    def visit_Import(self, node):
        for alias in node.names:
            self._add(alias.name, node)

    def visit_ImportFrom(self, node):
        if node.level:  # relative: symctl uses absolute imports only
            pytest.fail(f"{self.module}:{node.lineno}: relative import")
        for alias in node.names:
            full = f"{node.module}.{alias.name}"
            self._add(full if _resolve(full) in MODULES else node.module, node)


def _imports() -> dict[str, list[tuple[str, str | None, bool, int]]]:
    out = {}
    for module, path in MODULES.items():
        visitor = _Imports(module)
        visitor.visit(ast.parse(path.read_text(), str(path)))
        out[module] = visitor.found
    return out


IMPORTS = _imports()


def _symctl_edges():
    for module, found in IMPORTS.items():
        for target, func, delegation, line in found:
            if target == "symctl" or target.startswith("symctl."):
                yield module, _resolve(target), func, delegation, line


def test_every_module_has_a_stage():
    missing = [m for m in MODULES if m != "symctl" and _rank(m) is None]
    assert not missing, f"modules outside every stage of STAGES: {missing}"


def test_no_import_goes_up_a_stage_except_delegations():
    upward = []
    for module, target, func, delegation, line in _symctl_edges():
        if module == "symctl" or target == "symctl":
            continue  # the package's lazy table names every stage; importing it is checked below
        r_from, r_to = _rank(module), _rank(target)
        if r_to is None or r_from is None or r_to <= r_from:
            continue
        if delegation and target.startswith(DELEGATION_TARGETS):
            continue
        upward.append(f"{module}:{line} ({func or 'module level'}) imports {target}")
    assert not upward, "upward imports:\n" + "\n".join(sorted(set(upward)))


def test_no_module_imports_the_package_root():
    # `from symctl import x` inside the package hides which stage x comes from
    bad = [
        f"{m}:{line}"
        for m, target, _f, _d, line in _symctl_edges()
        if target == "symctl" and m != "symctl"
    ]
    assert not bad, "use the defining module instead of `from symctl import ...`: " + ", ".join(bad)


def test_no_import_cycle_between_modules():
    g = nx.DiGraph()
    for module, target, _func, delegation, _line in _symctl_edges():
        if module != target and module != "symctl" and not delegation:
            g.add_edge(module, target)
    cycles = list(nx.simple_cycles(g))
    assert not cycles, f"import cycles: {cycles}"


def test_matplotlib_is_imported_only_in_plotting():
    bad = {
        f"{m}:{line}"
        for m, found in IMPORTS.items()
        for target, _f, _d, line in found
        if target.split(".")[0] == "matplotlib" and not m.startswith("symctl.plotting")
    }
    assert not bad, f"matplotlib imported outside symctl.plotting: {sorted(bad)}"


@pytest.mark.parametrize("module", sorted(MODULES))
def test_module_is_small(module):
    """Counted as ruff formats it: no formatter pragma packs lines under the limit."""
    text = MODULES[module].read_text()
    assert not re.search(r"#\s*fmt:\s*(skip|off)", text), f"{module}: a fmt pragma packs code"
    lines = len(text.splitlines())
    assert lines <= MAX_LINES, f"{module}: {lines} lines (split it: about 700 at most)"


def test_the_rules_catch_an_upward_import(tmp_path):
    # the checker itself: a design module importing the neural stage is flagged
    visitor = _Imports("symctl.design.fake")
    visitor.visit(ast.parse("def f():\n    from symctl.neural.circuit import Circuit\n"))
    target, func, delegation, _ = visitor.found[0]
    assert _rank(_resolve(target)) > _rank("symctl.design.fake")
    assert (func, delegation) == ("f", False)
    visitor = _Imports("symctl.neural.fake")
    visitor.visit(
        ast.parse(
            'def draw(self):\n    """Doc."""\n    from symctl.plotting import x\n    return x(self)\n'
        )
    )
    assert visitor.found[0][1:3] == ("draw", True)
