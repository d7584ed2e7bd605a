r"""Sensor and actuator delays built into an augmented state.

With net delay :math:`T = d_s + d_a`, :math:`\mu` reaches the plant through a chain of
delayed copies (the paper's eqs. (augmented_states)–(augmented_cost), any :math:`T`):

.. math::
    \gamma_1(t+1) = \mu(t),\quad \gamma_{k+1}(t+1) = \gamma_k(t),\quad
    \delta_r(t) = \gamma_T(t) = \mu(t - T),

with :math:`\chi = [x;\ \gamma_1;\ \dots;\ \gamma_{T-1};\ \delta_r]`. For the paper's
scalar ``T = 2``, :math:`\chi = [\delta_f, \gamma, \delta_r]` and

.. math::
    \tilde A = \begin{bmatrix} A & 0 & B \\ 0 & 0 & 0 \\ 0 & I & 0 \end{bmatrix},\quad
    \tilde B = \begin{bmatrix} 0 \\ I \\ 0 \end{bmatrix},\quad
    \tilde Q = \operatorname{diag}(Q, 0, R).

Only the net delay enters; the split is kept for :math:`G = G_3 G_2 G_1`.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from symctl._util.display import LatexMixin, latex
from symctl._util.validate import (
    MAX_DELAY,
    MAX_STATES,
    check_magnitude,
    common_dt,
    nonneg_int,
    psd_matrix,
    to_matrix,
)
from symctl.design._foreign import is_control_system, plant_from_control
from symctl.design.plant import DiscretePlant, MuscleModel
from symctl.errors import DimensionError, ParameterError, SymctlTypeError

__all__ = ["AugmentedSystem", "as_plant", "augment", "chain_names", "same_dt"]


def as_plant(plant) -> DiscretePlant:
    """The plant that every function taking a ``plant`` works with: a DiscretePlant, a
    MuscleModel's, ``(A, B)``, or a discrete python-control system (:func:`plant_from_control`);
    another type raises SymctlTypeError."""
    if isinstance(plant, DiscretePlant):
        return plant
    if isinstance(plant, MuscleModel):
        return plant.plant()
    if isinstance(plant, tuple) and len(plant) == 2:
        return DiscretePlant(*plant)
    if is_control_system(plant):
        return plant_from_control(plant, "plant")
    raise SymctlTypeError(
        "plant: expected a DiscretePlant, a MuscleModel, a tuple (A, B) or a discrete "
        f"python-control StateSpace or TransferFunction, got {type(plant).__name__}"
    )


def same_dt(plant: DiscretePlant, dt, argname: str, of: str = "the controller") -> None:
    """Refuse ``argname`` (ParameterError) when the plant's ``dt`` and that of ``of`` differ
    (``None`` fits any)."""
    try:
        common_dt(plant.dt, dt, argname)
    except ParameterError:
        raise ParameterError(
            f"{argname}: the plant is sampled with Ts = {plant.dt}, {of} with dt = {dt}; "
            "they must agree (or one be unspecified)"
        ) from None


@dataclass(frozen=True)
class AugmentedSystem(LatexMixin):
    r"""The delay-augmented system :math:`\chi(t+1) = \tilde A \chi(t) + \tilde B \mu(t)` (a value).

    Attributes
    ----------
    plant : DiscretePlant
    sensor_delay, actuator_delay, T : int
        The delays in steps and their sum.
    A, B, Q, Q_plant, R : sympy.ImmutableMatrix
        :math:`\tilde A`, :math:`\tilde B`, :math:`\tilde Q`, and the plant's penalties.
    state_names : tuple of str
        Names of the entries of :math:`\chi`.

    Examples
    --------
    >>> from symctl import MuscleModel, augment
    >>> s = augment(MuscleModel(), 1, 1)
    >>> s.T, s.n, s.m, s.chi.T
    (2, 1, 1, Matrix([[delta_f, gamma, delta_r]]))
    """

    plant: DiscretePlant
    sensor_delay: int
    actuator_delay: int
    A: sp.ImmutableMatrix
    B: sp.ImmutableMatrix
    Q: sp.ImmutableMatrix
    Q_plant: sp.ImmutableMatrix
    R: sp.ImmutableMatrix
    state_names: tuple[str, ...]

    @property
    def T(self) -> int:
        return self.sensor_delay + self.actuator_delay

    @property
    def n(self) -> int:
        return self.plant.n

    @property
    def m(self) -> int:
        return self.plant.m

    @property
    def R_mu(self) -> sp.ImmutableMatrix:
        """Penalty on mu: ``R`` when ``T = 0``, else zero (the paper's)."""
        return self.R if self.T == 0 else sp.ImmutableMatrix(sp.zeros(self.m, self.m))

    @property
    def chi(self) -> sp.ImmutableMatrix:
        r""":math:`\chi` as a column of symbols named after ``state_names``."""
        return sp.ImmutableMatrix([sp.Symbol(s) for s in self.state_names])

    def latex(self) -> str:
        return (
            rf"\chi = {latex(self.chi)},\quad \tilde A = {latex(self.A)},\quad "
            rf"\tilde B = {latex(self.B)},\quad \tilde Q = {latex(self.Q)}"
        )


def _chain_names(plant: DiscretePlant, T: int) -> tuple[str, ...]:
    if T == 0:
        return plant.state_names
    m = plant.m
    copies = []
    for k in range(1, T):
        stem = "gamma" if T == 2 else f"gamma_{k}"
        copies += [stem] if m == 1 else [f"{stem}[{i + 1}]" for i in range(m)]
    return (*plant.state_names, *copies, *plant.input_names)


def augment(
    plant, sensor_delay: int = 1, actuator_delay: int = 1, Q=None, R=None
) -> AugmentedSystem:
    r"""Build the delay-augmented system and cost of the paper, for any delays and plant size.

    Parameters
    ----------
    plant : DiscretePlant, MuscleModel, (A, B) or a python-control system
        Numeric or symbolic (read by :func:`as_plant`).
    sensor_delay, actuator_delay : int
        Delays in steps, >= 0, their sum ``T <= MAX_DELAY`` (500).
    Q, R : matrix-like, optional
        State (``n x n``) and input (``m x m``) penalties; identity by default.

    Returns
    -------
    AugmentedSystem

    Raises
    ------
    ParameterError
        Negative delays or ``T > MAX_DELAY``; numeric ``Q`` or ``R`` not symmetric PSD or
        above 1e100; more than ``MAX_STATES`` (1000) augmented states.
    SymctlTypeError, DimensionError
        Non-integer delays; ``Q`` or ``R`` of the wrong shape.

    Examples
    --------
    >>> import sympy as sp
    >>> from symctl import augment
    >>> a, b = sp.symbols("A B")
    >>> aug = augment(([[a]], [[b]]), 1, 1)
    >>> aug.A.tolist(), aug.B.T
    ([[A, 0, B], [0, 0, 0], [0, 1, 0]], Matrix([[0, 1, 0]]))
    """
    p = as_plant(plant)
    ds = nonneg_int(sensor_delay, "sensor_delay")
    da = nonneg_int(actuator_delay, "actuator_delay")
    n, m, T = p.n, p.m, ds + da
    if T > MAX_DELAY:
        raise ParameterError(
            f"sensor_delay, actuator_delay: the net delay must be at most {MAX_DELAY} steps, "
            f"got {ds} + {da} = {T}"
        )
    if n + T * m > MAX_STATES:
        raise ParameterError(
            f"sensor_delay, actuator_delay: the augmented system would have n + T m = "
            f"{n} + {T} * {m} = {n + T * m} states, more than {MAX_STATES}"
        )
    Qm = sp.eye(n) if Q is None else to_matrix(Q, "Q")
    Rm = sp.eye(m) if R is None else to_matrix(R, "R")
    for value, name, k, what in ((Qm, "Q", n, "states"), (Rm, "R", m, "inputs")):
        if value.shape != (k, k):
            raise DimensionError(
                f"{name}: expected shape {(k, k)} for a plant with {k} {what}, got {value.shape}"
            )
        if not value.free_symbols:
            check_magnitude(psd_matrix(value, name, k), name)
    size = n + T * m
    A = sp.zeros(size, size)
    B = sp.zeros(size, m)
    Qt = sp.zeros(size, size)
    A[:n, :n] = p.A
    Qt[:n, :n] = Qm
    if T == 0:
        B[:, :] = p.B
    else:
        A[:n, size - m :] = p.B  # delta_r = gamma_T drives the plant
        B[n : n + m, :] = sp.eye(m)  # gamma_1(t+1) = mu(t)
        for k in range(1, T):  # gamma_{k+1}(t+1) = gamma_k(t)
            rows, cols = n + k * m, n + (k - 1) * m
            A[rows : rows + m, cols : cols + m] = sp.eye(m)
        Qt[size - m :, size - m :] = Rm
    return AugmentedSystem(
        p,
        ds,
        da,
        sp.ImmutableMatrix(A),
        sp.ImmutableMatrix(B),
        sp.ImmutableMatrix(Qt),
        sp.ImmutableMatrix(Qm),
        sp.ImmutableMatrix(Rm),
        _chain_names(p, T),
    )


def chain_names(T: int, m: int) -> tuple[str, ...]:
    """The delay chain's names, ``gamma_1 .. gamma_{T-1}, delta_r`` (``[i]`` per input; none at T = 0)."""
    if T < 1:
        return ()
    base = [f"gamma_{k}" for k in range(1, T)] + ["delta_r"]
    return tuple(b if m == 1 else f"{b}[{i + 1}]" for b in base for i in range(m))
