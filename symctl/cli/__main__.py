"""``python -m symctl.cli``: the ``symctl`` command (as the console script)."""

from symctl.cli import run

run()
