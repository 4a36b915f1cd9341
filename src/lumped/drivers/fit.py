"""A least-squares fit of a system's parameters to a measured record, with the exact Jacobian.

:func:`fit` estimates the parameters named ``free`` (``dashpot.threshold``,
``spring.stiffness``, ``m.x0``: :mod:`lumped.model.system_parameters`) from
a record of displacements (:class:`~lumped.model.records.Record`: any
subset of the masses) by SciPy's ``least_squares`` from the values in the
system, with the Jacobian of the residuals given exactly by the
sensitivities of the exact solution, of one mass or of a network
(:func:`lumped.drivers.sensitivity.system_sensitivities`).

Notes
-----
With ``r`` the residuals (model less data, ``n`` of them) and ``J`` their
Jacobian at the estimate, the residual variance is ``s^2 = |r|^2/(n - p)``
and the estimates' covariance ``s^2 (J^T J)^-1`` (the linearised model,
Gaussian errors of equal variance).  Identifiability is read from the SVD
of the *relative* Jacobian ``J diag(theta)`` (``theta`` a parameter's
estimate, 1 where that is 0): a right singular vector ``u_i`` is a
combination ``sum_j u_ij dtheta_j/theta_j`` whose standard error is
``s/sigma_i``.  It is **not identified** when ``sigma_i < rcond sigma_1``
(the columns dependent to the precision of the sensitivities, whatever the
noise: a symmetry of the model, such as scaling ``m``, ``k``, ``tau`` and
``1/gamma`` together in a free decay) or when its standard error exceeds 1
(the data cannot tell it to within a factor ``e``).  A parameter with a
weight ``|u_ij| > 0.1`` in such a combination gets no standard error; the
others' come from the pseudo-inverse on the identified combinations.

**The search** (issue 31).  *Units:* ``least_squares``' tolerances are
absolute, so it runs in units-free variables: the residuals divided by the
record's largest ``|x|``, a parameter that must stay positive as
``u = ln(theta/start)``, another as ``u = (theta - start)/size`` with
``size`` its start (a phase: pi; ``x0`` or ``v0`` starting at 0: the record's
largest ``|x|`` or ``|dx/dt|``).  The same record in metres or micrometres is
then the same problem.  ``u`` is bounded to ``|u| <= ln 1000``: a parameter
that ends there (one running toward its bound 0, a threshold the record
cannot tell from 0, or away) is not identified, and so is every other whose
estimate moving it back would shift by more than its standard error (the
linearised model).  The Jacobian handed to ``least_squares`` has its singular
values below ``rcond`` times the largest set to 0, so that the search does not
wander along a combination the record does not determine.

*Local minima:* the residual of an oscillating record has a minimum for
every way of matching its cycles, so a start a few per cent off in a
frequency can end at the wrong one.  Each local fit therefore starts on the
record's first eighth (at least ``4 p`` times), then doubles the part fitted,
each from the last estimate, to the whole record: the cycles are matched one
by one.  It is run from the system's values and from ``starts - 1`` points of
a Halton sequence around them (a factor 1/2 to 2 for a positive parameter,
``-+ 2`` sizes for another).  The lowest end is the estimate (the one from the
system's values unless another is lower beyond round-off).  The cost is
``starts`` times that of one such fit, each about twice one local fit to the
whole record (``benchmarks/bench_fit.py``; the guide's benchmarks page).

*Rival minima:* another end ``theta'`` whose sum of squares ``S'`` is within
the 95 % confidence region of the estimate's, ``S' - S <= p F(0.95; p, n - p)
s^2`` (the likelihood region of the Gaussian model, where the data cannot
reject ``theta'``), yet outside the linearised region, ``|J (theta' -
theta)|^2 > p F s^2`` (so the standard errors would exclude it), fits the
record as well: the parameters it moves by more than one standard error are
not identified, with that reason (a phase's difference taken modulo
``2 pi``).  Not guaranteed: a minimum that no start's windowed fit reaches.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from lumped.drivers.sensitivity import plan, system_sensitivities
from lumped.model.forcing import closed_form, kind_of
from lumped.model.network import Network
from lumped.model.records import Record, check_record
from lumped.model.system_parameters import SystemParameter, system_parameters, with_values
from lumped.numerics import validate
from lumped.numerics.sine import MAX_ARGUMENT
from lumped.solvers.network_sensitivities import NetworkSensitivities

__all__ = ["Combination", "FitResult", "fit"]

#: Keys whose values must stay positive (a lower bound of 0 for the fit).
_POSITIVE = frozenset({"mass", "stiffness", "threshold", "gamma", "damping", "consistency", "length", "v_lock"})
#: Weight above which a parameter takes part in a combination (its share of the unit vector: 1 %).
_WEIGHT = 0.1


@dataclass(frozen=True)
class Combination:
    """``sum_j coefficients_j dtheta_j/theta_j`` (a unit vector), a right singular vector of the relative Jacobian.

    ``ratio`` is ``sigma_i/sigma_1``; ``standard_error`` the combination's, ``s/sigma_i`` (relative);
    ``identified`` whether the data determine it (module Notes).
    """

    coefficients: np.ndarray
    ratio: float
    standard_error: float
    identified: bool

    def text(self, names: Sequence[str]) -> str:
        """``0.71 dln(a) - 0.71 dln(b)``: the terms whose weight exceeds 0.1, largest first."""
        order = np.argsort(-np.abs(self.coefficients))
        terms = [(self.coefficients[j], names[j]) for j in order if abs(self.coefficients[j]) > _WEIGHT]
        sign = 1.0 if terms[0][0] > 0 else -1.0
        out = " ".join(f"{'+' if sign * c > 0 else '-'} {abs(c):.2f} dln({n})" for c, n in terms)
        return out.removeprefix("+ ")


@dataclass(frozen=True)
class FitResult:
    """The fit of :func:`fit`.

    Attributes
    ----------
    parameters : tuple of str
    start, estimate, standard_error : ndarray, (p,)
        ``standard_error`` is ``nan`` for a parameter in a combination the data do not identify.
    correlation : ndarray, (p, p)
        ``nan`` in the rows and columns of those parameters.
    identified : ndarray of bool, (p,)
    combinations : tuple of Combination
        Every right singular vector of the relative Jacobian, largest singular value first.
    residual_std : float
        ``s`` (m).
    record : Record
    model : dict of str to ndarray
        The fitted displacements of each measured mass at the record's times.
    network : Network
        The system with the estimates.
    evaluations : int
        The model runs of every local fit, all starts and windows.
    message : str
        ``least_squares``' reason for stopping the best local fit.
    reasons : tuple of str
        Why each parameter is not identified (``""`` for one that is): in a combination the record does not
        identify, or moved by another minimum that fits the record as well.
    rival : ndarray, (p,), or None
        That other minimum's parameters, if any (module Notes).
    """

    parameters: tuple[str, ...]
    start: np.ndarray
    estimate: np.ndarray
    standard_error: np.ndarray
    correlation: np.ndarray
    identified: np.ndarray
    combinations: tuple[Combination, ...]
    residual_std: float
    record: Record
    model: dict[str, np.ndarray]
    network: Network
    evaluations: int
    message: str
    reasons: tuple[str, ...] = ()
    rival: np.ndarray | None = None

    def residuals(self) -> dict[str, np.ndarray]:
        """Data less model for each measured mass (m)."""
        return {name: self.record.x[name] - self.model[name] for name in self.record.x}

    def summary(self) -> str:
        """One line: each estimate with its standard error, and the combinations not identified."""
        parts = []
        for name, value, se in zip(self.parameters, self.estimate, self.standard_error):
            parts.append(f"{name} = {value:.6g}" + (f" +- {se:.2g}" if math.isfinite(se) else " (not identified)"))
        line = ", ".join(parts) + f"; residual std {self.residual_std:.3g} m"
        missing = [c.text(self.parameters) for c in self.combinations if not c.identified]
        others = list(dict.fromkeys(r for r in self.reasons if r and not r.startswith("in a combination")))
        return line + "".join(f"; not identified: {m}" for m in missing + others)


class _Model:
    """Residuals and their exact Jacobian at a parameter vector, the last one kept (``least_squares``
    asks for both at the same point)."""

    def __init__(self, network: Network, params: tuple[SystemParameter, ...], record: Record) -> None:
        self.network, self.params, self.record = network, params, record
        self.names = [p.name for p in params]
        self.last: tuple[np.ndarray, np.ndarray, np.ndarray, dict[str, np.ndarray]] | None = None

    def __call__(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
        if self.last is not None and np.array_equal(self.last[0], theta):
            return self.last[1:]  # type: ignore[return-value]
        try:
            net = with_values(self.network, self.params, theta)
            solution, sens = system_sensitivities(net, self.record.t, self.names, "free")
        except (ValueError, ArithmeticError) as err:  # an overflow far out in the parameters' range included
            shown = ", ".join(f"{n} = {v:.6g}" for n, v in zip(self.names, theta))
            raise ValueError(f"free: the model cannot be run at {shown}: {err}") from None
        if isinstance(sens, NetworkSensitivities):  # x (T, n) and its derivatives (T, n, p), masses in order
            index = {name: i for i, name in enumerate(net.mass_names)}
            model = {name: sens.positions[:, index[name]] for name in self.record.x}
            J = np.vstack([sens.x[:, index[name], :] for name in self.record.x])
        else:
            model = {net.masses[0].name: solution.evaluate(self.record.t)["x"]}  # type: ignore[union-attr]
            J = np.vstack([sens.x for _ in self.record.x])
        r = np.concatenate([model[name] - self.record.x[name] for name in self.record.x])
        if not (np.all(np.isfinite(r)) and np.all(np.isfinite(J))):
            shown = ", ".join(f"{n} = {v:.6g}" for n, v in zip(self.names, theta))
            raise ValueError(f"free: the model's residuals or derivatives are not finite at {shown}")
        self.last = (theta.copy(), r, J, model)
        return r, J, model


class _Variables(NamedTuple):
    """The dimensionless variables ``u`` of the search (module Notes): ``u = ln(theta/start)`` for a parameter
    that must stay positive (``log``), ``u = (theta - start)/scale`` for one of either sign."""

    start: np.ndarray
    log: np.ndarray
    scale: np.ndarray
    phase: np.ndarray

    def apart(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """``a - b``, a phase's difference taken modulo 2 pi into [-pi, pi) (a turn more is the same motion)."""
        d = a - b
        return np.where(self.phase, (d + math.pi) % (2 * math.pi) - math.pi, d)

    def theta(self, u: np.ndarray) -> np.ndarray:
        return np.where(self.log, self.start * np.exp(np.where(self.log, u, 0.0)), self.start + self.scale * u)

    def dtheta(self, u: np.ndarray) -> np.ndarray:
        return np.where(self.log, self.theta(u), self.scale)


