"""Self-excited oscillations of one mass on a belt: steady sliding, its limit cycles and their branches (issue 34).

* :mod:`~lumped.drivers.cycles.shooting`: a limit cycle as the fixed point of the return map to the section
  ``x = x*`` (:func:`find_cycle`), the map and its exact derivative (:func:`return_map`), its Floquet multiplier.
"""

from lumped.drivers.cycles.shooting import Cycle, cycle_derivative_in, find_cycle, return_map, section_of

__all__ = ["Cycle", "cycle_derivative_in", "find_cycle", "return_map", "section_of"]
