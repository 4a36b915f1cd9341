"""``import lumped`` and the command line's modules stay light: no SciPy solver at import time.

SciPy's ``integrate`` and ``optimize`` cost about half a second to import,
more than a whole event-driven run; the package imports them (and
``scipy.linalg``) inside the functions that need them.  A fresh interpreter
per check, since this test session has SciPy loaded already.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

HEAVY = ("scipy.integrate", "scipy.optimize", "scipy.linalg")


@pytest.mark.parametrize(
    "modules",
    [
        "lumped",
        "lumped.cli, lumped.drivers.simulation, lumped.model.files, lumped.drivers.network, lumped.solvers.event_driven",
    ],
)
def test_importing_loads_no_scipy_solver(modules):
    code = f"import sys, {modules}; print(' '.join(m for m in {HEAVY!r} if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
    assert out.stdout.strip() == ""


def test_an_event_driven_run_loads_no_scipy_solver():
    """The event-driven method's whole run (integrator and stop search) is SciPy-free."""
    code = (
        "import sys, lumped as L\n"
        "osc = L.Oscillator(1.0, L.LinearSpring(100.0), L.HerschelBulkleyDashpot(1.0, 1.0, 0.5))\n"
        "L.simulate(osc, 1.0, 1e-3, x0=0.5, method='event-driven', rtol=1e-8)\n"
        f"print(' '.join(m for m in {HEAVY!r} if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
    assert out.stdout.strip() == ""


# Start-up (issue 35): ``import lumped`` imports no module of the package, every public name is imported on
# first use (PEP 562), and ``python -m lumped simulate`` imports the modules of its run and no more.

#: Modules that a ``simulate`` run of the paper's system has no use for: SciPy, the other commands and
#: their drivers (fit, sensitivities, response curves, limit cycles, sweeps), the system files' reader and
#: the distribution's metadata (read for ``--version`` only).
NOT_FOR_SIMULATE = (
    "scipy",
    "matplotlib",
    "importlib.metadata",
    "lumped.cli.cycles",
    "lumped.cli.fit",
    "lumped.cli.response",
    "lumped.cli.sweep",
    "lumped.drivers.cycles",
    "lumped.drivers.fit",
    "lumped.drivers.response",
    "lumped.drivers.sensitivity",
    "lumped.drivers.steady_sensitivity",
    "lumped.drivers.sweep",
    "lumped.model.files",
    "lumped.solvers.network_sensitivities",
    "lumped.solvers.sensitivities",
)


def _loaded(names: list[str], prefixes: tuple[str, ...]) -> list[str]:
    """The modules of ``names`` that are one of ``prefixes`` or inside one."""
    return sorted(n for n in names if any(n == p or n.startswith(p + ".") for p in prefixes))


def test_import_lumped_imports_no_module_of_the_package():
    code = "import sys, lumped; print(' '.join(m for m in sys.modules if m.startswith('lumped') or m == 'numpy'))"
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
    assert out.stdout.split() == ["lumped"]


@pytest.mark.parametrize("name", __import__("lumped").__all__)
def test_every_public_name_resolves_where_it_lives(name):
    """``lumped.X`` and ``from lumped import X`` give the object of its home module, the one ``_HOMES`` names."""
    import importlib

    import lumped

    home = importlib.import_module(_home(name))
    assert getattr(lumped, name) is getattr(home, name)
    namespace: dict[str, object] = {}
    exec(f"from lumped import {name}", namespace)  # noqa: S102 (the statement users write)
    assert namespace[name] is getattr(home, name)


def _home(name: str) -> str:
    import lumped

    (module,) = [m for m, names in lumped._HOMES.items() if name in names]
    return module


def test_the_public_names_are_all_and_dir_lists_them():
    import lumped

    homes = [name for names in lumped._HOMES.values() for name in names]
    assert sorted(homes) == sorted(set(lumped.__all__)) and len(homes) == len(lumped.__all__)
    with pytest.raises(AttributeError, match="has no attribute 'no_such_name'"):
        lumped.no_such_name  # noqa: B018


def test_dir_lists_what_it_listed_when_every_name_was_imported_at_once():
    """In a fresh interpreter, before and after a name is used: ``__all__``, the layers and ``__version__``."""
    show = "print(sorted(n for n in dir(L) if not n.startswith('_') or n == '__version__'))"
    code = f"import lumped as L; {show}; L.solve; {show}; print(sorted([*L.__all__, '__version__', *{LAYERS!r}]))"
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
    before, after, expected = out.stdout.splitlines()
    assert before == after == expected


#: The layers that ``import lumped`` made attributes of the package when it imported every public name.
LAYERS = ("drivers", "kernels", "laws", "model", "numerics", "solvers")


def _imported(*args: str) -> list[str]:
    """The modules that ``python -X importtime *args`` imports, in order, from its report on stderr."""
    out = subprocess.run([sys.executable, "-X", "importtime", *args], check=True, capture_output=True, text=True)
    return [line.rsplit("|", 1)[1].strip() for line in out.stderr.splitlines() if line.startswith("import time:")]


def test_a_simulate_run_imports_what_it_needs_and_no_more(tmp_path):
    """The command itself, ``python -m lumped simulate``, of the paper's system: its imports read from
    ``-X importtime`` (one line per module imported, whatever the timings), less those of the bare
    interpreter (its ``site``, which may differ between environments)."""
    run = ["-m", "lumped", "simulate", "--x0", "0.5", "--t-end", "0.01", "--output", str(tmp_path / "run.npz")]
    names = sorted(set(_imported(*run)) - set(_imported("-c", "pass")))
    assert "lumped.drivers.simulation" in names and "lumped.solvers.backward_euler" in names  # the reader reads
    assert _loaded(names, NOT_FOR_SIMULATE) == []
