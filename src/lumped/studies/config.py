"""The shared parameter file ``config/config.yaml``: where it is, and its check.

The runs it describes are built by :mod:`lumped.studies.examples`.

The notebooks, the Snakemake pipeline and the article all read the same file.
The environment variable ``LUMPED_CONFIG`` points to another file (the
pipeline sets it to the configuration after ``--config`` overrides).  An
installed package (``pip install .``, no checkout at hand) carries a copy of
the file as built, ``lumped/studies/paper_config.yaml`` (``setup.py`` copies it), so
:func:`load` gives the paper's values from any folder.

Every reader checks the values the same way, here: :func:`problems` lists what
is wrong, one line each, and :func:`check` (which :func:`load` calls) returns
the values or raises :class:`ValueError` with the first of those lines, e.g.::

    config: dt must be a finite number > 0 (s); got -1

The accepted ranges are the JSON schema ``config_schema.yaml`` shipped with
the package, plus two checks a schema cannot state (:func:`problems`).  The
keys that are single-mass parameters (``mass``, ``x0_small``, ...) take their
range and unit from :data:`lumped.model.parameters.PARAMETERS`, as the command line
and the sweep do (:func:`schema`).  The
schema is checked by :func:`_violates`, which implements the few keywords it
uses (:data:`SCHEMA_KEYWORDS`) rather than importing ``jsonschema``: with the
notebook environment's format extras installed, ``import jsonschema`` compiles
some forty grammars and takes a second or more, paid by every notebook, study
job and pipeline start.  The tests check :func:`_violates` against
``jsonschema`` on the schema and on values in and out of every range.
"""

from __future__ import annotations

import difflib
import math
import os
from functools import cache
from importlib.resources import files
from importlib.resources.abc import Traversable
from pathlib import Path
from typing import Any

from lumped.model.parameters import PARAMETERS

__all__ = ["load", "default", "check", "problems", "schema"]

#: End-time keys: dt must be below each of them.
END_TIMES = ("t_end_forced", "t_end_small", "t_end_large")
#: Most steps one run of the pipeline may take: the pipeline's memory budget, well
#: below :data:`lumped.numerics.validate.MAX_STEPS` (the bound of every run, a guard
#: against typos).  A run keeps six float64 columns per step (plus the exact
#: solution sampled on the same grid), about 1 GB at 1e7 steps, and a notebook
#: holds several runs at once; the paper's runs take at most 4e4.
MAX_PIPELINE_STEPS = 10**7


#: The JSON-schema keywords :func:`_violates` implements, each as the 2020-12 draft defines it for numbers
#: and strings; a schema with another keyword is refused (:func:`schema`).
SCHEMA_KEYWORDS = frozenset({"type", "enum", "minimum", "maximum", "exclusiveMinimum", "$ref", "description"})

#: The keyword of ``config_schema.yaml`` (not JSON schema's) that makes a property the entry of
#: :data:`lumped.model.parameters.PARAMETERS` it names; :func:`schema` replaces it by that entry's rule.
TABLE_KEYWORD = "parameter"

#: The copy of config/config.yaml that setup.py puts into the built package.
PACKAGED_CONFIG = "paper_config.yaml"


def load(path: str | os.PathLike[str] | None = None) -> dict[str, Any]:
    """Read and check the configuration; the paper's values unless told otherwise.

    Parameters
    ----------
    path : str or path-like, optional
        The file to read.  Without it, the first of: ``$LUMPED_CONFIG``; the
        ``config/config.yaml`` of the checkout this package is imported from
        (a source tree or an editable install); the copy built into the
        package (:data:`PACKAGED_CONFIG`).  The current folder plays no part,
        so another project's ``config/config.yaml`` is never read by chance.

    Returns
    -------
    dict
        The values as :func:`check` returns them.

    Raises
    ------
    ValueError
        With the line ``config: <key> ...`` of the first problem, or
        ``config: no configuration found ...`` if there is no file to read.
    OSError
        If ``path`` or ``$LUMPED_CONFIG`` names a file that cannot be read
        (never replaced by the default).
    """
    return check(_read(_source(path or os.environ.get("LUMPED_CONFIG"))))


def default() -> dict[str, Any]:
    """The repository's configuration, whatever ``$LUMPED_CONFIG`` says (what ``--config`` overrides)."""
    return check(_read(_source(None)))


