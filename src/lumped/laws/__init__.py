"""Layer 1, the constitutive laws: what each element of a system says about its force and its motion.

Dashpot laws, each a graph ``v = phi(F_d)`` and its implicit step:

* :mod:`~lumped.laws.contract`: the dashpot contract :class:`Dashpot` (the
  only way a solver asks a law anything), the values its step returns and
  the linear spring;
* :mod:`~lumped.laws.bingham`: the Bingham law with Algorithm 1's stick test
  and corrector, and Coulomb friction;
* :mod:`~lumped.laws.monotone`: the monotone laws (any ``w = phi(f)``, and
  Herschel-Bulkley), solved by Brent's method through
  :mod:`~lumped.laws.monotone_graph`;
* :mod:`~lumped.laws.regularised`: the Papanastasiou law, a new law in one
  file that no solver names.

Friction laws, each a graph in (rate, tension) that may fall (static above
kinetic, Stribeck), picked by a rule where it is not monotone:

* :mod:`~lumped.laws.contract`: the law contract :class:`SlipLaw`, which
  every law (the dashpots included) provides;
* :mod:`~lumped.laws.slip`: :class:`SlipCurve` (any slip curve, a callable);
* :mod:`~lumped.laws.stribeck`: static, kinetic, Stribeck and viscous
  friction, the ``friction`` kind, a law in one file;
* :mod:`~lumped.laws.slip_elements`: a friction law as a network element;
* :mod:`~lumped.laws.curve`: a relation given by points that may fold back in
  both coordinates (the ``curve`` kind), followed branch by branch, with a
  jump at each fold.

Elements of a network, each a constitutive graph between its force and its
elongation:

* :mod:`~lumped.laws.element`: the element contract :class:`Element`;
* :mod:`~lumped.laws.step_graph`: how one backward-Euler step sees an
  element (:class:`Piece`, the graph contract :class:`StepGraph`);
* :mod:`~lumped.laws.spring_elements` and
  :mod:`~lumped.laws.dashpot_elements`: the kinds, listed by name in
  :mod:`~lumped.laws.kinds`.

Nothing here imports a solver, a driver or the model above it.
"""

from lumped.laws.bingham import BinghamDashpot, bingham_corrector, coulomb, sticks
from lumped.laws.contract import BinghamForm, Dashpot, DashpotState, LinearSpring, SlipLaw, Slope, StepBound
from lumped.laws.curve import Curve
from lumped.laws.dashpot_elements import Bingham, HerschelBulkley, LawElement, LinearDashpot, LockingBingham, Monotone
from lumped.laws.element import GROUND, Element
from lumped.laws.kinds import KINDS
from lumped.laws.monotone import HerschelBulkleyDashpot, MonotoneDashpot
from lumped.laws.monotone_graph import MONOTONE_SAMPLE
from lumped.laws.regularised import PapanastasiouDashpot
from lumped.laws.slip import SlipCurve
from lumped.laws.slip_elements import Contact, SlipElement
from lumped.laws.stribeck import Friction, StribeckLaw
from lumped.laws.spring_elements import MaxwellBingham, Spring, SpringString
from lumped.laws.step_graph import Piece

__all__ = [
    "GROUND",
    "KINDS",
    "MONOTONE_SAMPLE",
    "Bingham",
    "BinghamDashpot",
    "Contact",
    "Curve",
    "Friction",
    "SlipCurve",
    "SlipElement",
    "SlipLaw",
    "Slope",
    "StribeckLaw",
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
