"""The configuration check of ``lumped.studies.config``, in-process (milliseconds a case).

The pipeline runs the same check on ``config/config.yaml`` after ``--config``
overrides (tests/test_config_pipeline.py runs a few cases end to end). Here an
override is turned into values by Snakemake's own ``--config`` parser, so each
case sees exactly what the pipeline sees.
"""

import math
import tomllib
from pathlib import Path

import pytest
import yaml

import lumped.studies.config

ROOT = Path(__file__).resolve().parent.parent
DEFAULTS = yaml.safe_load((ROOT / "config" / "config.yaml").read_text(encoding="utf-8"))


def _overridden(*entries: str) -> dict:
    """config/config.yaml after ``--config entries``, parsed as Snakemake parses them."""
    cli = pytest.importorskip("snakemake.cli")
    return DEFAULTS | cli.parse_config(list(entries))


# (--config arguments, the one line the user must see)
BAD = [
    (["dt=-1"], "config: dt must be a finite number > 0 (s); got -1"),
    (["dt=0"], "config: dt must be a finite number > 0 (s); got 0"),
    (["dt=abc"], "config: dt must be a finite number > 0 (s); got 'abc'"),
    (["dt="], "config: dt must be a finite number > 0 (s); got an empty value"),
    (["dt=nan"], "config: dt must be a finite number > 0 (s); got nan"),
    (["dt=True"], "config: dt must be a finite number > 0 (s); got True"),
    (["mass=1e400"], "config: mass must be a finite number > 0 (kg); got inf"),
    (["mass=-.inf"], "config: mass must be a finite number > 0 (kg); got '-.inf'"),
    (["stiffness=0"], "config: stiffness must be a finite number > 0 (N/m); got 0"),
    (["dtt=1e-3"], "config: unknown key dtt; did you mean dt?"),
    (["gamma=0"], "config: gamma must be a number > 0, or inf for Coulomb friction (m/(N s)); got 0"),
    (["gamma=-inf"], "config: gamma must be a number > 0, or inf for Coulomb friction (m/(N s)); got -inf"),
    (
        ["threshold=-0.5"],
        "config: threshold must be a finite number > 0 (N) for the tutorial,"
        " whose demonstrations need a static band; got -0.5",
    ),
    (
        ["threshold=0"],
        "config: threshold must be a finite number > 0 (N) for the tutorial,"
        " whose demonstrations need a static band; got 0",
    ),
    (["force_amplitude_large=inf"], "config: force_amplitude_large must be a finite number (N); got inf"),
    (
        ["force_until=-1"],
        "config: force_until must be a number >= 0, or inf for a forcing never switched off (s); got -1",
    ),
    (["force_omega_over_pi=0"], "config: force_omega_over_pi must be a finite number > 0 (1/s); got 0"),
    (["x0_small=inf"], "config: x0_small must be a finite number (m); got inf"),
    (["x0_large=True"], "config: x0_large must be a finite number (m); got True"),
    (["t_end_small=nan"], "config: t_end_small must be a finite number > 0 (s); got nan"),
    (["dt=3"], "config: dt must be smaller than t_end_forced = 2.5 s; got 3"),
    (["dt=2", "t_end_forced=5"], "config: dt must be smaller than t_end_small = 1 s; got 2"),
    (
        ["dt=1e-9"],
        "config: dt must be at least t_end_forced/1e+07 = 2.5e-07 s (a run takes at most 1e+07 steps); got 1e-09",
    ),
]


@pytest.mark.parametrize(("overrides", "expected"), BAD, ids=[" ".join(c) for c, _ in BAD])
def test_bad_override_is_one_line(overrides, expected):
    raw = _overridden(*overrides)
    assert lumped.studies.config.problems(raw) == [expected]
    with pytest.raises(ValueError) as caught:
        lumped.studies.config.check(raw)
    assert str(caught.value) == expected


def test_every_problem_has_its_line_and_the_first_is_raised():
    raw = _overridden("dt=-1", "dtt=1", "mass=0")
    assert lumped.studies.config.problems(raw) == [
        "config: unknown key dtt; did you mean dt?",
        "config: mass must be a finite number > 0 (kg); got 0",
        "config: dt must be a finite number > 0 (s); got -1",
    ]
    with pytest.raises(ValueError, match="^config: unknown key dtt; did you mean dt[?]$"):
        lumped.studies.config.check(raw)


def test_unknown_key_without_a_close_one_lists_the_keys():
    (line,) = lumped.studies.config.problems(DEFAULTS | {"zzz": 1})
    assert line == f"config: unknown key zzz (keys: {', '.join(DEFAULTS)})"


