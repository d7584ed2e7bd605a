"""Conversions between symctl's objects and python-control, SciPy and SymPy (docs/interop.md).

``tf_*`` convert a :class:`~symctl.DiscreteTF`, ``ss_*`` a :class:`~symctl.Realization`
(``(F, H, M, N)`` as ``(A, B, C, D)``); the objects' ``to_*``/``from_*`` methods call them.
python-control and SciPy hold numbers (free symbols are a ParameterError), SymPy holds the
symbols exactly. ``dt`` is kept both ways, their ``dt=True`` being symctl's ``dt=None``;
continuous time is a ParameterError, another type a SymctlTypeError naming the argument.
SymPy 1.14 has no sampling time: give it back with ``dt=``.

>>> import sympy as sp
>>> from symctl import DiscreteTF, z
>>> from symctl.interop import tf_from_sympy, tf_to_control, tf_to_sympy
>>> G = DiscreteTF.from_expr(sp.Symbol("K") / (z - sp.Rational(1, 2)), dt=sp.Rational(1, 10))
>>> tf_from_sympy(tf_to_sympy(G), dt=sp.Rational(1, 10)) == G
True
>>> tf_to_control(G.subs({sp.Symbol("K"): 2})).dt
0.1
"""

from __future__ import annotations

import control
import numpy as np
import sympy as sp
from scipy import signal

from symctl._util.validate import common_dt, sampling_time
from symctl.design._foreign import canonical_columns, control_dt
from symctl.design.tf import DiscreteTF
from symctl.errors import DimensionError, ParameterError, SymctlTypeError
from symctl.realization.realization import Realization, controllable_canonical
from symctl.symbols import z

__all__ = [
    "ss_from_control",
    "ss_from_scipy",
    "ss_from_sympy",
    "ss_to_control",
    "ss_to_scipy",
    "ss_to_sympy",
    "tf_from_control",
    "tf_from_scipy",
    "tf_from_sympy",
    "tf_to_control",
    "tf_to_scipy",
    "tf_to_sympy",
]


def _checked(obj, cls, argname: str):
    if not isinstance(obj, cls):
        raise SymctlTypeError(f"{argname}: expected a {cls.__name__}, got {type(obj).__name__}")
    return obj


def _floats(coeffs, what: str) -> list[float]:
    try:
        return [float(c) for c in coeffs]
    except TypeError:
        raise ParameterError(f"G: {what} has free symbols; substitute numbers first") from None


def _numeric(G) -> tuple[list[float], list[list[list[float]]]]:
    """The denominator and the numerators ``nums[i][j]`` of a numeric DiscreteTF, as floats."""
    den = _floats(_checked(G, DiscreteTF, "G").den_coeffs(), "the denominator")
    rows, cols = G.shape
    return den, [
        [_floats(G.num_coeffs(i, j), "the numerator") for j in range(cols)] for i in range(rows)
    ]


def _z_expr(coeffs) -> sp.Expr:
    """The polynomial in z of float coefficients (descending powers) of another library."""
    return sp.Poly([float(c) for c in np.atleast_1d(coeffs)], z).as_expr()


