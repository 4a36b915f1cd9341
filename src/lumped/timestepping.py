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
environment variable ``LUMPED_PURE_PYTHON=1`` forces the Python loop.  Any other :class:`~lumped.laws.Dashpot`
runs the generic loop, which calls the law's resolvent.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable

import numpy as np

from lumped import _validate
from lumped.forcing import SwitchedSine, evaluate
from lumped.laws import BinghamDashpot, Dashpot
from lumped.results import COLUMNS, Trajectory
from lumped.system import Oscillator, initial_dashpot_force

__all__ = ["backward_euler", "algorithm1", "KERNEL"]


def _bingham_loop(
    m: float, k: float, dt: float, tau: float, c: float,
    x0: float, v0: float, n_steps: int, save_every: int,
    amp: float, omega: float, phase: float, until: float,
    force_values: np.ndarray, out: np.ndarray,
) -> None:  # fmt: skip
    """Algorithm 1 for the Bingham law; fills ``out[1:]`` (rows t, x, v, F_s, F_d, F).

    ``force_values`` holds ``F(t_n)`` for a general forcing; when it is empty
    the forcing is the switched sine ``amp*sin(omega t + phase)``, ``t <= until``.
    """
    eta = m / dt + k * dt
    tabulated = force_values.shape[0] > 0
    f_s = k * x0
    v = v0
    row = 1
    for n in range(1, n_steps + 1):
        t = n * dt
        if tabulated:
            f = force_values[n]
        elif t <= until:
            f = amp * math.sin(omega * t + phase)
        else:
            f = 0.0
        predictor = (m / dt) * v + f - f_s  # line 3, eq. (15b)
        if abs(predictor) <= tau:  # lines 5-6: stick
            v = 0.0
            f_d = predictor
        else:  # lines 8-9, divided through by gamma (see laws.bingham_corrector)
            signed = math.copysign(tau, predictor)
            f_d = (eta * signed + c * predictor) / (eta + c)
            v = (predictor - signed) / (eta + c)
        f_s = f_s + dt * k * v  # line 11, eq. (14)
        if n % save_every == 0 or n == n_steps:
            out[row, 0] = t
            out[row, 1] = f_s / k
            out[row, 2] = v
            out[row, 3] = f_s
            out[row, 4] = f_d
            out[row, 5] = f
            row += 1


_python_loop = _bingham_loop
KERNEL = "python"
if os.environ.get("LUMPED_PURE_PYTHON", "") in ("", "0"):
    try:
        from lumped._kernel import bingham_loop as _bingham_loop  # type: ignore[no-redef]

        KERNEL = "compiled"
    except ImportError:  # no C compiler at install: the Python loop, same numbers
        pass


def _generic_loop(
    osc: Oscillator, dt: float, x0: float, v0: float, n_steps: int,
    save_every: int, force_values: np.ndarray, out: np.ndarray,
) -> None:  # fmt: skip
    """Backward Euler for any dashpot law, through its resolvent."""
    m, k, law = osc.mass, osc.spring.stiffness, osc.dashpot
    eta = m / dt + k * dt
    f_s, v, row = k * x0, v0, 1
    for n in range(1, n_steps + 1):
        f = force_values[n]
        predictor = (m / dt) * v + f - f_s
        f_d, v = law._resolvent_impl(predictor, eta)
        f_s = f_s + dt * k * v
        if n % save_every == 0 or n == n_steps:
            out[row] = (n * dt, f_s / k, v, f_s, f_d, f)
            row += 1


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
        External force ``F(t)`` in N; ``None`` for free vibration.
    save_every : int
        Keep every ``save_every``-th grid point (``t = 0`` and the last point
        are always kept).
    kernel : {"auto", "compiled", "python"}
        Loop used for Bingham and Coulomb laws; ``"auto"`` takes the compiled
        kernel when it was built.  Ignored for other laws.

    Returns
    -------
    Trajectory
        ``t, x, v, F_s, F_d, F`` at the saved grid points.
    """
    t_end = _validate.positive("t_end", t_end)
    dt = _validate.positive("dt", dt)
    x0, v0 = _validate.finite("x0", x0), _validate.finite("v0", v0)
    save_every = _validate.positive_int("save_every", save_every)
    if kernel not in ("auto", "compiled", "python"):
        raise ValueError(f"kernel must be 'auto', 'compiled' or 'python', got {kernel!r}")
    if kernel == "compiled" and KERNEL != "compiled":
        raise ValueError("kernel: 'compiled' requested but the C kernel was not built")
    n_steps = _validate.step_count(t_end, dt)
    rows = _validate.output_size(n_steps, save_every)
    out = np.empty((rows, len(COLUMNS)))
    f0 = float(evaluate(force, np.zeros(1))[0])
    out[0] = (0.0, x0, v0, oscillator.spring.force(x0), 0.0, f0)
    out[0, 4] = initial_dashpot_force(oscillator, f0, x0, v0)
    law = oscillator.dashpot
    m, k = oscillator.mass, oscillator.spring.stiffness
    if isinstance(law, BinghamDashpot):
        loop = _python_loop if kernel == "python" else _bingham_loop
        sine = force if isinstance(force, SwitchedSine) else SwitchedSine()
        table = np.empty(0, dtype=float)
        if force is not None and not isinstance(force, SwitchedSine):
            table = evaluate(force, np.arange(n_steps + 1) * dt)
        loop(m, k, dt, law.threshold, law.viscosity, x0, v0, n_steps, save_every,
             sine.amplitude, sine.omega, sine.phase, sine.until, table, out)  # fmt: skip
    else:
        table = evaluate(force, np.arange(n_steps + 1) * dt)
        _generic_loop(oscillator, dt, x0, v0, n_steps, save_every, table, out)
    return Trajectory.from_array(out, oscillator, method="backward-euler", dt=dt,
                                 save_every=save_every)  # fmt: skip


#: The paper's name for the method.
algorithm1 = backward_euler
