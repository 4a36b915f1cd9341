"""Layer 1, the constitutive laws: what each element of a system says about its force and its motion.

* :mod:`~lumped.laws.dashpots`: the dashpot contract :class:`Dashpot` (the
  only way a solver asks a law anything), the linear spring, the Bingham law
  with Algorithm 1's stick test and corrector, and the monotone laws
  (Herschel-Bulkley and any ``w = phi(f)``);
* :mod:`~lumped.laws.regularised`: the Papanastasiou law, a new law in one
  file that no solver names;
* :mod:`~lumped.laws.elements`: the element kinds of a network, each a
  constitutive graph between its force and its elongation.

Nothing here imports a solver, a driver or the model above it.
"""

from lumped.laws.dashpots import (
    MONOTONE_SAMPLE,
    BinghamDashpot,
    BinghamForm,
    Dashpot,
    DashpotState,
    HerschelBulkleyDashpot,
    LinearSpring,
    MonotoneDashpot,
    StepBound,
    bingham_corrector,
    coulomb,
    sticks,
)
from lumped.laws.elements import (
    GROUND,
    KINDS,
    Bingham,
    Element,
    HerschelBulkley,
    LawElement,
    LinearDashpot,
    LockingBingham,
    MaxwellBingham,
    Monotone,
    Piece,
    Spring,
    SpringString,
)
from lumped.laws.regularised import PapanastasiouDashpot

__all__ = [
    "GROUND",
    "KINDS",
    "MONOTONE_SAMPLE",
    "Bingham",
    "BinghamDashpot",
    "BinghamForm",
    "Dashpot",
    "DashpotState",
    "Element",
    "HerschelBulkley",
    "HerschelBulkleyDashpot",
    "LawElement",
    "LinearDashpot",
    "LinearSpring",
    "LockingBingham",
    "MaxwellBingham",
    "Monotone",
    "MonotoneDashpot",
    "PapanastasiouDashpot",
    "Piece",
    "Spring",
    "SpringString",
    "StepBound",
    "bingham_corrector",
    "coulomb",
    "sticks",
]
