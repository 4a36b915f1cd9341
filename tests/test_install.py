"""Installing the package: where ``lumped.studies.config.load()`` finds the paper's values.

``config/config.yaml`` is the one file holding them; ``setup.py`` copies it into
the built package (``lumped/studies/paper_config.yaml``), so that a plain ``pip install
.`` works away from the checkout.  The fast tests check the order ``load()``
follows in this checkout.  The one marked ``slow`` builds a wheel from a copy
of the tracked files, installs it into a folder of its own and runs it from
another folder (3.5 s on an idle 2-core machine, 9 s on a busy one: pip and
the C compiler); ``pytest -m slow`` and .ci/run run it.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
import yaml
from conftest import copy_tracked_files

import lumped as L
import lumped.studies.config

ROOT = Path(__file__).resolve().parent.parent
PAPER = ROOT / "config" / "config.yaml"


def _decoy(folder: Path, mass: float) -> Path:
    """A ``config/config.yaml`` under ``folder`` that differs from the paper's in ``mass``."""
    values = yaml.safe_load(PAPER.read_text(encoding="utf-8")) | {"mass": mass}
    path = folder / "config" / "config.yaml"
    path.parent.mkdir(parents=True)
    path.write_text(yaml.safe_dump(values), encoding="utf-8")
    return path


@pytest.fixture
def no_env(monkeypatch):
    monkeypatch.delenv("LUMPED_CONFIG", raising=False)


def test_the_checkout_file_is_read_whatever_the_current_folder(tmp_path, monkeypatch, no_env):
    # another project's config/config.yaml in the current folder must not be read
    _decoy(tmp_path, mass=7.0)
    monkeypatch.chdir(tmp_path)
    assert lumped.studies.config.load() == lumped.studies.config.load(PAPER)
    assert lumped.studies.config.load()["mass"] == 1.0


def test_an_explicit_path_beats_the_environment_which_beats_the_checkout(tmp_path, monkeypatch, no_env):
    monkeypatch.setenv("LUMPED_CONFIG", str(_decoy(tmp_path / "env", mass=2.0)))
    assert lumped.studies.config.load()["mass"] == 2.0
    assert lumped.studies.config.load(_decoy(tmp_path / "arg", mass=3.0))["mass"] == 3.0


def test_a_named_file_that_is_missing_is_an_error_not_a_fallback(tmp_path, monkeypatch, no_env):
    monkeypatch.setenv("LUMPED_CONFIG", str(tmp_path / "absent.yaml"))
    with pytest.raises(FileNotFoundError):
        lumped.studies.config.load()


def test_no_configuration_anywhere_is_one_line(tmp_path, monkeypatch, no_env):
    # the package seen as installed outside any src/ folder, without its packaged copy
    # (an editable install imports from src/lumped, whose studies/ holds no paper_config.yaml)
    assert not (ROOT / "src" / "lumped" / "studies" / lumped.studies.config.PACKAGED_CONFIG).exists()
    monkeypatch.setattr(lumped.studies.config, "__file__", str(tmp_path / "site" / "lumped" / "studies" / "config.py"))
    with pytest.raises(ValueError, match=r"^config: no configuration found \(.*\); pass a path or set LUMPED_CONFIG$"):
        lumped.studies.config.load()


def test_plotting_without_matplotlib_names_the_extra():
    # sys.modules[name] = None makes `import name` fail as if it were not installed
    code = "import sys; sys.modules['matplotlib'] = None; import lumped.plotting"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 1
    last = done.stderr.strip().splitlines()[-1]
    assert last == (
        "ImportError: lumped.plotting needs matplotlib, which is not installed:"
        ' pip install "lumped[plot]" (in the checkout: pip install ".[plot]")'
    )


#: Run in the installed copy: where lumped comes from, its values, a short run.
INSTALLED = textwrap.dedent("""
    import json, lumped, lumped.studies.config
    tr = lumped.backward_euler(lumped.Oscillator.bingham(), 0.05, 1e-4, x0=0.5)  # the paper's values
    print(json.dumps({"file": lumped.__file__, "cfg": lumped.studies.config.load(), "x": tr.x.tolist()}))
""")


def _pip(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "pip", *args, "-q"], check=True, capture_output=True, timeout=300)


@pytest.mark.slow
def test_a_built_wheel_works_away_from_the_checkout(tmp_path):
    # built from a copy of the tracked files, as from a fresh clone: no build/ left over here
    source = copy_tracked_files(tmp_path / "clone")
    _pip("wheel", "--no-deps", "--no-build-isolation", str(source), "-w", str(tmp_path / "wheel"))
    (wheel,) = (tmp_path / "wheel").glob("lumped-*.whl")
    site = tmp_path / "site"
    _pip("install", "--no-deps", "--target", str(site), str(wheel))
    assert (site / "lumped" / "studies" / "paper_config.yaml").read_bytes() == PAPER.read_bytes()

    work = tmp_path / "work"
    _decoy(work, mass=7.0)  # an unrelated project's file in the current folder: not read
    env = {k: v for k, v in os.environ.items() if k != "LUMPED_CONFIG"} | {"PYTHONPATH": str(site)}

    def run(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run(
            [sys.executable, *args], cwd=work, env=env, capture_output=True, text=True, timeout=120, check=True
        )

    found = json.loads(run("-c", INSTALLED).stdout)
    assert Path(found["file"]).resolve().is_relative_to(site.resolve())
    assert found["cfg"] == lumped.studies.config.load(PAPER)
    reference = L.backward_euler(L.Oscillator.bingham(), 0.05, 1e-4, x0=0.5)
    assert np.array_equal(found["x"], reference.x)  # json round-trips doubles exactly

    run("-m", "lumped", "simulate", "--x0", "0.5", "--t-end", "0.05", "--output", "x.csv")
    assert np.array_equal(np.loadtxt(work / "x.csv", delimiter=",", skiprows=1), reference.as_array())
