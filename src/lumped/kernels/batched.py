"""Algorithm 1 over many parameter sets at once, keeping per-trajectory summaries.

Each trajectory is one run of :func:`lumped.solvers.backward_euler.backward_euler` (a
mass on a linear spring and a Bingham or Coulomb dashpot, forced by a
:class:`~lumped.model.forcing.SwitchedSine`): the same operations in the same
order, so its velocities and spring forces are bit-identical to the single
run's.  The time steps of one trajectory depend on each other; different
trajectories do not, so the compiled kernel (``_batch_kernel.c``) advances a
block of them together in a vectorised loop and shares the blocks among the
cores (OpenMP), the forcing included: its sine is the project's own
(``_sine.h``), vectorised like the rest.  Without the extension (or with
``LUMPED_PURE_PYTHON=1``) a NumPy loop over the time steps, vectorised over
trajectories, does the same arithmetic and gives the same numbers, its sine
:func:`lumped.numerics.sine.sin_array`, the twin of ``_sine.h``.

Each call of the kernel is bounded in work: at most :data:`CALL_SIZE`
trajectories and about :data:`CALL_WORK` trajectory-steps, the steps split
into spans that resume from the summaries the previous span wrote.  Python's
signal handlers (Ctrl-C, SIGTERM) and the progress report run between calls.

Only summaries are kept (:class:`BatchSummary`); the displacements at every
``save_every``-th step are kept as well when asked.
"""

from __future__ import annotations

import os
from typing import NamedTuple

import numpy as np

from lumped.laws import sticks
from lumped.numerics import validate
from lumped.numerics.sine import sin_array

__all__ = ["BatchParameters", "BatchSummary", "batch_backward_euler", "BATCH_KERNEL"]

#: Trajectories per kernel call.
CALL_SIZE = 8192
#: Trajectory-steps per kernel call, about (a call takes at least one step): 2^24, about 25 ms forced
#: on two cores, so that Ctrl-C, SIGTERM and the progress report are seen several times a second.
CALL_WORK = 1 << 24


class BatchParameters(NamedTuple):
    """One value per trajectory (arrays of equal length ``n``).

    ``mass`` (kg), ``stiffness`` (N/m), ``threshold`` (N), ``viscosity``
    ``c = 1/gamma`` (N s/m, ``0`` for Coulomb), ``x0`` (m), ``v0`` (m/s) and the
    switched sine ``force_amplitude`` (N), ``force_omega`` (rad/s),
    ``force_phase`` (rad), ``force_until`` (s).
    """

    mass: np.ndarray
    stiffness: np.ndarray
    threshold: np.ndarray
    viscosity: np.ndarray
    x0: np.ndarray
    v0: np.ndarray
    force_amplitude: np.ndarray
    force_omega: np.ndarray
    force_phase: np.ndarray
    force_until: np.ndarray


class BatchSummary(NamedTuple):
    """What the batched kernel keeps of each trajectory (arrays of length ``n``).

    Attributes
    ----------
    v_end, x_end : ndarray
        Velocity (m/s) and displacement ``F_s/k`` (m) at the last step ``N``.
    rest_step : ndarray of int
        First step of the final run of ``v == 0`` (``N + 1`` if ``v_N != 0``;
        ``0`` if the mass starts at rest and never moves).
    stops : ndarray of int
        Steps ``n >= 1`` with ``v_n == 0`` and ``v_{n-1} != 0``.
    window_stops : ndarray of int
        The same, counted over the steps ``n >= window`` only.
    max_abs_x : ndarray
        Largest ``|x_n|`` over ``n = 0..N`` (m).
    window_max_abs_x : ndarray
        Largest ``|x_n|`` over ``n >= window`` (m); ``nan`` without a window.
    x : ndarray, shape (rows, n), or None
        Displacements at the saved steps when ``save_every`` was given
        (step 0, every ``save_every``-th step and the last).
    """

    v_end: np.ndarray
    x_end: np.ndarray
    rest_step: np.ndarray
    stops: np.ndarray
    window_stops: np.ndarray
    max_abs_x: np.ndarray
    window_max_abs_x: np.ndarray
    x: np.ndarray | None


