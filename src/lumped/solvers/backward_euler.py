"""Backward-Euler time stepping of the DAE (8): Algorithm 1 of the paper.

The step from ``t_n`` to ``t_{n+1} = (n+1) dt`` is

1. predictor, eq. (15b):  ``F~ = (m/dt) v_n + F_{n+1} - F_s,n``;
2. corrector: the dashpot resolvent ``F_d = (I + eta*phi)^{-1}(F~)`` with
   ``eta = m/dt + k dt`` (lines 5 to 10; see :mod:`lumped.laws`), and
   ``v_{n+1} = (F~ - F_d)/eta``, which is eq. (15a);
3. ``F_s,n+1 = F_s,n + dt k v_{n+1}`` (eq. 14) and ``x_{n+1} = F_s,n+1 / k``.

For the Bingham and Coulomb laws the loop runs in a small C kernel
(``_kernel.c``, built at install when a compiler is present) or, with the same
operations in the same order, in plain Python; both give bit-identical numbers
(the C code is compiled without floating-point contraction).  Setting the
environment variable ``LUMPED_PURE_PYTHON=1`` forces the Python loop.  Any
other :class:`~lumped.laws.Dashpot` runs the generic loop, which calls the
law's resolvent.

The driver advances the loop in blocks of steps.  Between blocks Python sees
Ctrl-C, and a forcing given as a callable is evaluated one block at a time, so
memory is bounded by the saved output whatever the number of steps.  Every
step is checked: a non-finite velocity or force stops the run with a
``ValueError`` that names the quantity and the time.
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable

import numpy as np

from lumped.laws import bingham_corrector
from lumped.model.forcing import SwitchedSine, as_sine, check_span, evaluate, validate_force
from lumped.model.oscillator import Oscillator, check_magnitudes, initial_dashpot_force
from lumped.model.trajectory import COLUMNS, Trajectory
from lumped.numerics import sine, validate

__all__ = ["backward_euler", "algorithm1", "KERNEL"]

#: Steps per kernel call with the switched sine (about 40 ms compiled).
BLOCK_SINE = 1 << 22
#: Steps per block when the forcing is tabulated (512 KiB of forcing values).
BLOCK_TABLE = 1 << 16
#: Quantities named when a step is not finite (index = bad_quantity code).
_QUANTITIES = ("", "velocity v", "dashpot force F_d", "spring force F_s")


def _bingham_block(
    m: float,
    k: float,
    dt: float,
    tau: float,
    c: float,
    n_first: int,
    n_last: int,
    n_steps: int,
    save_every: int,
    amp: float,
    omega: float,
    phase: float,
    until: float,
    force_values: np.ndarray,
    state: np.ndarray,
    counters: np.ndarray,
    out: np.ndarray,
) -> None:
    """Algorithm 1 for the Bingham law over steps ``n_first..n_last``.

    ``state`` is ``(F_s, v, F_d)`` and ``counters`` is ``(row, rest_start,
    bad_step, bad_quantity)``, both updated in place (see ``_kernel.c``).
    ``force_values`` holds ``F(t_n)`` for ``n_first..n_last`` for a general
    forcing; when it is empty the forcing is the switched sine
    ``amp*sin(omega t + phase)``, ``t <= until``, with the project's sine
    (:func:`lumped.numerics.sine.sin`, the twin of ``sine.h``).  Saved rows go to ``out``
    (columns t, x, v, F_s, F_d, F).

    The corrector is :func:`~lumped.laws.bingham_corrector`, the one Python
    copy of lines 5 to 10; ``_kernel.c`` repeats it in C, and the tests
    require the two loops to agree bit for bit.
    """
    eta = m / dt + k * dt
    tabulated = force_values.shape[0] > 0
    f_s, v, f_d = float(state[0]), float(state[1]), float(state[2])
    row, rest_start = int(counters[0]), int(counters[1])
    for n in range(n_first, n_last + 1):
        t = n * dt
        if tabulated:
            f = float(force_values[n - n_first])
        elif t <= until:
            f = amp * sine.sin(omega * t + phase)  # the kernels' sine, bit for bit
        else:
            f = 0.0
        predictor = (m / dt) * v + f - f_s  # line 3, eq. (15b)
        f_d, v = bingham_corrector(predictor, eta, tau, c)  # lines 5-10
        f_s = f_s + dt * k * v  # line 11, eq. (14)
        if not (math.isfinite(v) and math.isfinite(f_d) and math.isfinite(f_s)):
            counters[2] = n
            counters[3] = 1 if not math.isfinite(v) else 2 if not math.isfinite(f_d) else 3
            break
        if v != 0.0:
            rest_start = n + 1
        if n % save_every == 0 or n == n_steps:
            out[row] = (t, f_s / k, v, f_s, f_d, f)
            row += 1
    state[:] = (f_s, v, f_d)
    counters[0], counters[1] = row, rest_start


_python_block = _bingham_block
KERNEL = "python"
if os.environ.get("LUMPED_PURE_PYTHON", "") in ("", "0"):
    try:
        from lumped.kernels._kernel import bingham_block as _bingham_block  # type: ignore[no-redef]

        KERNEL = "compiled"
    except ImportError:  # no C compiler at install: the Python loop, same numbers
        pass

#: Estimated cost of one step (s) of the Bingham loops, for the run-time bound
#: (measured on this project's 2-core machine: about 1e-8 s compiled and
#: 5.5e-7 s in Python free, 9e-7 s forced (the project's sine in Python), with
#: the other core busy; a margin of about 1.5 to 2).
_SECONDS_PER_STEP = {"compiled": 1.5e-8, "python": 1.8e-6}


def _generic_block(
    osc: Oscillator,
    dt: float,
    n_first: int,
    n_last: int,
    n_steps: int,
    save_every: int,
    force_values: np.ndarray,
    state: np.ndarray,
    counters: np.ndarray,
    out: np.ndarray,
) -> None:
    """Backward Euler for any dashpot law, through its resolvent (same contract)."""
    m, k, law = osc.mass, osc.spring.stiffness, osc.dashpot
    f_s, v = float(state[0]), float(state[1])
    f_d, row, rest_start = float(state[2]), int(counters[0]), int(counters[1])
    for n in range(n_first, n_last + 1):
        f = float(force_values[n - n_first])
        predictor = (m / dt) * v + f - f_s
        f_d, v = law._resolvent_impl(predictor, m / dt + k * dt)
        f_s = f_s + dt * k * v
        if not (math.isfinite(v) and math.isfinite(f_d) and math.isfinite(f_s)):
            counters[2] = n
            counters[3] = 1 if not math.isfinite(v) else 2 if not math.isfinite(f_d) else 3
            break
        if v != 0.0:
            rest_start = n + 1
        if n % save_every == 0 or n == n_steps:
            out[row] = (n * dt, f_s / k, v, f_s, f_d, f)
            row += 1
    state[:] = (f_s, v, f_d)
    counters[0], counters[1] = row, rest_start


def _seconds_per_step(osc: Oscillator, force: object, kernel: str, dt: float) -> float:
    """Estimated cost of one step (s): measured for a general law or forcing."""
    law = osc.dashpot
    if law.bingham_form() is not None:  # Algorithm 1's own loop (contract point 6)
        cost = _SECONDS_PER_STEP[kernel]
    else:
        eta = osc.mass / dt + osc.spring.stiffness * dt
        probes = np.linspace(-4.0, 4.0, 16) * (law.threshold + 1.0)
        law._resolvent_impl(float(probes[0]), eta)  # first call: imports, caches
        start = time.perf_counter()
        for p in probes:
            law._resolvent_impl(float(p), eta)
        cost = 1.5 * (time.perf_counter() - start) / probes.size + 1e-6
    if force is not None and as_sine(force) is None:  # tabulated: its evaluation costs too
        grid = np.arange(1, 257) * dt
        start = time.perf_counter()
        evaluate(force, grid)
        cost += 1.5 * (time.perf_counter() - start) / grid.size
    return cost


def _stopped(counters: np.ndarray, dt: float, force: float) -> ValueError:
    """The error for a step that gave a non-finite value."""
    n, what = int(counters[2]), _QUANTITIES[int(counters[3])]
    return ValueError(
        f"the run overflowed at t = {n * dt:.6g} s (step {n}): the {what} is not finite "
        f"(the external force there was {force:.3g} N)"
    )


def _check_run(
    osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, force: object, kernel: str, n_steps: int
) -> None:
    """Refuse up front what would overflow or run too long."""
    sine = as_sine(force)
    check_span(force, n_steps * dt)  # a sine's range, to the grid's last time
    check_magnitudes(osc, t_end, dt, x0, v0, sine.amplitude if sine is not None else 0.0)
    what = "Algorithm 1" if osc.dashpot.bingham_form() is not None else "the generic loop"
    validate.run_time(n_steps, _seconds_per_step(osc, force, kernel, dt), what)


def _march(
    osc: Oscillator,
    dt: float,
    n_steps: int,
    save_every: int,
    force: object,
    kernel: str,
    state: np.ndarray,
    counters: np.ndarray,
    out: np.ndarray,
) -> None:
    """Advance steps ``1..n_steps`` block by block; raise on a non-finite step."""
    law, m, k = osc.dashpot, osc.mass, osc.spring.stiffness
    form = law.bingham_form()  # (tau, c) of Algorithm 1's loops, or None: the law's resolvent
    bingham = form is not None
    sine = as_sine(force)
    tabulate = not (bingham and (force is None or sine is not None))  # Algorithm 1's loop forms a sine itself
    sine = sine or SwitchedSine()
    block = BLOCK_TABLE if tabulate else BLOCK_SINE
    loop = (_python_block if kernel == "python" else _bingham_block) if bingham else None
    for first in range(1, n_steps + 1, block):
        last = min(first + block - 1, n_steps)
        table = evaluate(force, np.arange(first, last + 1) * dt) if tabulate else np.empty(0)
        if loop is None:
            _generic_block(osc, dt, first, last, n_steps, save_every, table, state, counters, out)
        else:
            loop(
                m,
                k,
                dt,
                form.threshold,
                form.viscosity,
                first,
                last,
                n_steps,
                save_every,
                sine.amplitude,
                sine.omega,
                sine.phase,
                sine.until,
                table,
                state,
                counters,
                out,
            )
        if counters[2]:
            n = int(counters[2])
            f = float(table[n - first]) if tabulate else float(sine(n * dt))
            raise _stopped(counters, dt, f)


def backward_euler(
    oscillator: Oscillator,
    t_end: float,
    dt: float,
    *,
    x0: float = 0.0,
    v0: float = 0.0,
    force: SwitchedSine | Callable[[np.ndarray], np.ndarray] | None = None,
    save_every: int = 1,
    kernel: str = "auto",
) -> Trajectory:
    """Integrate the DAE (8) with Algorithm 1 on the grid ``t_n = n*dt``.

    A shim of the one entry point, kept for the name users know:
    ``lumped.solve(Problem.oscillator(oscillator, t_end, x0=x0, v0=v0,
    force=force), dt, method="backward-euler")`` runs this function for the
    paper's system (Algorithm 1's kernel is chosen inside) and gives the same
    numbers, with each element's force.  Called directly it adds ``kernel``
    (the compiled or the Python loop).  ``lumped.algorithm1`` is this function.

    Parameters
    ----------
    oscillator : Oscillator
        Mass, spring and dashpot.
    t_end : float, s
        Final time ``> 0``; the grid ends at the first ``t_n >= t_end``.
    dt : float, s
        Step ``> 0`` (the paper uses ``1e-4``).
    x0, v0 : float, m and m/s
        Initial displacement and velocity.
    force : SwitchedSine or callable or None
        External force ``F(t)`` in N; ``None`` for free vibration.  A callable
        is evaluated on blocks of the time grid (see
        :func:`~lumped.model.forcing.evaluate`) and must return finite values.
    save_every : int
        Keep every ``save_every``-th grid point (``t = 0`` and the last point
        are always kept); from 1 to ``lumped.numerics.validate.MAX_STEPS`` (2e9, the
        most steps of a run).
    kernel : {"auto", "compiled", "python"}
        Loop used for Bingham and Coulomb laws; ``"auto"`` takes the compiled
        kernel when it was built.  Ignored for other laws.

    Returns
    -------
    Trajectory
        ``t, x, v, F_s, F_d, F`` at the saved grid points; its ``rest_time``
        is the first step of the final run of ``v == 0`` on the full grid.

    Raises
    ------
    ValueError
        For a bad argument (named); for a run that could overflow, would need
        more than 2e9 steps, 4 GiB of output or about 600 s; and for a step
        that gives a non-finite value (the quantity and time named).
    """
    if not isinstance(oscillator, Oscillator):
        raise ValueError(f"oscillator must be an Oscillator, got {type(oscillator).__name__}")
    t_end, dt, save_every, n_steps = validate.grid(t_end, dt, save_every)
    x0, v0 = validate.finite("x0", x0), validate.finite("v0", v0)
    force = validate_force(force)
    kernel = validate.kernel(kernel, KERNEL, "the C kernel")
    out = np.empty((validate.output_size(n_steps, save_every), len(COLUMNS)))
    _check_run(oscillator, t_end, dt, x0, v0, force, kernel, n_steps)
    f0 = float(evaluate(force, np.zeros(1))[0])
    out[0] = (0.0, x0, v0, oscillator.spring.force(x0), 0.0, f0)
    out[0, 4] = initial_dashpot_force(oscillator, f0, x0, v0)
    state = np.array([oscillator.spring.force(x0), v0, out[0, 4]])
    counters = np.array([1, 0 if v0 == 0 else 1, 0, 0], dtype=np.int64)
    stride = min(save_every, n_steps + 1)  # a larger stride saves the same rows
    _march(oscillator, dt, n_steps, stride, force, kernel, state, counters, out)
    rest = int(counters[1])
    final_rest = (rest * dt, float(out[-1, 1])) if state[1] == 0 else (math.nan, math.nan)
    path = "algorithm1" if oscillator.dashpot.bingham_form() is not None else "resolvent"
    return Trajectory.from_array(
        out, oscillator, method="backward-euler", dt=dt, save_every=save_every, final_rest=final_rest, solver=path
    )


#: The paper's name for the method.
algorithm1 = backward_euler
