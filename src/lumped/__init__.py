"""lumped: vibrations of lumped-parameter systems governed by DAEs.

A mass on a linear spring and a Bingham (or Coulomb, or any monotone) dashpot,
whose velocity is a function of its force but not the other way round
(Darbha, Nakshatrala and Rajagopal, 2020).

Modules, one idea each: :mod:`~lumped.laws` (springs and dashpots),
:mod:`~lumped.timestepping` (Algorithm 1), :mod:`~lumped.schemes` (the θ-method
and the event-capturing scheme), :mod:`~lumped.event_driven` (exact
solution), :mod:`~lumped.event_integration` (event-driven integration for any
law), :mod:`~lumped.textbook` (the ``sgn(0) = 0`` model),
:mod:`~lumped.forcing`, :mod:`~lumped.driver` (:func:`simulate`),
:mod:`~lumped.results`, :mod:`~lumped.cli`; the paper's runs are
:mod:`~lumped.examples`.
"""

from lumped.event_driven import Event, ExactSolution, Phase, solve_exact
from lumped.event_integration import IntegratedSolution, solve_event_driven
from lumped.forcing import SwitchedSine
from lumped.laws import (
    BinghamDashpot,
    Dashpot,
    DashpotState,
    HerschelBulkleyDashpot,
    LinearSpring,
    MonotoneDashpot,
    coulomb,
)
from lumped.laws_regularised import PapanastasiouDashpot
from lumped.results import COLUMNS, EnergyBalance, Trajectory
from lumped.driver import METHODS, simulate
from lumped.schemes import CapturedRun, event_capturing, theta_method
from lumped.system import Oscillator
from lumped.timestepping import algorithm1, backward_euler

__all__ = [
    "BinghamDashpot",
    "COLUMNS",
    "CapturedRun",
    "Dashpot",
    "DashpotState",
    "EnergyBalance",
    "Event",
    "ExactSolution",
    "HerschelBulkleyDashpot",
    "IntegratedSolution",
    "LinearSpring",
    "METHODS",
    "MonotoneDashpot",
    "Oscillator",
    "PapanastasiouDashpot",
    "Phase",
    "SwitchedSine",
    "Trajectory",
    "algorithm1",
    "backward_euler",
    "coulomb",
    "event_capturing",
    "simulate",
    "solve_event_driven",
    "solve_exact",
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