def _numpy_batch(
    dt: float,
    first: int,
    last: int,
    n_steps: int,
    save_every: int,
    par: np.ndarray,
    nw: np.ndarray,
    sums: np.ndarray,
    xs: np.ndarray,
) -> None:
    """NumPy twin of ``_batch_kernel.bingham_batch`` (same arguments and layout).

    Steps ``first..last``; with ``first > 1`` the state is read back from
    ``sums``, which a call ending at step ``first - 1`` wrote.
    """
    m, k, tau, c, x0, v0, amp, omega, phase, until = par
    mdt, dtk, eta_c = m / dt, dt * k, (m / dt + k * dt) + c
    if first > 1:
        v, fs, rest, stops, wstops, mx, mw = (row.copy() for row in sums)
    else:
        v, fs, rest = v0, k * x0, np.where(v0 == 0.0, 0.0, 1.0)
        stops, wstops, mx, mw = (np.zeros_like(m) for _ in range(4))
    forced, f, row = amp != 0.0, np.zeros_like(m), 0
    for s in range(first, last + 1):
        t = s * dt
        if forced.any():
            f = np.where(forced & (t <= until), amp * sin_array(omega * t + phase), 0.0)
        predictor = mdt * v + f - fs  # line 3, eq. (15b)
        v_new = np.where(sticks(predictor, -tau, tau), 0.0, (predictor - np.copysign(tau, predictor)) / eta_c)
        fs = fs + dtk * v_new  # line 11, eq. (14)
        stop = (v_new == 0.0) & (v != 0.0)
        stops = stops + stop
        wstops = wstops + (stop & (s >= nw))
        rest = np.where(v_new != 0.0, s + 1.0, rest)
        mx = np.maximum(mx, np.abs(fs))
        mw = np.where((s >= nw) & (np.abs(fs) > mw), np.abs(fs), mw)
        v = v_new
        if save_every and (s % save_every == 0 or s == n_steps):
            xs[row] = fs / k
            row += 1
    sums[:] = (v, fs, rest, stops, wstops, mx, mw)


def saved_rows(first: int, last: int, n_steps: int, save_every: int) -> int:
    """Saved steps among ``first..last``: the multiples of ``save_every``, and ``n_steps`` (0 if not saving)."""
    if not save_every or last < first:
        return 0
    return last // save_every - (first - 1) // save_every + (last == n_steps and n_steps % save_every != 0)


BATCH_KERNEL = "python"
_compiled_batch = None
if os.environ.get("LUMPED_PURE_PYTHON", "") in ("", "0"):
    try:
        from lumped.kernels._batch_kernel import bingham_batch as _compiled_batch  # type: ignore[no-redef]

        BATCH_KERNEL = "compiled"
    except ImportError:  # no compiler (or no OpenMP) at install: the NumPy loop, same numbers
        pass


def _as_columns(params: BatchParameters) -> np.ndarray:
    """The parameters as a C-contiguous ``(10, n)`` array, checked finite where required."""
    par = np.ascontiguousarray(np.broadcast_arrays(*(np.asarray(p, dtype=float) for p in params)), dtype=float)
    if par.ndim != 2:
        raise ValueError("params: every parameter must be a number or a 1-d array")
    for name, row in zip(BatchParameters._fields, par):
        if name != "force_until" and not np.isfinite(row).all():
            raise ValueError(f"{name}: every value must be finite")
    return par


def _call(kernel: str, dt: float, steps: range, n_steps: int, save_every: int, par, nw, sums, xs) -> None:  # noqa: ANN001
    """One call of the kernel over the steps ``steps`` (``sums`` in and out, ``xs`` out)."""
    loop = _numpy_batch if kernel == "python" else _compiled_batch
    loop(dt, steps.start, steps.stop - 1, n_steps, save_every, par, nw, sums, xs)  # type: ignore[misc]


