r"""A derivation's ``results.json`` read back: :func:`load_results`.

The symbolic objects are text there, read back by the safe parser (never evaluated); the
model it holds re-creates the whole :class:`~symctl.derivation.Derivation`.
"""

from __future__ import annotations

import itertools
import json
import operator
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from types import MappingProxyType

import numpy as np
import sympy as sp

from symctl._util.parse import MAX_OPERATORS, MAX_TEXT, NAMES, parse_expr
from symctl._util.pickling import CachedState
from symctl.derivation.derivation import Derivation
from symctl.design.ode import exact_value
from symctl.design.tf import DiscreteTF
from symctl.errors import ParameterError, SymctlError, SymctlTypeError
from symctl.model.model import Model
from symctl.model.saved import model_from_dict
from symctl.symbols import T_s, z

__all__ = ["SavedDerivation", "load_results"]

MAX_RESULTS_BYTES = 200_000_000  # the largest results.json load_results reads

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(?:\{[0-9,]+\})?")
_REAL = re.compile(r"^(K|C|L|epsilon|sigma)_")  # the derivation's real symbols
_TOKEN = re.compile(r"\*\*|[-+*/,()\[\]{}]")  # what _split reads: operators and brackets
_BINARY = {"+": operator.add, "-": operator.sub, "*": operator.mul, "/": operator.truediv}


def _symbol(name: str, known: Mapping) -> sp.Symbol:
    if name in known:
        return known[name]
    return sp.Symbol(name, real=True) if _REAL.match(name) else sp.Symbol(name)


def parse_saved(text: str, known: Mapping, argname: str) -> sp.Expr:
    """An expression as ``results.json`` writes it (``sp.sstr``), read by the safe parser.

    A name is a symbol of ``known``, else real for ``K_``, ``C_``, ``epsilon_``, ``sigma_``
    (``K_{0,11}``, a MIMO gain, is one symbol).
    """
    if not isinstance(text, str):
        raise SymctlTypeError(f"{argname}: expected text, got {type(text).__name__}")
    keys: dict[str, str] = {}  # each name of the text -> a placeholder the parser takes

    def placeholder(m: re.Match) -> str:
        word = m.group(0)
        if word in NAMES:  # the parser's own functions and constants, never symbols
            return word
        return keys.setdefault(word, f"_s{len(keys)}")

    plain = _NAME.sub(placeholder, text)
    names = {key: z if word == "z" else _symbol(word, known) for word, key in keys.items()}
    return _parse_long(plain, names, argname)


def _parse_long(text: str, names: Mapping, argname: str) -> sp.Expr:
    """``parse_expr``, on a text beyond its bounds split (at the outer level) into sums,
    products and powers, every piece read by the safe parser."""
    text = text.strip()
    if len(text) <= MAX_TEXT // 2 and sum(text.count(c) for c in "+-*/(") <= MAX_OPERATORS // 2:
        return parse_expr(text, names, argname=argname)
    for ops in (("+", "-"), ("*", "/")):
        parts = _split(text, ops)
        if len(parts) > 1:
            out = None
            for op, piece in parts:
                value = _parse_long(piece, names, argname)
                out = value if out is None else _BINARY[op](out, value)
            return out
    if text.startswith("-"):
        return -_parse_long(text[1:], names, argname)
    power = _split(text, ("**",))
    if len(power) > 1:
        base = _parse_long(power[0][1], names, argname)
        return base ** _parse_long(text[len(power[0][1]) + 2 :], names, argname)
    if text.startswith("(") and _closing(text) == len(text) - 1:
        return _parse_long(text[1:-1], names, argname)
    return parse_expr(text, names, argname=argname)  # a call too long to split: refused


def _closing(text: str) -> int:
    """Where the parenthesis that opens ``text`` closes (-1: nowhere)."""
    depths = itertools.accumulate({"(": 1, ")": -1}.get(c, 0) for c in text)
    return next((i for i, depth in enumerate(depths) if depth == 0), -1)


def _split(text: str, ops: tuple[str, ...]) -> list[tuple[str, str]]:
    """``text`` cut at the binary operators ``ops`` outside brackets: ``[(op, piece)]``."""
    parts, depth, start, op = [], 0, 0, ""
    for m in _TOKEN.finditer(text):
        token, i = m.group(), m.start()
        if token in "([{":
            depth += 1
        elif token in ")]}":
            depth -= 1
        elif depth == 0 and token in ops:
            if token == "*" and text[i - 1] == "*":
                continue  # the last of three stars or more: no product
            prev = text[:i].rstrip()
            if token in "+-" and (not prev or prev[-1] in "+-*/(" or re.search(r"\de$", prev)):
                continue  # a sign, or the exponent of a decimal such as 1e-5
            parts.append((op, text[start:i]))
            op, start = token, m.end()
    parts.append((op, text[start:]))
    return [(o, p) for o, p in parts if p.strip()] if len(parts) > 1 else parts


