"""The table of the single-mass parameters (issue 20, item 5) and its readers agree.

``lumped.model.parameters.PARAMETERS`` is read by the command line, the sweep and the
configuration's schema and the oscillator's constructors (``Oscillator``,
``Oscillator.bingham``).  The laws sit a layer below the table and keep their own
defaults (a law is defined before any system); they are held here to the table's.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import sys
from pathlib import Path

import pytest
import yaml

import lumped.studies.config
from lumped.cli import build_parser
from lumped.drivers import sweep
from lumped.laws import BinghamDashpot, LinearSpring
from lumped.model.oscillator import Oscillator
from lumped.model.parameters import PARAMETERS, PER_ROW, shown
from lumped.numerics import validate

ROOT = Path(__file__).resolve().parent.parent
CONFIG = yaml.safe_load((ROOT / "config" / "config.yaml").read_text(encoding="utf-8"))
RANGED = [name for name, p in PARAMETERS.items() if p.range is not None]

#: Values at, just inside and just outside every bound of the table's ranges.  Subnormal
#: numbers are left out: the checks refuse a positive value below the smallest normal
#: double (``validate.TINY``), which a configuration's range leaves to the runs to refuse.
PROBES = [0.0, -0.0, validate.TINY, -validate.TINY, 1.0, -1.0, 2e8, -2e8, 2.0000001e8, -2.0000001e8]
PROBES += [sys.float_info.max, -sys.float_info.max, math.inf, -math.inf, math.nan]


def _accepted(name: str, value: float) -> bool:
    try:
        PARAMETERS[name].check(name, value)
    except ValueError:
        return False
    return True


def test_oscillator_bingham_defaults_are_the_tables():
    defaults = {n: p.default for n, p in inspect.signature(Oscillator.bingham).parameters.items() if n != "cls"}
    assert defaults == {name: PARAMETERS[name].default for name in defaults}
    assert set(defaults) == {"mass", "stiffness", "threshold", "gamma"}


def test_the_default_oscillator_is_the_tables():
    assert (
        Oscillator()
        == Oscillator.bingham()
        == Oscillator(
            PARAMETERS["mass"].default,
            LinearSpring(PARAMETERS["stiffness"].default),
            BinghamDashpot(PARAMETERS["threshold"].default, PARAMETERS["gamma"].default),
        )
    )


def test_bingham_dashpot_defaults_are_the_tables():
    fields = {f.name: f.default for f in dataclasses.fields(BinghamDashpot) if f.name in ("threshold", "gamma")}
    assert fields == {"threshold": PARAMETERS["threshold"].default, "gamma": PARAMETERS["gamma"].default}


@pytest.mark.parametrize("name", list(PARAMETERS))
def test_the_default_passes_its_check_and_reads_back_from_its_text(name):
    p = PARAMETERS[name]
    parse = validate.parse_int if p.integer else validate.parse_float
    assert p.check(name, p.default) == p.default
    assert parse(name, p.default_text) == p.default


@pytest.mark.parametrize("name", RANGED)
def test_the_range_is_the_checks(name):
    """What a configuration file accepts is what the API accepts (subnormals aside, see PROBES)."""
    for value in PROBES:
        assert PARAMETERS[name].range.accepts(value) == _accepted(name, value), value


@pytest.mark.parametrize("name", [n for n, p in PARAMETERS.items() if p.unit])
def test_the_help_states_the_unit(name):
    assert f"({PARAMETERS[name].unit})" in PARAMETERS[name].help


def test_the_options_are_the_tables_in_order():
    sub = build_parser()._subparsers._group_actions[0].choices  # noqa: SLF001
    for command, names in (("simulate", list(PARAMETERS)), ("sweep", [n for n in PARAMETERS if n != "save_every"])):
        actions = [a for a in sub[command]._actions if a.dest in PARAMETERS]  # noqa: SLF001
        assert [a.dest for a in actions] == names
        for a in actions:
            p = PARAMETERS[a.dest]
            assert a.option_strings == [p.option]
            assert a.help == f"{p.help} [default: {p.default_text}]"


def test_the_sweeps_parameters_are_the_tables():
    assert sweep.PARAMETERS == {name: PARAMETERS[name].default for name in PER_ROW}
    assert list(sweep.PARAMETERS) == list(PER_ROW)


#: Configuration key -> the table's parameter whose range and unit it takes.
CONFIG_KEYS = {
    "mass": "mass",
    "stiffness": "stiffness",
    "gamma": "gamma",
    "dt": "dt",
    "force_until": "force_until",
    "force_amplitude_small": "force_amplitude",
    "force_amplitude_large": "force_amplitude",
    "t_end_forced": "t_end",
    "x0_small": "x0",
    "t_end_small": "t_end",
    "x0_large": "x0",
    "t_end_large": "t_end",
}


@pytest.mark.parametrize("key", sorted(CONFIG_KEYS))
def test_the_configurations_ranges_are_the_tables(key):
    p = PARAMETERS[CONFIG_KEYS[key]]
    assert lumped.studies.config.schema()["properties"][key] == {**p.range.rule(), "description": p.describe()}


def test_the_configuration_narrows_threshold_only():
    """The tutorial needs a static band: threshold > 0 where the package accepts 0; the unit is the table's."""
    rule = lumped.studies.config.schema()["properties"]["threshold"]
    assert rule == {**PARAMETERS["threshold"].range.rule(), "exclusiveMinimum": 0, "description": rule["description"]}
    assert rule["description"].startswith(f"a finite number > 0 ({PARAMETERS['threshold'].unit})")


@pytest.mark.parametrize("key", ["mass", "stiffness", "threshold", "gamma", "dt"])
def test_the_paper_values_of_the_configuration_are_the_defaults(key):
    """The paper's section 3 values, in the configuration and in the table (``force_until`` differs on purpose:
    the configuration switches eq. (17) off at 1 s, the command line's default force is never switched off)."""
    assert CONFIG[key] == PARAMETERS[key].default


@pytest.mark.parametrize(
    ("value", "text"), [(1.0, "1"), (100.0, "100"), (1e-4, "1e-4"), (math.inf, "inf"), (2e9, "2e9")]
)
def test_shown(value, text):
    assert shown(value) == text