#: How YAML writes infinity (any other literal that overflows to inf is refused).
_INF_WORDS = frozenset({".inf", "+.inf", "-.inf", ".Inf", "+.Inf", "-.Inf", ".INF", "+.INF", "-.INF"})


def _read(source: Path | Traversable) -> Any:
    """The YAML of ``source``; ``ValueError`` naming the file and line of malformed YAML or of a number beyond
    double precision (``1.0e400``, which YAML would read as infinity: Coulomb friction for ``gamma``)."""
    import yaml

    class Loader(yaml.SafeLoader):
        pass

    def number(loader: yaml.SafeLoader, node: yaml.ScalarNode) -> float:
        value = loader.construct_yaml_float(node)
        if math.isinf(value) and node.value not in _INF_WORDS:
            raise ValueError(
                f"config: {source}, line {node.start_mark.line + 1}: {node.value} is beyond double precision "
                "(about 1.8e308); write .inf for infinity"
            )
        return value

    Loader.add_constructor("tag:yaml.org,2002:float", number)
    text = source.read_text(encoding="utf-8")
    try:
        return yaml.load(text, Loader=Loader)  # noqa: S506 (a SafeLoader)
    except yaml.YAMLError as err:
        mark = getattr(err, "problem_mark", None)
        where = f", line {mark.line + 1}" if mark is not None else ""
        what = " ".join(str(getattr(err, "problem", None) or err).split())
        raise ValueError(f"config: {source}{where}: not valid YAML: {what}") from None


def _source(chosen: str | os.PathLike[str] | None) -> Path | Traversable:
    """The file ``chosen``, else the checkout's ``config/config.yaml``, else the packaged copy."""
    if chosen:
        return Path(chosen)
    package = Path(__file__).resolve().parents[1]  # <root>/src/lumped in a checkout
    checkout = package.parents[1] / "config" / "config.yaml"
    if package.parent.name == "src" and checkout.is_file():
        return checkout
    packaged = files("lumped.studies").joinpath(PACKAGED_CONFIG)
    if packaged.is_file():
        return packaged
    raise ValueError(
        f"config: no configuration found (lumped in {package} is neither in a checkout"
        f" nor built with its {PACKAGED_CONFIG}); pass a path or set LUMPED_CONFIG"
    )


@cache
def schema() -> dict[str, Any]:
    """The JSON schema (draft 2020-12) of the configuration, from the package data.

    A property ``{parameter: NAME}`` of ``config_schema.yaml`` becomes the
    rule and the description of :data:`lumped.model.parameters.PARAMETERS` ``[NAME]``
    (its :class:`~lumped.model.parameters.Range` and unit); keywords written beside
    ``parameter`` replace the entry's.  What is returned is JSON schema alone.

    Raises
    ------
    ValueError
        If a property or definition uses a keyword outside :data:`SCHEMA_KEYWORDS`
        (and :data:`TABLE_KEYWORD`), or names no parameter of the table.
    """
    import yaml

    doc = yaml.safe_load(files("lumped.studies").joinpath("config_schema.yaml").read_text("utf-8"))
    for name, rule in {**doc["$defs"], **doc["properties"]}.items():
        extra = set(rule) - SCHEMA_KEYWORDS - {TABLE_KEYWORD}
        if extra:
            raise ValueError(
                f"config_schema.yaml: {name} uses {sorted(extra)}, which lumped.studies.config does not check"
            )
    doc["properties"] = {key: _from_table(key, rule) for key, rule in doc["properties"].items()}
    return doc


def _from_table(key: str, rule: dict[str, Any]) -> dict[str, Any]:
    """``rule`` with its :data:`TABLE_KEYWORD` replaced by the parameter's rule and description."""
    if TABLE_KEYWORD not in rule:
        return rule
    entry = PARAMETERS.get(rule[TABLE_KEYWORD])
    if entry is None or entry.range is None:
        raise ValueError(f"config_schema.yaml: {key} names {rule[TABLE_KEYWORD]!r}, not a parameter with a range")
    own = {k: v for k, v in rule.items() if k != TABLE_KEYWORD}
    return {**entry.range.rule(), "description": entry.describe(), **own}