class _Minimum(NamedTuple):
    """A local fit's end: the variables ``u``, the parameters, the sum of squared scaled residuals, whether
    ``least_squares`` converged, its model runs and its message."""

    u: np.ndarray
    theta: np.ndarray
    squares: float
    converged: bool
    evaluations: int
    message: str
    reasons: tuple[str, ...] = ()
    rival: np.ndarray | None = None


def _variables(params: tuple[SystemParameter, ...], record: Record, what: str) -> _Variables:
    """The search's variables; a one-line ``ValueError`` for a start the search cannot leave."""
    start = np.array([p.value for p in params])
    for p in params:
        if not math.isfinite(p.value):
            raise ValueError(f"{what}: {p.name} starts at {p.value}; give it a finite start in the system file")
        if p.key in _POSITIVE and not p.value > 0:
            raise ValueError(f"{what}: {p.name} starts at {p.value:g}; a fitted {p.key} needs a start > 0")
    log, phase = (np.array([p.key in keys for p in params]) for keys in (_POSITIVE, ("phase",)))
    return _Variables(start, log, _typical(params, record), phase)


def _typical(params: tuple[SystemParameter, ...], record: Record) -> np.ndarray:
    """A parameter's typical size, in its units: pi for a phase (its starts then cover every angle), else its
    start, or where that is 0 the record's own scale of a position (``x0``) or a speed (``v0``), else 1."""
    x = np.concatenate(list(record.x.values()))
    dx = np.concatenate([np.abs(np.diff(v)) / np.diff(record.t) for v in record.x.values()])
    fallback = {"x0": float(np.max(np.abs(x))), "v0": float(np.max(dx))}
    out = [
        math.pi if p.key == "phase" else abs(p.value) if p.value != 0 else fallback.get(p.key, 0.0) or 1.0
        for p in params
    ]
    return np.array(out)


