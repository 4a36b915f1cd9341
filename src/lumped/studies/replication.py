"""The replication article's numbers and verdicts, computed from the package.

``scripts/paper_numbers.py`` writes :func:`compute`'s dictionary to
``paper/build/numbers.json``; the article (``paper/paper.typ``) reads it with
Typst's ``json()``, types no number by hand and decides no verdict: every
"reproduced" or "deviates" it prints is a :class:`Verdict` from here, with the
tolerance it was decided by.

Layout of the dictionary
------------------------
``parameters``
    The configured values (``m``, ``k``, ``tau``, ``gamma``, ``dt``, ...).
``original``
    The original's values (its section 3), ``changed`` (every parameter whose
    configured value differs from the original's, with both values) and
    ``ours`` (the end times, which the original does not state).
``forced_small``, ``forced_large``, ``free_small``, ``free_large``
    One object per run of the original's section 3 (Figures 5, 6-9, 10,
    11-14): the exact solution (``exact``), Algorithm 1 at the configured step
    (``be``) and their differences (``error``); ``be_original`` and
    ``error_original`` are the same at the original's step ``ORIGINAL_DT``
    (identical to ``be`` and ``error`` when the configured step is the
    original's).
``verdicts``
    ``configured`` and ``original``: one :class:`Verdict` per claim, decided
    from Algorithm 1 at the configured and at the original's step.
``convergence``, ``convergence_rest``
    The differences for the steps :data:`CONVERGENCE_STEPS`, and how each of
    those runs ends (rest position, reversals, side of zero).
``textbook``
    The ``sgn(0) = 0`` model and its ``tanh`` regularisation, with the
    settings of notebook 02 (:data:`TEXTBOOK`).
``provenance``
    Python, key package versions and the machine; no wall-clock time.

Times in s, displacements in m, velocities in m/s, forces in N. The
dictionary is strict JSON (:func:`clean`): a run not at rest by its end time
has ``"still moving"`` as rest time and position; a difference or fitted
order that cannot be formed is ``None``; an infinite parameter is ``"inf"``.
"""

from __future__ import annotations

import importlib.metadata
import math
import os
import platform
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

import lumped.studies.config
from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import Trajectory, sign_changes
from lumped.solvers import textbook
from lumped.solvers.exact import ExactSolution
from lumped.studies import examples

__all__ = [
    "ORIGINAL",
    "ORIGINAL_DT",
    "CONVERGENCE_STEPS",
    "CURVE_TOL",
    "STRETCH_TOL",
    "TEXTBOOK",
    "VERDICT_KEYS",
    "Verdict",
    "compute",
    "clean",
]

ORIGINAL_DT = examples.ORIGINAL_DT
#: The original's values (its section 3 and eqs. 17), under the configuration's keys.
ORIGINAL: dict[str, float] = {
    "mass": 1.0,
    "stiffness": 100.0,
    "threshold": 1.0,
    "gamma": 1.0,
    "dt": ORIGINAL_DT,
    "force_amplitude_small": 0.5,
    "force_amplitude_large": 10.0,
    "force_omega_over_pi": 5.0,
    "force_until": 1.0,
    "x0_small": 0.005,
    "x0_large": 0.5,
}
#: Configuration keys the original does not state (ours whatever their value).
OURS = ("t_end_forced", "t_end_small", "t_end_large")
#: Steps of the convergence study (s); the original's is 1e-4.
CONVERGENCE_STEPS = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5)

#: A curve of Algorithm 1 reproduces the exact one when their largest
#: difference is at most this fraction of the exact curve's largest magnitude
#: (about a line width on a figure); for the dashpot force, whose pointwise
#: difference is the jump 2 mu_s N_f at every reversal whatever the step, the
#: time integral of the difference is compared with that of |F_d|.
CURVE_TOL = 0.01
#: A mass rests "with the spring stretched" when |x_rest| is at least this
#: fraction of the static band half-width mu_s N_f / k.
STRETCH_TOL = 0.01
#: Settings of notebook 02 (notebooks/02_sgn_zero_failure.py), used here so
#: that the article and the notebook print the same numbers: release point
#: (fraction of the static band), forward-Euler step and duration, RK45
#: tolerances and budget, tanh scales, their duration and LSODA tolerances.
TEXTBOOK: dict[str, Any] = {
    "x0_band_fraction": 0.5,
    "t_end": 1.0,
    "euler_dt": 1e-4,
    "rk45_rtol": 1e-8,
    "rk45_atol": 1e-10,
    "rk45_budget": 100_000,
    "tanh_eps": (1e-2, 1e-3, 1e-4, 1e-5),
    "tanh_t_end": 5.0,
    "tanh_rtol": 1e-8,
    "tanh_atol": 1e-12,
}
#: Rest time and rest position of a run still moving at its end time.
STILL_MOVING = "still moving"
#: Packages whose versions the article reports.
PACKAGES = ("lumped", "numpy", "scipy", "matplotlib", "snakemake", "typst", "PyYAML")
#: The quantity each time-history figure shows, per run.
CURVES = {"forced_large": (6, 7, 8, 9), "free_large": (11, 12, 13, 14)}
QUANTITIES = ("x", "v", "F_s", "F_d")