def _arrays(entry):
    """Lists of numbers (None: NaN) as float arrays, in nested mappings."""
    if isinstance(entry, Mapping):
        return {k: _arrays(v) for k, v in entry.items()}
    if isinstance(entry, list):
        return np.array([np.nan if v is None else v for v in entry], dtype=float)
    return entry


def _matrix_text(text: str) -> tuple[list[list[str]], str | None]:
    """A matrix transfer function's text ``[[a, b], [c, d]]/(den)``: its entries and denominator."""
    end = text.index("]]") + 2
    rows = text[2 : end - 2].split("], [")
    entries = [[e.strip() for _, e in _split(row, (",",))] for row in rows]
    rest = text[end:].strip()
    return entries, rest[1:] if rest.startswith("/") else None


@dataclass(frozen=True, eq=False)
class SavedDerivation(CachedState):
    r"""A derivation as ``results.json`` holds it, read back by :func:`load_results`.

    Numbers as arrays (:attr:`K`, :attr:`poles`), symbolic objects exact (:attr:`G_symbolic`,
    :attr:`factors`, :attr:`realizations`; parsed on first use), the figures' data
    (:attr:`simulation`, :attr:`peak_firing`).

    Attributes
    ----------
    data : mapping
        The document itself (every key of ``results.json``), read-only at the top.
    model : Model or None
        The model the derivation ran on (None for a file that does not hold it).
    path : str
        The file read.

    Examples
    --------
    >>> from symctl import SavedDerivation, derive_paper
    >>> res = derive_paper()
    >>> saved = SavedDerivation(res.to_dict(), res.spec)   # what load_results makes
    >>> saved.factors["N"], saved.derive() is res
    (K_0/(C_1*C_3), True)
    """

    data: Mapping
    model: Model | None
    path: str = "<results>"
    _known: Mapping = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "data", MappingProxyType(dict(self.data)))
        known = {"T_s": T_s}
        if self.model is not None and self.model.ode is not None:
            known.update({p.name: p for p in self.model.ode.params})
        object.__setattr__(self, "_known", MappingProxyType(known))

    def __eq__(self, other) -> bool:
        if not isinstance(other, SavedDerivation):
            return NotImplemented
        return self.model == other.model and json.dumps(dict(self.data), sort_keys=True) == (
            json.dumps(dict(other.data), sort_keys=True)
        )

    def __hash__(self) -> int:
        return hash((self.model, self.data.get("schema_version")))

    def _expr(self, text: str, where: str) -> sp.Expr:
        return parse_saved(text, self._known, f"{self.path}: {where}")

    def _matrix(self, rows, where: str) -> sp.ImmutableMatrix:
        return sp.ImmutableMatrix(
            [
                [self._expr(e, f"{where}[{i}][{j}]") for j, e in enumerate(r)]
                for i, r in enumerate(rows)
            ]
        )

    @property
    def dt(self):
        """The sampling time, as the derivation's transfer functions hold it (its plant's)."""
        if self.model is not None:
            return self.model.plant.dt
        return exact_value(float(self.data["controller"]["dt"]), "dt")

    @property
    def K(self) -> np.ndarray:
        """The optimal gains, one row per input."""
        return np.array(self.data["gains"]["K"], dtype=float)

    @property
    def poles(self) -> np.ndarray:
        """The closed loop's poles (complex)."""
        return np.array([complex(re_, im) for re_, im in self.data["closed_loop"]["poles"]])

    @cached_property
    def G_symbolic(self) -> DiscreteTF:
        """The controller :math:`G(z)` in the gains' symbols, exact."""
        sym = self.data["controller"]["symbolic"]
        N = self._factor(sym["numerator"], "controller.symbolic.numerator")
        den = self._expr(sym["denominator"], "controller.symbolic.denominator")
        return DiscreteTF(N, den, dt=self.dt)

    @cached_property
    def factors(self) -> dict[str, sp.Expr] | None:
        r""":math:`G_1`, :math:`G_2`, :math:`G_3` (expressions in :math:`z`) and :math:`N`, exact."""
        f = self.data["factorization"]
        if f is None:
            return None
        return {k: self._factor(f[k], f"factorization.{k}") for k in ("G1", "G2", "G3", "N")}

    def _factor(self, text, where: str):
        """An expression's text, rows of texts, or ``[[...]]/(den)`` for a matrix over ``den``."""
        if isinstance(text, list):
            return self._matrix(text, where)
        if not text.startswith("[["):
            return self._expr(text, where)
        entries, den = _matrix_text(text)
        M = self._matrix(entries, where)
        return M / self._expr(den, f"{where} (denominator)") if den is not None else M

    @cached_property
    def realizations(self) -> dict[str, dict]:
        """Per realization of :math:`G_2`: ``symbolic`` (exact F, H, M, N) and ``numeric`` (arrays)."""
        f = self.data["factorization"] or {"realizations": {}}
        out = {}
        for name, rec in sorted(
            f["realizations"].items(), key=lambda kv: "transform" in kv[1]["symbolic"]
        ):
            where = f"factorization.realizations.{name}"
            symbolic = {
                k: self._matrix(v, f"{where}.symbolic.{k}")
                for k, v in rec["symbolic"].items()
                if k in "FHMN" and v is not None
            }
            if "transform" in rec["symbolic"]:
                symbolic = self._transform(out, rec["symbolic"]["transform"], symbolic, where)
            out[name] = {
                "symbolic": symbolic,
                "numeric": {k: np.array(v, dtype=float) for k, v in rec["numeric"].items()},
            }
        return {name: out[name] for name in f["realizations"]}

    def _transform(self, out: dict, transform, symbolic: dict, where: str) -> dict:
        """``(P^-1 F0 P, P^-1 H0, M0 P, N)`` of a realization written as its base and ``P``."""
        from symctl.realization.realization import Realization

        where = f"{where}.symbolic.transform"
        if not isinstance(transform, Mapping) or transform.get("of") not in out:
            raise ParameterError(
                f"{self.path}: {where}: expected the name of a realization written before it and P"
            )
        base, P = out[transform["of"]]["symbolic"], transform.get("P")
        if not isinstance(P, list) or not all(isinstance(row, list) for row in P):
            raise ParameterError(f"{self.path}: {where}.P: expected a matrix as nested lists")
        P = self._matrix(P, f"{where}.P")
        try:
            R = Realization(base["F"], base["H"], base["M"], symbolic.get("N", base["N"]), self.dt)
            R = R.similar(P)
        except SymctlError as err:
            raise ParameterError(f"{self.path}: {where}: {err}") from None
        return {k: sp.ImmutableMatrix(getattr(R, k)) for k in "FHMN"}

    @property
    def simulation(self) -> dict:
        """The figures' traces: time, open loop, closed loop (arrays), the nonlinear check."""
        return _arrays(self.data["simulation"])

    @property
    def peak_firing(self) -> dict[str, dict[str, np.ndarray]]:
        """Per circuit, each neuron's peak firing in every realization (NaN: no such neuron)."""
        return {name: _arrays(c["peak_firing"]) for name, c in self.data["circuits"].items()}

    def derive(self) -> Derivation:
        """The whole derivation, re-created from the model (:func:`~symctl.derivation.derive`).

        Raises
        ------
        ParameterError
            The file does not hold the model (written before ``results.json`` held it).
        """
        from symctl.derivation.pipeline import derive

        if self.model is None:
            raise ParameterError(
                f"{self.path}: holds no model (model.file), so the derivation cannot be re-created"
            )
        return derive(self.model)


