"""docs/saving.md: its examples run as written (derive, save and load)."""

from __future__ import annotations

import doctest
from pathlib import Path

PAGE = Path(__file__).resolve().parents[2] / "docs" / "saving.md"


def test_the_save_and_load_page_runs_as_written():
    result = doctest.testfile(
        str(PAGE), module_relative=False, optionflags=doctest.ELLIPSIS, verbose=False
    )
    assert result.attempted >= 10 and result.failed == 0
