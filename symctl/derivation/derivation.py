r"""What a derivation produced: :class:`Derivation`, with one record per realization and circuit.

The report stage writes it (:mod:`symctl.report.results`); ``PaperResults`` is its former name.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType

import sympy as sp

from symctl._util.deprecate import renamed_attribute
from symctl.compatibility.check import CompatibilityResult
from symctl.compatibility.delaygraph import DelayGraph
from symctl.compatibility.structure import Structure
from symctl.design.augment import AugmentedSystem
from symctl.design.kalman import KalmanGains
from symctl.design.lqr import Gains
from symctl.design.ode import ODEModel
from symctl.design.plant import DiscretePlant
from symctl.design.tf import DiscreteTF
from symctl.model.model import Model
from symctl.neural.circuit import Circuit
from symctl.neural.firing import FiringPatterns
from symctl.neural.montecarlo import MonteCarlo
from symctl.neural.nonlinear import NonlinearCheck
from symctl.neural.simulate import Response
from symctl.realization.check import RealizationCheck
from symctl.realization.factorization import Factorization
from symctl.realization.realization import Realization
from symctl.realization.realizers import REALIZERS
from symctl.realization.reduction import ControllerReduction

__all__ = ["CircuitRecord", "Derivation", "PaperResults", "RealizationRecord"]


_MUSCLE_UNITS = {"f": "N", "r": "spikes/s", "tau": "s", "f_max": "N", "r_bar": "spikes/s"}


def _hash_fields(obj) -> int:
    """A hash of a frozen dataclass's fields, mappings hashed by their items."""
    values = (getattr(obj, f.name) for f in dataclasses.fields(obj))
    return hash(tuple(tuple(v.items()) if isinstance(v, Mapping) else v for v in values))


class _Record:
    """The JSON entry of a record (``to_dict``; ``to_json`` is its old name), by ``_json``."""

    _json = ""
    to_json = renamed_attribute("to_json", "to_dict")

    def to_dict(self) -> dict:
        """This record's entry of ``results.json``."""
        from symctl.report import results

        return getattr(results, self._json)(self)


@dataclass(frozen=True)
class RealizationRecord(_Record):
    """One realization of :math:`G_2`, by realizer ``name``: ``symbolic`` (in the factorization's
    symbols) and ``numeric`` (with the simulations' ``values``, by symbol name), the exact check
    of each (``check_symbolic``, ``check_numeric``), and for a transformed realizer the
    similarity transforms ``P``, ``P_numeric`` from its canonical base.

    Examples
    --------
    >>> from symctl import derive_paper
    >>> rec = derive_paper().realizations["controllable"]
    >>> rec.name, bool(rec.check_symbolic), bool(rec.check_numeric)
    ('controllable', True, True)
    >>> sorted(rec.values)
    ['C_1', 'C_3', 'epsilon_1', 'epsilon_3']
    """

    name: str
    symbolic: Realization
    numeric: Realization
    values: Mapping[str, object]
    check_symbolic: RealizationCheck
    check_numeric: RealizationCheck
    P: sp.MatrixBase | None = None
    P_numeric: sp.MatrixBase | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "values", MappingProxyType(dict(self.values)))

    __hash__ = _hash_fields
    _json = "realization_json"


@dataclass(frozen=True)
class CircuitRecord(_Record):
    """One circuit of :data:`~symctl.report.spec.CIRCUITS`: its symbolic ``structure``, its
    ``compatibility`` with the delay graph, the ``circuit`` of neurons (placed on the graph when
    compatible), the ``firing`` of its random realizations and, for ``"pathways"``, the proof
    ``realizes`` that its structure realizes :math:`G` with the optimal gains.

    Examples
    --------
    >>> from symctl import derive_paper
    >>> rec = derive_paper().circuits["observable"]
    >>> rec.circuit.n_neurons, rec.g2_neurons, bool(rec.compatibility)
    (5, 3, True)
    """

    name: str
    structure: Structure
    compatibility: CompatibilityResult
    circuit: Circuit
    firing: FiringPatterns
    realizes: RealizationCheck | None = None

    @property
    def g2_neurons(self) -> int | None:
        """The neurons of the G2 parts (None for the IFP controller, which has no G2)."""
        if self.name in REALIZERS and REALIZERS[self.name].controller:
            return None
        return sum(1 for n in self.circuit.neurons if n.part == "G2" or n.part.endswith(".G2"))

    _json = "circuit_json"


