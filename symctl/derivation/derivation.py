r"""What a derivation produced: :class:`Derivation`, with one record per realization and circuit.

The report stage writes a derivation (:mod:`symctl.report.results`);
:meth:`Derivation.to_dict`, :meth:`Derivation.write` and :meth:`Derivation.figure`
hand it over there. ``PaperResults`` is its former name, kept.

Examples
--------
>>> from symctl import derive_paper
>>> res = derive_paper()
>>> round(res.to_dict()["plant"]["f_bar"], 4)
43.8635
>>> res.circuits["controllable"].circuit.n_neurons
4
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType

import sympy as sp

from symctl._util.deprecate import renamed_method
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


def _hash_fields(obj) -> int:
    """A hash of a frozen dataclass's fields, mappings hashed by their items."""
    values = (getattr(obj, f.name) for f in dataclasses.fields(obj))
    return hash(tuple(tuple(v.items()) if isinstance(v, Mapping) else v for v in values))


@dataclass(frozen=True)
class RealizationRecord:
    """One realization of :math:`G_2` for the report: symbolic, numeric, and the checks of both.

    Parameters
    ----------
    name : str
        ``"controllable"``, ``"observable"`` or ``"general"``.
    symbolic, numeric : Realization
        The realization in the symbols of the factorization, and with the
        numbers of the simulations.
    values : mapping
        The numbers substituted (``epsilon_1``, ``C_1``, ... by name); kept read-only.
    check_symbolic, check_numeric : RealizationCheck
        The exact checks that each realizes :math:`G_2`.
    P, P_numeric : sympy Matrix or None
        The similarity transforms of the two from their canonical base (the
        realizer's :class:`~symctl.realization.realizers.RealizerResult`), or
        None for a canonical form.

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

    to_json = renamed_method("to_json", "to_dict")

    def to_dict(self) -> dict:
        """The entry of ``results.json``'s ``factorization.realizations`` for this realization."""
        from symctl.report import results

        return results.realization_json(self)


@dataclass(frozen=True)
class CircuitRecord:
    """One circuit of the report: its structure, compatibility, neurons and simulations.

    Parameters
    ----------
    name : str
        One of :data:`~symctl.report.spec.CIRCUITS`.
    structure : Structure
        The structure (gains, adders, unit delays); symbolic, for ``"general"``
        with the symbolic or seeded ``P`` of the :class:`RealizationRecord`.
    compatibility : CompatibilityResult
        Whether the structure fits the delay graph, with its evidence.
    circuit : Circuit
        The neurons of the structure (placed on the delay graph when compatible).
    firing : FiringPatterns
        The closed-loop simulations of the random realizations
        (:func:`~symctl.neural.firing.circuit_firing`).
    realizes : RealizationCheck, optional
        For the circuit ``"pathways"``: the proof that its structure realizes :math:`G` with the
        optimal gains (:math:`G_3 G_2 G_1 = G` for every section pole); the other circuits' proofs are
        their realization's check and the factorization's.

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

    to_json = renamed_method("to_json", "to_dict")

    def to_dict(self) -> dict:
        """The entry of ``results.json``'s ``circuits`` for this circuit."""
        from symctl.report import results

        return results.circuit_json(self)


