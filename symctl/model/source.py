"""A model file's text: parsed by :mod:`tomllib`, with the line of every key (:func:`key_lines`,
as :mod:`tomllib` does not say where a value is), so an error says ``m.toml:12: states[0].rhs:``.

>>> from symctl.model.source import Source
>>> src = Source.from_text('[model]\\nname = "m"\\n[[states]]\\nname = "x"\\n', "m.toml")
>>> src.line("states[0].name"), src.line("model")
(4, 1)
"""

from __future__ import annotations

import difflib
import re
import tomllib
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from symctl.errors import ModelFileError, SymctlTypeError

__all__ = ["MAX_FILE_BYTES", "Source", "key_lines"]

MAX_FILE_BYTES = 1_000_000  # largest model file read

_HEADER = re.compile(r"^\s*(\[\[?)\s*([^\]]+?)\s*\]\]?\s*(#.*)?$")
_KEY = re.compile(
    r'^\s*((?:[A-Za-z0-9_-]+|"[^"]*"|\'[^\']*\')(?:\s*\.\s*(?:[A-Za-z0-9_-]+|"[^"]*"))*)\s*='
)
_INLINE_KEY = re.compile(r'[{,]\s*([A-Za-z0-9_-]+|"[^"]*")\s*=')


def _split(dotted: str) -> list[str]:
    return [p.strip().strip("\"'") for p in re.findall(r'"[^"]*"|\'[^\']*\'|[^.]+', dotted)]


def key_lines(text: str) -> dict[str, int]:
    """The line (1-based) of every table and key, by dotted path (``states[0].rhs``).

    >>> from symctl.model.source import key_lines
    >>> lines = key_lines('[parameters]\\ntau = { value = 1, unit = "s" }\\n')
    >>> lines["parameters.tau"], lines["parameters.tau.unit"]
    (2, 2)
    """
    out: dict[str, int] = {}
    table: list[str] = []
    counts: dict[str, int] = {}
    for number, line in enumerate(text.splitlines(), start=1):
        header = _HEADER.match(line)
        if header and not _KEY.match(line):
            parts = _split(header.group(2))
            if header.group(1) == "[[":
                base = ".".join(parts)
                index = counts.get(base, 0)
                counts[base] = index + 1
                parts = [*parts[:-1], f"{parts[-1]}[{index}]"]
            table = _resolve(parts, counts)
            out.setdefault(".".join(table), number)
            continue
        key = _KEY.match(line)
        if key:
            path = [*table, *_split(key.group(1))]
            out.setdefault(".".join(path), number)
            rest = line[key.end() :]
            for inner in _INLINE_KEY.findall(rest):
                out.setdefault(".".join([*path, inner.strip("\"'")]), number)
    return out


def _resolve(parts: list[str], counts: dict[str, int]) -> list[str]:
    """Index the arrays of tables that a header's path goes through (their latest item)."""
    out: list[str] = []
    for part in parts:
        plain = part.split("[", 1)[0]
        prefix = ".".join([*out, plain]) if "[" not in part else None
        if prefix is not None and prefix in counts and counts[prefix] > 0:
            out.append(f"{plain}[{counts[prefix] - 1}]")
        else:
            out.append(part)
    return out


@dataclass(frozen=True)
class Source:
    """A parsed model file: its ``data`` (:func:`tomllib.loads`), ``path``, the ``lines`` of its
    keys (:func:`key_lines`) and its ``text``."""

    data: dict
    path: str
    lines: dict = field(repr=False)
    text: str = field(repr=False, default="")

    @classmethod
    def from_text(cls, text: str, path: str = "<text>") -> Source:
        """Parse TOML text; a syntax error is a :class:`~symctl.errors.ModelFileError` with its line."""
        if not isinstance(text, str):
            raise SymctlTypeError(f"text: expected a string, got {type(text).__name__}")
        if len(text.encode("utf-8", "surrogatepass")) > MAX_FILE_BYTES:
            raise ModelFileError(f"larger than {MAX_FILE_BYTES} bytes", path=path)
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            message = str(exc)
            found = re.search(r"\(at line (\d+), column \d+\)", message)
            line = int(found.group(1)) if found else None
            problem = re.sub(r"\s*\(at line \d+, column \d+\)", "", message)
            raise ModelFileError(f"not valid TOML: {problem}", path=path, line=line) from None
        return cls(data, path, key_lines(text), text)

    @classmethod
    def from_path(cls, path) -> Source:
        """Read a file (UTF-8) and parse it."""
        if not isinstance(path, str | Path):
            raise SymctlTypeError(f"path: expected a path, got {type(path).__name__}")
        p = Path(path)
        try:
            too_large = p.stat().st_size > MAX_FILE_BYTES
            text = "" if too_large else p.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            raise ModelFileError("not UTF-8 text", path=str(p)) from None
        except OSError as exc:
            raise ModelFileError(f"cannot read it ({exc.strerror or exc})", path=str(p)) from None
        if too_large:
            raise ModelFileError(f"larger than {MAX_FILE_BYTES} bytes", path=str(p))
        return cls.from_text(text, str(p))

    def line(self, dotted: str) -> int | None:
        """The line of a key, or of the nearest enclosing table that has one."""
        parts = dotted.split(".")
        first = self.lines.get(dotted) or self.lines.get(f"{dotted}[0]")  # an array of tables
        if first is not None:
            return first
        while parts:
            found = self.lines.get(".".join(parts))
            if found is not None:
                return found
            last = parts.pop()
            if "[" in last:  # an item of an inline array: its key's line
                parts.append(last.split("[", 1)[0])
        return None

    def error(self, dotted: str, problem: str) -> ModelFileError:
        """The error for a field: file, line, field and problem in one line."""
        return ModelFileError(problem, path=self.path, line=self.line(dotted), field=dotted)

    def check_keys(self, table: dict, allowed: Iterable[str], where: str) -> None:
        """Refuse a key that is not ``allowed``, suggesting the nearest valid one."""
        allowed = list(allowed)
        for key in table:
            if key not in allowed:
                near = difflib.get_close_matches(key, allowed, n=1, cutoff=0.5)
                hint = f"did you mean {near[0]!r}?" if near else f"valid keys: {', '.join(allowed)}"
                raise self.error(f"{where}.{key}" if where else key, f"unknown key {key!r}; {hint}")