def load_results(path) -> SavedDerivation:
    """Read a ``results.json`` back: its numbers, symbolic objects, figures' data and model.

    Parameters
    ----------
    path : str or pathlib.Path
        A ``results.json`` (``symctl paper``, ``symctl derive``, ``Derivation.write``) or its folder.

    Returns
    -------
    SavedDerivation

    Raises
    ------
    SymctlTypeError
        ``path`` is not a path.
    ParameterError
        The file is missing, too large, not JSON, or not a ``results.json``.
    ModelFileError
        The model it holds is not a valid model file.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from symctl import derive_paper, load_results
    >>> res = derive_paper()
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = res.write(Path(folder) / "paper", figures=False, pdf=False)[0]
    ...     saved = load_results(path)
    >>> saved.G_symbolic == res.G_symbolic, saved.K.round(6).tolist()
    (True, [[-0.045972, -0.580041, -0.351813]])
    >>> saved.derive() is res                  # the same model: the same derivation
    True
    """
    if not isinstance(path, str | Path):
        raise SymctlTypeError(f"path: expected a path to results.json, got {type(path).__name__}")
    p = Path(path)
    if p.is_dir():
        p = p / "results.json"
    try:
        if p.stat().st_size > MAX_RESULTS_BYTES:
            raise ParameterError(f"path: {p} is larger than {MAX_RESULTS_BYTES} bytes")
        data = json.loads(p.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise ParameterError(f"path: cannot read {p}: {exc.__class__.__name__}") from None
    except json.JSONDecodeError as exc:
        raise ParameterError(f"path: {p} is not JSON ({exc.msg}, line {exc.lineno})") from None
    keys = ("schema_version", "parameters", "gains", "controller", "factorization", "model")
    if not isinstance(data, dict) or not all(k in data for k in keys):
        raise ParameterError(f"path: {p} is not a results.json (it lacks {', '.join(keys)})")
    saved = data["model"].get("file") if isinstance(data["model"], dict) else None
    model = model_from_dict(saved) if saved is not None else None
    return SavedDerivation(data, model, str(p))
