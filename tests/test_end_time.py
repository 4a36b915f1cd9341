"""No verdict of the article depends on the end time of a run, once both solutions are at rest.

The original states no end times; ours (``config/config.yaml``) are a choice.
So a verdict must not change when a run's end time moves: here the end time
of each run that comes to rest is set 1.5 s beyond its exact stop and moved
by -1 s and +1 s from there (every end time still beyond both stops, the
exact one and Algorithm 1's), and every verdict, its word, its reason and
the differences reported beside it, must be the same as with the configured
end time.  It holds because every difference is measured over the
motion (up to the later stop) and the rest state apart
(:mod:`lumped.studies.replication.verdicts`): an integral over the whole run
would grow with the held force's difference for as long as the run lasts.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

import lumped.studies.config
from lumped.studies import examples
from lumped.studies.replication import VERDICT_KEYS
from lumped.studies.replication.runs import eq19, paper_run, rest_sweep
from lumped.studies.replication.verdicts import verdicts

ROOT = Path(__file__).resolve().parent.parent
#: The runs that come to rest, and the configuration key of their end time.
END_KEYS = {"free_large": "t_end_large", "forced_large": "t_end_forced"}


@pytest.fixture(scope="module")
def base() -> tuple[dict[str, Any], dict[str, Any]]:
    """The configuration and every run's summary with the configured end times."""
    cfg = lumped.studies.config.load(ROOT / "config" / "config.yaml")
    runs = examples.paper(cfg)
    out = {name: paper_run(run) for name, run in runs.items()}
    out["forced_small"]["eq19"] = out["forced_small"]["eq19_original"] = eq19(runs["forced_small"], cfg["dt"])
    out["free_large"]["sweep"] = rest_sweep(runs["free_large"], cfg["dt"])
    return cfg, out


def _judged(cfg: dict[str, Any], out: dict[str, Any]) -> dict[str, tuple[str, str]]:
    v = verdicts(cfg, out, "", examples.oscillator(cfg))
    return {key: (v[key]["verdict"], v[key]["reason"], v[key]["differences"]) for key in VERDICT_KEYS}


@pytest.mark.parametrize("name", sorted(END_KEYS))
@pytest.mark.parametrize("shift", [-1.0, 0.0, 1.0])
def test_no_verdict_changes_with_the_end_time(base: tuple[dict, dict], name: str, shift: float) -> None:
    cfg, out = base
    stops = (out[name]["exact"]["rest_time"], out[name]["be"]["rest_time"])
    assert all(isinstance(s, float) for s in stops), "the run must come to rest"
    end = round(stops[0] + 1.5 + shift, 1)  # a whole number of steps of 1e-4 s and 1e-3 s
    assert end > max(stops) + 0.3  # beyond both stops, by more than Algorithm 1's lag
    moved = cfg | {END_KEYS[name]: end}
    changed = out | {name: paper_run(examples.paper(moved)[name])}
    if name == "free_large":
        changed[name]["sweep"] = rest_sweep(examples.paper(moved)[name], cfg["dt"])
    assert changed[name]["be"]["steps"] != out[name]["be"]["steps"]  # the run did change length
    assert _judged(moved, changed) == _judged(cfg, out)