@dataclass(frozen=True)
class Verdict:
    """The article's judgement of one claim of the original.

    Attributes
    ----------
    verdict : str
        ``"reproduced"``, ``"deviates"`` or ``"not checked"``.
    reason : str
        One sentence with the numbers the verdict follows from.
    tolerance : str or None
        The criterion, in words, or ``None`` where none applies.
    """

    verdict: str
    reason: str
    tolerance: str | None = None


# ------------------------------------------------------------------ the runs
def _rest(value: float) -> float | str:
    """A rest time or position, or STILL_MOVING where the trajectory gives ``nan``."""
    return STILL_MOVING if math.isnan(value) else value


def _deviation(be: Trajectory, ref: Trajectory) -> dict[str, float]:
    """Largest absolute differences over the run, column by column.

    ``int_F_d`` is the time integral of ``|F_d - F_d,exact|`` (N s): the
    largest difference in ``F_d`` is the jump ``2 mu_s N_f`` seen at a grid
    point between a reversal of the exact motion and that of Algorithm 1, so
    it does not shrink with the step, while the integral does.
    """
    out = {f"max_{c}": float(np.max(np.abs(getattr(be, c) - getattr(ref, c)))) for c in QUANTITIES}
    out["int_F_d"] = float(np.sum(np.abs(be.F_d - ref.F_d)[1:]) * be.dt)
    out["rest_position"] = abs(be.rest_position - ref.rest_position)
    out["rest_time"] = abs(be.rest_time - ref.rest_time)
    return out


def _exact_summary(ex: ExactSolution, sampled: Trajectory) -> dict[str, Any]:
    kinds = [e.kind for e in ex.events]
    moving = [e for e in ex.events if e.kind in ("breakaway", "reversal", "stop")]
    return {
        "rest_time": _rest(ex.rest_time),
        "rest_position": _rest(ex.rest_position),
        "reversals": kinds.count("reversal"),
        "breakaways": kinds.count("breakaway"),
        "first_event_time": moving[0].time if moving else math.nan,
        "reversal_times": [e.time for e in ex.events if e.kind == "reversal"],
        "reversal_positions": [e.x for e in ex.events if e.kind == "reversal"],
        "peak_x": float(np.max(np.abs(sampled.x))),
        "peak_v": float(np.max(np.abs(sampled.v))),
        "int_abs_F_d": float(np.sum(np.abs(sampled.F_d)[1:]) * sampled.dt),
    }


def _be_summary(be: Trajectory) -> dict[str, Any]:
    return {
        "dt": be.dt,
        "rest_time": _rest(be.rest_time),
        "rest_position": _rest(be.rest_position),
        "peak_x": float(np.max(np.abs(be.x))),
        "peak_v": float(np.max(np.abs(be.v))),
        "min_F_d": float(np.min(be.F_d)),
        "max_F_d": float(np.max(be.F_d)),
        "stick_fraction": float(np.mean(be.v == 0.0)),
        "reversals": sign_changes(be.v),
        "energy_residual": float(np.max(np.abs(be.energy_balance().residual))),
        "steps": int(be.t.size - 1),
    }


def _example(run: examples.Example) -> dict[str, Any]:
    """Exact solution, and Algorithm 1 at the configured and the original's step."""
    exact = run.exact()
    out: dict[str, Any] = {"exact": _exact_summary(exact, exact.sample(run.dt))}
    for suffix, dt in (("", run.dt), ("_original", ORIGINAL_DT)):
        be = run.algorithm1(dt)
        out["be" + suffix], out["error" + suffix] = _be_summary(be), _deviation(be, exact.sample(dt))
    return out


