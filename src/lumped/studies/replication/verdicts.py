"""The article's verdicts: each figure judged by the claim the original makes with it.

Every result is a :class:`Verdict` on one claim of the original, stated as a
sentence that can be tested (``claim``), made of parts, each tested on our
exact solution and on Algorithm 1 (at the configured or at the original's
step) by a yes-or-no question about the runs: does the mass move, does it come
to rest, is ``0 < |F_s| <= mu_s N_f`` at rest, does ``(v, F_d)`` lie on the
graph of eq. (6) at every grid point, and so on.  No question compares a
difference with a tolerance: the claims are qualitative, and so are their
tests.  A claim is *reproduced* when every part holds in both solutions; it
*deviates* when a part fails in either (the reason says which); it is *not
checked* when the run does not meet the claim's premise (a release outside
the band for Figure 10, a motion not at rest by the end of the run).

How far Algorithm 1 lies from the exact solution is reported beside each
verdict (``differences``), each number with the scale it is divided by, and
decides nothing.  The reasons, claims and differences are Typst markup
(mathematics between $ signs): the article evaluates them as it evaluates
``paper/deviations.yaml``.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from lumped.model.oscillator import Oscillator
from lumped.studies.replication.runs import CURVES, QUANTITIES

__all__ = ["CHECKS", "VERDICT_KEYS", "Verdict", "summary", "verdicts"]


@dataclass(frozen=True)
class Verdict:
    """The article's judgement of one claim of the original.

    Attributes
    ----------
    verdict : str
        For a result: ``"reproduced"``, ``"deviates"`` or ``"not checked"``;
        for one of the :data:`CHECKS`, which hold by construction: ``"holds"``
        or ``"fails"``.
    reason : str
        One sentence: which solutions the claim holds in, or which part fails.
    claim : str or None
        The claim, as the sentence that was tested (for a check: the rule).
    differences : str or None
        How far Algorithm 1 lies from the exact solution, each number with its
        normalisation; it decides nothing.
    exact, algorithm1 : bool or None
        Whether the claim holds in the exact solution and with Algorithm 1
        (``None`` for a check, or where the premise fails).
    """

    verdict: str
    reason: str
    claim: str | None = None
    differences: str | None = None
    exact: bool | None = None
    algorithm1: bool | None = None


#: One part of a claim: the sentence, and whether it holds in the exact solution and with Algorithm 1.
Part = tuple[str, bool, bool]


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


def _moving(value: Any) -> bool:
    """Whether a rest time or position of the runs says "still moving"."""
    return isinstance(value, str)


def _judged(label: str, claim: str, parts: list[Part], differences: str | None) -> dict[str, Any]:
    """``reproduced`` if every part holds in both solutions, else ``deviates`` with the failing parts."""
    ex_ok, be_ok = all(p[1] for p in parts), all(p[2] for p in parts)
    fails = [f"not in the exact solution: {text}" for text, ok, _ in parts if not ok]
    fails += [f"not with Algorithm 1: {text}" for text, _, ok in parts if not ok]
    reason = "; ".join(fails) if fails else "the claim holds in the exact solution and with Algorithm 1"
    word = "reproduced" if ex_ok and be_ok else "deviates"
    return {"label": label} | asdict(Verdict(word, reason, claim, differences, ex_ok, be_ok))


def _check(label: str, problems: list[str], fine: str, rule: str | None) -> dict[str, Any]:
    """A claim that holds by construction: ``fails`` with the problems as the reason, else ``holds``."""
    word = "fails" if problems else "holds"
    return {"label": label} | asdict(Verdict(word, "; ".join(problems) or fine, rule))


def _not_checked(label: str, claim: str, reason: str) -> dict[str, Any]:
    return {"label": label} | asdict(Verdict("not checked", reason, claim))


# ------------------------------------------------------------------ differences
_UNITS = {"x": "m", "v": "m/s", "F_s": "N", "F_d": "N s"}


def _motion_difference(q: str, block: dict[str, Any], suffix: str, osc: Oscillator) -> str:
    """The largest difference over the motion (for ``F_d`` its time integral), as a share of the exact curve's."""
    ex, err = block["exact"], block["error" + suffix]
    if q == "F_d":
        diff, scale = err["int_F_d"], ex["int_abs_F_d"]
        what, of = "$integral |Delta F_d| dif t$ over the motion", "$integral |F_d| dif t$"
    else:
        diff, scale = err[f"max_{q}"], {"x": ex["peak_x"], "v": ex["peak_v"], "F_s": osc.stiffness * ex["peak_x"]}[q]
        what, of = f"$max|Delta {q}|$ over the motion", f"$max|{q}|$"
    unit = _UNITS[q]
    share = f", {_pct(diff / scale)} of the exact {of} = {_num(scale)} {unit}" if scale else ""
    return f"{what} = {_num(diff, 2)} {unit}{share}"