@dataclass(frozen=True)
class Derivation:
    r"""Everything a derivation produced: its inputs and each stage's result, in pipeline order.

    Made by :func:`~symctl.derivation.derive`; a frozen, picklable value, equal by its fields;
    :func:`~symctl.derivation.load_results` reads it back from ``results.json``.

    Parameters
    ----------
    model : ODEModel or None
        The nonlinear plant (None for a discrete plant given directly).
    plant_symbolic, plant : DiscretePlant
        The discretized linear plant in symbols (one state and input, else None), and in numbers.
    system, gains : AugmentedSystem, Gains
        The delay-augmented system and cost; the optimal gains and closed-loop poles.
    G_symbolic, G : DiscreteTF
        The controller :math:`G(z)` in the gains' symbols, and with the optimal gains.
    proved : bool
        Whether :math:`G` was proved against the state-space matrices.
    seed : int
        The seed of the random realizations.
    factors : Factorization
        :math:`G = G_3 G_2 G_1`.
    realizations, circuits : mapping of str to RealizationRecord, CircuitRecord
        The realizations of :math:`G_2` and the circuits, by name (read-only).
    graph : DelayGraph
        The delay graph of the circuits.
    open_loop, closed_loop : Response
        The plant's open-loop pulse response and the optimal closed loop's.
    nonlinear : NonlinearCheck
        The linear controller around the nonlinear plant.
    G2_symbolic : DiscreteTF, optional
        The :math:`G_2` the symbolic realizations realize: ``factors.G2``, or beyond
        :data:`~symctl.realization.factorization.EXPANDED_ZEROS_MAX` sections
        ``factors.abbreviated()`` (zeros' coefficients :math:`\sigma_k = e_k(\epsilon)`).
    atlas, candidates : optional
        The circuit atlas and its candidate circuits for this controller.
    spec : Model
        The model the derivation ran on (a key of :func:`derive`'s cache).
    longest, skipped : DelaySearch, str, optional
        The longest-delay search, when the model asks for it; the stages left out, and why.
    pathways : ControllerCompatibility, optional
        The exact verdict on the delay graph, with the structure built along its pathways.
    verified : Proof, optional
        The proof that :math:`G_3 G_2 G_1 = G`.
    reduction : ControllerReduction, optional
        Whether the controller is minimal; when not, ``G_symbolic``, ``G``, ``gains`` and every
        later stage are the minimal controller's (None for an estimating model).
    kalman : KalmanGains, optional
        The delayed Kalman filter of a model that measures through noise: ``G`` is then the LQG
        compensator (:func:`~symctl.lqg_tf`) and the circuits are driven by the outputs.
    variance : MonteCarlo, optional
        With ``kalman``: the closed loop's stationary covariance, predicted and measured.
    spiking_cost : SpikingCost, optional
        What spikes cost each circuit (``symctl paper --spiking``).

    Examples
    --------
    >>> from symctl import derive_paper
    >>> res = derive_paper()
    >>> print(res.G_symbolic)
    (K_0)/(z**2 - K_1*z - K_2)
    >>> res.figure_names()[:3]
    ['open_loop', 'closed_loop', 'delay_graph']
    >>> res.circuits["ifp"] = None
    Traceback (most recent call last):
    ...
    TypeError: 'mappingproxy' object does not support item assignment
    """

    model: ODEModel | None
    plant_symbolic: DiscretePlant
    plant: DiscretePlant
    system: AugmentedSystem
    gains: Gains
    G_symbolic: DiscreteTF
    G: DiscreteTF
    proved: bool
    seed: int
    factors: Factorization
    realizations: Mapping[str, RealizationRecord]
    graph: DelayGraph
    circuits: Mapping[str, CircuitRecord]
    open_loop: Response
    closed_loop: Response
    nonlinear: NonlinearCheck
    G2_symbolic: DiscreteTF | None = None
    atlas: object = None
    candidates: tuple | None = None
    spec: Model | None = None
    longest: object = None
    skipped: str | None = None
    pathways: object = None
    verified: object = None
    reduction: ControllerReduction | None = None
    kalman: KalmanGains | None = None
    variance: MonteCarlo | None = None
    spiking_cost: object = None

    def __post_init__(self) -> None:
        for name in ("realizations", "circuits"):
            object.__setattr__(self, name, MappingProxyType(dict(getattr(self, name))))
        if self.G2_symbolic is None and self.factors is not None:
            object.__setattr__(self, "G2_symbolic", self.factors.G2)

    @property
    def abbreviated(self) -> bool:
        r"""Whether the symbolic realizations write :math:`G_2`'s zeros as :math:`\sigma_k`."""
        return self.factors is not None and self.G2_symbolic != self.factors.G2

    @property
    def names(self) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """The states' and inputs' names as the model gives them (the muscle's ``f``, ``r``)."""
        return self.spec.signal_names if self.spec is not None else (("f",), ("r",))

    def unit(self, name: str) -> str:
        """The unit of a state, input or parameter of the model ('' when not given)."""
        return self.spec.unit(name) if self.spec is not None else _MUSCLE_UNITS.get(name, "")

    __hash__ = _hash_fields

    def parameters(self) -> dict:
        """The inputs (``results.json``'s ``parameters``): the model's values, delays, Q, R, seed.

        Returns
        -------
        dict

        Examples
        --------
        >>> from symctl import derive_paper
        >>> derive_paper(tau=0.05).parameters()["tau"]
        0.05
        """
        from symctl.report import results

        return results.parameters(self)

    to_json = renamed_attribute("to_json", "to_dict")

    def to_dict(self) -> dict:
        """The ``results.json`` document, of JSON types (its keys: docs/guide/paper.md).

        Returns
        -------
        dict

        Examples
        --------
        >>> from symctl import derive_paper
        >>> data = derive_paper().to_dict()
        >>> data["schema_version"], data["controller"]["proved"], len(data["gains"]["K"][0])
        (1, True, 3)
        """
        from symctl.report import results

        return results.results_json(self)

    def figure_names(self) -> list[str]:
        """The report's figures, in reading order (the file names of :meth:`write`).

        Returns
        -------
        list of str

        Examples
        --------
        >>> from symctl import derive_paper
        >>> names = derive_paper().figure_names()
        >>> len(names), names[-4:]
        (20, ['nonlinear', 'atlas_overview', 'simplified_A16', 'simplified_A17'])
        """
        from symctl.report import figures

        return figures.figure_names(self)

    def figure(self, name: str):
        """One figure of the report, ``name`` of :meth:`figure_names`, as a matplotlib ``Figure``.

        Examples
        --------
        >>> from symctl import derive_paper
        >>> type(derive_paper().figure("closed_loop")).__name__
        'Figure'
        """
        from symctl.report import figures

        return figures.make_figure(self, name)

    def write(
        self,
        out: Path | str,
        *,
        figures: bool = True,
        pdf: bool = True,
        jobs: int | None = None,
        progress: Callable[[str], None] | None = None,
        formats: str | tuple[str, ...] = ("pdf", "png"),
    ) -> list[Path]:
        """Write the outputs of ``symctl paper`` into folder ``out``, all at once (never a mix of
        two runs, never partial: docs/reliability.md).

        Parameters
        ----------
        out : path
            New (made, with its parents), empty, or an earlier run's folder (replaced).
        figures, pdf : bool
            Also write the figures; also compile ``derivation.pdf`` (when ``pdflatex`` is found).
        jobs : int, optional
            Processes drawing the figures.
        progress : callable, optional
            Called with each step's name (``"figures"``, ``"documents"``, ...) before it runs.
        formats : str or sequence of str
            The figures' formats: ``"pdf"`` (for ``derivation.tex``), ``"png"`` (``report.md``), ``"svg"``.

        Returns
        -------
        list of Path
            The files written: ``results.json``, the figures, the documents.

        Raises
        ------
        SymctlTypeError
            ``out`` is not a path.
        ParameterError
            ``out`` is empty, a file, a folder of other files, cannot be made or is being
            written; ``jobs`` < 1; an unknown format.
        LatexError
            ``pdflatex`` failed on ``derivation.tex``.
        OSError
            Writing failed (``out`` is then as it was).

        Examples
        --------
        >>> import tempfile
        >>> from pathlib import Path
        >>> from symctl import derive_paper
        >>> with tempfile.TemporaryDirectory() as parent:
        ...     paths = derive_paper().write(Path(parent) / "paper", figures=False, pdf=False)
        ...     [p.name for p in paths], sorted(p.name for p in Path(parent).iterdir())
        (['results.json', 'derivation.tex', 'report.md'], ['paper'])
        """
        from symctl.report import results

        return results.write(
            self, out, figures=figures, pdf=pdf, jobs=jobs, progress=progress, formats=formats
        )


PaperResults = Derivation
"""The former name of :class:`Derivation` (the results of any model, not only the paper's)."""
