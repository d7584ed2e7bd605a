"""Doctests run in a fresh namespace: an Examples block must import what it uses.

pytest gives a module's doctests the module's globals, so an example that forgets
an import still passes there but fails when pasted into a fresh interpreter.
Emptying the namespace makes every doctest self-contained.
"""

from __future__ import annotations

from _pytest.doctest import DoctestItem


def pytest_collection_modifyitems(items):
    for item in items:
        if isinstance(item, DoctestItem):
            item.dtest.globs = {"__name__": "__main__"}
