"""The element kinds by their name in system files: the one list that the file reader and the command line read."""

from __future__ import annotations

from lumped.laws.curve import Curve
from lumped.laws.dashpot_elements import Bingham, HerschelBulkley, LinearDashpot, LockingBingham
from lumped.laws.element import Element
from lumped.laws.spring_elements import MaxwellBingham, Spring, SpringString
from lumped.laws.stribeck import Friction

__all__ = ["KINDS"]

#: Element kinds by their name in system files.
KINDS: dict[str, type[Element]] = {
    cls.kind: cls
    for cls in (
        Spring,
        SpringString,
        Bingham,
        MaxwellBingham,
        LinearDashpot,
        LockingBingham,
        HerschelBulkley,
        Friction,
        Curve,
    )
}