@pytest.mark.parametrize("key", sorted(DEFAULTS))
def test_missing_key_is_named_with_its_range(key):
    rule = lumped.studies.config.schema()["properties"][key]
    raw = {k: v for k, v in DEFAULTS.items() if k != key}
    assert lumped.studies.config.problems(raw) == [f"config: {key} is missing; it must be {rule['description']}"]


@pytest.mark.parametrize("raw", [None, [], "dt: 1"], ids=repr)
def test_a_file_that_is_not_a_mapping_is_one_line(raw):
    (line,) = lumped.studies.config.problems(raw)
    assert line.startswith("config: the configuration must be a mapping of keys to values; got ")


def test_an_integer_beyond_double_range_is_refused():
    (line,) = lumped.studies.config.problems(DEFAULTS | {"mass": 10**400})
    assert line.startswith("config: mass must be a finite number > 0 (kg); got 1000")


# The paper's values varied one at a time: each is a valid configuration.
VALID = [
    ["gamma=inf"],
    ["gamma=.inf"],
    ["force_until=inf"],
    ["force_until=.inf"],
    ["mass=1", "dt=1e-3"],
    ["x0_small=0.05"],
    ["x0_small=-0.005"],
    ["force_amplitude_small=5"],
    ["force_amplitude_large=-10"],
    ["t_end_large=10"],
    ["mass=2"],
    ["stiffness=50"],
    ["gamma=10"],
    ["dt=5e-4"],
    ["force_omega_over_pi=1"],
    ["threshold=1e-3"],
]


@pytest.mark.parametrize("overrides", VALID, ids=" ".join)
def test_valid_override_is_checked_to_floats(overrides):
    values = lumped.studies.config.check(_overridden(*overrides))
    assert values.keys() == DEFAULTS.keys()
    assert all(type(v) is float for k, v in values.items() if k != "studies"), values
    for key, text in (o.split("=") for o in overrides):
        assert values[key] == float(text.replace(".inf", "inf"))


def test_the_defaults_are_valid_and_unchanged():
    assert lumped.studies.config.check(DEFAULTS) == DEFAULTS


def test_load_checks_what_it_reads(tmp_path, monkeypatch):
    bad = tmp_path / "config.yaml"
    bad.write_text(yaml.safe_dump(DEFAULTS | {"dt": -1}), encoding="utf-8")
    monkeypatch.setenv("LUMPED_CONFIG", str(bad))
    with pytest.raises(ValueError, match=r"^config: dt must be a finite number > 0 \(s\); got -1$"):
        lumped.studies.config.load()


def test_load_reads_inf_from_yaml(tmp_path):
    path = tmp_path / "config.yaml"
    path.write_text(yaml.safe_dump(DEFAULTS).replace("gamma: 1.0", "gamma: .inf"), encoding="utf-8")
    assert lumped.studies.config.load(path)["gamma"] == math.inf


def test_the_schema_is_package_data_and_its_only_copy():
    """Found by importlib.resources wherever the package is installed; no second copy."""
    shipped = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]
    assert "studies/config_schema.yaml" in shipped["lumped"]
    assert lumped.studies.config.schema()["properties"].keys() == DEFAULTS.keys()
    assert not (ROOT / "config" / "schema.yaml").exists()


@pytest.mark.parametrize("value", ["fast", 1, None])
def test_studies_other_than_default_or_full_is_refused_with_one_line(value):
    (line,) = lumped.studies.config.problems(DEFAULTS | {"studies": value})
    shown = repr(value) if isinstance(value, str) else ("an empty value" if value is None else "1")
    assert line == (
        "config: studies must be default or full (the resolution of the studies in results/studies/); got " + shown
    )


@pytest.mark.parametrize("value", ["default", "full"])
def test_studies_default_and_full_are_accepted(value):
    assert lumped.studies.config.check(DEFAULTS | {"studies": value})["studies"] == value


#: Values of every JSON kind around every bound of the schema (numbers at, just inside and just outside them).
PROBES = [
    0,
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    1,
    -1,
    1e308,
    -1e308,
    1.7976931348623157e308,
    -1.7976931348623157e308,
    math.inf,
    -math.inf,
    10**400,
    -(10**400),
    True,
    False,
    None,
    "default",
    "full",
    "fast",
    "1",
    [],
    {},
]


@pytest.mark.parametrize("key", list(lumped.studies.config.schema()["properties"]))
def test_the_schema_check_agrees_with_jsonschema(key):
    """lumped.studies.config checks the schema itself (import jsonschema costs a second); jsonschema is the reference."""
    from jsonschema import Draft202012Validator

    doc = lumped.studies.config.schema()
    reference = Draft202012Validator({**doc, "required": [], "additionalProperties": True})
    for value in PROBES:
        expected = any(e.path and e.path[0] == key for e in reference.iter_errors({key: value}))
        assert lumped.studies.config._violates(value, doc["properties"][key], doc["$defs"]) == expected, (key, value)