def _eq19(run: examples.Example, dt: float) -> dict[str, float]:
    """Figure 5 against eq. (19): F_d = F_1, and x = v = F_s = 0."""
    be = run.algorithm1(dt)
    return {
        "max_F1": float(np.max(np.abs(be.F))),
        "eq19_max_F_d": float(np.max(np.abs(be.F_d - be.F))),
        "eq19_max_x": float(np.max(np.abs(be.x))),
        "eq19_max_v": float(np.max(np.abs(be.v))),
        "eq19_max_F_s": float(np.max(np.abs(be.F_s))),
    }


# ------------------------------------------------------------------ convergence
def _order(steps: list[float], errors: list[float]) -> float:
    """Least-squares slope of log(error) against log(step); ``nan`` unless every error is > 0."""
    if not all(e > 0 and math.isfinite(e) for e in errors):
        return math.nan  # a zero error (exact at that step) or a run still moving
    return float(np.polyfit(np.log(steps), np.log(errors), 1)[0])


def _convergence(runs: dict[str, examples.Example]) -> tuple[dict[str, Any], dict[str, Any]]:
    """Differences from the exact solution for each step, and how each run ends."""
    steps = list(CONVERGENCE_STEPS)
    table: dict[str, Any] = {"steps": steps}
    ends: dict[str, Any] = {"steps": steps}
    for name in CURVES:
        exact = runs[name].exact()
        trajectories = [runs[name].algorithm1(dt) for dt in steps]
        rows = [_deviation(be, exact.sample(be.dt)) for be in trajectories]
        table[name] = {key: [r[key] for r in rows] for key in rows[0]}
        for col, key in (("x", "max_x"), ("v", "max_v"), ("int_F_d", "int_F_d")):
            table[name][f"order_{col}"] = _order(steps, table[name][key])
        ends[name] = _ends(trajectories, exact)
    return table, ends


def _ends(trajectories: list[Trajectory], exact: ExactSolution) -> dict[str, Any]:
    """Rest position and reversals of each run, and the steps at which it ends differently."""
    n_exact = [e.kind for e in exact.events].count("reversal")
    same = [_same_side(be.rest_position, exact.rest_position) for be in trajectories]
    reversals = [sign_changes(be.v) for be in trajectories]
    return {
        "rest_position": [_rest(be.rest_position) for be in trajectories],
        "reversals": reversals,
        "same_side": same,
        "fewer_reversals": [be.dt for be, n in zip(trajectories, reversals) if n < n_exact],
        "other_side": [be.dt for be, s in zip(trajectories, same) if s is False],
    }


def _same_side(x: float, x_exact: float) -> bool | None:
    """Whether two rest positions lie on the same side of zero; ``None`` if either is missing."""
    if math.isnan(x) or math.isnan(x_exact):
        return None
    return bool(np.sign(x) == np.sign(x_exact))


# ------------------------------------------------------------------ verdicts
# The reasons and tolerances are Typst markup (mathematics between $ signs):
# the article evaluates them as it evaluates paper/deviations.yaml.
def _num(value: float, digits: int = 3) -> str:
    """``value`` as Typst markup with ``digits`` significant digits, as the article's ``num()``.

    Plain decimals for ``1e-3 <= |value| < 1e4``, else ``$a times 10^(n)$``.
    """
    if value == 0 or not math.isfinite(value):
        return "0" if value == 0 else "$infinity$"
    mantissa, power = f"{value:.{digits - 1}e}".split("e")
    if -3 <= int(power) < 4:
        return f"{value:.{max(0, digits - 1 - int(power))}f}".replace("-", "−")
    return f"${mantissa} times 10^({int(power)})$"


def _pct(fraction: float) -> str:
    """A fraction as a percentage with two significant digits (``"1.6 %"``)."""
    return _num(100 * fraction, 2) + " %"


def _verdict(label: str, problems: list[str], fine: str, tolerance: str | None) -> dict[str, Any]:
    """``deviates`` with the problems as the reason, else ``reproduced`` with ``fine``."""
    word = "deviates" if problems else "reproduced"
    return {"label": label} | asdict(Verdict(word, "; ".join(problems) or fine, tolerance))


def _not_checked(label: str, reason: str) -> dict[str, Any]:
    return {"label": label} | asdict(Verdict("not checked", reason, None))


