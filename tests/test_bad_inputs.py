"""Every bad or extreme input of the robustness issue, with its clean outcome.

The API raises ``ValueError`` with one line that names the argument, within a
bounded time, and never returns a NaN or an infinity it was not given.  (The
command line's cases are in ``test_cli_robust.py``, the pipeline
configuration's in ``test_config_pipeline.py``; the exact solver's extreme
physics in ``test_exact_robust.py``.)
"""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

import lumped as L
from lumped import timestepping
from lumped.textbook import TextbookModel, integrate_adaptive, integrate_fixed

OSC = L.Oscillator.bingham()
#: A refusal must come before any real work: well under a second here.
BOUND_SECONDS = 2.0


def _run(**kw):
    args = dict(t_end=1.0, dt=1e-3)
    args.update(kw)
    return L.backward_euler(args.pop("oscillator", OSC), args.pop("t_end"), args.pop("dt"), **args)


def _monotone(phi):
    return L.Oscillator(1.0, L.LinearSpring(100.0), L.MonotoneDashpot(phi))


API = {
    # name in the message: call
    "save_every 10**30 is fine": None,
    "save_every=1e30": ("save_every", lambda: _run(save_every=1e30)),
    "save_every=inf": ("save_every", lambda: _run(save_every=math.inf)),
    "save_every=2.0": ("save_every", lambda: _run(save_every=2.0)),
    "save_every='3'": ("save_every", lambda: _run(save_every="3")),
    "mass=10**400": ("mass", lambda: L.Oscillator.bingham(mass=10**400)),
    "mass=True": ("mass", lambda: L.Oscillator.bingham(mass=True)),
    "x0='0.5'": ("x0", lambda: _run(x0="0.5")),
    "oscillator=None": ("oscillator", lambda: L.backward_euler(None, 1.0, 1e-3)),
    "force=3": ("force", lambda: _run(force=3)),
    "force returns None": ("force", lambda: _run(force=lambda t: None)),
    "force returns a string": ("force", lambda: _run(force=lambda t: "abc")),
    "force of the wrong shape": ("force", lambda: _run(force=lambda t: np.zeros((np.size(t), 2)))),
    "force returns nan": ("force", lambda: _run(force=lambda t: np.full(np.shape(t), np.nan))),
    "force raises": ("force", lambda: _run(force=lambda t: 1 / 0)),
    "law not monotone": ("velocity_of_force", lambda: _run(oscillator=_monotone(lambda f: -f), x0=0.5)),
    "law returns nan": ("velocity_of_force", lambda: _run(
        oscillator=_monotone(lambda f: math.nan if f > 0.5 else f), x0=0.5)),
    "law returns an array": ("velocity_of_force", lambda: _monotone(lambda f: np.array([f, f]))),
    "law returns a string": ("velocity_of_force", lambda: _monotone(lambda f: "fast")),
    "x0=1e307": ("x0", lambda: _run(x0=1e307)),
    "v0=1e307": ("v0", lambda: _run(v0=1e307)),
    "force amplitude 1e307": ("force_amplitude", lambda: _run(force=L.SwitchedSine(1e307, 1.0))),
    "stiffness 1e300, x0 1e10": ("x0", lambda: _run(
        oscillator=L.Oscillator.bingham(stiffness=1e300), x0=1e10)),
    "gamma 1e400 (an overflow, not Coulomb)": ("gamma", lambda: L.BinghamDashpot(1.0, 10**400)),
    "a monotone law for 1e3 s at 1e-5 s": ("t_end/dt", lambda: _run(
        oscillator=_monotone(lambda f: f), t_end=1e3, dt=1e-5, save_every=10**6)),
    "rtol nan": ("rtol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, rtol=math.nan)),
    "rtol inf": ("rtol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, rtol=math.inf)),
    "rtol 0": ("rtol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, rtol=0.0)),
    "rtol '1e-6'": ("rtol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, rtol="1e-6")),
    "atol -1": ("atol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, atol=-1.0)),
    "atol nan": ("atol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, atol=math.nan)),
    "textbook Euler for 1.2e8 steps": ("t_end/dt", lambda: integrate_fixed(
        TextbookModel(OSC), 1.2e4, 1e-4)),
}
API = {key: value for key, value in API.items() if value is not None}


@pytest.mark.parametrize("case", list(API))
def test_api_refuses_with_one_line_naming_the_argument(case):
    name, call = API[case]
    start = time.perf_counter()
    with pytest.raises(ValueError) as err:
        call()
    message = str(err.value)
    assert time.perf_counter() - start < BOUND_SECONDS
    assert "\n" not in message
    assert message.startswith(name), message


def test_forcing_that_overflows_stops_at_the_step_naming_the_quantity():
    # 1e308 N is finite; its first step gives v ~ 1e304 m/s, the second overflows.
    with pytest.raises(ValueError, match=r"^the run overflowed at t = 0\.002 s \(step 2\): the velocity v"):
        _run(force=lambda t: np.full(np.shape(t), 1e308))


def test_numpy_integers_and_huge_strides_are_valid():
    every = _run(x0=0.5, save_every=np.int64(7))
    assert np.array_equal(every.t, _run(x0=0.5, save_every=7).t)
    ends = _run(x0=0.5, save_every=10**30)  # only t = 0 and the last point
    assert ends.t.tolist() == [0.0, 1.0]
    assert ends.x[-1] == _run(x0=0.5).x[-1]


@pytest.mark.parametrize("save_every", [1, 7, 1000, 10**6])
def test_rest_time_does_not_depend_on_save_every(save_every):
    # The free decay from x0 = 0.5 at the paper's step stops at t = 3.1458 s
    # (a grid point), which a stride of 1000 does not sample.
    full = L.backward_euler(OSC, 4.0, 1e-4, x0=0.5)
    runs = full.stick_intervals()
    strided = L.backward_euler(OSC, 4.0, 1e-4, x0=0.5, save_every=save_every)
    assert strided.rest_time == runs[-1][0] == full.rest_time
    assert strided.rest_position == full.x[-1]


def test_rest_time_is_nan_while_moving_and_zero_for_a_mass_that_never_moves():
    assert math.isnan(_run(x0=0.5, t_end=0.1).rest_time)
    assert _run(x0=0.005, save_every=100).rest_time == 0.0


@pytest.mark.parametrize("force", [None, L.paper_forcing(10.0), lambda t: 10 * np.sin(5 * np.pi * t)])
def test_blocks_do_not_change_a_single_bit(monkeypatch, force):
    whole = L.backward_euler(OSC, 4.0, 1e-4, x0=0.5, force=force, save_every=3)
    monkeypatch.setattr(timestepping, "BLOCK_SINE", 997)
    monkeypatch.setattr(timestepping, "BLOCK_TABLE", 1009)
    blocks = L.backward_euler(OSC, 4.0, 1e-4, x0=0.5, force=force, save_every=3)
    assert np.array_equal(whole.as_array(), blocks.as_array())
    assert np.array_equal(whole.final_rest, blocks.final_rest, equal_nan=True)


def test_a_callable_forcing_is_never_tabulated_whole(monkeypatch):
    # Memory: the forcing table is one block, whatever the number of steps.
    monkeypatch.setattr(timestepping, "BLOCK_TABLE", 1000)
    sizes = []

    def force(t):
        sizes.append(np.size(t))
        return np.sin(t)

    L.backward_euler(OSC, 1.0, 1e-4, force=force, save_every=10**6)
    assert max(sizes) <= 1000 and sum(sizes[1:]) >= 10_000