def _rest_difference(q: str, block: dict[str, Any], suffix: str, osc: Oscillator) -> str:
    """Where the two solutions rest, and when, after how many reversals; the rest error over the band."""
    ex, be = block["exact"], block["be" + suffix]
    if _moving(ex["rest_position"]) or _moving(be["rest_position"]):
        return "one of the two is still moving at the end of the run"
    dx = abs(be["rest_position"] - ex["rest_position"])
    side = "" if np.sign(be["rest_position"]) == np.sign(ex["rest_position"]) else ", on the other side of zero"
    if q in ("F_s", "F_d"):
        held = f"held {'spring' if q == 'F_s' else 'dashpot'} force"
        where = (
            f'the {held} differs by $k |Delta x_"rest"|$ = {_num(osc.stiffness * dx, 2)} N{side},'
            f" {_pct(dx / osc.static_band)} of $mu_s N_f$"
        )
    else:
        where = (
            f"Algorithm 1 rests at $x$ = {_num(be['rest_position'])} m, the exact solution at"
            f' {_num(ex["rest_position"])} m{side}: $|Delta x_"rest"|$ = {_num(dx, 2)} m,'
            f" {_pct(dx / osc.static_band)} of the band half-width $mu_s N_f slash k$"
            f" and {_pct(dx / ex['peak_x'])} of $max|x|$"
        )
    return (
        f"{where}; it stops at $t$ = {_num(be['rest_time'], 5)} s against {_num(ex['rest_time'], 5)} s,"
        f" after {be['reversals']} reversals against {ex['reversals']}"
    )


def _differences(q: str, block: dict[str, Any], suffix: str, osc: Oscillator) -> str:
    return f"{_motion_difference(q, block, suffix, osc)}; {_rest_difference(q, block, suffix, osc)}"


# ------------------------------------------------------------------ the checks
def _figure1(osc: Oscillator) -> dict[str, Any]:
    """The velocity is a function of the force: true of eq. (6) for gamma < inf only."""
    rule = "eq. (6) with the configured $gamma$: $v$ is single-valued in $F_d$ if and only if $gamma < infinity$"
    if math.isinf(osc.dashpot.gamma):
        problem = (
            "with $gamma = infinity$ the configured law is Coulomb friction, whose"
            " velocity is not a function of the force either"
        )
        return _check("Figure 1", [problem], "", rule)
    return _check("Figure 1", [], "$gamma < infinity$: $v$ is a single-valued function of $F_d$", rule)


def _remark_3_1(cfg: dict[str, Any]) -> dict[str, Any]:
    """Eq. (18): max F_1 < mu_s N_f < max F_2."""
    small, large, tau = cfg["force_amplitude_small"], cfg["force_amplitude_large"], cfg["threshold"]
    problems = [f"$max F_1$ = {_num(small)} N is not below $mu_s N_f$ = {_num(tau)} N"] * (small >= tau)
    problems += [f"$max F_2$ = {_num(large)} N is not above $mu_s N_f$ = {_num(tau)} N"] * (large <= tau)
    fine = f"$max F_1$ = {_num(small)} N $<$ $mu_s N_f$ = {_num(tau)} N $<$ $max F_2$ = {_num(large)} N"
    return _check("Remark 3.1", problems, fine, "eq. (18), strict inequalities")


