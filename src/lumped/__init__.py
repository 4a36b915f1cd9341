"""lumped: vibrations of lumped-parameter systems governed by DAEs.

A mass on a linear spring and a Bingham (or Coulomb, or any monotone) dashpot,
whose velocity is a function of its force but not the other way round
(Darbha, Nakshatrala and Rajagopal, 2020), and networks of such elements.

The package is built in layers, each a folder that imports only the ones
below it: :mod:`~lumped.numerics` (validation, the sine, the root finder),
:mod:`~lumped.laws` (dashpots, springs and network elements),
:mod:`~lumped.model` (the oscillator, networks, loads, parameters,
trajectories), :mod:`~lumped.kernels` (the compiled loops),
:mod:`~lumped.solvers` (one module per method), :mod:`~lumped.drivers`
(:func:`solve`, the one entry point, which runs any :class:`Problem` by any
method of :data:`METHODS` and returns one :class:`Trajectory`; the sweep; the
response curves, :func:`response_curve`; the limit cycles on a belt, :func:`cycles`), :mod:`~lumped.studies`,
:mod:`~lumped.plotting` and :mod:`~lumped.cli`.  The names below are the
public API.

The other ways to start a run that users know are shims over :func:`solve`,
each documented with the call it stands for and what it adds:
:func:`simulate` (one oscillator, given as its parts) and
:func:`simulate_network` (backward Euler with its ``solver``) add nothing;
the one-mass solvers that ``solve`` runs for the paper's system
(:func:`backward_euler`, alias :func:`algorithm1`; :func:`solve_exact`;
:func:`solve_event_driven`; :func:`event_capturing`; :func:`theta_method`)
add what a :class:`Trajectory` does not carry (the solution in continuous
time, the located events, a ``kernel`` or ``theta`` of one's own).
"""

from lumped.drivers.cycles.api import CyclesTable, cycles
from lumped.drivers.fit import FitResult, fit
from lumped.drivers.methods import METHODS
from lumped.drivers.simulation import simulate, simulate_network, solve
from lumped.drivers.response import continue_orbits, find_orbit
from lumped.drivers.response.curve import response_curve
from lumped.drivers.sensitivity import one_sided_sensitivities, system_sensitivities
from lumped.drivers.steady_sensitivity import steady_amplitude_sensitivities
from lumped.laws import (
    Bingham,
    BinghamDashpot,
    Contact,
    Curve,
    Dashpot,
    DashpotState,
    Friction,
    HerschelBulkley,
    HerschelBulkleyDashpot,
    LinearDashpot,
    LinearSpring,
    LockingBingham,
    MaxwellBingham,
    Monotone,
    MonotoneDashpot,
    PapanastasiouDashpot,
    SlipCurve,
    SlipLaw,
    Spring,
    SpringString,
    StribeckLaw,
    coulomb,
)
from lumped.model.files import load_system, parse_system
from lumped.model.forcing import Constant, LoadSum, SwitchedSine, Table
from lumped.model.network import Driver, Load, Mass, Network
from lumped.model.oscillator import Oscillator
from lumped.model.problem import Problem
from lumped.model.records import Record, read_record
from lumped.model.tables import read_table
from lumped.model.trajectory import COLUMNS, EnergyBalance, Trajectory
from lumped.solvers.backward_euler import algorithm1, backward_euler
from lumped.solvers.event_capturing import CapturedRun, event_capturing
from lumped.solvers.event_driven import IntegratedSolution, solve_event_driven
from lumped.solvers.events import Event, Phase
from lumped.solvers.exact import ExactSolution, solve_exact
from lumped.solvers.network_sensitivities import NetworkSensitivities
from lumped.solvers.one_sided import one_sided
from lumped.solvers.sensitivities import Sensitivities, sensitivities
from lumped.solvers.theta import theta_method

__all__ = [
    "Bingham",
    "BinghamDashpot",
    "COLUMNS",
    "CapturedRun",
    "Constant",
    "Contact",
    "Curve",
    "CyclesTable",
    "Dashpot",
    "DashpotState",
    "Driver",
    "EnergyBalance",
    "Event",
    "ExactSolution",
    "FitResult",
    "Friction",
    "HerschelBulkley",
    "HerschelBulkleyDashpot",
    "IntegratedSolution",
    "LinearDashpot",
    "LinearSpring",
    "Load",
    "LoadSum",
    "LockingBingham",
    "METHODS",
    "Mass",
    "MaxwellBingham",
    "Monotone",
    "MonotoneDashpot",
    "Network",
    "NetworkSensitivities",
    "Oscillator",
    "PapanastasiouDashpot",
    "Phase",
    "Problem",
    "Record",
    "Sensitivities",
    "SlipCurve",
    "SlipLaw",
    "Spring",
    "SpringString",
    "StribeckLaw",
    "SwitchedSine",
    "Table",
    "Trajectory",
    "algorithm1",
    "backward_euler",
    "cycles",
    "continue_orbits",
    "coulomb",
    "event_capturing",
    "find_orbit",
    "fit",
    "load_system",
    "one_sided",
    "one_sided_sensitivities",
    "parse_system",
    "read_record",
    "read_table",
    "response_curve",
    "sensitivities",
    "simulate",
    "simulate_network",
    "solve_event_driven",
    "solve",
    "solve_exact",
    "steady_amplitude_sensitivities",
    "system_sensitivities",
    "theta_method",
]


def _version() -> str:
    """The installed distribution's version (pyproject.toml is its one source).

    Run from a source tree that was never installed, there is no metadata:
    the version is then read from ``pyproject.toml`` next to ``src/``.
    """
    from importlib import metadata

    try:
        return metadata.version("lumped")
    except metadata.PackageNotFoundError:
        import pathlib
        import tomllib

        pyproject = pathlib.Path(__file__).resolve().parents[2] / "pyproject.toml"
        try:
            return str(tomllib.loads(pyproject.read_text(encoding="utf-8"))["project"]["version"])
        except (OSError, KeyError, tomllib.TOMLDecodeError):
            return "unknown"


__version__ = _version()
