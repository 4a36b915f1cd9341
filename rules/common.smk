# Names shared by the rules: the checked configuration, and which notebook draws
# which paper figure.
import difflib
import math
import sys
from glob import glob

import yaml
from jsonschema import Draft202012Validator

#: JSON schema of the configuration (config/config.yaml after --config overrides).
CONFIG_SCHEMA = "config/schema.yaml"
#: End-time keys: dt must be below each of them.
END_TIMES = ("t_end_forced", "t_end_small", "t_end_large")
#: Most steps one run may take. A run keeps six float64 columns per step (plus
#: the exact solution sampled on the same grid), about 1 GB at 1e7 steps, and a
#: notebook holds several runs at once; the paper's runs take at most 4e4.
MAX_STEPS = 10**7


def _coerce(value):
    """One configuration value as the notebooks will read it from YAML.

    ``--config`` parses ``.inf`` as the string ".inf" (it tries int, float,
    bool and then YAML's base loader, which types nothing), while the YAML
    file means infinity: strings that YAML reads as numbers become numbers.
    Numbers become floats, so ``mass=1`` and ``mass: 1.0`` are the same value.
    """
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


def _shown(value):
    """A configuration value as the user typed it, for an error message."""
    if value is None:
        return "an empty value"
    return repr(value) if isinstance(value, str) else str(value)


def _schema_problems(values, raw, schema):
    """One line per key that breaks the schema (unknown, missing, out of range)."""
    known = schema["properties"]
    problems = []
    for key in sorted(set(values) - set(known)):
        close = difflib.get_close_matches(key, known, n=1)
        hint = f"; did you mean {close[0]}?" if close else f" (keys: {', '.join(known)})"
        problems.append(f"config: unknown key {key}{hint}")
    bad = {e.path[0] for e in Draft202012Validator(schema).iter_errors(values) if e.path}
    bad |= {k for k, v in values.items() if isinstance(v, float) and math.isnan(v)}
    for key, rule in known.items():
        if key not in values:
            problems.append(f"config: {key} is missing; it must be {rule['description']}")
        elif key in bad:
            problems.append(f"config: {key} must be {rule['description']}; got {_shown(raw[key])}")
    return problems


def _step_problems(values):
    """dt must be below each end time and leave at most MAX_STEPS steps per run."""
    dt = values["dt"]
    for key in END_TIMES:
        if dt >= values[key]:
            return [f"config: dt must be smaller than {key} = {values[key]:g} s; got {dt:g}"]
        if values[key] / dt > MAX_STEPS:
            return [
                f"config: dt must be at least {key}/{MAX_STEPS:.0e} = {values[key] / MAX_STEPS:g} s"
                f" (a run takes at most {MAX_STEPS:.0e} steps); got {dt:g}"
            ]
    return []


def checked_config(raw):
    """The configuration with values coerced, or exit 2 with one line per problem.

    Exiting from the Snakefile prints only our lines; a WorkflowError would add
    the file, line and a traceback frame.
    """
    with open(CONFIG_SCHEMA, encoding="utf-8") as fh:
        schema = yaml.safe_load(fh)
    values = {key: _coerce(value) for key, value in raw.items()}
    problems = _schema_problems(values, raw, schema) or _step_problems(values)
    if problems:
        print("\n".join(problems), file=sys.stderr)
        sys.exit(2)
    return values


config.update(checked_config(config))
#: The configuration as canonical text (keys sorted, floats by repr): the
#: effective_config rule's parameter, so that an override equal to the default
#: (dt=1e-4 against 1.0e-4, or keys in another order) changes nothing.
CONFIG_TEXT = yaml.safe_dump(dict(config), sort_keys=True)

#: notebook stem -> figure stems, in the paper's numbering (figNN_<slug>).
NOTEBOOK_FIGURES = {
    "01_governing_equations": [],
    "02_sgn_zero_failure": [],
    "03_constitutive_pictures": [
        "fig01_bingham_relations",
        "fig02_spring_with_string",
        "fig03_mass_spring_dashpot",
        "fig04_bingham_pictorial",
    ],
    "04_forced_vibrations": [
        "fig05_forced_small",
        "fig06_forced_large_x",
        "fig07_forced_large_v",
        "fig08_forced_large_Fs",
        "fig09_forced_large_Fd",
    ],
    "05_free_vibrations": [
        "fig10_free_small",
        "fig11_free_large_x",
        "fig12_free_large_v",
        "fig13_free_large_Fs",
        "fig14_free_large_Fd",
    ],
}

#: Report section of each notebook.
CATEGORY = {
    "03_constitutive_pictures": "Constitutive pictures (Figs 1-4)",
    "04_forced_vibrations": "Forced vibrations (Figs 5-9)",
    "05_free_vibrations": "Free vibrations (Figs 10-14)",
}

#: Every figure file the pipeline makes.
FIGURE_FILES = [
    f"figures/{stem}.{ext}"
    for stems in NOTEBOOK_FIGURES.values()
    for stem in stems
    for ext in ("pdf", "png")
]

#: Every notebook, executed: build artefacts to read with their outputs.
EXECUTED_NOTEBOOKS = [f"results/notebooks/{name}.ipynb" for name in NOTEBOOK_FIGURES]

#: The package sources: editing any of them reruns every notebook.
PACKAGE_SOURCES = sorted(
    glob("src/lumped/**/*.py", recursive=True) + glob("src/lumped/**/*.mplstyle", recursive=True)
)


def notebook_outputs(notebook):
    """The figures of one notebook, PNGs listed in the report with their captions."""
    outputs = []
    for stem in NOTEBOOK_FIGURES[notebook]:
        outputs.append(f"figures/{stem}.pdf")
        png = f"figures/{stem}.png"
        caption = f"../report/{stem[:5]}.rst"
        outputs.append(report(png, caption=caption, category=CATEGORY[notebook]))
    return outputs
