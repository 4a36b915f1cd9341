/* The project's own sine, for every compiled kernel: one branch-free
 * implementation in GCC vector extensions, instantiated once per lane width.
 * Its Python twin, lumped.numerics.sine (a float and a NumPy version), takes the same
 * IEEE operations in the same order, so the four give the same bits, on every
 * x86-64 machine: no C library, no contraction (the kernels are compiled with
 * -ffp-contract=off), only correctly rounded + - * and bit masks.
 *
 * Supported range |x| <= SINE_MAX = 2e8 rad; the stated error bound there is
 * 1 ulp: the reduction's relative error (at most 2^-81 on the test set, the
 * doubles nearest a multiple of pi/2 included) and the polynomials' (below
 * 2^-58) leave the rounding of the last additions.  tests/test_sine.py checks
 * it against mpmath on 50000 random and adversarial arguments; the largest
 * error found is 0.76 ulp, near pi/4.  Outside the range, and for inf, the
 * result is NaN; NaN gives NaN.
 *
 * Algorithm.
 * 1. k = nearest integer to x * 2/pi, by adding and subtracting 0x1.8p52
 *    (exact under round-to-nearest while |x * 2/pi| < 2^51); the low bits of
 *    the sum hold k mod 4, the quadrant.
 * 2. Cody-Waite reduction r = x - k pi/2 with pi/2 split as P1 + P2 + P3 + P4
 *    + P5: P1..P4 of 26 significant bits each, so k*Pi is exact for
 *    |k| < 2^27 (|x| <= 2e8 gives |k| <= 1.28e8); x - k*P1 is exact (Sterbenz);
 *    the next three subtractions are Knuth's two-sum, their errors summed
 *    with k*P5 into a low part; the result r + rr, a double-double, carries
 *    pi/2 to about 157 bits, enough for the arguments nearest a multiple of
 *    pi/2 in the range.
 * 3. sin and cos of r + rr on [-pi/4, pi/4] by fdlibm's __kernel_sin and
 *    __kernel_cos (FreeBSD's branch-free versions, polynomial errors below
 *    2^-58), the quadrant choosing between them and the sign by masks.
 *
 * Use: define SINE_LANES (1, 2, 4 or 8) and include; this defines
 * project_sine<SINE_LANES>(vector of SINE_LANES doubles). */
#ifndef LUMPED_SINE_CONSTANTS
#define LUMPED_SINE_CONSTANTS
#define SINE_PASTE2(a, b) a##b
#define SINE_PASTE(a, b) SINE_PASTE2(a, b)
#define SINE_MAX 2e8
#define SINE_SHIFT 0x1.8p52
#define SINE_INV_PIO2 0x1.45f306dc9c883p-1 /* 2/pi rounded */
#define SINE_P1 0x1.921fb58p+0             /* pi/2 = P1 + ... + P5 to about 157 bits */
#define SINE_P2 -0x1.dde974p-27
#define SINE_P3 0x1.1a6263p-54
#define SINE_P4 0x1.8a2e038p-81
#define SINE_P5 -0x1.f1976b7ed8fbcp-110
#define SINE_S1 -0x1.5555555555549p-3 /* fdlibm k_sin.c */
#define SINE_S2 0x1.111111110f8a6p-7
#define SINE_S3 -0x1.a01a019c161d5p-13
#define SINE_S4 0x1.71de357b1fe7dp-19
#define SINE_S5 -0x1.ae5e68a2b9cebp-26
#define SINE_S6 0x1.5d93a5acfd57cp-33
#define SINE_C1 0x1.555555555554cp-5 /* fdlibm k_cos.c */
#define SINE_C2 -0x1.6c16c16c15177p-10
#define SINE_C3 0x1.a01a019cb159p-16
#define SINE_C4 -0x1.27e4f809c52adp-22
#define SINE_C5 0x1.1ee9ebdb4b1c4p-29
#define SINE_C6 -0x1.8fae9be8838d4p-37
#endif

#define sine_vd SINE_PASTE(sine_vd, SINE_LANES)
#define sine_vl SINE_PASTE(sine_vl, SINE_LANES)
#define project_sine SINE_PASTE(project_sine, SINE_LANES)

typedef double sine_vd __attribute__((vector_size(8 * SINE_LANES)));
typedef long long sine_vl __attribute__((vector_size(8 * SINE_LANES)));

static inline __attribute__((always_inline)) sine_vd project_sine(sine_vd x) {
    const sine_vd zero = {0.0};
    const sine_vd big = x * SINE_INV_PIO2 + SINE_SHIFT; /* 1. */
    const sine_vd k = big - SINE_SHIFT;
    const sine_vl quadrant = (sine_vl)big & 3;
    const sine_vd a = x - k * SINE_P1; /* 2. exact; below, k*-P is -(k*P) (rounding is symmetric) */
    sine_vd c = k * -SINE_P2, hi = a + c, bb = hi - a;
    sine_vd lo = (a - (hi - bb)) + (c - bb);
    sine_vd h = hi;
    c = k * -SINE_P3, hi = h + c, bb = hi - h;
    lo = lo + ((h - (hi - bb)) + (c - bb));
    h = hi;
    c = k * -SINE_P4, hi = h + c, bb = hi - h;
    lo = lo + ((h - (hi - bb)) + (c - bb));
    lo = lo - k * SINE_P5;
    const sine_vd r = hi + lo, rr = lo - (r - hi);
    const sine_vd z = r * r, w = z * z, v = z * r; /* 3. */
    const sine_vd ps = SINE_S2 + z * (SINE_S3 + z * SINE_S4) + z * w * (SINE_S5 + z * SINE_S6);
    const sine_vd s = r - ((z * (0.5 * rr - v * ps) - rr) - v * SINE_S1);
    const sine_vd pc = z * (SINE_C1 + z * (SINE_C2 + z * SINE_C3)) + w * w * (SINE_C4 + z * (SINE_C5 + z * SINE_C6));
    const sine_vd hz = 0.5 * z, one_hz = 1.0 - hz;
    const sine_vd co = one_hz + (((1.0 - one_hz) - hz) + (z * pc - r * rr));
    /* masks by negation and shift, not by 64-bit integer compares (SSE2 has none) */
    const sine_vl odd = -(quadrant & 1), negative = (quadrant & 2) << 62;
    const sine_vl value = (((sine_vl)co & odd) | ((sine_vl)s & ~odd)) ^ negative;
    const sine_vd size = (sine_vd)((sine_vl)x & 0x7fffffffffffffffLL);
    const sine_vl inside = size <= SINE_MAX; /* false for nan */
    return (sine_vd)((value & inside) | ((sine_vl)(zero + __builtin_nan("")) & ~inside));
}

#undef sine_vd
#undef sine_vl
#undef project_sine