def _shaped(values: list, cols: int):
    """SymPy values (not text) as a matrix of ``cols`` columns, or the one value for 1 x 1."""
    if len(values) == 1:
        return values[0]
    out = sp.zeros(len(values) // cols, cols)
    for k, value in enumerate(values):
        out[k // cols, k % cols] = value
    return out


def _z_matrix(nums, dens=None):
    """``nums[i][j] / dens[i][j]`` (coefficient lists) in z, shaped by :func:`_shaped`."""
    ratios = [
        _z_expr(coeffs) / (1 if dens is None else _z_expr(dens[i][j]))
        for i, row in enumerate(nums)
        for j, coeffs in enumerate(row)
    ]
    return _shaped(ratios, len(nums[0]))


def _their_dt(dt):
    """symctl's dt as python-control's and SciPy's: None (unspecified) is ``True``."""
    return True if dt is None else float(dt)


def tf_to_control(G: DiscreteTF) -> control.TransferFunction:
    """``control.TransferFunction`` of a numeric :class:`DiscreteTF` (SISO or MIMO)."""
    den, nums = _numeric(G)
    if G.is_siso:
        return control.tf(nums[0][0], den, _their_dt(G.dt))
    return control.tf(nums, [[den] * len(nums[0])] * len(nums), _their_dt(G.dt))


def _discrete(sys):
    if not isinstance(sys, control.LTI):
        raise SymctlTypeError(f"sys: expected a python-control system, got {type(sys).__name__}")
    return control_dt(sys, "sys")


def tf_from_control(sys) -> DiscreteTF:
    """A :class:`DiscreteTF`, in lowest terms, of a discrete python-control system."""
    dt = _discrete(sys)
    tf = control.tf(sys)
    return DiscreteTF.from_expr(_z_matrix(tf.num_array, tf.den_array), dt=dt)


def ss_to_control(R: Realization) -> control.StateSpace:
    """A ``control.StateSpace`` of a numeric :class:`Realization`."""
    F, H, M, N = _checked(R, Realization, "R").numeric()
    return control.ss(F, H, M, N, _their_dt(R.dt))


def ss_from_control(sys) -> Realization:
    """A :class:`Realization` of a discrete python-control system (a transfer function in the
    column-wise controllable canonical form; improper ones refused)."""
    dt = _discrete(sys)
    if isinstance(sys, control.TransferFunction):
        return Realization(*canonical_columns(sys.num_array, sys.den_array, "sys"), dt)
    ss = control.ss(sys)
    return Realization(ss.A, ss.B, ss.C, ss.D, dt)


def _scipy_dt(sys):
    if isinstance(sys, signal.lti):
        raise ParameterError(
            "sys: a continuous-time SciPy system (scipy.signal.lti); discretize it first "
            "(its .to_discrete(dt) or scipy.signal.cont2discrete)"
        )
    if not isinstance(sys, signal.dlti):
        raise SymctlTypeError(
            "sys: expected a discrete scipy.signal system (dlti: StateSpace, TransferFunction "
            f"or ZerosPolesGain), got {type(sys).__name__}"
        )
    return None if sys.dt is True or sys.dt is None else sampling_time(float(sys.dt), "sys")


def tf_to_scipy(G: DiscreteTF) -> signal.TransferFunction:
    """A ``scipy.signal.TransferFunction`` of a numeric :class:`DiscreteTF` with one input (SISO
    or SIMO: one ``num`` row per output); more inputs are a DimensionError (use ``ss_to_scipy``)."""
    if _checked(G, DiscreteTF, "G").shape[1] != 1:
        raise DimensionError(
            f"G: scipy.signal.TransferFunction holds one input, G has shape {G.shape}; "
            "use ss_to_scipy (a StateSpace holds any shape)"
        )
    den, columns = _numeric(G)
    nums = [row[0] for row in columns]
    width = max(len(n) for n in nums)
    num = np.array([[0.0] * (width - len(n)) + n for n in nums])
    return signal.TransferFunction(num[0] if G.is_siso else num, den, dt=_their_dt(G.dt))


def _scipy_tf_parts(sys) -> tuple[list[list[np.ndarray]], np.ndarray]:
    """``nums[i][j]`` and the common denominator of a discrete SciPy system."""
    if isinstance(sys, signal.StateSpace):
        rows, cols = sys.D.shape
        if not rows or not cols:
            raise DimensionError(f"sys: no inputs or no outputs, D has shape {sys.D.shape}")
        columns = [signal.ss2tf(sys.A, sys.B, sys.C, sys.D, input=j) for j in range(cols)]
        den = np.atleast_1d(columns[0][1])
        return [[np.atleast_2d(num)[i] for num, _ in columns] for i in range(rows)], den
    if isinstance(sys, signal.ZerosPolesGain):
        sys = sys.to_tf()
    return [[row] for row in np.atleast_2d(sys.num)], np.atleast_1d(sys.den)


def tf_from_scipy(sys) -> DiscreteTF:
    """A :class:`DiscreteTF` of a discrete SciPy ``TransferFunction`` (SISO or SIMO),
    ``ZerosPolesGain`` or ``StateSpace`` (any shape, ``scipy.signal.ss2tf`` input by input)."""
    dt = _scipy_dt(sys)
    nums, den = _scipy_tf_parts(sys)
    return DiscreteTF(_z_matrix(nums), _z_expr(den), dt)


def ss_to_scipy(R: Realization) -> signal.StateSpace:
    """A ``scipy.signal.StateSpace`` of a numeric :class:`Realization`."""
    F, H, M, N = _checked(R, Realization, "R").numeric()
    return signal.StateSpace(F, H, M, N, dt=_their_dt(R.dt))


def ss_from_scipy(sys) -> Realization:
    """A :class:`Realization` of a discrete SciPy system (a transfer function or
    zeros-poles-gain in the controllable canonical form)."""
    dt = _scipy_dt(sys)
    if isinstance(sys, signal.StateSpace):
        return Realization(sys.A, sys.B, sys.C, sys.D, dt)
    nums, den = _scipy_tf_parts(sys)
    return Realization(*canonical_columns(nums, [[den]] * len(nums), "sys"), dt)


class _SymPy:
    """``sympy.physics.control``'s classes, None where this SymPy lacks one (``StateSpace``: 1.13)."""

    def __init__(self):
        import sympy.physics.control as ctl

        self.ctl = ctl
        self.ss = getattr(ctl, "StateSpace", None)
        self.dtf = getattr(ctl, "DiscreteTransferFunction", None)
        self.dss = getattr(ctl, "DiscreteStateSpace", None)
        self.tfs = tuple(c for c in (ctl.TransferFunction, self.dtf) if c is not None)
        self.sss = tuple(c for c in (self.ss, self.dss) if c is not None)


def _sympy_dt(sys, dt):
    """The sampling time of a SymPy system merged with ``dt=``; continuous time refused."""
    if getattr(sys, "is_continuous", None) is True:  # only a SymPy with discrete classes says
        raise ParameterError(
            f"sys: a continuous-time SymPy {type(sys).__name__}; use DiscreteTransferFunction "
            "or DiscreteStateSpace (e.g. DiscreteTransferFunction.from_gbt) to discretize"
        )
    own = None
    if getattr(sys, "is_continuous", None) is False:
        own = sampling_time(sys.sampling_time, "sys")
    return common_dt(own, None if dt is None else sampling_time(dt, "dt"), "dt")


def _variable(sys, var, discrete: bool) -> sp.Symbol:
    """The variable of ``sys`` that is z: ``var``, else any of a discrete class, else z."""
    if var is not None:
        if not isinstance(var, sp.Symbol):
            raise SymctlTypeError(f"var: expected a sympy Symbol, got {type(var).__name__}")
        if var != sys.var:
            raise ParameterError(f"var: sys is a transfer function in {sys.var}, not in {var}")
        return var
    if not discrete and sys.var != z:
        raise ParameterError(
            f"sys: a transfer function in {sys.var}, not in z; pass var={sys.var} if "
            f"{sys.var} is the z-transform variable"
        )
    return sys.var


def tf_to_sympy(G: DiscreteTF):
    """``G`` as a SymPy ``TransferFunction`` (MIMO: a ``TransferFunctionMatrix`` over its common
    denominator), or a later SymPy's ``DiscreteTransferFunction`` carrying ``dt``."""
    G = _checked(G, DiscreteTF, "G")
    lib = _SymPy()

    def entry(num):
        if lib.dtf is None:
            return lib.ctl.TransferFunction(num, G.den, z)
        return lib.dtf(num, G.den, z, 1 if G.dt is None else G.dt)

    if G.is_siso:
        return entry(G.num)
    return lib.ctl.TransferFunctionMatrix(
        [[entry(e) for e in row] for row in G.num_matrix.tolist()]
    )


def tf_from_sympy(sys, dt=None, *, var=None) -> DiscreteTF:
    """A :class:`DiscreteTF` of a SymPy transfer function, matrix or state space, exactly.

    SymPy 1.14's classes are read as discrete in ``z``, or in ``var`` when given; ``dt`` is the
    sampling time (or must agree with the system's). Entries over one common denominator come
    back as written, others in lowest terms; Series, Parallel, Feedback need ``.doit()`` first.
    """
    lib = _SymPy()
    if isinstance(sys, lib.sss):
        return ss_from_sympy(sys, dt).to_tf()
    if isinstance(sys, lib.ctl.TransferFunctionMatrix):
        entries = [list(row) for row in sys.args[0]]
    elif isinstance(sys, lib.tfs):
        entries = [[sys]]
    else:
        raise SymctlTypeError(
            "sys: expected a sympy.physics.control TransferFunction, TransferFunctionMatrix "
            f"or StateSpace (Series, Parallel, Feedback: call .doit() first), got "
            f"{type(sys).__name__}"
        )
    dt = _sympy_dt(sys, dt)
    v = _variable(sys, var, getattr(sys, "is_continuous", None) is False)
    flat = [e for row in entries for e in row]
    if not all(isinstance(e, lib.tfs) for e in flat):
        raise SymctlTypeError("sys: entries other than transfer functions; call .doit() first")
    if v != z and any(z in e.num.free_symbols | e.den.free_symbols for e in flat):
        raise ParameterError(f"sys: uses z as a parameter besides its variable {v}")
    nums = [e.num.xreplace({v: z}) for e in flat]
    dens = [e.den.xreplace({v: z}) for e in flat]
    for n, d in zip(nums, dens, strict=True):
        if not (n.is_rational_function(z) and d.is_rational_function(z)):
            raise ParameterError(f"sys: ({n})/({d}) is not rational in {v}")
    cols = len(entries[0])
    if len(set(dens)) == 1 and all(e.is_polynomial(z) for e in (*nums, *dens)):
        return DiscreteTF(_shaped(nums, cols), dens[0], dt)  # as it is: exact, not cancelled
    return DiscreteTF.from_expr(_shaped([n / d for n, d in zip(nums, dens, strict=True)], cols), dt)


def ss_to_sympy(R: Realization):
    """``R`` as a SymPy ``StateSpace`` (SymPy >= 1.13), or a later SymPy's ``DiscreteStateSpace``
    carrying ``dt``."""
    R = _checked(R, Realization, "R")
    lib = _SymPy()
    if lib.ss is None:
        raise ParameterError(f"R: SymPy {sp.__version__} has no StateSpace (SymPy >= 1.13 has)")
    if lib.dss is None:
        return lib.ss(R.F, R.H, R.M, R.N)
    return lib.dss(R.F, R.H, R.M, R.N, 1 if R.dt is None else R.dt)


def ss_from_sympy(sys, dt=None, *, var=None) -> Realization:
    """A :class:`Realization` of a SymPy state space, or of a SISO transfer function (controllable
    canonical form); ``dt`` and ``var`` as in :func:`tf_from_sympy`; a matrix is refused."""
    lib = _SymPy()
    if isinstance(sys, lib.tfs):
        return controllable_canonical(tf_from_sympy(sys, dt, var=var))
    if isinstance(sys, lib.ctl.TransferFunctionMatrix):
        raise DimensionError(
            "sys: a transfer function matrix has no canonical realization here; use "
            "tf_from_sympy and a symctl realizer"
        )
    if not isinstance(sys, lib.sss):
        raise SymctlTypeError(
            f"sys: expected a sympy.physics.control StateSpace, got {type(sys).__name__}"
        )
    return Realization(sys.A, sys.B, sys.C, sys.D, _sympy_dt(sys, dt))