# ------------------------------------------------------------------ runs without motion
def _figure5(cfg: dict[str, Any], block: dict[str, Any], suffix: str, osc: Oscillator) -> dict[str, Any]:
    """Eq. (19) holds (premise: eq. 18 for F_1)."""
    claim = "under $F_1$, whose peak stays below $mu_s N_f$, the mass does not move: $x = v = F_s = 0$ and $F_d = F_1$"
    if cfg["force_amplitude_small"] >= osc.threshold:
        reason = f"eq. (18) fails, $max F_1$ = {_num(cfg['force_amplitude_small'])} N $>= mu_s N_f$"
        return _not_checked("Figure 5", claim, reason)
    ex, eq = block["exact"], block["eq19" + suffix]
    still = ex["breakaways"] == 0 and ex["peak_v"] == 0
    parts = [
        ("$x = v = F_s = 0$", still, eq["eq19_max_x"] == eq["eq19_max_v"] == eq["eq19_max_F_s"] == 0),
        ("$F_d = F_1$", still, eq["eq19_max_F_d"] == 0),
    ]
    diff = (
        f"largest departures of Algorithm 1 from eq. (19): $max|x|$ = {_num(eq['eq19_max_x'])} m,"
        f" $max|v|$ = {_num(eq['eq19_max_v'])} m/s, $max|F_s|$ = {_num(eq['eq19_max_F_s'])} N,"
        f" $max|F_d - F_1|$ = {_num(eq['eq19_max_F_d'])} N"
    )
    return _judged("Figure 5", claim, parts, diff)


def _figure10(cfg: dict[str, Any], block: dict[str, Any], suffix: str, osc: Oscillator) -> dict[str, Any]:
    """Released at rest inside the band, the mass does not move (section 2.2)."""
    claim = "released at rest inside the static band, the mass stays at $x_0$: $v = 0$ and $x = x_0$ throughout"
    x0, band = cfg["x0_small"], osc.static_band
    if abs(x0) >= band:
        reason = f"$x_0$ = {_num(x0)} m is not inside the static band $|x| <$ {_num(band)} m, the case of section 2.2"
        return _not_checked("Figure 10", claim, reason)
    ex, be, err = block["exact"], block["be" + suffix], block["error" + suffix]
    parts = [("$v = 0$ and $x = x_0$", ex["peak_v"] == 0, be["peak_v"] == 0 and err["max_x"] == 0)]
    diff = f'$max|x - x^"exact"|$ = {_num(err["max_x"])} m, $max|v|$ = {_num(be["peak_v"])} m/s with Algorithm 1'
    return _judged("Figure 10", claim, parts, diff)


# ------------------------------------------------------------------ runs that move
def _rests(s: dict[str, Any], tau: float) -> tuple[bool, bool, bool]:
    """Whether a run is at rest at its end, with the spring stretched, and with ``|F_s| <= mu_s N_f``."""
    at_rest = not _moving(s["rest_position"])
    return at_rest, at_rest and s["end_F_s"] != 0, at_rest and abs(s["end_F_s"]) <= tau


def _holds_spring(s: dict[str, Any]) -> bool:
    """At rest and unforced, the dashpot holds the spring: ``F_d = -F_s`` (the stick step's own arithmetic)."""
    return not _moving(s["rest_position"]) and s["end_F_d"] == -s["end_F_s"]


def _decays(turning: list[float]) -> bool:
    """Whether each turning point lies nearer zero than the one before."""
    return all(abs(b) < abs(a) for a, b in itertools.pairwise(turning))


def _forced_parts(n: int, block: dict[str, Any], suffix: str, osc: Oscillator) -> tuple[str, list[Part]]:
    """Figures 6 to 9: the claim and its parts."""
    ex, be, tau = block["exact"], block["be" + suffix], osc.threshold
    rest_e, rest_b = _rests(ex, tau), _rests(be, tau)
    if n == 6:
        moved = ("the mass moves", ex["breakaways"] > 0, be["peak_v"] > 0)
        return (
            (
                "$F_2$ exceeds $mu_s N_f$, so the mass breaks away; after the forcing ends it comes to rest"
                " inside the static band, $|F_s| <= mu_s N_f$"
            ),
            [moved, ("it comes to rest", rest_e[0], rest_b[0]), ("$|F_s| <= mu_s N_f$ at rest", rest_e[2], rest_b[2])],
        )
    if n == 7:
        t_b = ex["first_event_time"]
        first = be["first_move_time"]
        sharp = first is not None and t_b is not None and t_b < first <= t_b + be["dt"]
        return (
            (
                "the mass sticks ($v = 0$ exactly) until $F_2$ first exceeds $mu_s N_f$ and moves from then on,"
                " until a final stop after which $v = 0$ exactly"
            ),
            [
                ("it first moves at the first grid point after the breakaway", ex["breakaways"] > 0, sharp),
                ("it comes to a final stop", rest_e[0], rest_b[0]),
            ],
        )
    if n == 8:
        return (
            "at rest the spring still holds a force, $0 < |F_s| <= mu_s N_f$",
            [("$F_s != 0$ at rest", rest_e[1], rest_b[1]), ("$|F_s| <= mu_s N_f$ at rest", rest_e[2], rest_b[2])],
        )
    return (
        (
            "$F_d$ lies on the graph of eq. (6) at every instant ($|F_d| <= mu_s N_f$ where $v = 0$, the sign of"
            " $v$ where $v != 0$), and at rest it holds the spring, $F_d = -F_s$"
        ),
        [
            ("$(v, F_d)$ on the graph of eq. (6)", ex["law_violations"] == 0, be["law_violations"] == 0),
            ("$F_d = -F_s$ at rest", _holds_spring(ex), _holds_spring(be)),
        ],
    )


