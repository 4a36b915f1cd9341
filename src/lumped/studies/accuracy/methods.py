"""The methods the work-precision study compares, grouped by what their resolution is.

Every method of the registry (:data:`lumped.drivers.methods.METHODS`) runs
one mass, so every one is in the study, in one of three groups read from its
capabilities, and the groups are run in this order:

* :data:`SCHEMES`, the fixed-step schemes (``Method.fixed_step``): their
  resolution is the step ``dt``, against which their orders are fitted;
* :data:`TOLERANCED`, the methods that solve in continuous time for any law
  (a ``Method.solution`` and not ``bingham_only``): their resolution is their
  option ``rtol``;
* :data:`CLOSED_FORM`, those that solve in continuous time in closed form,
  which needs the Bingham form of the law (``bingham_only``): run once, and
  the reference of the cases they apply to.

The study adds one method the registry does not hold, :data:`TANH`: SciPy's
``solve_ivp`` (LSODA) on the ``tanh`` regularisation of the textbook model,
the baseline the issue asks to compare with.
"""

from __future__ import annotations

from lumped.drivers.methods import METHODS

__all__ = ["CLOSED_FORM", "SCHEMES", "STUDY_METHODS", "TANH", "TOLERANCED"]

#: The fixed-step schemes, whose errors are fitted against ``dt``.
SCHEMES = tuple(name for name, m in METHODS.items() if m.fixed_step)
#: The methods that integrate any law in continuous time to a tolerance ``rtol``.
TOLERANCED = tuple(name for name, m in METHODS.items() if not m.fixed_step and not m.bingham_only)
#: The methods in closed form (Bingham and Coulomb laws only).
CLOSED_FORM = tuple(name for name, m in METHODS.items() if not m.fixed_step and m.bingham_only)
#: ``solve_ivp`` (LSODA) on the ``tanh`` model: the study's own baseline, not a method of the registry.
TANH = "tanh"
#: Every method of the study, in the order it runs them.
STUDY_METHODS = (*SCHEMES, *TOLERANCED, *CLOSED_FORM, TANH)
