"""Symbolic matrices as one NumPy function of chosen symbols, broadcast like arrays (an output
has shape ``broadcast + (rows, cols)``, so 10^5 parameter sets evaluate in one call).

>>> import numpy as np, sympy as sp
>>> from symctl._util.evaluate import lambdify_matrices
>>> a, b = sp.symbols("a b")
>>> f = lambdify_matrices([sp.Matrix([[a, 1], [0, a * b]])], [a, b])
>>> f(np.array([1.0, 2.0]), 3.0)[0].shape
(2, 2, 2)
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import sympy as sp

from symctl._util.validate import symbol_tuple
from symctl.errors import ParameterError


def lambdify_matrices(
    matrices: Sequence[sp.MatrixBase], symbols: Sequence[sp.Symbol]
) -> Callable[..., tuple[np.ndarray, ...]]:
    """One vectorized NumPy function evaluating every matrix at the given symbol values."""
    symbols = symbol_tuple(symbols, "symbols")  # names become code in lambdify: no text
    free = set().union(*(m.free_symbols for m in matrices)) - set(symbols)
    if free:
        names = ", ".join(sorted(map(str, free)))
        raise ParameterError(f"symbols: values are needed for {names} as well")
    shapes = [m.shape for m in matrices]
    flat = [e for m in matrices for e in m]
    raw = sp.lambdify(symbols, flat, modules="numpy", cse=True)

    def evaluate(*values):
        arrays = [np.asarray(v, dtype=float) for v in values]
        shape = np.broadcast_shapes(*(a.shape for a in arrays)) if arrays else ()
        out = [np.broadcast_to(np.asarray(v, dtype=float), shape) for v in raw(*arrays)]
        results, k = [], 0
        for rows, cols in shapes:
            block = out[k : k + rows * cols]
            k += rows * cols
            stacked = np.stack(block, axis=-1) if block else np.zeros((*shape, 0))
            results.append(stacked.reshape(*shape, rows, cols))
        return tuple(results)

    return evaluate
