"""Every public name is documented in numpydoc form, with an example that runs on its own.

The doctests themselves run in the suite (``--doctest-modules``), each in a fresh
namespace (the repository's ``conftest.py``), so an example that borrows its
module's imports fails as it would pasted into a fresh interpreter.
"""

from __future__ import annotations

import inspect

import pytest

import symctl

NAMES = [n for n in symctl.__all__ if n != "z"]  # z is a SymPy Symbol: its docstring is SymPy's


def _doc(name: str) -> str:
    return inspect.getdoc(getattr(symctl, name)) or ""


@pytest.mark.parametrize("name", NAMES)
def test_public_name_has_an_example(name):
    doc = _doc(name)
    assert "Examples\n--------" in doc and ">>> " in doc.partition("Examples\n--------")[2], name


@pytest.mark.parametrize("name", NAMES)
def test_public_name_has_numpydoc_sections(name):
    obj, doc = getattr(symctl, name), _doc(name)
    if isinstance(obj, type) and issubclass(obj, BaseException):
        return  # an exception's example is its documentation
    if inspect.isfunction(obj):
        assert "Parameters\n----------" in doc, name
        assert "Returns\n-------" in doc, name
    else:
        assert "Parameters\n----------" in doc or "Attributes\n----------" in doc, name
