"""The article's verdicts: each claim of the original judged from the runs, with the tolerance it was decided by.

:func:`verdicts` gives one :class:`Verdict` per claim (:data:`VERDICT_KEYS`,
in the article's order), from Algorithm 1 at the configured or at the
original's step; :func:`summary` groups their labels by verdict.  The
reasons and tolerances are Typst markup (mathematics between $ signs): the
article evaluates them as it evaluates ``paper/deviations.yaml``.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from lumped.model.oscillator import Oscillator
from lumped.studies.replication.runs import CURVES, ORIGINAL_DT, QUANTITIES, same_side

__all__ = ["CHECKS", "CURVE_TOL", "STRETCH_TOL", "VERDICT_KEYS", "Verdict", "summary", "verdicts"]

#: A curve of Algorithm 1 reproduces the exact one when their largest
#: difference is at most this fraction of the exact curve's largest magnitude
#: (about a line width on a figure); for the dashpot force, whose pointwise
#: difference is the jump 2 mu_s N_f at every reversal whatever the step, the
#: time integral of the difference is compared with that of |F_d|.
CURVE_TOL = 0.01
#: A mass rests "with the spring stretched" when |x_rest| is at least this
#: fraction of the static band half-width mu_s N_f / k.
STRETCH_TOL = 0.01


@dataclass(frozen=True)
class Verdict:
    """The article's judgement of one claim of the original.

    Attributes
    ----------
    verdict : str
        For a result (Algorithm 1 against the exact solution): ``"reproduced"``,
        ``"deviates"`` or ``"not checked"``; for one of the :data:`CHECKS`,
        which hold by construction: ``"holds"`` or ``"fails"``.
    reason : str
        One sentence with the numbers the verdict follows from.
    tolerance : str or None
        The criterion, in words, or ``None`` where none applies.
    """

    verdict: str
    reason: str
    tolerance: str | None = None


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
    reason = "; ".join(problems).replace(", but; ", ", but ") or fine
    return {"label": label} | asdict(Verdict(word, reason, tolerance))


def _check(label: str, problems: list[str], fine: str, tolerance: str | None) -> dict[str, Any]:
    """A claim that holds by construction: ``fails`` with the problems as the reason, else ``holds``."""
    word = "fails" if problems else "holds"
    return {"label": label} | asdict(Verdict(word, "; ".join(problems) or fine, tolerance))


def _not_checked(label: str, reason: str) -> dict[str, Any]:
    return {"label": label} | asdict(Verdict("not checked", reason, None))


_CURVE_TEXT = (
    f"the motion, up to the later of the two stops: difference at most {_pct(CURVE_TOL)} of the exact curve's"
    " largest magnitude (for $F_d$, of the time integral of $|F_d|$ over the exact motion), equal numbers of"
    f" reversals; the rest state: rest on the same side of zero, held values at most {_pct(CURVE_TOL)} of the exact"
    " curve's largest magnitude apart; neither depends on the end time of the run"
)
_EQ19 = {
    "eq19_max_x": "$max|x|$",
    "eq19_max_v": "$max|v|$",
    "eq19_max_F_s": "$max|F_s|$",
    "eq19_max_F_d": "$max|F_d - F_1|$",
}


def _curve_scale(q: str, ex: dict[str, Any], osc: Oscillator) -> float:
    """The exact curve's largest magnitude, or a floor for a curve that stays at zero.

    For ``F_d`` this is the time integral of ``|F_d|`` over the exact motion
    (N s), the scale of the motion's ``int_F_d``; :func:`_rest_scale` gives
    the pointwise one.
    """
    band, k, tau = osc.static_band, osc.stiffness, osc.threshold
    return {
        "x": max(ex["peak_x"], band),
        "v": max(ex["peak_v"], band * math.sqrt(k / osc.mass)),
        "F_s": max(k * ex["peak_x"], tau),
        "F_d": max(ex["int_abs_F_d"], tau * ORIGINAL_DT),
    }[q]


def _rest_scale(q: str, ex: dict[str, Any], osc: Oscillator) -> float:
    """The exact curve's largest magnitude, pointwise (``F_d`` in N), for the rest state."""
    return max(ex["peak_F_d"], osc.threshold) if q == "F_d" else _curve_scale(q, ex, osc)


_UNITS = {"x": "m", "v": "m/s", "F_s": "N", "F_d": "N s"}
_REST_UNITS = {"x": "m", "v": "m/s", "F_s": "N", "F_d": "N"}


def _curve_difference(q: str, err: dict[str, Any]) -> tuple[str, float]:
    if q == "F_d":
        return "$integral |Delta F_d| dif t$ over the motion", err["int_F_d"]
    return f"$max|Delta {q}|$", err[f"max_{q}"]


def _rest_difference(q: str, err: dict[str, Any], osc: Oscillator) -> float:
    """How far apart the two rest states hold ``q``: 0 for ``v``, ``k |Delta x_rest|`` for the forces."""
    return {"x": 1.0, "v": 0.0, "F_s": osc.stiffness, "F_d": osc.stiffness}[q] * err["rest_position"]


def _rest_state(q: str, block: dict[str, Any], suffix: str, osc: Oscillator) -> tuple[list[str], str]:
    """The rest state's problems (empty if it agrees) and a phrase with its numbers."""
    ex, err = block["exact"], block["error" + suffix]
    if isinstance(ex["rest_position"], str) or isinstance(block["be" + suffix]["rest_position"], str):
        return [], ""
    diff, scale, unit = _rest_difference(q, err, osc), _rest_scale(q, ex, osc), _REST_UNITS[q]
    if diff == 0:
        return [], ""
    phrase = (
        f"at rest the held {_HELD[q]} differs by {_num(diff, 2)} {unit},"
        f" {_pct(diff / scale)} of the exact curve's largest {_num(scale)} {unit}"
    )
    return [phrase] * (diff > CURVE_TOL * scale), phrase