_CURVE_TEXT = (
    f"difference at most {_pct(CURVE_TOL)} of the exact curve's largest magnitude (for $F_d$, of the time"
    " integral of $|F_d|$), equal numbers of reversals, rest on the same side of zero"
)
_EQ19 = {
    "eq19_max_x": "$max|x|$",
    "eq19_max_v": "$max|v|$",
    "eq19_max_F_s": "$max|F_s|$",
    "eq19_max_F_d": "$max|F_d - F_1|$",
}


def _curve_scale(q: str, ex: dict[str, Any], osc: Oscillator) -> float:
    """The exact curve's largest magnitude, or a floor for a curve that stays at zero."""
    band, k, tau = osc.static_band, osc.stiffness, osc.threshold
    return {
        "x": max(ex["peak_x"], band),
        "v": max(ex["peak_v"], band * math.sqrt(k / osc.mass)),
        "F_s": max(k * ex["peak_x"], tau),
        "F_d": max(ex["int_abs_F_d"], tau * ORIGINAL_DT),
    }[q]


_UNITS = {"x": "m", "v": "m/s", "F_s": "N", "F_d": "N s"}


def _curve_difference(q: str, err: dict[str, Any]) -> tuple[str, float]:
    if q == "F_d":
        return "$integral |Delta F_d| dif t$", err["int_F_d"]
    return f"$max|Delta {q}|$", err[f"max_{q}"]


def _end_problems(ex: dict[str, Any], be: dict[str, Any]) -> list[str]:
    """Why Algorithm 1's motion ends differently from the exact one (empty if it does not)."""
    problems = []
    if be["reversals"] != ex["reversals"]:
        problems.append(f"{be['reversals']} reversals against {ex['reversals']} in the exact solution")
    x_be, x_ex = be["rest_position"], ex["rest_position"]
    if isinstance(x_be, str) != isinstance(x_ex, str):
        problems.append("one solution comes to rest by the end of the run and the other does not")
    elif not isinstance(x_be, str) and _same_side(x_be, x_ex) is False:
        problems.append(
            f"Algorithm 1 comes to rest on the other side of zero ($x$ = {_num(x_be)} m, exact {_num(x_ex)} m)"
        )
    return problems


def _curve_verdict(n: int, q: str, block: dict[str, Any], suffix: str, osc: Oscillator) -> dict[str, Any]:
    """A time-history figure: Algorithm 1's curve of ``q`` against the exact one."""
    ex, be, err = block["exact"], block["be" + suffix], block["error" + suffix]
    what, diff = _curve_difference(q, err)
    scale = _curve_scale(q, ex, osc)
    unit = _UNITS[q]
    share = f"{what} = {_num(diff, 2)} {unit}, {_pct(diff / scale)} of the exact curve's {_num(scale)} {unit}"
    problems = [share] * (diff > CURVE_TOL * scale) + _end_problems(ex, be)
    ending = (
        "still moving at the end in both" if isinstance(ex["rest_position"], str) else "rest on the same side of zero"
    )
    fine = f"{share}; {ex['reversals']} reversals in both; {ending}"
    return _verdict(f"Figure {n}", problems, fine, _CURVE_TEXT)


def _figure1(osc: Oscillator) -> dict[str, Any]:
    """The velocity is a function of the force: true of eq. (6) for gamma < inf only."""
    rule = "eq. (6) with the configured $gamma$: $v$ is single-valued in $F_d$ if and only if $gamma < infinity$"
    if math.isinf(osc.dashpot.gamma):
        return _verdict(
            "Figure 1",
            [
                "with $gamma = infinity$ the configured law is Coulomb friction, whose"
                " velocity is not a function of the force either"
            ],
            "",
            rule,
        )
    return _verdict("Figure 1", [], "$gamma < infinity$: $v$ is a single-valued function of $F_d$", rule)


def _remark_3_1(cfg: dict[str, Any]) -> dict[str, Any]:
    """Eq. (18): max F_1 < mu_s N_f < max F_2."""
    small, large, tau = cfg["force_amplitude_small"], cfg["force_amplitude_large"], cfg["threshold"]
    problems = [f"$max F_1$ = {_num(small)} N is not below $mu_s N_f$ = {_num(tau)} N"] * (small >= tau)
    problems += [f"$max F_2$ = {_num(large)} N is not above $mu_s N_f$ = {_num(tau)} N"] * (large <= tau)
    fine = f"$max F_1$ = {_num(small)} N $<$ $mu_s N_f$ = {_num(tau)} N $<$ $max F_2$ = {_num(large)} N"
    return _verdict("Remark 3.1", problems, fine, "eq. (18), strict inequalities")


