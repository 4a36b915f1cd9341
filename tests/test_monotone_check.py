"""``MonotoneDashpot`` refuses a law that decreases on its stated sample (issue 19).

Before, ``phi(F) = sin(F)`` was accepted: backward Euler ran on it silently
and the event-driven method wandered for minutes.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import lumped as L
from lumped.laws import MONOTONE_SAMPLE

NOT_MONOTONE = {
    "sin": (lambda f: math.sin(f), 0.0),
    "negative slope": (lambda f: -f, 0.0),
    "dip beyond the band": (lambda f: f - 3 * math.copysign(max(0.0, min(abs(f), 4.0) - 2.0), f) if f else 0.0, 0.0),
    "negative side only": (lambda f: f if f > 0 else math.sin(f), 0.0),
    "dip far out, scaled by the threshold": (
        lambda f: math.copysign(max(abs(f) - 1e3, 0.0), f) if abs(f) < 1e8 else 0.0,
        1e3,
    ),
}


@pytest.mark.parametrize("case", list(NOT_MONOTONE))
def test_a_decreasing_law_is_refused_naming_where(case: str) -> None:
    phi, tau = NOT_MONOTONE[case]
    with pytest.raises(ValueError, match=r"^velocity_of_force must be monotone non-decreasing, but phi\(") as info:
        L.MonotoneDashpot(phi, threshold=tau)
    message = str(info.value)
    assert "\n" not in message and len(message) < 200
    lo, hi = (float(s.split(" N)")[0]) for s in message.split("phi(")[1:])
    assert lo < hi and phi(lo) > phi(hi)  # the two forces named do show the decrease


def test_the_issue_law_is_refused_before_any_run(monkeypatch) -> None:
    """The law is refused when it is built: the solver (which ran past 300 s) is never reached."""

    def never(*args, **kwargs):  # noqa: ANN002, ANN003, ANN202
        raise AssertionError("the solver was called")

    monkeypatch.setattr(L, "solve_event_driven", never)
    with pytest.raises(ValueError, match="velocity_of_force"):
        osc = L.Oscillator(1.0, L.LinearSpring(100.0), L.MonotoneDashpot(math.sin))
        L.solve_event_driven(osc, 2.0, x0=0.5)


MONOTONE = {
    "linear": (lambda f: 0.5 * f, 0.0),
    "bingham": (lambda f: math.copysign(max(abs(f) - 1.0, 0.0), f), 1.0),
    "power": (lambda f: math.copysign(max(abs(f) - 1.0, 0.0) ** 2, f), 1.0),
    "overflows far out": (lambda f: math.expm1(f), 0.0),  # inf beyond 709 N: the sample stops there
    "flat everywhere but a step": (lambda f: float(np.sign(f)) * (abs(f) > 10.0), 10.0),
}


@pytest.mark.parametrize("case", list(MONOTONE))
def test_monotone_laws_are_accepted(case: str) -> None:
    phi, tau = MONOTONE[case]
    assert L.MonotoneDashpot(phi, threshold=tau).threshold == tau


def test_the_sample_is_the_stated_one() -> None:
    """16 forces a decade from 1e-6 to 1e6, so neighbours are 10**(1/16) (15 %) apart."""
    assert MONOTONE_SAMPLE.size == 193 and MONOTONE_SAMPLE[0] == 1e-6 and MONOTONE_SAMPLE[-1] == 1e6
    assert np.allclose(MONOTONE_SAMPLE[1:] / MONOTONE_SAMPLE[:-1], 10 ** (1 / 16), rtol=1e-12)