@dataclass(frozen=True)
class Derivation:
    r"""Everything a derivation produced, symbolic and numeric: its inputs and each stage's result.

    Made by :func:`~symctl.derivation.derive` (and :func:`~symctl.derivation.derive_paper`);
    the fields are in the order of the pipeline. A value: frozen, equal when its fields
    are, picklable; :func:`~symctl.derivation.load_results` reads it back from
    ``results.json``.

    Parameters
    ----------
    model : ODEModel or None
        The nonlinear plant of the model (None for a discrete plant given directly).
    plant_symbolic, plant : DiscretePlant
        The discretized linear plant, in symbols (one state and one input, else None)
        and with the numbers.
    system : AugmentedSystem
        The delay-augmented system and cost.
    gains : Gains
        The optimal gains :math:`K_0, \dots, K_T` and the closed-loop poles.
    G_symbolic, G : DiscreteTF
        The controller :math:`G(z)` in the gains' symbols, and with the optimal gains.
    proved : bool
        Whether the derivation of :math:`G` was proved against the state-space matrices.
    seed : int
        The seed of the random realizations.
    factors : Factorization
        :math:`G = G_3 G_2 G_1`.
    realizations : mapping of str to RealizationRecord
        The realizations of :math:`G_2` (read-only).
    graph : DelayGraph
        The delay graph of the circuits.
    circuits : mapping of str to CircuitRecord
        The circuits, by name, in the order of :data:`~symctl.report.spec.CIRCUITS` (read-only).
    open_loop, closed_loop : Response
        The open-loop pulse response of the muscle and the optimal closed loop's.
    nonlinear : NonlinearCheck
        The linear controller around the nonlinear muscle.
    G2_symbolic : DiscreteTF, optional
        The :math:`G_2` the symbolic realizations realize: ``factors.G2``
        (the default), or beyond :data:`~symctl.realization.factorization.EXPANDED_ZEROS_MAX`
        sections ``factors.abbreviated()``, its zeros' coefficients written
        :math:`\sigma_k = e_k(\epsilon)`.
    atlas, candidates : optional
        The circuit atlas and its candidate circuits for this controller.
    spec : Model
        The inputs: the model the derivation ran on (a key of :func:`derive`'s cache).
    longest : DelaySearch, optional
        The longest-delay search, when the model asks for it.
    skipped : str, optional
        The stages left out, and why (e.g. the IFP circuit and the atlas of a
        controller with several states or inputs).
    pathways : ControllerCompatibility, optional
        The exact verdict on the delay graph (a MIMO controller's up to
        :data:`~symctl.derivation.pipeline.MIMO_GENERAL_MAX_ORDER`): the theorem,
        and the structure built along the graph's pathways.
    verified : Proof, optional
        The proof that :math:`G_3 G_2 G_1 = G` (``factors.verify()``), truthy when it holds.
    reduction : ControllerReduction, optional
        Whether the controller is minimal (truthy when it is); when not, ``G_symbolic``,
        ``G``, ``gains`` and every stage after them are the minimal controller's
        (:func:`~symctl.realization.reduction.controller_reduction`); None for an estimating model.
    kalman : KalmanGains, optional
        For a model that measures some states, or through noise: the delayed Kalman filter;
        ``G_symbolic`` and ``G`` are then the LQG compensator (:func:`~symctl.lqg_tf`, predictor
        form) and every circuit is driven by the measured outputs.
    variance : MonteCarlo, optional
        With ``kalman``: the closed loop's stationary covariance under the model's noise,
        predicted (Lyapunov) and measured (:func:`~symctl.monte_carlo`).
    spiking_cost : SpikingCost, optional
        What spikes cost each circuit (:func:`~symctl.spiking.cost.spiking_cost`), when
        asked for (``symctl paper --spiking``): a section and a figure of the report.

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
        if self.spec is not None:
            return self.spec.signal_names
        return ("f",), ("r",)

    def unit(self, name: str) -> str:
        """The unit of a state, input or parameter of the model ('' when not given)."""
        if self.spec is not None:
            return self.spec.unit(name)
        return {"f": "N", "r": "spikes/s", "tau": "s", "f_max": "N", "r_bar": "spikes/s"}.get(
            name, ""
        )

    __hash__ = _hash_fields

    def parameters(self) -> dict:
        """The inputs of the derivation (the ``parameters`` entry of :meth:`to_dict`).

        Returns
        -------
        dict
            ``tau``, ``f_max``, ``r_bar``, ``Ts``, the delays, ``Q``, ``R``
            (nested lists of floats) and ``seed``.

        Examples
        --------
        >>> from symctl import derive_paper
        >>> derive_paper(tau=0.05).parameters()["tau"]
        0.05
        """
        from symctl.report import results

        return results.parameters(self)

    to_json = renamed_method("to_json", "to_dict")

    def to_dict(self) -> dict:
        """The ``results.json`` document: a dictionary of plain lists, floats and strings.

        Returns
        -------
        dict
            Keys ``schema_version``, ``parameters``, ``plant``, ``augmented``,
            ``gains``, ``controller``, ``factorization``, ``closed_loop``,
            ``delay_graph``, ``circuits``, ``simulation`` and ``atlas`` (README,
            "results.json").

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
        """The names of the report's figures, in reading order (the file names of :meth:`write`).

        Returns
        -------
        list of str
            ``open_loop``, ``closed_loop``, ``delay_graph``, ``g1g3_structures``, then ``structure_<c>``,
            ``circuit_<c>`` and ``firing_<c>`` per circuit ``c``, ``nonlinear``, then
            ``atlas_overview`` and ``simplified_<class>`` for the paper's simplified
            circuits (table in :mod:`symctl.report.figures`).

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
        """One figure of the report, as a matplotlib ``Figure`` (saved by the caller).

        A hand-over to :func:`symctl.report.figures.make_figure`; ``name`` is one of
        :meth:`figure_names`, else a :class:`~symctl.errors.ParameterError`.

        Examples
        --------
        >>> from symctl import derive_paper
        >>> res = derive_paper()
        >>> type(res.figure("closed_loop")).__name__
        'Figure'
        >>> res.figure("no_such_figure")
        Traceback (most recent call last):
        ...
        symctl.errors.ParameterError: name: no figure 'no_such_figure'; the figures are [...]
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
        """Write the outputs of ``symctl paper`` into folder ``out``, all at once.

        The files are written into a fresh folder beside ``out`` and moved into
        place only when all are written (:class:`~symctl.report.output.OutputFolder`):
        ``out`` is always either the old complete folder or the new complete
        one, and on any error it is left as it was. ``out`` is checked before
        anything is written, and a second run on the same ``out`` is refused
        while one is under way.

        Parameters
        ----------
        out : path
            The folder: new (made, with its parents), empty, or the folder of
            an earlier run (replaced).
        figures : bool
            Also write the figures (:func:`symctl.report.figures.figure_names`).
        pdf : bool
            Also compile ``derivation.pdf`` when ``pdflatex`` is on the PATH.
        jobs : int, optional
            Processes drawing the figures (:func:`symctl.report.figures.write_figures`).
        progress : callable, optional
            Called with the name of each step (``"figures"``, ``"documents"``,
            ``"pdflatex"``) before it runs.
        formats : str or sequence of str
            The figures' formats (:func:`symctl.report.figures.figure_formats`): by
            default the PDF that ``derivation.tex`` includes and the PNG that
            ``report.md`` shows; add ``"svg"`` for SVG files. A document shows the
            figures written in its format.

        Returns
        -------
        list of Path
            The files written, inside ``out``: ``results.json``, the figures,
            ``derivation.tex``, ``report.md`` and ``derivation.pdf``.

        Raises
        ------
        SymctlTypeError
            ``out`` is not a path.
        ParameterError
            ``out`` is empty, a file, a folder holding other files, cannot be
            made, or is being written by another run; or ``jobs`` is not an
            integer >= 1; or ``formats`` names an unknown format.
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
        >>> derive_paper().write("")
        Traceback (most recent call last):
        ...
        symctl.errors.ParameterError: out: must name a folder, got ''
        """
        from symctl.report import results

        return results.write(
            self, out, figures=figures, pdf=pdf, jobs=jobs, progress=progress, formats=formats
        )


PaperResults = Derivation
"""The former name of :class:`Derivation` (the results of any model, not only the paper's)."""