def _figure5(cfg: dict[str, Any], eq19: dict[str, float], osc: Oscillator) -> dict[str, Any]:
    """Eq. (19) holds for Algorithm 1 (premise: eq. 18 for F_1)."""
    if cfg["force_amplitude_small"] >= osc.threshold:
        return _not_checked(
            "Figure 5",
            f"eq. (18) fails, $max F_1$ = {_num(cfg['force_amplitude_small'])} N"
            " $>= mu_s N_f$, so eq. (19) is not the solution of this run",
        )
    band, tau = osc.static_band, osc.threshold
    limits = {
        "eq19_max_x": band,
        "eq19_max_v": band * math.sqrt(osc.stiffness / osc.mass),
        "eq19_max_F_s": tau,
        "eq19_max_F_d": tau,
    }
    problems = [
        f"{_EQ19[key]} = {_num(eq19[key])} exceeds {_num(CURVE_TOL * s)}"
        for key, s in limits.items()
        if eq19[key] > CURVE_TOL * s
    ]
    return _verdict(
        "Figure 5",
        problems,
        "$x$, $v$, $F_s$ and $F_d - F_1$ stay within the tolerance of eq. (19)",
        f"$|x|$, $|v|$, $|F_s|$ and $|F_d - F_1|$ at most {_pct(CURVE_TOL)} of $mu_s N_f slash k$,"
        " $mu_s N_f slash sqrt(k m)$ and $mu_s N_f$",
    )


def _figure10(cfg: dict[str, Any], block: dict[str, Any], suffix: str, osc: Oscillator) -> dict[str, Any]:
    """Released at rest inside the band, the mass does not move (section 2.2)."""
    x0, band = cfg["x0_small"], osc.static_band
    if abs(x0) >= band:
        return _not_checked(
            "Figure 10",
            f"$x_0$ = {_num(x0)} m is not inside the static band $|x| <$ {_num(band)} m, the case of section 2.2",
        )
    ex, be = block["exact"], block["be" + suffix]
    drift = block["error" + suffix]["max_x"]
    problems = ["the exact solution moves"] * (ex["peak_v"] > 0)
    problems += [f"Algorithm 1 moves by {_num(drift)} m"] * (drift > CURVE_TOL * band or be["peak_v"] > 0)
    return _verdict(
        "Figure 10",
        problems,
        "the mass stays at $x_0$ in both solutions",
        f"$v = 0$ throughout and $|x - x_0|$ at most {_pct(CURVE_TOL)} of $mu_s N_f slash k$",
    )


def _rest_stretched(block: dict[str, Any], suffix: str, osc: Oscillator) -> dict[str, Any]:
    """The introduction's claim: a free vibration may stop with the spring stretched."""
    ex, be = block["exact"]["rest_position"], block["be" + suffix]["rest_position"]
    label, limit = "rest with the spring stretched", STRETCH_TOL * osc.static_band
    tolerance = (
        f'$|x_"rest"|$ at least {_pct(STRETCH_TOL)} of $mu_s N_f slash k$ in both solutions,'
        " Algorithm 1 on the same side of zero as the exact solution"
    )
    if isinstance(ex, str):
        return _not_checked(label, "the exact solution is still moving at the end of the run")
    problems = [f"the exact solution rests at $x$ = {_num(ex)} m, within {_num(limit)} m of zero"] * (abs(ex) < limit)
    if isinstance(be, str):
        problems.append("Algorithm 1 is still moving at the end of the run")
    elif abs(be) < limit or np.sign(be) != np.sign(ex):
        problems.append(f"Algorithm 1 rests at $x$ = {_num(be)} m, the exact solution at {_num(ex)} m")
    fine = f"both rest with $x != 0$ on the same side (exact {_num(ex)} m, Algorithm 1 {_num(be)} m)"
    return _verdict(label, problems, fine, tolerance)


#: The verdicts' keys, in the article's order.
VERDICT_KEYS = (
    "figure_1",
    "figure_2",
    "figure_3",
    "figure_4",
    "remark_3_1",
    *(f"figure_{n}" for n in range(5, 15)),
    "rest_stretched",
)


