"""The compiled backward-Euler step for one mass with a friction contact (``_friction_kernel.c``).

The system it runs: one mass; linear springs (``linear_stiffness``, point 8 of
:class:`~lumped.laws.element.Element`) and linear dashpots (the dashpot's
``kernel_form()``, point 9), each between the mass and the ground or a driven
point; one friction contact whose law has a ``kernel_form()``
(:class:`~lumped.laws.StribeckLaw`: static above kinetic with or without a
Stribeck fall, a viscous part), found through the element's ``slip_law()``
(point 12), to the ground or a driven point; any loads on the mass; every
driven point it touches at a constant velocity.  The block on a belt is the
example.  The step is the Python step's (:func:`lumped.solvers.network_step.solve_step`
with the contact's rule, :func:`lumped.laws.step_graph._slip_rule`): bit for bit
on a linear slip curve, to the root solve's tolerance on a Stribeck curve
(the C file's comment says how; ``tests/test_friction_kernel.py``).

:func:`ineligible` says why a network is not such a system; the driver
(:func:`lumped.drivers.network.simulate_network`) takes this loop when the
network kernel cannot run the network and this one can, and the trajectory's
``solver`` is then :data:`PATH`.
"""

from __future__ import annotations

import os
from typing import NamedTuple

import numpy as np

from lumped.model.network import Network

__all__ = ["KERNEL", "PATH", "FrictionPlan", "ineligible", "plan", "march_block"]

#: The trajectory's ``solver`` when this loop ran it.
PATH = "one-mass-friction"
#: ``"compiled"`` when ``_friction_kernel.c`` was built (and ``LUMPED_PURE_PYTHON`` is unset).
KERNEL = "python"
if os.environ.get("LUMPED_PURE_PYTHON", "") in ("", "0"):
    try:
        from lumped.kernels._friction_kernel import friction_block as _friction_block  # type: ignore[import-not-found]

        KERNEL = "compiled"
    except ImportError:  # no C compiler at install: the Python step runs these networks
        pass

#: The roles of ``_friction_kernel.c``.
_SPRING, _DASHPOT, _CONTACT = 0, 1, 2
#: The linear dashpot's kind code in ``_network_elements.h`` (``Element.kernel_form``, point 9).
_DASHPOT_CODE = 4


class FrictionPlan(NamedTuple):
    """What the C loop reads: each element's ``role`` (0 spring, 1 dashpot, 2 the contact), ``par``
    (stiffness or damping), ``sign`` (+1 if the mass is its ``second`` point) and ``delta`` (the
    velocity its other point adds to the problem's rate, as the Python step shifts it), and the contact's
    ``law``: ``(code, static, kinetic, v_s, viscous)`` of ``SlipLaw.kernel_form()``."""

    role: np.ndarray
    par: np.ndarray
    sign: np.ndarray
    delta: np.ndarray
    law: tuple[int, float, float, float, float]


def _role(el: object) -> tuple[int, float] | None:
    """``(role, parameter)`` of a spring or a linear dashpot, through the element contract; else ``None``."""
    k = el.linear_stiffness  # type: ignore[attr-defined]
    if k is not None:
        return _SPRING, float(k)
    form = el.kernel_form()  # type: ignore[attr-defined]
    if form is not None and form.code == _DASHPOT_CODE:
        return _DASHPOT, float(form.parameters[0])
    return None


def ineligible(net: Network) -> str | None:
    """Why this loop cannot run ``net``, or ``None`` if it can."""
    if KERNEL != "compiled":
        return "the compiled friction kernel was not built"
    if len(net.masses) != 1:
        return f"the network has {len(net.masses)} masses"
    contacts = [el for el in net.elements if el.slip_law() is not None]
    if len(contacts) != 1:
        return f"the network has {len(contacts)} friction contacts"
    if contacts[0].slip_law().kernel_form() is None:
        return f"the slip curve of {contacts[0].name!r} has no kernel form"
    first, second = net.incidence()
    for e, el in enumerate(net.elements):
        if (first[e] == 0) == (second[e] == 0):
            return f"element {el.name!r} does not join the mass to the ground or a driven point"
        if el.slip_law() is None and _role(el) is None:
            return f"element {el.name!r} is neither a linear spring, a linear dashpot nor a friction contact"
    for d in net.driven():
        if net.drivers[d.driver].constant_velocity is None:
            return f"driven point {net.drivers[d.driver].name!r} does not move at a constant velocity"
    return None


def plan(net: Network) -> FrictionPlan:
    """The C loop's arrays for ``net`` (which :func:`ineligible` accepts)."""
    n = len(net.elements)
    role, par, delta = np.zeros(n, dtype=np.int64), np.zeros(n), np.zeros(n)
    _, second = net.incidence()
    law = None
    for e, el in enumerate(net.elements):
        if el.slip_law() is not None:
            role[e] = _CONTACT
            code, parameters = el.slip_law().kernel_form()
            law = (int(code), *(float(p) for p in parameters))
        else:
            role[e], par[e] = _role(el)  # type: ignore[misc]
    for d in net.driven():  # as backward_euler_network._shifts for a constant velocity
        delta[d.element] += d.sign * float(net.drivers[d.driver].constant_velocity)  # type: ignore[arg-type]
    sign = np.where(second == 0, 1.0, -1.0)
    return FrictionPlan(role, par, sign, delta, law)  # type: ignore[arg-type]


def march_block(
    topology: FrictionPlan,
    inertia: float,
    marching: tuple[np.ndarray, ...],
    record: tuple[np.ndarray, ...],
    table: np.ndarray,
    dt: float,
    steps: tuple[int, int, int, int],
) -> None:
    """Advance steps ``n_first..n_last`` in C (``steps = (n_first, n_last, n_steps, save_every)``).

    ``marching = (x, v, state, rest, counters)`` is updated in place (``counters = (row, bad_step,
    bad_kind, most_iterations)``, ``bad_kind`` 1: the rule did not settle, 2: not finite); saved rows
    go to ``record = (t, x, v, force, state, rigid)``; ``table`` holds the load on the mass at each step
    of the block, or nothing (no load).
    """
    arrays = (topology.role, topology.par, topology.sign, topology.delta)
    _friction_block(
        arrays, topology.law, marching, record, np.ascontiguousarray(table, dtype=float), dt, inertia, *steps
    )
