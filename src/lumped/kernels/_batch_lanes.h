/* The vector loop of the batched kernel over one block (_batch_block.h):
 * LANES doubles to a vector (GCC vector extensions: 8 for one AVX-512
 * register, 4 for one AVX2 register, 2 for one SSE2 register), GROUP vectors
 * interleaved.  Every lane operation is the IEEE operation of the scalar
 * code; fabs and copysign are the same sign-bit masks as the C library's, the
 * branches of the corrector and of the switched sine are blends of both
 * sides, and the sine is the project's (_sine.h, instantiated here for LANES
 * lanes), so the forcing is computed in the lanes too.
 *
 * Use: define LANES and GROUP and include; this defines run_block<LANES> (one
 * block's steps first..last) and sine_buffer<LANES> (a test hook), each name
 * below with the suffix LANES (run_block -> run_block4).  _batch_kernel.c
 * includes it once per instruction set, under that set's target pragma. */
#if !defined(LANES) || !defined(GROUP)
#error "_batch_lanes.h: define LANES (doubles to a vector) and GROUP (vectors interleaved) before including it"
#endif
#include <math.h>
#include <string.h>

#include "_batch_block.h" /* Block and its helpers (load, store, chunk_steps), BLOCK, CHUNK, INLINE */

#ifndef LUMPED_BATCH_LANES_ONCE
#define LUMPED_BATCH_LANES_ONCE
#define SIGN ((long long)0x8000000000000000ULL)
#define PASTE2(a, b) a##b
#define PASTE(a, b) PASTE2(a, b)
#endif

#define SINE_LANES LANES
#include "_sine.h"
#undef SINE_LANES
#define STICK_LANES LANES
#include "_stick.h" /* sticks<LANES>: the stick test of every kernel */
#undef STICK_LANES
#define vd PASTE(vd, LANES)
#define vl PASTE(vl, LANES)
#define get PASTE(get, LANES)
#define put PASTE(put, LANES)
#define pick PASTE(pick, LANES)
#define vabs PASTE(vabs, LANES)
#define lane_state PASTE(lane_state, LANES)
#define begin PASTE(begin, LANES)
#define end PASTE(end, LANES)
#define step PASTE(step, LANES)
#define lanes PASTE(lanes, LANES)
#define advance PASTE(advance, LANES)
#define chunk PASTE(chunk, LANES)
#define run_block PASTE(run_block, LANES)
#define sine_buffer PASTE(sine_buffer, LANES)
#define sine PASTE(project_sine, LANES)
#define force PASTE(force, LANES)

typedef double vd __attribute__((vector_size(8 * LANES)));
typedef long long vl __attribute__((vector_size(8 * LANES)));

INLINE vd get(const double *p) { vd x; memcpy(&x, p, sizeof x); return x; }
INLINE void put(double *p, vd x) { memcpy(p, &x, sizeof x); }
INLINE vd pick(vl mask, vd a, vd b) { return (vd)(((vl)a & mask) | ((vl)b & ~mask)); }
INLINE vd vabs(vd x) { return (vd)((vl)x & ~SIGN); }

/* One trajectory-step's state, in registers for a chunk of steps. */
typedef struct {
    vd v, fs, rest, stops, mx, wstops, mw;
    vl moving;
} lane_state;

INLINE void begin(lane_state *q, const Block *b, Py_ssize_t i, int window) {
    const vd zero = {0.0};
    q->v = get(b->v + i), q->fs = get(b->fs + i), q->rest = get(b->rest + i);
    q->stops = get(b->stops + i), q->mx = get(b->mx + i);
    q->wstops = window ? get(b->wstops + i) : zero, q->mw = window ? get(b->mw + i) : zero;
    q->moving = ~(q->v == zero);
}

INLINE void end(const lane_state *q, Block *b, Py_ssize_t i, int window) {
    put(b->v + i, q->v), put(b->fs + i, q->fs), put(b->rest + i, q->rest);
    put(b->stops + i, q->stops), put(b->mx + i, q->mx);
    if (window) put(b->wstops + i, q->wstops), put(b->mw + i, q->mw);
}

/* The switched sine at t = s*dt: amp*sin(omega*t + phase) where amp != 0 and
 * t <= until, else +0.0 (the single-run kernel's expression, its sine the
 * project's). */
INLINE vd force(const Block *b, Py_ssize_t i, double s) {
    const vd zero = {0.0}, amp = get(b->amp + i);
    const double t = s * b->dt;
    const vl on = (amp != zero) & (zero + t <= get(b->until + i));
    return pick(on, amp * sine(get(b->omega + i) * t + get(b->phase + i)), zero);
}

/* Step s of lanes i .. i+LANES-1; forced: add the forcing (else it is +0.0
 * and adding it could only change the sign of a zero predictor, which sticks
 * either way); window: track the window's stops and maximum. */