def _free_parts(n: int, block: dict[str, Any], suffix: str, osc: Oscillator) -> tuple[str, list[Part]]:
    """Figures 11 to 13: the claim and its parts."""
    ex, be, tau = block["exact"], block["be" + suffix], osc.threshold
    rest_e, rest_b = _rests(ex, tau), _rests(be, tau)
    stretched = ("with the spring stretched, $F_s != 0$", rest_e[1], rest_b[1])
    inside = ("inside the static band, $|F_s| <= mu_s N_f$", rest_e[2], rest_b[2])
    if n == 11:
        return (
            'the mass comes to rest with the spring stretched, inside the static band: $0 < |k x_"rest"| <= mu_s N_f$',
            [("it comes to rest", rest_e[0], rest_b[0]), stretched, inside],
        )
    if n == 12:
        return (
            (
                "the oscillation decays and ends: each turning point lies nearer zero than the one before,"
                " and from a final stop on $v = 0$ exactly"
            ),
            [
                ("the turning points decrease", _decays(ex["reversal_positions"]), _decays(be["turning_positions"])),
                ("it comes to a final stop", rest_e[0], rest_b[0]),
            ],
        )
    return ("at rest the spring still holds a force, $0 < |F_s| <= mu_s N_f$", [stretched, inside])


def _curve_verdict(n: int, q: str, name: str, out: dict[str, Any], suffix: str, osc: Oscillator) -> dict[str, Any]:
    """A time-history figure: its claim tested on both solutions, the differences beside."""
    block = out[name]
    if n == 14:
        return _figure14(block, suffix, osc)
    claim, parts = (_forced_parts if name == "forced_large" else _free_parts)(n, block, suffix, osc)
    if _moving(block["exact"]["rest_position"]):
        return _not_checked(f"Figure {n}", claim, _STILL.replace(" of a release", ""))
    return _judged(f"Figure {n}", claim, parts, _differences(q, block, suffix, osc))


# ------------------------------------------------------------------ the release sweep
def _sweep_facts(rests: list[Any], band: float) -> dict[str, Any]:
    """At rest, inside the band, on both sides of zero, never exactly at zero; the share of the band covered."""
    values = [r for r in rests if not _moving(r)]
    if len(values) < len(rests) or not values:
        return {"rest": False, "band": False, "sides": False, "nonzero": False, "span": math.nan}
    return {
        "rest": True,
        "band": all(abs(r) <= band for r in values),
        "sides": min(values) < 0 < max(values),
        "nonzero": all(r != 0 for r in values),
        "span": (max(values) - min(values)) / (2 * band),
    }


def _zero_release(x0: list[float], rests: list[Any]) -> float:
    """The release nearest ``x0[0]`` whose rest is zero, interpolated linearly between neighbours; ``nan`` if none."""
    for a, b, ra, rb in zip(x0, x0[1:], rests, rests[1:]):
        if not (_moving(ra) or _moving(rb)) and ra * rb < 0:
            return a - ra * (b - a) / (rb - ra)
    return math.nan


def _sweep_text(sweep: dict[str, Any]) -> str:
    x0 = sweep["x0"]
    return (
        f"released at rest from {len(x0)} positions $x_0$ from {_num(x0[-1])} m to {_num(x0[0])} m,"
        f" {_num(sweep['spacing'])} m apart"
    )