def _truncated(J: np.ndarray, rcond: float) -> np.ndarray:
    """``J`` with its singular values below ``rcond`` times the largest set to 0: the search then takes no step
    along a combination the record does not identify (module Notes), where round-off alone would drive it."""
    U, sigma, Vt = np.linalg.svd(J, full_matrices=False)
    return (U * np.where(sigma >= rcond * sigma[0], sigma, 0.0)) @ Vt


def _local(
    model: _Model,
    var: _Variables,
    u0: np.ndarray,
    size: float,
    rows: np.ndarray,
    max_evaluations: int,
    rcond: float,
) -> _Minimum:
    """``least_squares`` in the variables ``u`` from ``u0`` on the residuals ``rows`` divided by ``size``."""
    from scipy.optimize import least_squares  # here: importing the package loads no SciPy solver

    sol = least_squares(
        lambda u: model(var.theta(u))[0][rows] / size,
        u0,
        jac=lambda u: _truncated(model(var.theta(u))[1][rows] * (var.dtheta(u) / size), rcond),
        bounds=(-_REACH, _REACH),
        method="trf",
        max_nfev=max_evaluations,
    )
    r = model(var.theta(sol.x))[0][rows] / size
    return _Minimum(sol.x, var.theta(sol.x), float(r @ r), sol.status > 0, int(sol.nfev), str(sol.message))


