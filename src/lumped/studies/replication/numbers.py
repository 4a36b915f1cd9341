"""All the article's numbers: :func:`compute`, with the configured and the original's parameters and the provenance.

``scripts/paper_numbers.py`` writes :func:`compute`'s dictionary to
``paper/build/numbers.json`` (its layout: :mod:`lumped.studies.replication`).
"""

from __future__ import annotations

import importlib.metadata
import math
import os
import platform
from typing import Any

import lumped.studies.config
from lumped.model.oscillator import Oscillator
from lumped.studies import examples
from lumped.studies.replication.runs import (
    ORIGINAL_DT,
    convergence,
    eq19,
    friction_oscillator_ends,
    paper_run,
    rest_sweep,
)
from lumped.studies.replication.textbook_model import textbook_runs
from lumped.studies.replication.verdicts import CHECKS, summary, verdicts
from lumped.studies.strict_json import clean

__all__ = ["ORIGINAL", "OURS", "PACKAGES", "compute"]

#: The original's values (its section 3 and eqs. 17), under the configuration's keys.
ORIGINAL: dict[str, float] = {
    "mass": 1.0,
    "stiffness": 100.0,
    "threshold": 1.0,
    "gamma": 1.0,
    "dt": ORIGINAL_DT,
    "force_amplitude_small": 0.5,
    "force_amplitude_large": 10.0,
    "force_omega_over_pi": 5.0,
    "force_until": 1.0,
    "x0_small": 0.005,
    "x0_large": 0.5,
}
#: Configuration keys the original does not state (ours whatever their value).
OURS = ("t_end_forced", "t_end_small", "t_end_large")
#: Packages whose versions the article reports.
PACKAGES = ("lumped", "numpy", "scipy", "matplotlib", "snakemake", "typst", "PyYAML")


def _parameters(cfg: dict[str, Any], osc: Oscillator) -> dict[str, Any]:
    return {
        "m": osc.mass,
        "k": osc.stiffness,
        "tau": osc.threshold,
        "gamma": float(cfg["gamma"]),
        "dt": float(cfg["dt"]),
        "band": osc.static_band,
        "omega_over_pi": cfg["force_omega_over_pi"],
        "force_until": cfg["force_until"],
        "P_small": cfg["force_amplitude_small"],
        "P_large": cfg["force_amplitude_large"],
        "t_end_forced": cfg["t_end_forced"],
        "t_end_small": cfg["t_end_small"],
        "t_end_large": cfg["t_end_large"],
        "x0_small": cfg["x0_small"],
        "x0_large": cfg["x0_large"],
    }


def _original(cfg: dict[str, Any]) -> dict[str, Any]:
    """The original's values, those the configuration changes, and ours."""
    changed = [{"key": k, "original": v, "ours": float(cfg[k])} for k, v in ORIGINAL.items() if float(cfg[k]) != v]
    return {
        "values": dict(ORIGINAL),
        "dt": ORIGINAL_DT,
        "changed": changed,
        "dt_differs": float(cfg["dt"]) != ORIGINAL_DT,
        "ours": {k: cfg[k] for k in OURS},
    }


def _rest_error(block: dict[str, Any], x0: float, band: float) -> dict[str, float]:
    """The rest-position error at the original's step as fractions of the rest position, the band and ``x0``.

    The error of a rest position is a fraction of a small quantity: these
    three put it in scale (``nan`` where either solution still moves at the end).
    """
    err, rest = block["error_original"]["rest_position"], block["exact"]["rest_position"]
    if isinstance(rest, str) or not math.isfinite(err):
        return {"of_value": math.nan, "of_band": math.nan, "of_x0": math.nan}
    return {"of_value": err / abs(rest), "of_band": err / band, "of_x0": err / abs(x0)}


def _shown(value: Any) -> str:
    """A configuration value as ``--config`` spells it (``.inf`` for infinity)."""
    return ".inf" if value == math.inf else repr(value)


def _provenance(cfg: dict[str, Any]) -> dict[str, Any]:
    """What built the numbers: Python, packages, machine, command; no clock time."""
    default = lumped.studies.config.default()
    overrides = [f"{k}={_shown(cfg[k])}" for k in sorted(cfg) if cfg[k] != default.get(k)]
    command = "snakemake --cores all" + (" --config " + " ".join(overrides) if overrides else "")
    from lumped.solvers.backward_euler import KERNEL

    return {
        "python": platform.python_version(),
        "implementation": platform.python_implementation(),
        "packages": {name: importlib.metadata.version(name) for name in PACKAGES},
        "machine": platform.machine(),
        "system": platform.system(),
        "cpus": os.cpu_count(),
        "kernel": KERNEL,
        "command": command,
    }


def compute(cfg: dict[str, Any] | None = None) -> dict[str, Any]:
    """All numbers and verdicts of the article, as a JSON-ready dictionary (:func:`~lumped.studies.strict_json.clean`).

    Parameters
    ----------
    cfg : dict, optional
        A checked configuration (:func:`lumped.studies.config.load`); by default the
        one :func:`lumped.studies.config.load` finds.
    """
    cfg = cfg if cfg is not None else lumped.studies.config.load()
    osc, runs = examples.oscillator(cfg), examples.paper(cfg)
    out: dict[str, Any] = {"parameters": _parameters(cfg, osc), "original": _original(cfg)}
    out |= {name: paper_run(run) for name, run in runs.items()}
    for suffix, dt in (("", float(cfg["dt"])), ("_original", ORIGINAL_DT)):
        out["forced_small"]["eq19" + suffix] = eq19(runs["forced_small"], dt)
        out["free_large"]["sweep" + suffix] = rest_sweep(runs["free_large"], dt)
    out["free_large"]["rest_error"] = _rest_error(out["free_large"], cfg["x0_large"], osc.static_band)
    out["convergence"], out["convergence_rest"] = convergence(runs)
    out["textbook"] = textbook_runs(osc)
    out["friction_oscillator"] = friction_oscillator_ends()
    judged = {"configured": verdicts(cfg, out, "", osc), "original": verdicts(cfg, out, "_original", osc)}
    out["verdicts"] = judged | {
        "summary": {key: summary(v) for key, v in judged.items()},
        "checks": [judged["configured"][key]["label"] for key in CHECKS],
    }
    out["provenance"] = _provenance(cfg)
    return clean(out)