def _sweep_parts(sweep: dict[str, Any], osc: Oscillator) -> tuple[dict[str, Any], dict[str, Any]]:
    band = osc.static_band
    return _sweep_facts(sweep["exact"], band), _sweep_facts(sweep["algorithm1"], band)


def _sweep_differences(sweep: dict[str, Any], e: dict[str, Any], b: dict[str, Any]) -> str:
    spans = f"the rests span {_pct(e['span'])} of the band in the exact solution and {_pct(b['span'])} with Algorithm 1"
    zero_e, zero_b = (_zero_release(sweep["x0"], sweep[k]) for k in ("exact", "algorithm1"))
    if math.isnan(zero_e) or math.isnan(zero_b):
        return spans
    return (
        f"{spans}; the rest is zero for $x_0$ = {_num(zero_e, 4)} m in the exact solution and {_num(zero_b, 4)} m"
        " with Algorithm 1 (linear interpolation between neighbouring releases)"
    )


_STILL = "the exact solution of a release is still moving at the end of the run, so the claim cannot be tested"


def _figure14(block: dict[str, Any], suffix: str, osc: Oscillator) -> dict[str, Any]:
    """Existential: the held dashpot force can be any value of the band; zero only at isolated releases."""
    sweep = block["sweep" + suffix]
    e, b = _sweep_parts(sweep, osc)
    claim = (
        "at rest the dashpot holds the spring, $F_d = -F_s$, and the held force can be any value of the band:"
        f" {_sweep_text(sweep)}, the mass rests inside the band, on both sides of zero and never exactly at zero,"
        " so the unstretched rest is met only at isolated $x_0$"
    )
    parts = [
        ("$F_d = -F_s$ at rest", _holds_spring(block["exact"]), _holds_spring(block["be" + suffix])),
        ("every release comes to rest inside the band", e["rest"] and e["band"], b["rest"] and b["band"]),
        ("rests on both sides of zero", e["sides"], b["sides"]),
        ("no rest exactly at zero", e["nonzero"], b["nonzero"]),
    ]
    if _moving(block["exact"]["rest_position"]) or not e["rest"]:
        return _not_checked("Figure 14", claim, _STILL)
    diff = f"{_differences('F_d', block, suffix, osc)}; {_sweep_differences(sweep, e, b)}"
    return _judged("Figure 14", claim, parts, diff)


def _rest_stretched(block: dict[str, Any], suffix: str, osc: Oscillator) -> dict[str, Any]:
    """The introduction's claim: a free vibration may stop with the spring stretched."""
    sweep = block["sweep" + suffix]
    e, b = _sweep_parts(sweep, osc)
    claim = (
        "a free vibration can end with the spring stretched, so the rest is not the minimum of the energy:"
        f' {_sweep_text(sweep)}, the mass comes to rest inside the band with $x_"rest" != 0$'
    )
    parts = [
        ("every release comes to rest inside the band", e["rest"] and e["band"], b["rest"] and b["band"]),
        ('$x_"rest" != 0$', e["nonzero"], b["nonzero"]),
    ]
    if not e["rest"]:
        return _not_checked("rest with the spring stretched", claim, _STILL)
    return _judged("rest with the spring stretched", claim, parts, _sweep_differences(sweep, e, b))


#: Claims that hold by construction (pictures drawn from the text, an inequality
#: between parameters): checked, but not counted among the reproduced results,
#: which test the original's claims on Algorithm 1 and the exact solution.
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
        "figure_5": _figure5(cfg, out["forced_small"], suffix, osc),
        "figure_10": _figure10(cfg, out["free_small"], suffix, osc),
        "rest_stretched": _rest_stretched(out["free_large"], suffix, osc),
    }
    for name, figures in CURVES.items():
        for n, q in zip(figures, QUANTITIES):
            v[f"figure_{n}"] = _curve_verdict(n, q, name, out, suffix, osc)
    return {key: v[key] for key in VERDICT_KEYS}


def summary(verdicts: dict[str, Any]) -> dict[str, list[str]]:
    """Labels grouped by verdict, in the article's order: the results (``reproduced``, ``deviates``,
    ``not_checked``) apart from the :data:`CHECKS` (``holds``, ``fails``)."""
    words = ("reproduced", "deviates", "not checked", "holds", "fails")
    return {w.replace(" ", "_"): [d["label"] for d in verdicts.values() if d["verdict"] == w] for w in words}