def _verdicts(cfg: dict[str, Any], out: dict[str, Any], suffix: str, osc: Oscillator) -> dict[str, Any]:
    """Every claim's verdict, from Algorithm 1 at the configured (``""``) or the original's step."""
    drawn = "redrawn from the original's description; no configured value enters"
    v: dict[str, Any] = {
        "figure_1": _figure1(osc),
        "figure_2": _verdict("Figure 2", [], drawn, None),
        "figure_3": _verdict("Figure 3", [], drawn, None),
        "figure_4": _verdict("Figure 4", [], "drawn from eq. (6) with the configured $mu_s N_f$ and $gamma$", None),
        "remark_3_1": _remark_3_1(cfg),
        "figure_5": _figure5(cfg, out["forced_small"]["eq19" + suffix], osc),
        "figure_10": _figure10(cfg, out["free_small"], suffix, osc),
        "rest_stretched": _rest_stretched(out["free_large"], suffix, osc),
    }
    for name, figures in CURVES.items():
        for n, q in zip(figures, QUANTITIES):
            v[f"figure_{n}"] = _curve_verdict(n, q, out[name], suffix, osc)
    return {key: v[key] for key in VERDICT_KEYS}


def _summary(verdicts: dict[str, Any]) -> dict[str, list[str]]:
    """Labels of the claims, grouped by verdict, in the article's order."""
    words = ("reproduced", "deviates", "not checked")
    return {w.replace(" ", "_"): [d["label"] for d in verdicts.values() if d["verdict"] == w] for w in words}


# ------------------------------------------------------------------ the textbook model
def _creep(osc: Oscillator, x0: float, eps: float) -> dict[str, float]:
    """The ``tanh`` model released at rest at ``x0``, run as notebook 02 runs it.

    Returns the state at the end, the measured creep rate ``v/x`` (1/s), the
    linear rate ``-k eps/(tau + c eps)`` of the quasi-static law
    ``k x + tau tanh(v/eps) + c v = 0`` linearised at ``x = 0`` (``c = 1/gamma``),
    and ``k x/tau`` at the end, which the linearisation needs small.
    """
    s = TEXTBOOK
    run = textbook.integrate_adaptive(
        textbook.TextbookModel(osc, eps=eps),
        s["tanh_t_end"],
        x0=x0,
        method="LSODA",
        rtol=s["tanh_rtol"],
        atol=s["tanh_atol"],
        max_seconds=600.0,
    )
    if not run.finished:
        raise RuntimeError(run.message)
    x, v, c = float(run.x[-1]), float(run.v[-1]), osc.dashpot.viscosity
    return {
        "eps": eps,
        "x_end": x,
        "v_end": v,
        "rate": v / x,
        "linear_rate": -osc.stiffness * eps / (osc.threshold + c * eps),
        "load_end": osc.stiffness * x / osc.threshold,
    }


def _textbook(osc: Oscillator) -> dict[str, Any]:
    """Forward Euler, RK45 and the ``tanh`` regularisation from rest inside the band."""
    s = TEXTBOOK
    x0 = s["x0_band_fraction"] * osc.static_band
    model = textbook.TextbookModel(osc)
    euler = textbook.integrate_fixed(model, s["t_end"], s["euler_dt"], x0=x0, scheme="euler")
    rk45 = textbook.integrate_adaptive(
        model,
        s["t_end"],
        x0=x0,
        method="RK45",
        rtol=s["rk45_rtol"],
        atol=s["rk45_atol"],
        max_nfev=s["rk45_budget"],
        max_seconds=600.0,
    )
    tanh = [_creep(osc, x0, eps) for eps in s["tanh_eps"]]
    ratios = [r["rate"] / r["linear_rate"] for r in tanh]
    return {key: s[key] for key in ("t_end", "euler_dt", "rk45_rtol", "rk45_atol", "rk45_budget", "tanh_t_end")} | {
        "x0": x0,
        "load_0": osc.stiffness * x0 / osc.threshold,
        "euler_steps": int(euler.t.size - 1),
        "euler_sign_changes": euler.sign_changes,
        "euler_max_v": float(np.max(np.abs(euler.v))),
        "euler_x_end": float(euler.x[-1]),
        "rk45_finished": rk45.finished,
        "rk45_nfev": rk45.nfev,
        "rk45_t_reached": rk45.t_reached,
        "rk45_median_step": rk45.median_step,
        "tanh": tanh,
        "linear_ratio_min": min(ratios),
        "linear_ratio_max": max(ratios),
    }


