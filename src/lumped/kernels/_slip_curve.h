/* The slip curve of a friction contact of lumped.laws.StribeckLaw in C: its kernel_form()
 * (code 0 no fall, 1 exponential, 2 gaussian, 3 rational decay; law = (static, kinetic, v_s,
 * viscous)), g(s) and g'(s) (slip_curve), and the slip speed of one backward-Euler step, the root
 * s > 0 of g(s) + E s = y (slip_speed).  One home for both compiled steps that slip on a Stribeck
 * branch: the one-mass friction loop (_friction_kernel.c) and the network steps
 * (_network_elements.h, read by the sparse step).  The decays are
 * lumped.laws.stribeck.DECAYS: change both together (tests/test_friction_kernel.py,
 * tests/test_network_banded.py compare them with the Python step). */
#ifndef LUMPED_SLIP_CURVE_H
#define LUMPED_SLIP_CURVE_H

#include <float.h>
#include <math.h>

typedef struct {
    int code;
    double stat, kin, vs, visc;
} law_t;

/* g(s) and g'(s) at s >= 0, with the decay of `code` (1 exp(-x), 2 exp(-x^2), 3 1/(1+x), x = s/v_s). */
static double slip_curve(const law_t *l, double s, double *slope) {
    const double x = s / l->vs, drop = l->stat - l->kin;
    double d, dd;
    if (l->code == 1) {
        d = exp(-x), dd = -d;
    } else if (l->code == 2) {
        d = exp(-x * x), dd = -2.0 * x * d;
    } else {
        d = 1.0 / (1.0 + x), dd = -d * d;
    }
    *slope = l->visc + drop * dd / l->vs;
    return l->kin + l->visc * s + drop * d;
}

/* The s > 0 with h(s) = g(s) + E s - y = 0, for y > static = g(0+) and E above the curve's steepest
 * fall (so that h increases): Newton's method from `guess` (the last step's slip speed on this
 * branch, or the tangent at 0 if it is not in the bracket), any iterate that leaves the bracket
 * (lo, hi) replaced by the bisection; g >= 0 puts the root in (0, y/E].  It stops after a Newton
 * step ds whose successor would move s by at most half an ulp, M2 ds^2 / (2 h') <= eps s / 2 (M2 >= |g''|:
 * the decay's |d''| is at most 1 (exponential) or 2, over v_s^2), which saves the evaluation that
 * would only confirm it; or after a step of at most 2 ulps, or on a bracket that narrow. */
static double slip_speed(const law_t *l, double y, double E, double guess) {
    double lo = 0.0, hi = y / E, slope;
    const double m2 = (l->stat - l->kin) / (l->vs * l->vs) * (l->code == 1 ? 1.0 : 2.0);
    double s = guess;
    if (!(s > lo && s < hi)) {
        slip_curve(l, 0.0, &slope);
        s = (y - l->stat) / (E + slope);
    }
    if (!(s > lo && s < hi)) s = 0.5 * (lo + hi);
    for (int it = 0; it < 200; it++) {
        const double h = slip_curve(l, s, &slope) + E * s - y;
        if (h == 0.0) return s;
        if (h < 0.0) lo = s;
        else hi = s;
        const double ds = h / (slope + E);
        double next = s - ds;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        else if (m2 * ds * ds <= DBL_EPSILON * next * (slope + E)) return next;
        if (fabs(next - s) <= 2.0 * DBL_EPSILON * next || hi - lo <= 2.0 * DBL_EPSILON * hi) return next;
        s = next;
    }
    return s;
}
#endif