def _violates(value: Any, rule: dict[str, Any], defs: dict[str, Any]) -> bool:
    """Whether ``value`` breaks ``rule`` (keywords :data:`SCHEMA_KEYWORDS`; ``$ref`` into ``defs``)."""
    if "$ref" in rule and _violates(value, defs[rule["$ref"].removeprefix("#/$defs/")], defs):
        return True
    if "enum" in rule and not any(value == e and isinstance(value, bool) == isinstance(e, bool) for e in rule["enum"]):
        return True
    number = isinstance(value, (int, float)) and not isinstance(value, bool)
    if rule.get("type") == "number" and not number:
        return True
    if rule.get("type") == "integer" and not (number and (isinstance(value, int) or float(value).is_integer())):
        return True  # JSON schema's integer: a number with no fractional part (1000 or 1000.0, not inf)
    if not number:
        return False
    return (
        ("minimum" in rule and not value >= rule["minimum"])
        or ("maximum" in rule and not value <= rule["maximum"])
        or ("exclusiveMinimum" in rule and not value > rule["exclusiveMinimum"])
    )


def check(raw: Any) -> dict[str, Any]:
    """The configuration with its values coerced (see :func:`problems`), if it has no problem.

    Raises
    ------
    ValueError
        With the first line :func:`problems` returns.
    """
    found = problems(raw)
    if found:
        raise ValueError(found[0])
    return _coerced(raw)


def problems(raw: Any, overrides: list[str] | None = None) -> list[str]:
    """One line ``config: ...`` per problem of the configuration ``raw``; empty if none.

    Parameters
    ----------
    raw : dict
        Keys to values as YAML or ``snakemake --config`` gives them (a value
        may be a string such as ``".inf"``).
    overrides : list of str, optional
        The ``KEY=VALUE`` texts of ``snakemake --config``: Snakemake reads
        ``gamma=1e400`` with ``float()`` as infinity, which the values alone
        cannot tell from ``gamma=inf``; the texts can (as the command line
        refuses ``--gamma 1e400``).

    Notes
    -----
    First the overrides' texts, then the schema: unknown keys (with the
    closest known one), missing keys, values out of range. NaN passes every
    JSON-schema comparison, so it is refused here. Only if the schema holds,
    the time step: ``dt`` below each end time and at most :data:`MAX_PIPELINE_STEPS`
    steps per run; then the runs themselves (:func:`_run_problems`): the
    checks every run makes before it starts, on the four runs of
    :func:`lumped.studies.examples.paper` (built by :func:`lumped.studies.paper_runs.runs`), so that a value a run would refuse (``stiffness:
    1e300``) is refused before any job.
    """
    if not isinstance(raw, dict):
        return [f"config: the configuration must be a mapping of keys to values; got {_shown(raw)}"]
    found = _override_problems(overrides or [])
    if found:
        return found
    values = _coerced(raw)
    return _schema_problems(values, raw) or _step_problems(values) or _run_problems(values)


def _override_problems(overrides: list[str]) -> list[str]:
    """``KEY=VALUE`` texts whose number overflows to infinity (``gamma=1e400``), one line each."""
    found = []
    for text in overrides:
        key, _, value = text.partition("=")
        word = value.strip()
        try:
            number = float(word)
        except ValueError:
            continue
        if math.isinf(number) and word.lstrip("+-").lower() not in ("inf", "infinity", ".inf"):
            found.append(
                f"config: {key.strip()}={word} is beyond double precision (about 1.8e308); write .inf for infinity"
            )
    return found


def _coerced(raw: dict[str, Any]) -> dict[str, Any]:
    return {key: _coerce(value) for key, value in raw.items()}


def _coerce(value: Any) -> Any:
    """One configuration value as the notebooks will read it from YAML.

    ``--config`` parses ``.inf`` as the string ".inf" (it tries int, float,
    bool and then YAML's base loader, which types nothing), while the YAML
    file means infinity: strings that YAML reads as numbers become numbers.
    Numbers become floats, so ``mass=1`` and ``mass: 1.0`` are the same value.
    """
    import yaml

    if isinstance(value, str):
        try:
            parsed = yaml.safe_load(value)
        except yaml.YAMLError:
            return value
        if isinstance(parsed, (int, float)) and not isinstance(parsed, bool):
            value = parsed
    if isinstance(value, int) and not isinstance(value, bool):
        try:
            return float(value)
        except OverflowError:  # an integer beyond double range: the schema rejects it
            return value
    return value


def _shown(value: Any) -> str:
    """A configuration value as the user typed it, for an error message."""
    if value is None:
        return "an empty value"
    return repr(value) if isinstance(value, str) else str(value)


