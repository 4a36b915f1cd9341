"""The one registry of methods: :data:`METHODS`, name -> :class:`Method`.

Each method is declared here once, with what it can run and its options.
Everything that chooses a method by name reads this table:
:func:`lumped.solve` (the one entry point: a method's options, the
``solver`` of the method that runs any network), the command line (``--method``'s choices
and help, the option flags such as ``--rtol``, which methods run a
``--system`` network), :mod:`lumped.drivers.sweep` (the methods a sweep runs) and the
studies (:mod:`lumped.studies.accuracy` compares every method, grouped by
``fixed_step`` and ``bingham_only``; :mod:`lumped.studies.rest` two of them).

Adding a method
---------------
1. Write its one-mass solver with the signature of :data:`Solver`: the
   positional arguments ``(osc, t_end, dt, x0, v0, force, save_every)``, then
   its options, keyword-only, and return a :class:`~lumped.model.trajectory.Trajectory`
   on the grid ``t_n = n*dt``.
2. Declare a :class:`Method` in :data:`METHODS`: its one-line description
   (``--help`` shows it), whether it needs the Bingham form of the law
   (``bingham_only``), whether a sweep runs it (``batch``), the step solvers
   by which it runs any network (``network_solvers``; none: one-mass
   networks only, as an oscillator), its solver in continuous time if it
   has one (``solution``; none: a fixed-step scheme), whether its forcing
   must be a sine on from ``t = 0`` (``sine_forcing``: the load answers
   :meth:`~lumped.model.forcing.Forcing.sine`),
   its solver of the networks whose every phase is linear, if it has one
   (``piecewise_networks``: run for a network that is not of the one-mass
   form), whether it runs friction whose graph is not monotone and driven
   points (``runs_friction``), and its :class:`Option` s.

A method asked to run what it cannot says so in one line that names the
method and the reason (:meth:`Method.refusal`).  What ``--help`` and the
guide's reference page say a method runs, and its options, are read from
the same fields (:attr:`Method.runs`, :attr:`Method.option_texts`,
:mod:`lumped.cli.reference`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from lumped.model.forcing import SwitchedSine, as_sine, kind_of
from lumped.model.network import Network
from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import Trajectory
from lumped.solvers.backward_euler import backward_euler
from lumped.solvers.event_capturing import event_capturing
from lumped.solvers.event_capturing_network import solve_capturing_network
from lumped.solvers.event_driven import DEFAULT_RTOL, solve_event_driven, validate_rtol
from lumped.solvers.event_driven_network import TAKES as EVENT_DRIVEN_TAKES
from lumped.solvers.event_driven_network import refusal as event_driven_refusal
from lumped.solvers.event_driven_network import solve_event_driven_network
from lumped.solvers.exact import ExactSolution, solve_exact
from lumped.solvers.exact_network import solve_exact_network
from lumped.solvers.moreau_jean import BINGHAM_REASON, DEFAULT_THETA, moreau_jean, validate_theta
from lumped.solvers.network_phase import _TAKES as PIECEWISE_TAKES  # the one wording of what they take
from lumped.solvers.network_phase import SLIP_TAKES, refusal
from lumped.solvers.theta import theta_method

__all__ = ["ALIASES", "METHODS", "NETWORK_SOLVERS", "OPTIONS", "SWEEP_METHODS", "Method", "Option", "Solver"]

Force = SwitchedSine | Callable[[np.ndarray], np.ndarray] | None
#: A one-mass solver: ``(osc, t_end, dt, x0, v0, force, save_every, **options) -> Trajectory``.
Solver = Callable[..., Trajectory]
#: The keyword that picks a method's step solver of networks (:attr:`Method.network_solvers`).
SOLVER = "solver"


@dataclass(frozen=True)
class Option:
    """An option of a method: its keyword (the command line's flag is ``--`` + it,
    dashes for underscores), its check, its default (a float: the command line
    parses the flag's value as one) and its help.

    ``check(value)`` returns the cleaned value or raises a ``ValueError`` that
    begins with ``name``.
    """

    name: str
    check: Callable[[object], object]
    default: float
    #: What it is, for ``--help`` ("relative tolerance").
    help: str
    #: The values it accepts, for ``--help`` ("in [2.2e-14, 1e-2]").
    accepted: str

    @property
    def flag(self) -> str:
        """The command line's option, ``--rtol``."""
        return "--" + self.name.replace("_", "-")


@dataclass(frozen=True)
class Method:
    """A method: how it runs one mass, what else it can run, its options.

    Calling a method runs its one-mass solver (``METHODS[name](osc, t_end,
    dt, x0, v0, force, save_every, **options)``), as the registry's values
    did when they were the solvers themselves.
    """

    name: str
    #: The one-mass solver (:data:`Solver`).
    run: Solver
    #: One line for ``--help``.
    description: str
    #: True if it needs the law's Bingham form (``Dashpot.bingham_form()``, a Bingham or Coulomb law).
    bingham_only: bool = False
    #: True if a sweep runs it (a batch of rows).
    batch: bool = False
    #: The step solvers by which it runs any network (the option ``solver`` of :func:`lumped.solve`),
    #: the default first; empty if it runs one-mass networks only, as an oscillator.
    network_solvers: tuple[str, ...] = ()
    options: tuple[Option, ...] = ()
    #: Why it needs the Bingham form (when ``bingham_only``), for its refusal of another law.
    bingham_reason: str = "its closed forms need a Bingham or Coulomb law"
    #: Why a sweep does not run it (when ``batch`` is false), for its refusal.
    not_batch: str = "a sweep does not run it"
    #: Its solver in continuous time, ``(osc, t_end, *, x0, v0, force, **options) -> ExactSolution``
    #: (the events, the rest, the motion at any time), which ``run`` samples on the grid; ``None``
    #: for a fixed-step scheme, whose ``dt`` is its step.
    solution: Callable[..., ExactSolution] | None = None
    #: True if its forcing must be a sine on from ``t = 0`` (its closed forms or its events use the formula,
    #: asked of the load by :func:`~lumped.model.forcing.as_sine`); false if it takes any callable of time.
    sine_forcing: bool = False
    #: Its solver of piecewise-linear networks (springs, Bingham, Coulomb, linear dashpots; with
    #: ``piecewise_slip``, friction contacts with a linear slip curve and points driven at constant velocities),
    #: ``(network, t_end, dt, *, save_every) -> Trajectory``, which refuses any other network in one
    #: line (:meth:`network_refusal`); ``None`` if it runs one-mass networks only (or any network, by
    #: ``network_solvers``).
    piecewise_networks: Callable[..., Trajectory] | None = None
    #: True if that solver takes any load (it steps the loads as functions of time); false if only sines
    #: and constants (its closed forms carry them).  A one-mass system whose load the one-mass solver
    #: refuses then runs through it.
    piecewise_any_load: bool = False
    #: True if that solver also runs friction contacts whose slip curve is linear (static above kinetic,
    #: a viscous part) and points driven at constant velocities (:func:`~lumped.solvers.network_phase.refusal`'s
    #: ``slip``).
    piecewise_slip: bool = False
    #: The refusal of that solver, ``(network) -> str | None``, and what it runs in words, when they are not the
    #: piecewise-linear networks' (:func:`~lumped.solvers.network_phase.refusal`, ``PIECEWISE_TAKES``).
    piecewise_refusal: Callable[[Network], str | None] | None = None
    piecewise_takes: str | None = None
    #: Former names that still select it (``METHODS[alias]`` is this method; ``--help`` and a note on use say so).
    aliases: tuple[str, ...] = ()
    #: True if it runs friction contacts whose graph is not monotone (static above kinetic, a falling slip
    #: curve: point 12 of :class:`~lumped.laws.element.Element`) and driven points, on any network.
    runs_friction: bool = False

    def __call__(self, *args: object, **options: object) -> Trajectory:
        return self.run(*args, **options)

    @property
    def fixed_step(self) -> bool:
        """True if ``dt`` is its step, so that its error falls with ``dt``; false if ``dt`` only samples its solution."""
        return self.solution is None

    @property
    def runs_networks(self) -> bool:
        """True if it runs any network, not only one-mass networks."""
        return bool(self.network_solvers)

    @property
    def runs(self) -> str:
        """What it runs, in words (``--help`` and the guide): one mass with which law and load, and which networks."""
        law = "a Bingham or Coulomb law" if self.bingham_only else "any monotone dashpot law"
        load = "a sine or a constant load from t = 0" if self.sine_forcing else "any load"
        if self.sine_forcing and self.piecewise_any_load:  # a refused load runs as a one-mass network (by_network)
            load += " (any load with a Bingham or Coulomb law)"
        if self.runs_networks:
            networks = "any network"
        elif self.piecewise_takes is not None:
            networks = f"networks of {self.piecewise_takes}, and no network of more than one mass"
        elif self.piecewise_networks is not None:
            takes = PIECEWISE_TAKES.split(" under ")[0] + (" under any load" if self.piecewise_any_load else "")
            networks = "networks of " + (takes if self.piecewise_any_load else PIECEWISE_TAKES)
            if self.piecewise_slip:
                networks = networks.replace(" under ", f", {SLIP_TAKES} under ")
        else:
            networks = "no network of more than one mass"
        if self.runs_friction:
            networks += (
                ", with friction whose static force is above its kinetic one or whose slip curve falls "
                "(the step's dt bounded so that it is unique) and driven points (belts)"
            )
        return f"one mass with {law} under {load}; {networks}"

    @property
    def option_texts(self) -> tuple[str, ...]:
        """Each option as ``--flag: what it is, the values it accepts, its default`` (``--help`` and the guide)."""
        return tuple(f"{o.flag}: {o.help}, {o.accepted}, default {o.default:g}" for o in self.options)

    def refusal(self, oscillator: Oscillator) -> str | None:
        """Why this method cannot run ``oscillator`` (one line naming the method), or ``None`` if it can."""
        if self.bingham_only and oscillator.dashpot.bingham_form() is None:
            law = type(oscillator.dashpot).__name__
            return f"method: {self.name!r} cannot run a {law}: {self.bingham_reason}"
        return None

    def force_refusal(self, force: object) -> str | None:
        """Why this method cannot run the forcing ``force`` (one line naming the method), or ``None`` if it can."""
        if self.sine_forcing and callable(force) and as_sine(force) is None:
            *others, last = (n for n, m in METHODS.items() if not m.sine_forcing or m.piecewise_any_load)
            anyone = f"{', '.join(others)} and {last}" if others else last
            return (
                f"force: method {self.name!r} runs a sine or a constant load from t = 0, "
                f"not {kind_of(force)}; {anyone} run any load"
            )
        return None

    def network_refusal(self, network: Network) -> str | None:
        """Why :attr:`piecewise_networks` cannot run ``network`` (one line naming the method and the element
        or load), or ``None`` if it can; a method without one refuses every network in one line."""
        if self.piecewise_networks is None:
            return f"method {self.name!r} runs one-mass systems only"
        if self.piecewise_refusal is not None:
            return self.piecewise_refusal(network)
        return refusal(network, self.name, any_load=self.piecewise_any_load, slip=self.piecewise_slip)

    def by_network(self, force: object, network: Network) -> bool:
        """True if the one-mass solver refuses ``force`` (a table, ground motion) but the solver of
        piecewise-linear networks takes any load and runs ``network``, the one-mass system with it."""
        refused = self.force_refusal(force) is not None  # a constant from t = 0 runs as its sine (as_sine)
        return self.piecewise_any_load and refused and self.network_refusal(network) is None

    @property
    def option_names(self) -> tuple[str, ...]:
        """The keywords :func:`lumped.solve` takes for it: its :attr:`options`, and ``solver`` (one of
        :attr:`network_solvers`) if it runs any network.  ``solver`` is the API's alone: the command
        line and a sweep offer the :data:`OPTIONS` flags, and a network run from them takes ``"auto"``."""
        return tuple(o.name for o in self.options) + ((SOLVER,) if self.runs_networks else ())

    def takes(self, names: object, *, command_line: bool = False) -> None:
        """Refuse the first of ``names`` that is not one of this method's options; from the
        ``command_line``, the message lists only the options it offers as flags (not ``solver``)."""
        own = self.option_names
        shown = tuple(o.name for o in self.options) if command_line else own
        for name in names:  # type: ignore[attr-defined]
            if name not in own:
                takes = f"its options are {', '.join(shown)}" if shown else "it takes none"
                raise ValueError(f"{name}: method {self.name!r} takes no option {name!r} ({takes})")

    def check_options(self, options: Mapping[str, object]) -> dict[str, object]:
        """``options`` checked and cleaned, or a ``ValueError`` naming the first it does not take or refuses."""
        self.takes(options)
        own = {o.name: o.check for o in self.options} | {SOLVER: self._check_solver}
        return {name: own[name](value) for name, value in options.items()}

    def _check_solver(self, solver: object) -> str:
        """``solver`` if it is one of :attr:`network_solvers`, else a ``ValueError`` naming them."""
        if not isinstance(solver, str) or solver not in self.network_solvers:
            raise ValueError(f"solver must be one of {', '.join(self.network_solvers)}; got {solver!r}")
        return solver


def _backward_euler(
    osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, force: Force, save_every: int
) -> Trajectory:
    return backward_euler(osc, t_end, dt, x0=x0, v0=v0, force=force, save_every=save_every)


def _exact(osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, force: Force, save_every: int) -> Trajectory:
    sol = solve_exact(osc, t_end, x0=x0, v0=v0, force=force)  # type: ignore[arg-type]
    return sol.sample(dt, save_every)


def _event_capturing(
    osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, force: Force, save_every: int
) -> Trajectory:
    return event_capturing(osc, t_end, dt, x0=x0, v0=v0, force=force, save_every=save_every).trajectory  # type: ignore[arg-type]


def _theta(osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, force: Force, save_every: int) -> Trajectory:
    return theta_method(osc, t_end, dt, x0=x0, v0=v0, force=force, save_every=save_every)


def _moreau_jean(
    osc: Oscillator,
    t_end: float,
    dt: float,
    x0: float,
    v0: float,
    force: Force,
    save_every: int,
    *,
    theta: float = DEFAULT_THETA,
) -> Trajectory:
    return moreau_jean(osc, t_end, dt, theta=theta, x0=x0, v0=v0, force=force, save_every=save_every)


def _event_driven(
    osc: Oscillator,
    t_end: float,
    dt: float,
    x0: float,
    v0: float,
    force: Force,
    save_every: int,
    *,
    rtol: float = DEFAULT_RTOL,
) -> Trajectory:
    sol = solve_event_driven(osc, t_end, x0=x0, v0=v0, force=force, rtol=rtol)  # type: ignore[arg-type]
    return sol.sample(dt, save_every)


#: Why the schemes compared by the accuracy study do not run in a sweep.
_STUDY_ONLY = "a scheme of the accuracy study, for which a sweep has no cost estimate"
_RTOL = Option("rtol", validate_rtol, DEFAULT_RTOL, "relative tolerance", "in [2.2e-14, 1e-2]")
_THETA = Option("theta", validate_theta, DEFAULT_THETA, "weight of the new level of the smooth forces", "in (0, 1]")


class _Registry(Mapping[str, Method]):
    """The methods by name, read-only; a method's alias (:attr:`Method.aliases`) finds it too,
    but iteration, ``len`` and ``--help``'s list give each method once, by its name."""

    def __init__(self, methods: Mapping[str, Method]) -> None:
        self._methods = MappingProxyType(dict(methods))
        self._aliases = {a: m.name for m in methods.values() for a in m.aliases}

    def __getitem__(self, name: str) -> Method:
        return self._methods[self._aliases.get(name, name)]

    def __iter__(self) -> Iterator[str]:
        return iter(self._methods)

    def __len__(self) -> int:
        return len(self._methods)


#: The registry, in the order ``--help`` lists it.
METHODS: Mapping[str, Method] = _Registry(
    {
        m.name: m
        for m in (
            Method(
                "backward-euler",
                _backward_euler,
                "Algorithm 1 (backward Euler)",
                batch=True,
                network_solvers=("auto", "active-set", "compiled", "python"),
                runs_friction=True,
            ),
            Method(
                "exact",
                _exact,
                "Exact event-driven solution, sampled on the grid",
                bingham_only=True,
                batch=True,
                solution=solve_exact,
                sine_forcing=True,
                piecewise_networks=solve_exact_network,
                piecewise_slip=True,
            ),
            Method(
                "event-driven",
                _event_driven,
                "Event-driven integration for any monotone dashpot law or friction contact (DOP853 slip phases, "
                "exact stick), sampled on the grid",
                batch=True,
                options=(_RTOL,),
                solution=solve_event_driven,
                sine_forcing=True,
                piecewise_networks=solve_event_driven_network,
                piecewise_refusal=event_driven_refusal,
                piecewise_takes=EVENT_DRIVEN_TAKES,
            ),
            Method(
                "event-locating",
                _event_capturing,
                "Time stepping with event location: trapezoidal steps within each mode, every switch located "
                "inside its step (event-driven on a fixed grid), order 2 through the switches",
                not_batch=_STUDY_ONLY,
                sine_forcing=True,
                piecewise_networks=solve_capturing_network,
                piecewise_any_load=True,
                aliases=("event-capturing",),
            ),
            Method(
                "theta",
                _theta,
                "Theta-method with theta = 1/2 (trapezoidal rule), switches crossed blindly",
                not_batch=_STUDY_ONLY,
            ),
            Method(
                "moreau-jean",
                _moreau_jean,
                "Moreau-Jean theta-scheme as Siconos runs it: smooth forces by the theta-rule, "
                "the band implicit (theta = 1 is Algorithm 1)",
                bingham_only=True,
                bingham_reason=BINGHAM_REASON,
                not_batch=_STUDY_ONLY,
                options=(_THETA,),
            ),
        )
    }
)
#: Former names of methods -> their names (``METHODS`` finds a method by either).
ALIASES: Mapping[str, str] = MappingProxyType({a: m.name for m in METHODS.values() for a in m.aliases})
#: Views of the registry.  The methods a sweep runs (``batch``; backward Euler in the batched kernel):
SWEEP_METHODS = tuple(name for name, m in METHODS.items() if m.batch)
#: The step solvers of a network run (``solve``'s option ``solver``), of the method that runs any network:
NETWORK_SOLVERS = next(m.network_solvers for m in METHODS.values() if m.runs_networks)
#: Every option of a method, by name, with the methods that take it.
OPTIONS: Mapping[str, tuple[Option, tuple[str, ...]]] = MappingProxyType(
    {o.name: (o, tuple(n for n, m in METHODS.items() if o in m.options)) for m in METHODS.values() for o in m.options}
)


def get(method: object) -> Method:
    """The registered :class:`Method` named ``method``, or ``ValueError("method must be one of ...")``."""
    if not isinstance(method, str) or method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}; got {method!r}")
    return METHODS[method]


def refuse_sweep(method: object) -> None:
    """Refuse a method that a sweep does not run: an unknown name, or one in one line naming it and the reason."""
    if not isinstance(method, str) or method not in METHODS:
        raise ValueError(f"method: a sweep runs {', '.join(SWEEP_METHODS)}; got {method!r}")
    m = METHODS[method]
    named = repr(m.name) if method == m.name else f"{method!r} (an alias of {m.name!r})"
    if not m.batch:
        raise ValueError(f"method: {named} cannot run a sweep: {m.not_batch} (a sweep runs {', '.join(SWEEP_METHODS)})")