_HELD = {"x": "position", "v": "velocity", "F_s": "spring force", "F_d": "dashpot force"}


def _end_problems(ex: dict[str, Any], be: dict[str, Any]) -> list[str]:
    """Why Algorithm 1's motion ends differently from the exact one (empty if it does not)."""
    problems = []
    if be["reversals"] != ex["reversals"]:
        problems.append(f"{be['reversals']} reversals against {ex['reversals']} in the exact solution")
    x_be, x_ex = be["rest_position"], ex["rest_position"]
    if isinstance(x_be, str) != isinstance(x_ex, str):
        problems.append("one solution comes to rest by the end of the run and the other does not")
    elif not isinstance(x_be, str) and same_side(x_be, x_ex) is False:
        problems.append(
            f"Algorithm 1 comes to rest on the other side of zero ($x$ = {_num(x_be)} m, exact {_num(x_ex)} m)"
        )
    return problems


def _curve_verdict(n: int, q: str, block: dict[str, Any], suffix: str, osc: Oscillator) -> dict[str, Any]:
    """A time-history figure: Algorithm 1's curve of ``q`` against the exact one, motion and rest state apart."""
    ex, err = block["exact"], block["error" + suffix]
    what, diff = _curve_difference(q, err)
    scale = _curve_scale(q, ex, osc)
    unit = _UNITS[q]
    share = f"{what} = {_num(diff, 2)} {unit}, {_pct(diff / scale)} of the exact curve's {_num(scale)} {unit}"
    rest_problems, rest = _rest_state(q, block, suffix, osc)
    problems = [share] * (diff > CURVE_TOL * scale) + _end_problems(ex, block["be" + suffix]) + rest_problems
    if problems and diff <= CURVE_TOL * scale:
        problems.insert(0, f"the motion agrees ({share}), but")
    ending = (
        "still moving at the end in both"
        if isinstance(ex["rest_position"], str)
        else "rest on the same side of zero" + (f"; {rest}" if rest else "")
    )
    fine = f"{share}; {ex['reversals']} reversals in both; {ending}"
    return _verdict(f"Figure {n}", problems, fine, _CURVE_TEXT)


def _figure1(osc: Oscillator) -> dict[str, Any]:
    """The velocity is a function of the force: true of eq. (6) for gamma < inf only."""
    rule = "eq. (6) with the configured $gamma$: $v$ is single-valued in $F_d$ if and only if $gamma < infinity$"
    if math.isinf(osc.dashpot.gamma):
        return _check(
            "Figure 1",
            [
                "with $gamma = infinity$ the configured law is Coulomb friction, whose"
                " velocity is not a function of the force either"
            ],
            "",
            rule,
        )
    return _check("Figure 1", [], "$gamma < infinity$: $v$ is a single-valued function of $F_d$", rule)


def _remark_3_1(cfg: dict[str, Any]) -> dict[str, Any]:
    """Eq. (18): max F_1 < mu_s N_f < max F_2."""
    small, large, tau = cfg["force_amplitude_small"], cfg["force_amplitude_large"], cfg["threshold"]
    problems = [f"$max F_1$ = {_num(small)} N is not below $mu_s N_f$ = {_num(tau)} N"] * (small >= tau)
    problems += [f"$max F_2$ = {_num(large)} N is not above $mu_s N_f$ = {_num(tau)} N"] * (large <= tau)
    fine = f"$max F_1$ = {_num(small)} N $<$ $mu_s N_f$ = {_num(tau)} N $<$ $max F_2$ = {_num(large)} N"
    return _check("Remark 3.1", problems, fine, "eq. (18), strict inequalities")


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


#: Claims that hold by construction (pictures drawn from the text, an inequality
#: between parameters): checked, but not counted among the reproduced results,
#: which compare Algorithm 1 with the exact solution.
CHECKS = ("figure_1", "figure_2", "figure_3", "figure_4", "remark_3_1")
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


def verdicts(cfg: dict[str, Any], out: dict[str, Any], suffix: str, osc: Oscillator) -> dict[str, Any]:
    """Every claim's verdict, from Algorithm 1 at the configured (``""``) or the original's step."""
    drawn = "redrawn from the original's description; no configured value enters"
    v: dict[str, Any] = {
        "figure_1": _figure1(osc),
        "figure_2": _check("Figure 2", [], drawn, None),
        "figure_3": _check("Figure 3", [], drawn, None),
        "figure_4": _check("Figure 4", [], "drawn from eq. (6) with the configured $mu_s N_f$ and $gamma$", None),
        "remark_3_1": _remark_3_1(cfg),
        "figure_5": _figure5(cfg, out["forced_small"]["eq19" + suffix], osc),
        "figure_10": _figure10(cfg, out["free_small"], suffix, osc),
        "rest_stretched": _rest_stretched(out["free_large"], suffix, osc),
    }
    for name, figures in CURVES.items():
        for n, q in zip(figures, QUANTITIES):
            v[f"figure_{n}"] = _curve_verdict(n, q, out[name], suffix, osc)
    return {key: v[key] for key in VERDICT_KEYS}


def summary(verdicts: dict[str, Any]) -> dict[str, list[str]]:
    """Labels grouped by verdict, in the article's order: the results (Algorithm 1 against the exact
    solution: ``reproduced``, ``deviates``, ``not_checked``) apart from the :data:`CHECKS` (``holds``, ``fails``)."""
    words = ("reproduced", "deviates", "not checked", "holds", "fails")
    return {w.replace(" ", "_"): [d["label"] for d in verdicts.values() if d["verdict"] == w] for w in words}