def _spans(n: int, n_steps: int) -> list[tuple[slice, range]]:
    """The calls: rows by :data:`CALL_SIZE`, steps by about :data:`CALL_WORK` trajectory-steps."""
    out = []
    for first in range(0, n, CALL_SIZE):
        rows = slice(first, min(first + CALL_SIZE, n))
        span = max(1, CALL_WORK // (rows.stop - rows.start))
        out += [(rows, range(s, min(s + span, n_steps + 1))) for s in range(1, n_steps + 1, span)]
    return out


def _kernel_name(kernel: str) -> str:
    return validate.kernel(kernel, BATCH_KERNEL, "the batched C kernel")


def batch_backward_euler(
    params: BatchParameters,
    t_end: float,
    dt: float,
    *,
    window: np.ndarray | None = None,
    save_every: int | None = None,
    kernel: str = "auto",
    progress: object = None,
) -> BatchSummary:
    """Algorithm 1 for every parameter set of ``params`` on the grid ``t_n = n*dt``.

    Parameters
    ----------
    params : BatchParameters
        One value per trajectory (numbers are broadcast).  The values are
        taken as given: validate them first (:func:`lumped.drivers.sweep.sweep` does).
    t_end, dt : float, s
        As for :func:`~lumped.solvers.backward_euler.backward_euler`; all trajectories
        share the grid, of ``N`` steps.
    window : ndarray of int, optional
        Per trajectory, the first step of the window of
        :attr:`BatchSummary.window_stops` and ``window_max_abs_x``; a value
        above ``N`` means no window.
    save_every : int, optional
        Also keep ``x`` at every ``save_every``-th step (and the last).
    kernel : {"auto", "compiled", "python"}
        The C kernel or the NumPy loop (bit-identical).
    progress : callable, optional
        Called as ``progress(done, total)`` (trajectories, ``done`` counting
        a part-run block by the fraction of its steps) after each call of the
        kernel (:data:`CALL_SIZE` trajectories, about :data:`CALL_WORK`
        trajectory-steps).

    Returns
    -------
    BatchSummary
    """
    kernel = _kernel_name(kernel)
    t_end, dt, _, n_steps = validate.grid(t_end, dt)
    par = _as_columns(params)
    n = par.shape[1]
    nw = np.full(n, n_steps + 1.0) if window is None else np.minimum(np.asarray(window, dtype=float), n_steps + 1.0)
    stride = 0 if save_every is None else validate.positive_int("save_every", save_every)
    rows = 0 if not stride else validate.output_rows(n_steps, stride) - 1
    sums, xs = np.empty((7, n)), np.empty((rows, n))
    for part, steps in _spans(n, n_steps):
        width, before = part.stop - part.start, saved_rows(1, steps.start - 1, n_steps, stride)
        block_sums = np.ascontiguousarray(sums[:, part])  # read back when resuming
        block_x = np.empty((saved_rows(steps.start, steps.stop - 1, n_steps, stride), width))
        _call(kernel, dt, steps, n_steps, stride, np.ascontiguousarray(par[:, part]), nw[part], block_sums, block_x)
        sums[:, part] = block_sums
        xs[before : before + block_x.shape[0], part] = block_x
        if callable(progress):
            progress(part.start + width * (steps.stop - 1) // n_steps, n)
    return _summary(par, nw, n_steps, sums, xs if rows else None)


def _summary(par: np.ndarray, nw: np.ndarray, n_steps: int, sums: np.ndarray, xs: np.ndarray | None) -> BatchSummary:
    """Summaries from the kernel's sums; step 0 (``x = x0``) is added here."""
    k, x0 = par[1], par[4]
    v_end, fs_end, rest, stops, wstops, max_fs, window_fs = sums
    # rounding is monotone, so max_n |F_s,n| / k is max_n of the |x_n| = |F_s,n / k| of the single run
    max_abs_x = np.maximum(np.abs(x0), max_fs / k)
    has_window = nw <= n_steps
    window_x = np.where(nw == 0, np.maximum(np.abs(x0), window_fs / k), window_fs / k)
    x = None if xs is None else np.concatenate((x0[None, :], xs))
    return BatchSummary(
        v_end,
        fs_end / k,
        rest.astype(np.int64),
        stops.astype(np.int64),
        wstops.astype(np.int64),
        max_abs_x,
        np.where(has_window, window_x, np.nan),
        x,
    )
