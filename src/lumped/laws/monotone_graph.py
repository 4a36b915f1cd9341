"""A monotone graph ``v = phi(F)`` given as a callable: its checks and its bracketed roots.

:class:`lumped.laws.MonotoneDashpot` is made of these functions, and the
dashpot contract's default slip step
(:meth:`lumped.laws.Dashpot.band_free_resolvent`) runs them on a law's graph
with its band cut out; so they sit below both, and name no class.  A
``phi`` passed here is the *checked* graph, ``lambda F: checked(raw, F)``:
a finite float for every force, else a ``ValueError`` that names the force.
The roots are Brent's, by the package's one root finder
(:func:`lumped.numerics.roots.brentq`) with its tolerances.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from lumped.numerics.roots import MAXITER, NoConvergence, brentq

__all__ = ["MONOTONE_SAMPLE", "checked", "check_monotone", "resolvent", "inverse"]

#: Forces, relative to the threshold (or to 1 N), at which :class:`~lumped.laws.MonotoneDashpot`
#: checks that its law does not decrease: 16 a decade from 1e-6 to 1e6.
MONOTONE_SAMPLE = 10.0 ** (np.arange(-96, 97) / 16)


def checked(phi: Callable[[float], object], force: float) -> float:
    """``phi(force)`` checked: a finite real number, else a ``ValueError``."""
    try:
        raw = phi(force)
    except Exception as err:  # a user's callable: report its failure, named
        raise ValueError(f"velocity_of_force raised {type(err).__name__} at F = {force:.6g} N: {err}") from None
    if isinstance(raw, bool) or not isinstance(raw, (int, float, np.integer, np.floating)):
        raise ValueError(f"velocity_of_force must return a real number, got {raw!r:.40} at F = {force:.6g} N")
    if not math.isfinite(raw):
        raise ValueError(f"velocity_of_force must be finite, got {raw} at F = {force:.6g} N")
    return float(raw)


def check_monotone(phi: Callable[[float], float], threshold: float) -> None:
    """Refuse a ``phi`` that decreases on :data:`MONOTONE_SAMPLE` (one line naming where).

    The sample is scaled by ``threshold`` if it is positive, else by 1 N;
    it stops on each side at the first force where ``phi`` raises (see
    :class:`lumped.laws.MonotoneDashpot`, Notes).
    """
    scale = threshold if threshold > 0 else 1.0
    for side in (1.0, -1.0):
        previous = (0.0, 0.0)
        for ratio in MONOTONE_SAMPLE:
            force = side * scale * ratio
            try:
                value = phi(force)
            except ValueError:
                break  # not finite here: refused where a run meets it
            lo, hi = (previous, (force, value)) if side > 0 else ((force, value), previous)
            if hi[1] < lo[1]:
                raise ValueError(
                    f"velocity_of_force must be monotone non-decreasing, but phi({lo[0]:.4g} N) = "
                    f"{lo[1]:.4g} > phi({hi[0]:.4g} N) = {hi[1]:.4g} (MonotoneDashpot's check, 16 forces a decade)"
                )
            previous = (force, value)


def resolvent(
    phi: Callable[[float], float], predictor: float, eta: float, max_iterations: int = MAXITER
) -> tuple[float, float]:
    """The root ``F`` of ``F + eta phi(F) = predictor`` and ``v = (predictor - F) / eta``.

    ``g(F) = F + eta phi(F) - predictor`` is strictly increasing with
    ``g(0) = -predictor`` and ``g(predictor) = eta phi(predictor)``, of the
    sign of ``predictor``: the root lies between ``0`` and ``predictor``,
    where Brent's method, bracketing, finds it to a few ulps.

    Raises
    ------
    ValueError
        If ``phi(predictor)`` has the sign opposite to ``predictor``, or
        ``max_iterations`` pass.
    """
    if predictor == 0.0:
        return 0.0, 0.0
    if phi(predictor) * predictor < 0:
        raise ValueError(
            "velocity_of_force must be monotone non-decreasing with phi(0) = 0; "
            f"phi({predictor:.6g}) = {phi(predictor):.6g} has the opposite sign"
        )
    lo, hi = min(0.0, predictor), max(0.0, predictor)
    try:
        force = brentq(lambda F: F + eta * phi(F) - predictor, lo, hi, maxiter=max_iterations)
    except NoConvergence:
        raise ValueError(
            f"velocity_of_force: no convergence in {max_iterations} iterations; is the law monotone and finite?"
        ) from None
    return force, (predictor - force) / eta


def inverse(phi: Callable[[float], float], velocity: float) -> float:
    """The force ``F`` with ``phi(F) = velocity`` (``velocity != 0``), bracketed by doubling from 1 N.

    Raises
    ------
    ValueError
        If 200 doublings do not reach ``velocity`` (it is outside the range of ``phi``).
    """
    hi = math.copysign(1.0, velocity)
    for _ in range(200):
        if (phi(hi) - velocity) * math.copysign(1.0, velocity) >= 0:
            break
        hi *= 2.0
    else:
        raise ValueError(f"velocity {velocity} is outside the range of the law")
    return brentq(lambda F: phi(F) - velocity, 0.0, hi)
