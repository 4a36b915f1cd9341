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
:mod:`~lumped.plotting` and :mod:`~lumped.cli`.  The names of :data:`__all__`
are the public API, each imported from its module on first use (``_HOMES``).

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

#: Where each public name lives: module -> names.  ``import lumped`` imports none of them; the first
#: use of a name (``lumped.solve``, ``from lumped import solve``) imports its module (PEP 562,
#: :func:`__getattr__`), so that ``python -m lumped simulate`` loads what the run needs and not the
#: fit, the sensitivities or the limit cycles.  ``tests/test_imports.py`` holds it equal to :data:`__all__`.
_HOMES: dict[str, tuple[str, ...]] = {
    "lumped.drivers.cycles.api": ("CyclesTable", "cycles"),
    "lumped.drivers.fit": ("FitResult", "fit"),
    "lumped.drivers.methods": ("METHODS",),
    "lumped.drivers.simulation": ("simulate", "simulate_network", "solve"),
    "lumped.drivers.response": ("continue_orbits", "find_orbit"),
    "lumped.drivers.response.curve": ("response_curve",),
    "lumped.drivers.sensitivity": ("one_sided_sensitivities", "system_sensitivities"),
    "lumped.drivers.steady_sensitivity": ("steady_amplitude_sensitivities",),
    "lumped.laws": (
        "Bingham",
        "BinghamDashpot",
        "Contact",
        "Curve",
        "Dashpot",
        "DashpotState",
        "Friction",
        "HerschelBulkley",
        "HerschelBulkleyDashpot",
        "LinearDashpot",
        "LinearSpring",
        "LockingBingham",
        "MaxwellBingham",
        "Monotone",
        "MonotoneDashpot",
        "PapanastasiouDashpot",
        "SlipCurve",
        "SlipLaw",
        "Spring",
        "SpringString",
        "StribeckLaw",
        "coulomb",
    ),
    "lumped.model.files": ("load_system", "parse_system"),
    "lumped.model.forcing": ("Constant", "LoadSum", "SwitchedSine", "Table"),
    "lumped.model.network": ("Driver", "Load", "Mass", "Network"),
    "lumped.model.oscillator": ("Oscillator",),
    "lumped.model.problem": ("Problem",),
    "lumped.model.records": ("Record", "read_record"),
    "lumped.model.tables": ("read_table",),
    "lumped.model.trajectory": ("COLUMNS", "EnergyBalance", "Trajectory"),
    "lumped.solvers.backward_euler": ("algorithm1", "backward_euler"),
    "lumped.solvers.event_capturing": ("CapturedRun", "event_capturing"),
    "lumped.solvers.event_driven": ("IntegratedSolution", "solve_event_driven"),
    "lumped.solvers.events": ("Event", "Phase"),
    "lumped.solvers.exact": ("ExactSolution", "solve_exact"),
    "lumped.solvers.network_sensitivities": ("NetworkSensitivities",),
    "lumped.solvers.one_sided": ("one_sided",),
    "lumped.solvers.sensitivities": ("Sensitivities", "sensitivities"),
    "lumped.solvers.theta": ("theta_method",),
}
_HOME = {name: module for module, names in _HOMES.items() for name in names}

#: The layers that ``import lumped`` made attributes when it imported every name (``lumped.laws``
#: still works after ``import lumped`` alone, and ``dir(lumped)`` still lists them).
_SUBPACKAGES = ("drivers", "kernels", "laws", "model", "numerics", "solvers")

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


def __getattr__(name: str) -> object:
    """A public name, a layer or ``__version__``, imported on first use and kept (PEP 562)."""
    from importlib import import_module

    if name in _HOME:
        value = getattr(import_module(_HOME[name]), name)
    elif name in _SUBPACKAGES:
        value = import_module(f"{__name__}.{name}")
    elif name == "__version__":
        value = _version()
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """What ``dir(lumped)`` listed when every name was imported at once: the same whatever is loaded."""
    return sorted(set(globals()) | set(__all__) | set(_SUBPACKAGES) | {"__version__"})