def _schema_problems(values: dict[str, Any], raw: dict[str, Any]) -> list[str]:
    """One line per key that breaks the schema (unknown, missing, out of range)."""
    doc = schema()
    known = doc["properties"]
    found = []
    for key in sorted(set(values) - set(known), key=str):
        close = difflib.get_close_matches(str(key), known, n=1)
        hint = f"; did you mean {close[0]}?" if close else f" (keys: {', '.join(known)})"
        found.append(f"config: unknown key {key}{hint}")
    bad = {k for k, v in values.items() if k in known and _violates(v, known[k], doc["$defs"])}
    bad |= {k for k, v in values.items() if isinstance(v, float) and math.isnan(v)}
    for key, rule in known.items():
        if key not in values:
            found.append(f"config: {key} is missing; it must be {rule['description']}")
        elif key in bad:
            found.append(f"config: {key} must be {rule['description']}; got {_shown(raw[key])}{_hint(raw[key])}")
    return found


def _hint(value: Any) -> str:
    """Why a number YAML read as a string is one: ``1e-4`` has no dot (YAML 1.1 floats need one)."""
    if not isinstance(value, str):
        return ""
    try:
        number = float(value)
    except ValueError:
        return ""
    if math.isinf(number):
        return " (beyond double precision, about 1.8e308; write .inf for infinity)"
    mantissa, _, exponent = value.strip().lower().partition("e")
    fixed = f"{mantissa if '.' in mantissa else mantissa + '.0'}" + (
        f"e{exponent if exponent[:1] in '+-' else '+' + exponent}" if exponent else ""
    )
    return f" (YAML reads {value} as a string: its floats need a dot and a signed exponent; write {fixed})"


#: The examples' run arguments -> the configuration's key, per run (:func:`lumped.studies.paper_runs.runs`).
_RUN_KEYS = {
    "forced_small": {"t_end": "t_end_forced", "force_amplitude": "force_amplitude_small"},
    "forced_large": {"t_end": "t_end_forced", "force_amplitude": "force_amplitude_large"},
    "free_small": {"t_end": "t_end_small", "x0": "x0_small"},
    "free_large": {"t_end": "t_end_large", "x0": "x0_large"},
}


def _run_problems(values: dict[str, Any]) -> list[str]:
    """The up-front checks of Algorithm 1 and of the exact solution on the four runs, in the config's keys.

    The bounds are the runs' own (:func:`lumped.model.oscillator.check_magnitudes`, the
    exact solver's checks), not restated here; a refusal is reported with the
    key the run's argument comes from (``x0`` of the free large run is
    ``x0_large``, ``force_omega`` is ``force_omega_over_pi``).
    """
    from lumped.model.forcing import SwitchedSine
    from lumped.model.oscillator import check_magnitudes
    from lumped.solvers.exact import _check_inputs
    from lumped.studies.paper_runs import runs as paper_runs

    try:
        runs = paper_runs(values)
    except ValueError as err:  # a parameter an oscillator refuses (mass: 1e-320)
        return [f"config: {' '.join(str(err).split())}"]
    for name, run in runs.items():
        force = run.force or SwitchedSine()
        amplitude = run.force.amplitude if run.force else 0.0
        try:
            check_magnitudes(run.oscillator, run.t_end, run.dt, run.x0, run.v0, amplitude)
            _check_inputs(run.oscillator, force, run.t_end, run.x0, run.v0, 100_000)
        except ValueError as err:
            arg, _, rest = str(err).partition(":")
            key = _RUN_KEYS[name].get(arg, "force_omega_over_pi" if arg == "force_omega" else arg)
            return [f"config: {key}: {' '.join(rest.split())} (the {name} run)"]
    return []


def _step_problems(values: dict[str, Any]) -> list[str]:
    """dt must be below each end time and leave at most MAX_PIPELINE_STEPS steps per run."""
    dt = values["dt"]
    for key in END_TIMES:
        if dt >= values[key]:
            return [f"config: dt must be smaller than {key} = {values[key]:g} s; got {dt:g}"]
        if values[key] / dt > MAX_PIPELINE_STEPS:
            return [
                f"config: dt must be at least {key}/{MAX_PIPELINE_STEPS:.0e} = {values[key] / MAX_PIPELINE_STEPS:g} s"
                f" (a run takes at most {MAX_PIPELINE_STEPS:.0e} steps); got {dt:g}"
            ]
    return []