def test_a_schema_keyword_the_check_does_not_implement_is_refused(monkeypatch):
    import yaml

    text = lumped.studies.config.files("lumped.studies").joinpath("config_schema.yaml").read_text("utf-8")
    doc = yaml.safe_load(text)
    doc["properties"]["mass"]["multipleOf"] = 2
    monkeypatch.setattr(lumped.studies.config, "files", lambda _: _Text(yaml.safe_dump(doc)))
    lumped.studies.config.schema.cache_clear()
    try:
        with pytest.raises(ValueError, match=r"^config_schema.yaml: mass uses \['multipleOf'\], which lumped"):
            lumped.studies.config.schema()
    finally:
        monkeypatch.undo()
        lumped.studies.config.schema.cache_clear()


class _Text:
    """A stand-in for the package's files: every path reads ``text``."""

    def __init__(self, text):
        self.text = text

    def joinpath(self, _):
        return self

    def read_text(self, _):
        return self.text


# ---- issue 19: the runs' bounds, numbers YAML reads as strings, overflowing literals, malformed YAML ----------

#: Values the schema's ranges accept and the runs refuse: refused by problems() before any job, naming the key.
RUN_REFUSED = [
    ({"stiffness": 1e300}, "config: t_end_forced: the exact solution would have about 6.9e+149 events"),
    ({"x0_large": 1e300}, "config: x0_large: the run could reach spring force |F_s| = 1e+302"),
    ({"force_amplitude_large": 1e300}, "config: force_amplitude_large: the run could reach spring force"),
    ({"mass": 1e-320}, "config: mass: 1e-320 is below the smallest normal double"),
]


@pytest.mark.parametrize(("change", "expected"), RUN_REFUSED, ids=[next(iter(c)) for c, _ in RUN_REFUSED])
def test_values_the_runs_refuse_are_refused_by_the_check(change, expected):
    found = lumped.studies.config.problems(DEFAULTS | change)
    assert len(found) == 1 and found[0].startswith(expected), found


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("1e-4", "(YAML reads 1e-4 as a string: its floats need a dot and a signed exponent; write 1.0e-4)"),
        ("1e+4", "write 1.0e+4)"),
        ("2.5e3", "write 2.5e+3)"),
        ("1e400", "(beyond double precision, about 1.8e308; write .inf for infinity)"),
    ],
)
def test_a_number_yaml_reads_as_a_string_says_why(tmp_path, text, expected):
    path = tmp_path / "config.yaml"
    path.write_text((ROOT / "config" / "config.yaml").read_text().replace("dt: 1.0e-4", f"dt: {text}"))
    with pytest.raises(ValueError) as info:
        lumped.studies.config.load(path)
    message = str(info.value)
    assert message.startswith(f"config: dt must be a finite number > 0 (s); got '{text}' (") and message.endswith(
        expected
    )


def test_gamma_1e400_on_the_command_line_is_not_coulomb():
    """Snakemake reads gamma=1e400 as inf; with the --config texts it is refused, gamma=inf and .inf are not."""
    raw = _overridden("gamma=1e400")
    assert raw["gamma"] == math.inf and lumped.studies.config.problems(raw) == []  # the values alone cannot tell
    found = lumped.studies.config.problems(raw, ["gamma=1e400"])
    assert found == ["config: gamma=1e400 is beyond double precision (about 1.8e308); write .inf for infinity"]
    for text in ("gamma=inf", "gamma=.inf", "gamma=-inf"):
        assert not any("beyond double precision" in line for line in lumped.studies.config.problems(raw, [text]))


def test_an_overflowing_float_in_the_file_names_its_line(tmp_path):
    path = tmp_path / "config.yaml"
    path.write_text((ROOT / "config" / "config.yaml").read_text().replace("gamma: 1.0 ", "gamma: 1.0e+400 "))
    with pytest.raises(ValueError, match=rf"^config: {path}, line 8: 1\.0e\+400 is beyond double precision"):
        lumped.studies.config.load(path)
    path.write_text((ROOT / "config" / "config.yaml").read_text().replace("gamma: 1.0 ", "gamma: .inf "))
    assert lumped.studies.config.load(path)["gamma"] == math.inf


def test_malformed_yaml_names_the_file_and_line(tmp_path):
    path = tmp_path / "config.yaml"
    path.write_text("mass: 1.0\nstiffness: [1\n")
    with pytest.raises(ValueError, match=rf"^config: {path}, line 3: not valid YAML: expected ',' or ']'") as info:
        lumped.studies.config.load(path)
    assert "\n" not in str(info.value)
