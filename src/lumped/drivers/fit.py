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
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from lumped.drivers.sensitivity import system_sensitivities
from lumped.model.network import Network
from lumped.model.records import Record
from lumped.model.system_parameters import SystemParameter, system_parameters, with_values
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
    message : str
        ``least_squares``' reason for stopping.
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
        return line + "".join(f"; not identified: {m}" for m in missing)


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
        except ValueError as err:
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
        self.last = (theta.copy(), r, J, model)
        return r, J, model


def fit(
    network: Network, record: Record, free: str | Sequence[str], *, rcond: float = 1e-8, max_evaluations: int = 200
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
        Times and measured displacements (:func:`~lumped.model.records.read_record`).
    free : str or sequence of str
        Parameter names (``dashpot.threshold,dashpot.gamma``).
    rcond : float
        Singular values below ``rcond`` times the largest mark dependent combinations.
    max_evaluations : int
        Bound on the model runs of ``least_squares``.

    Raises
    ------
    ValueError
        One line: a bad name, a parameter with an infinite start (a Coulomb ``gamma``), a record with
        no more residuals than parameters, a model that cannot be run at some iterate.
    """
    from scipy.optimize import least_squares  # here: importing the package loads no SciPy solver

    params = system_parameters(network, free, "free")
    start = np.array([p.value for p in params])
    for p in params:
        if not math.isfinite(p.value):
            raise ValueError(f"free: {p.name} starts at {p.value}; give it a finite start in the system file")
    n = sum(x.size for x in record.x.values())
    if n <= len(params):
        raise ValueError(f"data: {n} measured values cannot determine {len(params)} parameters")
    model = _Model(network, params, record)
    scale = np.where(start != 0, np.abs(start), 1.0)
    lower = np.array([0.0 if p.key in _POSITIVE else -np.inf for p in params])
    sol = least_squares(
        lambda th: model(th)[0],
        start,
        jac=lambda th: model(th)[1],
        bounds=(lower, np.full(len(params), np.inf)),
        x_scale=scale,
        method="trf",
        max_nfev=max_evaluations,
    )
    r, J, fitted = model(sol.x)
    scale = np.where(sol.x != 0, np.abs(sol.x), 1.0)  # relative to the estimate
    return _result(params, start, sol, r, J * scale, scale, record, fitted, network, rcond)


def _result(
    params: tuple[SystemParameter, ...],
    start: np.ndarray,
    sol: object,
    r: np.ndarray,
    J_rel: np.ndarray,
    scale: np.ndarray,
    record: Record,
    fitted: dict[str, np.ndarray],
    network: Network,
    rcond: float,
) -> FitResult:
    """The statistics at the estimate ``sol`` (``least_squares``' result) from the residuals ``r`` and the
    relative Jacobian ``J_rel`` there (module Notes)."""
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
    x = sol.x  # type: ignore[attr-defined]
    net = with_values(network, params, x)
    evaluations, message = int(sol.nfev), str(sol.message)  # type: ignore[attr-defined]
    return FitResult(names, start, x, se, corr, identified, combos, s, record, fitted, net, evaluations, message)
