"""No verdict of the article changes with a choice the original did not make.

The original states no end times, and its claims are qualitative; our
verdicts test them part by part with yes-or-no questions
(:mod:`lumped.studies.replication.verdicts`), with no tolerance.  Here each
choice that remains is moved and every verdict word must stay as it is with
the default configuration:

* the free run's end time: 1.5 s after its exact stop, then 1 s either way
  (each end still beyond both stops);
* the threshold ``mu_s N_f`` by 3 % either way, and by +2.7 %, where the exact
  rest of the large free vibration lies at about zero (2e-5 m) and Algorithm 1
  rests on the other side of it: a verdict that asked for the same side of
  zero, as the article's did before, changes there;
* the spacing of the release sweep (Figure 14 and the stretched rest), halved
  and doubled; no tolerance remains to be scaled.

Each case runs the four runs and the release sweep again (under a second).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

import lumped.studies.config
from lumped.studies import examples
from lumped.studies.replication import VERDICT_KEYS
from lumped.studies.replication.runs import SWEEP_SPACING, eq19, paper_run, rest_sweep
from lumped.studies.replication.verdicts import verdicts

ROOT = Path(__file__).resolve().parent.parent
CFG = lumped.studies.config.load(ROOT / "config" / "config.yaml")


def words(cfg: dict[str, Any], spacing: float = SWEEP_SPACING) -> dict[str, str]:
    """Every verdict word at the configured step, from the runs of ``cfg``."""
    runs = examples.paper(cfg)
    out = {name: paper_run(run) for name, run in runs.items()}
    out["forced_small"]["eq19"] = eq19(runs["forced_small"], cfg["dt"])
    out["free_large"]["sweep"] = rest_sweep(runs["free_large"], cfg["dt"], spacing)
    v = verdicts(cfg, out, "", examples.oscillator(cfg))
    return {key: v[key]["verdict"] for key in VERDICT_KEYS}


@pytest.fixture(scope="module")
def base() -> dict[str, str]:
    judged = words(CFG)
    assert "deviates" not in judged.values() and "not checked" not in judged.values()
    return judged


def _free_end(shift: float) -> dict[str, Any]:
    stop = examples.paper(CFG)["free_large"].exact().rest_time
    return CFG | {"t_end_large": round(stop + 1.5 + shift, 1)}  # a whole number of steps


@pytest.mark.parametrize("shift", [-1.0, 1.0])
def test_free_run_end_time_changes_no_verdict(base: dict[str, str], shift: float) -> None:
    assert words(_free_end(shift)) == base


@pytest.mark.parametrize("factor", [0.97, 1.027, 1.03])
def test_threshold_changes_no_verdict(base: dict[str, str], factor: float) -> None:
    assert words(CFG | {"threshold": factor * CFG["threshold"]}) == base


@pytest.mark.parametrize("factor", [0.5, 2.0])
def test_sweep_spacing_changes_no_verdict(base: dict[str, str], factor: float) -> None:
    assert words(CFG, factor * SWEEP_SPACING) == base
