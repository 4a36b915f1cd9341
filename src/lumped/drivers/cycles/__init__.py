"""Self-excited oscillations of one mass on a belt: steady sliding, its limit cycles and their branches (issue 34).

* :mod:`~lumped.drivers.cycles.equilibria`: steady sliding, the eigenvalues of its linearisation, its Hopf
  points (:func:`steady_sliding`, :func:`hopf_points`) and the boundary check (:func:`check_autonomous`);
* :mod:`~lumped.drivers.cycles.shooting`: a limit cycle as the fixed point of the return map to the section
  ``x = x*`` (:func:`find_cycle`), the map and its exact derivative (:func:`return_map`), its Floquet multiplier;
* :mod:`~lumped.drivers.cycles.api`: :func:`cycles`, the API of ``python -m lumped cycles``, its table.
"""

from lumped.drivers.cycles.equilibria import Equilibrium, check_autonomous, hopf_points, steady_sliding
from lumped.drivers.cycles.shooting import Cycle, cycle_derivative_in, find_cycle, return_map, section_of

__all__ = [
    "Cycle",
    "Equilibrium",
    "check_autonomous",
    "cycle_derivative_in",
    "find_cycle",
    "hopf_points",
    "return_map",
    "section_of",
    "steady_sliding",
]