def _windowed(
    network: Network,
    params: tuple[SystemParameter, ...],
    record: Record,
    var: _Variables,
    u0: np.ndarray,
    size: float,
    max_evaluations: int,
    rcond: float,
) -> _Minimum:
    """The local fit from ``u0`` continued over growing windows of the record (module Notes): its first
    ``4 p`` times (at least 8), then twice as many, ..., then all of it."""
    n, evaluations, u = record.t.size, 0, u0
    count = max(4 * len(params), 8, n // FIRST)
    while True:
        count = min(count, n)
        window = Record(record.t[:count], {name: x[:count] for name, x in record.x.items()})
        rows = np.arange(count * len(record.x))
        end = _local(_Model(network, params, window), var, u, size, rows, max_evaluations, rcond)
        evaluations += end.evaluations
        if count == n:
            return end._replace(evaluations=evaluations)
        u, count = end.u, 2 * count


def _starts(var: _Variables, count: int) -> list[np.ndarray]:
    """The start, then ``count - 1`` points of a Halton sequence spread over each parameter's range around it:
    a factor 1/2 to 2 for a positive one, start -+ 2 typical sizes for one of either sign (module Notes)."""
    p, primes = var.start.size, (2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37)
    out = [np.zeros(p)]
    for i in range(1, count):
        h = np.array([_radical_inverse(i, primes[j % len(primes)]) for j in range(p)]) * 2 - 1  # in (-1, 1)
        out.append(np.where(var.log, h * math.log(2.0), 2.0 * h))
    return out


def _radical_inverse(i: int, base: int) -> float:
    """The ``i``-th term of van der Corput's sequence in ``base``: ``i``'s digits mirrored about the point."""
    out, f = 0.0, 1.0 / base
    while i:
        i, digit = divmod(i, base)
        out, f = out + digit * f, f / base
    return out


def fit(
    network: Network,
    record: Record,
    free: str | Sequence[str],
    *,
    rcond: float = 1e-8,
    max_evaluations: int = 200,
    starts: int = 4,
) -> FitResult:
    """Estimate the parameters ``free`` of ``network`` from ``record`` (module Notes).

    Parameters
    ----------
    network : Network
        The system, with the start values: one that the exact sensitivities
        take (one mass on springs and a Bingham or Coulomb dashpot under a
        sine or constant load, or a network of springs, Bingham, Coulomb and
        linear dashpots under sine and constant loads).
    record : Record
        Times and measured displacements (:func:`~lumped.model.records.read_record`;
        :func:`~lumped.model.records.check_record` says what one built in Python must hold).
    free : str or sequence of str
        Parameter names (``dashpot.threshold,dashpot.gamma``).
    rcond : float
        Singular values below ``rcond`` times the largest mark dependent combinations; in (0, 1).
    max_evaluations : int
        Bound on the model runs of each local fit (of each window).
    starts : int
        The local fits, each continued over growing windows of the record: from the system's values, then
        from ``starts - 1`` points spread around them (module Notes).  1 runs the one from the system's values.

    Raises
    ------
    ValueError
        One line naming the argument (``network``, ``record``, ``free``, ``rcond``, ``max_evaluations``,
        ``starts``) or the system: a bad name, a parameter with an infinite start (a Coulomb ``gamma``) or a
        positive one starting at 0, a record with no more residuals than parameters, a system the exact
        sensitivities do not run, a record longer than the system can be run, a fit that converges from no
        start.
    """
    if not isinstance(network, Network):
        raise ValueError(f"network: expected a lumped.Network, got {type(network).__name__}")  # noqa: TRY004 (the API's one error type)
    rcond = validate.finite("rcond", rcond)
    if not 0 < rcond < 1:
        raise ValueError(f"rcond must be in (0, 1), got {rcond!r}")
    max_evaluations = validate.positive_int("max_evaluations", max_evaluations)
    starts = validate.positive_int("starts", starts)
    if starts > _MAX_STARTS:
        raise ValueError(f"starts must be at most {_MAX_STARTS}, got {starts}")
    record = check_record(record, network.mass_names, "record")
    for load in network.loads:
        if closed_form(load.force) is None:
            kind = kind_of(load.force)
            why = f"system: the load on {load.on!r} is {kind}; the exact sensitivities take sines and constants"
            raise ValueError(why)
    plan(network, f"{network.mass_names[0]}.x0", "system")  # the system's own refusals, before the names'
    params = system_parameters(network, free, "free")
    plan(network, [p.name for p in params], "free")
    n = sum(x.size for x in record.x.values())
    if n <= len(params):
        raise ValueError(f"record: {n} measured values cannot determine {len(params)} parameters")
    _check_span(network, record)
    var = _variables(params, record, "free")
    return _search(network, params, record, var, rcond, max_evaluations, starts)


#: The first window of the record is its first ``1/FIRST`` (module Notes).
FIRST = 8
#: How far the search goes, in the variables ``u``: a factor ``e^REACH`` (about 1000) either way from the start
#: for a positive parameter, ``REACH`` typical sizes either way for one of either sign.
_REACH = math.log(1000.0)

#: Most starts :func:`fit` takes (each a windowed local fit).
_MAX_STARTS = 64


def _check_span(network: Network, record: Record) -> None:
    """Refuse a record longer than the system's sine loads can be evaluated over, naming the record's end."""
    t_end = float(record.t[-1])
    for load in network.loads:
        force = closed_form(load.force)  # a constant's, omega = 0 and phase pi/2, never leaves the range
        if force is not None:
            span = abs(force.omega) * min(t_end, force.until) + abs(force.phase)
            if not span <= MAX_ARGUMENT:
                raise ValueError(
                    f"record: it ends at t = {t_end:.6g} s, where the sine load on {load.on!r} (omega = "
                    f"{force.omega:.6g} rad/s) reaches {span:.3g} rad, beyond {MAX_ARGUMENT:.0e} rad, the range of "
                    "its sine; shorten the record"
                )


def _search(
    network: Network,
    params: tuple[SystemParameter, ...],
    record: Record,
    var: _Variables,
    rcond: float,
    max_evaluations: int,
    starts: int,
) -> FitResult:
    """The windowed local fits from each start, the best of them, and whether another fits as well."""
    full = _Model(network, params, record)
    try:
        r0 = full(var.start)[0]
    except ValueError as err:  # at the file's own values: the record's span is what the system cannot take
        raise ValueError(_over_record(str(err), float(record.t[-1]))) from None
    data = np.concatenate(list(record.x.values()))
    size = float(np.max(np.abs(data))) or float(np.max(np.abs(r0))) or 1.0  # the record's scale (m)
    ends, evaluations, first = [], 0, None
    for u0 in _starts(var, starts):
        try:
            with np.errstate(all="ignore"):  # a start that leaves the model's range is dropped, not shown
                end = _windowed(network, params, record, var, u0, size, max_evaluations, rcond)
        except ValueError:  # the model cannot be run at some iterate from this start
            continue
        evaluations += end.evaluations
        first = end if first is None and not u0.any() else first
        if end.converged:
            ends.append(end)
    if not ends:
        raise ValueError(
            f"free: the fit converged from none of its {starts} starts within {max_evaluations} model runs each; "
            "give start values nearer the record's in the system file"
        )
    least = min(e.squares for e in ends)
    # The end from the system's values unless another is lower beyond round-off: the same choice on any CPU.
    best = ends[0] if ends[0] is first and ends[0].squares <= least * (1 + 1e-9) else min(ends, key=_squares)
    r, J, fitted = full(best.theta)
    scale = np.where(best.theta != 0, np.abs(best.theta), 1.0)  # relative to the estimate
    result = _result(params, var.start, best, r, J * scale, scale, record, fitted, network, rcond, evaluations)
    return _at_reach(_ambiguity(result, ends, best, J / size, var), best, var, J, r)


#: The exact solvers' words for a run's span and its remedy, and the fit's for a record's.
_SPAN_WORDS = (
    ("before t_end", "before the record's end"),
    ("; shorten t_end or use backward Euler", ""),
)


def _over_record(message: str, t_end: float) -> str:
    """The one line of a model that cannot be run at the system's values over a record ending at ``t_end``."""
    why = message.split(": ", 2)[-1].removeprefix("t_end: ")  # past "free: the model cannot be run at ...: "
    for old, new in _SPAN_WORDS:
        why = why.replace(old, new)
    return f"record: the system cannot be run over it, from t = 0 to {t_end:.6g} s: {why}; shorten the record"


def _at_reach(result: FitResult, best: _Minimum, var: _Variables, J: np.ndarray, r: np.ndarray) -> FitResult:
    """``result`` with a parameter whose estimate ended at the edge of the search (:data:`_REACH`) not
    identified: one that ran toward its bound 0 (the record cannot tell it from 0: the Gauss-Newton step
    from the estimate, ``-J^+ r``, would take it to within a standard error of 0 or below; it stops short
    there only because its gradient in ``ln theta`` vanishes), or away from its start; and with it each
    other parameter that moving the first to 0 (or back to its start) would shift by more than its standard
    error, by the linearised model of the Jacobian ``J`` at the estimate."""
    newton = best.theta + np.linalg.lstsq(J, -r, rcond=None)[0]
    low = (best.u <= -_REACH * (1 - 1e-6)) | (var.log & (newton <= result.standard_error))
    high = best.u >= _REACH * (1 - 1e-6)
    edge = low | high
    if not edge.any():
        return result
    step = np.where(var.log & low, -best.theta, np.where(edge, var.start - best.theta, 0.0))
    others = np.linalg.lstsq(J[:, ~edge], -J[:, edge] @ step[edge], rcond=None)[0] if (~edge).any() else []
    shift = np.zeros(edge.size)
    shift[~edge] = others
    names = ", ".join(n for n, e in zip(result.parameters, edge) if e)
    result = _unidentified(result, ~edge & ~(np.abs(shift) <= result.standard_error), f"it depends on {names}")
    for which, why in (
        (var.log & low, "it ran toward 0, the bound of its range, where the record puts its minimum"),
        (~var.log & low, "it ran to the edge of the search, 1000 typical sizes below its start"),
        (high, "it ran to the edge of the search, 1000 times (typical sizes) above its start"),
    ):
        result = _unidentified(result, which, why) if which.any() else result
    return result


def _squares(end: _Minimum) -> float:
    return end.squares


def _ambiguity(result: FitResult, ends: list[_Minimum], best: _Minimum, J: np.ndarray, var: _Variables) -> FitResult:
    """``result`` with the parameters that another minimum in ``ends`` moves marked not identified, when it
    fits the record as well (module Notes); else ``result``."""
    from scipy.special import fdtri  # the F distribution's quantile (scipy.stats takes a second to import)

    n, p = J.shape
    threshold = p * float(fdtri(p, n - p, 0.95)) * best.squares / (n - p)
    rivals = []
    for end in ends:
        step = var.apart(end.theta, best.theta)
        if end.squares - best.squares <= threshold and float(np.sum((J @ step) ** 2)) > threshold:
            rivals.append(end)
    if not rivals:
        return result
    rival = max(rivals, key=lambda e: float(np.sum((J @ var.apart(e.theta, best.theta)) ** 2)))
    se = result.standard_error
    moved = ~(np.abs(var.apart(rival.theta, best.theta)) <= se)  # beyond one standard error (or none)
    if not moved.any():
        moved[:] = True
    shown = ", ".join(f"{n} = {v:.6g}" for n, v, m in zip(result.parameters, rival.theta, moved) if m)
    reason = (
        f"another minimum, {shown}, fits the record as well (its sum of squares within the 95 % confidence "
        "region of the estimate's)"
    )
    return dataclasses.replace(_unidentified(result, moved, reason), rival=rival.theta)


def _unidentified(result: FitResult, which: np.ndarray, reason: str) -> FitResult:
    """``result`` with the parameters ``which`` not identified for ``reason`` (no standard error, no correlation)."""
    corr = result.correlation.copy()
    corr[which, :], corr[:, which] = np.nan, np.nan
    return dataclasses.replace(
        result,
        identified=result.identified & ~which,
        standard_error=np.where(which, np.nan, result.standard_error),
        correlation=corr,
        reasons=tuple(reason if w else r for w, r in zip(which, result.reasons)),
    )


def _result(
    params: tuple[SystemParameter, ...],
    start: np.ndarray,
    best: _Minimum,
    r: np.ndarray,
    J_rel: np.ndarray,
    scale: np.ndarray,
    record: Record,
    fitted: dict[str, np.ndarray],
    network: Network,
    rcond: float,
    evaluations: int,
) -> FitResult:
    """The statistics at the estimate ``best`` from the residuals ``r`` and the relative Jacobian ``J_rel``
    there (module Notes)."""
    p = len(params)
    s = float(np.sqrt(r @ r / (r.size - p)))
    _, sigma, vt = np.linalg.svd(J_rel, full_matrices=False)
    with np.errstate(divide="ignore"):
        errors = np.where(sigma > 0, s / sigma, np.inf)
    ok = (sigma >= rcond * sigma[0]) & (errors <= 1.0) if sigma[0] > 0 else np.zeros(p, dtype=bool)
    combos = tuple(Combination(vt[i], float(sigma[i] / sigma[0]), float(errors[i]), bool(ok[i])) for i in range(p))
    identified = ~np.any(np.abs(vt[~ok]) > _WEIGHT, axis=0)
    cov = (vt[ok].T / sigma[ok] ** 2) @ vt[ok] * s**2  # relative units, on the identified combinations
    se = np.where(identified, scale * np.sqrt(np.abs(np.diag(cov))), np.nan)
    d = np.sqrt(np.abs(np.diag(cov)))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(d, d)
    corr[~identified, :] = np.nan
    corr[:, ~identified] = np.nan
    names = tuple(q.name for q in params)
    net = with_values(network, params, best.theta)
    why = "in a combination of the parameters that the record does not identify (combinations)"
    reasons = tuple("" if ok_j else why for ok_j in identified)
    statistics = (se, corr, identified, combos, s)
    return FitResult(names, start, best.theta, *statistics, record, fitted, net, evaluations, best.message, reasons)
