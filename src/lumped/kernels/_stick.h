/* The stick test, once for every compiled kernel (its Python twin is
 * lumped.laws.sticks; both are the closed-band test of Algorithm 1's line 5).
 *
 * sticks1(predictor, low, high) is low <= predictor <= high: closed, so a
 * predictor on an edge sticks, and false for NaN.  Algorithm 1 asks it of
 * the band [-tau, tau] (the same decisions as fabs(predictor) <= tau, for
 * negation and fabs are exact); the network step asks it of each rigid piece
 * [lo + sigma a, hi + sigma a] of an element's step graph.  bingham_corrector1
 * is lines 5 to 10 of Algorithm 1 in the form of lumped.laws.bingham_corrector
 * (line 8 divided through by gamma), operation for operation.
 *
 * Use: include once for the scalar forms (_kernel.c, _network_kernel.c); with
 * STICK_LANES defined (2, 4 or 8) it also defines sticks<STICK_LANES>, the
 * same test on vectors of STICK_LANES doubles (GCC vector extensions, as
 * _sine.h), returning a lane mask (-1 where the lane sticks), for
 * _batch_lanes.h.  tests/test_band_edge.py releases masses on both edges of
 * the band through every kernel. */
#ifndef LUMPED_STICK_SCALAR
#define LUMPED_STICK_SCALAR
#include <math.h>

static inline int sticks1(double predictor, double low, double high) { return low <= predictor && predictor <= high; }

static inline void bingham_corrector1(double predictor, double eta, double tau, double c, double *f_d, double *v) {
    if (sticks1(predictor, -tau, tau)) { /* line 5: |F~| <= mu_s N_f */
        *v = 0.0;
        *f_d = predictor;
    } else {
        const double signed_tau = copysign(tau, predictor);
        *f_d = (eta * signed_tau + c * predictor) / (eta + c);
        *v = (predictor - signed_tau) / (eta + c);
    }
}
#endif

#ifdef STICK_LANES
#define STICK_PASTE2(a, b) a##b
#define STICK_PASTE(a, b) STICK_PASTE2(a, b)
#define stick_vd STICK_PASTE(stick_vd, STICK_LANES)
#define stick_vl STICK_PASTE(stick_vl, STICK_LANES)
#define sticks_lanes STICK_PASTE(sticks, STICK_LANES)
typedef double stick_vd __attribute__((vector_size(8 * STICK_LANES)));
typedef long long stick_vl __attribute__((vector_size(8 * STICK_LANES)));

static inline stick_vl sticks_lanes(stick_vd predictor, stick_vd low, stick_vd high) {
    return (low <= predictor) & (predictor <= high);
}
#undef stick_vd
#undef stick_vl
#undef sticks_lanes
#endif