INLINE void step(lane_state *q, const Block *b, Py_ssize_t i, double s, int forced, int window) {
    const vd zero = {0.0}, one = zero + 1.0, tau = get(b->tau + i);
    vd predictor = get(b->mdt + i) * q->v; /* line 3, eq. (15b) */
    if (forced) predictor = predictor + force(b, i, s);
    predictor = predictor - q->fs;
    const vd signed_tau = (vd)(((vl)tau & ~SIGN) | ((vl)predictor & SIGN));
    const vd slip = (predictor - signed_tau) / get(b->eta_c + i); /* lines 8-9 */
    const vd v = pick(PASTE(sticks, LANES)(predictor, -tau, tau), zero, slip); /* lines 5-6: stick (_stick.h) */
    const vd fs = q->fs + get(b->dtk + i) * v;                       /* line 11, eq. (14) */
    const vl at_rest = v == zero, stop = at_rest & q->moving;
    const vd afs = vabs(fs);
    q->stops = q->stops + (vd)((vl)one & stop);
    q->rest = pick(at_rest, q->rest, zero + (s + 1.0));
    q->mx = pick(afs > q->mx, afs, q->mx);
    if (window) {
        const vl in_window = zero + s >= get(b->nw + i);
        q->wstops = q->wstops + (vd)((vl)one & stop & in_window);
        q->mw = pick(in_window & (afs > q->mw), afs, q->mw);
    }
    q->v = v, q->fs = fs, q->moving = ~at_rest;
}

/* Steps s0 .. s0+steps-1 of GROUP vectors of lanes from i, interleaved so
 * that their independent chains of dependent operations overlap. */
INLINE void lanes(Block *restrict b, Py_ssize_t i, double s0, int steps, int forced, int window) {
    lane_state q[GROUP];
    for (int g = 0; g < GROUP; g++) begin(&q[g], b, i + g * LANES, window);
    for (int k = 0; k < steps; k++)
        for (int g = 0; g < GROUP; g++) step(&q[g], b, i + g * LANES, s0 + k, forced, window);
    for (int g = 0; g < GROUP; g++) end(&q[g], b, i + g * LANES, window);
}

/* Steps s0 .. s0+steps-1 of the whole block (steps a compile-time constant where possible). */
INLINE void advance(Block *restrict b, Py_ssize_t w, double s0, int steps, int forced, int window) {
    for (Py_ssize_t i = 0; i < w; i += LANES * GROUP) lanes(b, i, s0, steps, forced, window);
}

/* The four variants of one chunk, each compiled with its flags as constants. */
INLINE void chunk(Block *restrict b, Py_ssize_t w, double s0, int steps, int forced, int window) {
    if (steps != CHUNK) advance(b, w, s0, steps, forced, window); /* the few short chunks */
    else if (forced) window ? advance(b, w, s0, CHUNK, 1, 1) : advance(b, w, s0, CHUNK, 1, 0);
    else window ? advance(b, w, s0, CHUNK, 0, 1) : advance(b, w, s0, CHUNK, 0, 0);
}

static void run_block(const double *par, const double *nw, double *sums, double *xs, Py_ssize_t n, Py_ssize_t j0,
                      double dt, Py_ssize_t first_step, Py_ssize_t last_step, Py_ssize_t n_steps,
                      Py_ssize_t save_every) {
    Block b;
    const Py_ssize_t w = (n - j0 < BLOCK) ? n - j0 : BLOCK, per_pass = LANES * GROUP;
    const Py_ssize_t wl = (w + per_pass - 1) / per_pass * per_pass; /* padded lanes stick at x = 0 */
    int forced = 0;
    double first = (double)n_steps + 1.0; /* the block's first window step: lanes count from ceil(nw) */
    for (Py_ssize_t i = 0; i < w; i++) {
        forced |= par[6 * n + j0 + i] != 0.0;
        if (nw[j0 + i] < first) first = nw[j0 + i];
    }
    const Py_ssize_t window_from = first < 1.0 ? 1 : (Py_ssize_t)ceil(first);
    load(&b, par, n, j0, w, dt, nw, first_step > 1 ? sums : NULL);
    Py_ssize_t row = 0;
    for (Py_ssize_t s = first_step; s <= last_step;) {
        const int steps = chunk_steps(s, last_step, window_from, xs != NULL, save_every);
        chunk(&b, wl, (double)s, steps, forced, s >= window_from);
        s += steps;
        if (xs != NULL && ((s - 1) % save_every == 0 || s - 1 == n_steps)) {
            double *r = xs + row * n + j0;
            for (Py_ssize_t i = 0; i < w; i++) r[i] = b.fs[i] / par[n + j0 + i];
            row++;
        }
    }
    store(&b, sums, n, j0, w);
}

/* The project's sine of x[0..count-1] in place, LANES at a time (a test hook). */
static void sine_buffer(double *x, Py_ssize_t count) {
    for (Py_ssize_t i = 0; i < count; i += LANES) {
        double lane[LANES] = {0.0};
        const Py_ssize_t m = count - i < LANES ? count - i : LANES;
        memcpy(lane, x + i, (size_t)m * sizeof(double));
        put(lane, sine(get(lane)));
        memcpy(x + i, lane, (size_t)m * sizeof(double));
    }
}

#undef vd
#undef vl
#undef get
#undef put
#undef pick
#undef vabs
#undef lane_state
#undef begin
#undef end
#undef step
#undef lanes
#undef advance
#undef chunk
#undef run_block
#undef sine_buffer
#undef sine
#undef force