# ------------------------------------------------------------------ parameters, provenance
def _parameters(cfg: dict[str, Any], osc: Oscillator) -> dict[str, Any]:
    return {
        "m": osc.mass,
        "k": osc.stiffness,
        "tau": osc.threshold,
        "gamma": float(cfg["gamma"]),
        "dt": float(cfg["dt"]),
        "band": osc.static_band,
        "omega_over_pi": cfg["force_omega_over_pi"],
        "force_until": cfg["force_until"],
        "P_small": cfg["force_amplitude_small"],
        "P_large": cfg["force_amplitude_large"],
        "t_end_forced": cfg["t_end_forced"],
        "t_end_small": cfg["t_end_small"],
        "t_end_large": cfg["t_end_large"],
        "x0_small": cfg["x0_small"],
        "x0_large": cfg["x0_large"],
    }


def _original(cfg: dict[str, Any]) -> dict[str, Any]:
    """The original's values, those the configuration changes, and ours."""
    changed = [{"key": k, "original": v, "ours": float(cfg[k])} for k, v in ORIGINAL.items() if float(cfg[k]) != v]
    return {
        "values": dict(ORIGINAL),
        "dt": ORIGINAL_DT,
        "changed": changed,
        "dt_differs": float(cfg["dt"]) != ORIGINAL_DT,
        "ours": {k: cfg[k] for k in OURS},
    }


def _shown(value: Any) -> str:
    """A configuration value as ``--config`` spells it (``.inf`` for infinity)."""
    return ".inf" if value == math.inf else repr(value)


def _provenance(cfg: dict[str, Any]) -> dict[str, Any]:
    """What built the numbers: Python, packages, machine, command; no clock time."""
    default = lumped.studies.config.default()
    overrides = [f"{k}={_shown(cfg[k])}" for k in sorted(cfg) if cfg[k] != default.get(k)]
    command = "snakemake --cores all" + (" --config " + " ".join(overrides) if overrides else "")
    from lumped.solvers.backward_euler import KERNEL

    return {
        "python": platform.python_version(),
        "implementation": platform.python_implementation(),
        "packages": {name: importlib.metadata.version(name) for name in PACKAGES},
        "machine": platform.machine(),
        "system": platform.system(),
        "cpus": os.cpu_count(),
        "kernel": KERNEL,
        "command": command,
    }


# ------------------------------------------------------------------ all of it
def compute(cfg: dict[str, Any] | None = None) -> dict[str, Any]:
    """All numbers and verdicts of the article, as a JSON-ready dictionary (:func:`clean`).

    Parameters
    ----------
    cfg : dict, optional
        A checked configuration (:func:`lumped.studies.config.load`); by default the
        one :func:`lumped.studies.config.load` finds.
    """
    cfg = cfg if cfg is not None else lumped.studies.config.load()
    osc, runs = examples.oscillator(cfg), examples.paper(cfg)
    out: dict[str, Any] = {"parameters": _parameters(cfg, osc), "original": _original(cfg)}
    out |= {name: _example(run) for name, run in runs.items()}
    for suffix, dt in (("", float(cfg["dt"])), ("_original", ORIGINAL_DT)):
        out["forced_small"]["eq19" + suffix] = _eq19(runs["forced_small"], dt)
    out["convergence"], out["convergence_rest"] = _convergence(runs)
    out["textbook"] = _textbook(osc)
    verdicts = {"configured": _verdicts(cfg, out, "", osc), "original": _verdicts(cfg, out, "_original", osc)}
    out["verdicts"] = verdicts | {
        "summary": {key: _summary(v) for key, v in verdicts.items()},
        "curve_tol": CURVE_TOL,
        "stretch_tol": STRETCH_TOL,
    }
    out["provenance"] = _provenance(cfg)
    return clean(out)


def clean(value: Any) -> Any:
    """NaN to None and infinities to "inf"/"-inf" (strict JSON); numpy scalars to Python numbers."""
    if isinstance(value, dict):
        return {k: clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [clean(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        if math.isnan(value):
            return None
        return float(value) if math.isfinite(value) else ("inf" if value > 0 else "-inf")
    return value
