"""The driver: one entry point for every method, ``simulate(...) -> Trajectory``.

:data:`METHODS` is the one registry of method names; :func:`simulate` and the
command line's ``--method`` both read it.  (The module is not called
``simulate``: ``lumped/__init__.py`` exports the function under that name, so
``import lumped.simulate`` would hand back the function, not a module.)
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Mapping
from types import MappingProxyType

import numpy as np

from lumped import _validate
from lumped.event_driven import solve_exact
from lumped.event_integration import DEFAULT_RTOL, solve_event_driven
from lumped.forcing import SwitchedSine
from lumped.results import Trajectory
from lumped.schemes import event_capturing, theta_method
from lumped.system import Oscillator
from lumped.timestepping import backward_euler

__all__ = ["METHODS", "simulate", "method_options"]

Force = SwitchedSine | Callable[[np.ndarray], np.ndarray] | None


def _backward_euler(
    osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, force: Force, save_every: int
) -> Trajectory:
    """Algorithm 1 (backward Euler)."""
    return backward_euler(osc, t_end, dt, x0=x0, v0=v0, force=force, save_every=save_every)


def _exact(osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, force: Force, save_every: int) -> Trajectory:
    """Exact event-driven solution, sampled on the grid."""
    sol = solve_exact(osc, t_end, x0=x0, v0=v0, force=force)  # type: ignore[arg-type]
    return sol.sample(dt, save_every)


def _event_capturing(
    osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, force: Force, save_every: int
) -> Trajectory:
    """Event-capturing trapezoidal scheme, order 2 through the switches."""
    return event_capturing(osc, t_end, dt, x0=x0, v0=v0, force=force, save_every=save_every).trajectory  # type: ignore[arg-type]


def _theta(osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, force: Force, save_every: int) -> Trajectory:
    """Theta-method with theta = 1/2 (trapezoidal rule), switches crossed blindly."""
    return theta_method(osc, t_end, dt, x0=x0, v0=v0, force=force, save_every=save_every)


def _event_driven(
    osc: Oscillator,
    t_end: float,
    dt: float,
    x0: float,
    v0: float,
    force: Force,
    save_every: int,
    *,
    rtol: float = DEFAULT_RTOL,
) -> Trajectory:
    """Event-driven integration for any monotone dashpot law (DOP853 slip phases, exact stick), sampled on the grid."""
    sol = solve_event_driven(osc, t_end, x0=x0, v0=v0, force=force, rtol=rtol)  # type: ignore[arg-type]
    return sol.sample(dt, save_every)


#: Method name -> solver ``(osc, t_end, dt, x0, v0, force, save_every, **options)``;
#: the first line of each solver's docstring describes it (``--help`` shows it),
#: and its keyword-only parameters are its options (:func:`method_options`).
METHODS: Mapping[str, Callable[..., Trajectory]] = MappingProxyType(
    {
        "backward-euler": _backward_euler,
        "exact": _exact,
        "event-driven": _event_driven,
        "event-capturing": _event_capturing,
        "theta": _theta,
    }
)


def method_options(method: str, options: Mapping[str, object]) -> dict[str, object]:
    """Check that ``method`` is registered and takes every option in ``options``.

    Raises
    ------
    ValueError
        ``method must be one of ...``, or ``<option>: method ... takes no option ...``.
    """
    if not isinstance(method, str) or method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}; got {method!r}")
    params = inspect.signature(METHODS[method]).parameters.values()
    accepted = [p.name for p in params if p.kind is inspect.Parameter.KEYWORD_ONLY]
    for name in options:
        if name not in accepted:
            takes = f"its options are {', '.join(accepted)}" if accepted else "it takes none"
            raise ValueError(f"{name}: method {method!r} takes no option {name!r} ({takes})")
    return dict(options)


def simulate(
    oscillator: Oscillator,
    t_end: float,
    dt: float,
    *,
    x0: float = 0.0,
    v0: float = 0.0,
    force: Force = None,
    method: str = "backward-euler",
    save_every: int = 1,
    **options: object,
) -> Trajectory:
    """Solve the DAE (8) on the grid ``t_n = n*dt`` by ``method``.

    ``"backward-euler"`` is Algorithm 1 (:func:`~lumped.timestepping.backward_euler`);
    ``"exact"`` samples the event-driven solution
    (:func:`~lumped.event_driven.solve_exact`) on the same grid;
    ``"event-driven"`` integrates the slip phases of any dashpot law
    (:func:`~lumped.event_integration.solve_event_driven`) and takes the
    option ``rtol``; ``"event-capturing"`` and ``"theta"`` are the schemes of
    :mod:`lumped.schemes` (the latter at ``theta = 1/2``).  ``method`` is a
    key of :data:`METHODS`; ``options`` are the method's own
    (:func:`method_options` refuses any other).  The other parameters are
    those of :func:`~lumped.timestepping.backward_euler`.
    """
    options = method_options(method, options)
    save_every = _validate.stride("save_every", save_every)  # before a method solves, then samples
    return METHODS[method](oscillator, t_end, dt, x0, v0, force, save_every, **options)
