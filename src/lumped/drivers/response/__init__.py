"""Forced response curves: periodic motions by shooting, followed in the forcing frequency (issue 23).

* :mod:`~lumped.drivers.response.shooting`: a periodic motion as the fixed
  point of the exact period map (:func:`find_orbit`), its Floquet multipliers;
* :mod:`~lumped.drivers.response.continuation`: pseudo-arclength continuation
  in omega with the changes along the branch located (:func:`continue_orbits`);
* :mod:`~lumped.drivers.response.curve`: :func:`response_curve`, the API of
  ``python -m lumped response``: a one-mass system with a sine load, its table;
* :mod:`~lumped.drivers.response.linear`: a linear system with an undamped
  mode, in closed form where its periodic motion is unique (issue 31).

The period map and its monodromy matrix are those of the exact solver's
phases (:mod:`lumped.solvers.monodromy`).
"""

from lumped.drivers.response.continuation import ResponsePoint, continue_orbits
from lumped.drivers.response.shooting import NEWTON_TOL, Orbit, Scales, find_orbit

__all__ = ["NEWTON_TOL", "Orbit", "ResponsePoint", "Scales", "continue_orbits", "find_orbit"]
