"""The package's public surface: every name resolves, and importing symctl is cheap."""

from __future__ import annotations

import subprocess
import sys

import pytest

import symctl


def test_every_public_name_resolves():
    for name in symctl.__all__:
        assert getattr(symctl, name) is not None, name
    assert set(symctl.__all__) <= set(dir(symctl))


def test_unknown_names_raise_attribute_error():
    with pytest.raises(AttributeError, match="no_such_name"):
        symctl.no_such_name  # noqa: B018


def test_import_symctl_loads_no_heavy_module():
    heavy = ("sympy", "scipy", "networkx", "control", "matplotlib", "flint")
    code = f"import sys, symctl; print(sorted(m for m in {heavy!r} if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_public_names_are_not_shadowed_by_submodules():
    import importlib
    import pkgutil
    import types

    for info in pkgutil.iter_modules(symctl.__path__):
        importlib.import_module(f"symctl.{info.name}")
    for name in symctl.__all__:
        assert not isinstance(getattr(symctl, name), types.ModuleType), name


def test_latex_module_is_reached_as_an_attribute():
    code = "import symctl; print(symctl.latex.export.__module__)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "symctl.latex"


def test_the_names_once_in_a_modules_all_stay_importable():
    from symctl import ifp_structure
    from symctl.compatibility.equations import structure_equations, structure_latex
    from symctl.fitting.fitmodel import FIXED_CLASSES, fixed_classes
    from symctl.plotting.style import BAND_ALPHA, legend_below
    from symctl.report.figures import MAX_DRAWN_PARTS
    from symctl.report.workers import FigureWorkers

    S = ifp_structure(2)
    assert structure_equations(S) == S.equations() and structure_latex(S) == S.latex()
    assert fixed_classes() == FIXED_CLASSES and 0 < BAND_ALPHA < 1 and MAX_DRAWN_PARTS > 0
    assert callable(legend_below) and callable(FigureWorkers.map)
    import sympy

    from symctl.cli.fit import model_parts
    from symctl.plotting.structure_layout import spread
    from symctl.report.model_json import float_rows, model, plant

    assert model_parts(None)[1:] == (1, 1, (1, 1)) and callable(spread)
    assert float_rows(sympy.eye(2)) == [[1.0, 0.0], [0.0, 1.0]]
    assert callable(model) and callable(plant)
    from symctl.realization.channels import channel_symbols
    from symctl.realization.factorization import section_symbols
    from symctl.report.spec import SYMBOLIC_P_MAX_ORDER, PaperSpec
    from symctl.report.story import COMPACT_LENGTH

    assert channel_symbols(3, 2, 1) == section_symbols(3, 1, 2)
    assert SYMBOLIC_P_MAX_ORDER >= 2 and COMPACT_LENGTH > 0 and callable(PaperSpec)
