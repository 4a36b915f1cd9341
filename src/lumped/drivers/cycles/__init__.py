"""Self-excited oscillations of one mass on a belt: steady sliding, its limit cycles and their branches (issue 34).

* :mod:`~lumped.drivers.cycles.equilibria`: steady sliding, the eigenvalues of its linearisation, its Hopf
  points (:func:`steady_sliding`, :func:`hopf_points`) and the boundary check (:func:`check_autonomous`);
* :mod:`~lumped.drivers.cycles.api`: :func:`cycles`, the API of ``python -m lumped cycles``, its table.
"""

from lumped.drivers.cycles.equilibria import Equilibrium, check_autonomous, hopf_points, steady_sliding

__all__ = ["Equilibrium", "check_autonomous", "hopf_points", "steady_sliding"]
