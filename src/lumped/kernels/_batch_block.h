/* The block layout of the batched kernel: how many trajectories a block holds
 * (BLOCK), how many steps a pass over it takes (CHUNK), the rows of its
 * buffers (NPAR parameters, NSUM summaries), the Block itself (parameters and
 * state of BLOCK trajectories, one array per quantity), and its helpers: load
 * (a block from the buffers), store (its summaries back) and chunk_steps (the
 * steps of the next pass).  INLINE is the always_inline of the batched loop.
 *
 * Included by _batch_kernel.c (the binding: it cuts the trajectories into
 * blocks) and by _batch_lanes.h (the vector loop over one block); _batch_kernel.c
 * includes it first, before any instruction-set pragma, so that these helpers
 * are compiled for the baseline x86-64 and inline into all three loops. */
#ifndef LUMPED_BATCH_BLOCK_H
#define LUMPED_BATCH_BLOCK_H

#include <Python.h>
#include <string.h>

#define BLOCK 128 /* trajectories per block: the block's state (16 KB) stays in the L1 data cache */
#define CHUNK 2 /* time steps taken per pass over the block, state held in registers */
#define NPAR 10
#define NSUM 7
#define INLINE static inline __attribute__((always_inline))

typedef struct {
    double mdt[BLOCK], eta_c[BLOCK], dtk[BLOCK], tau[BLOCK], nw[BLOCK];
    double amp[BLOCK], omega[BLOCK], phase[BLOCK], until[BLOCK]; /* the switched sine */
    double v[BLOCK], fs[BLOCK];
    double rest[BLOCK], stops[BLOCK], wstops[BLOCK], mx[BLOCK], mw[BLOCK];
    double dt;
} Block;

/* The block's parameters, and its state: the initial one, or (sums != NULL)
 * the one a previous call stored. */
INLINE void load(Block *b, const double *par, Py_ssize_t n, Py_ssize_t j0, Py_ssize_t w, double dt, const double *nw,
                 const double *sums) {
    memset(b, 0, sizeof *b); /* lanes past w: everything 0, they stick at x = 0, unforced */
    b->dt = dt;
    for (Py_ssize_t i = w; i < BLOCK; i++) b->eta_c[i] = 1.0;
    for (Py_ssize_t i = 0; i < w; i++) {
        const Py_ssize_t j = j0 + i;
        const double m = par[j], k = par[n + j], c = par[3 * n + j];
        const double eta = m / dt + k * dt;
        b->mdt[i] = m / dt;
        b->eta_c[i] = eta + c;
        b->dtk[i] = dt * k;
        b->tau[i] = par[2 * n + j];
        b->nw[i] = nw[j];
        b->fs[i] = k * par[4 * n + j]; /* spring.force(x0) */
        b->v[i] = par[5 * n + j];
        b->rest[i] = b->v[i] == 0.0 ? 0.0 : 1.0;
        b->amp[i] = par[6 * n + j], b->omega[i] = par[7 * n + j];
        b->phase[i] = par[8 * n + j], b->until[i] = par[9 * n + j];
        if (sums != NULL) {
            b->v[i] = sums[j], b->fs[i] = sums[n + j], b->rest[i] = sums[2 * n + j];
            b->stops[i] = sums[3 * n + j], b->wstops[i] = sums[4 * n + j];
            b->mx[i] = sums[5 * n + j], b->mw[i] = sums[6 * n + j];
        }
    }
}

INLINE void store(const Block *b, double *sums, Py_ssize_t n, Py_ssize_t j0, Py_ssize_t w) {
    for (Py_ssize_t i = 0; i < w; i++) {
        const Py_ssize_t j = j0 + i;
        sums[j] = b->v[i];
        sums[n + j] = b->fs[i];
        sums[2 * n + j] = b->rest[i];
        sums[3 * n + j] = b->stops[i];
        sums[4 * n + j] = b->wstops[i];
        sums[5 * n + j] = b->mx[i];
        sums[6 * n + j] = b->mw[i];
    }
}

/* Steps to take in one chunk from step s: CHUNK, cut at the window's first
 * step (the window's bookkeeping starts there), at a saved step and at the
 * call's last step. */
INLINE int chunk_steps(Py_ssize_t s, Py_ssize_t last, Py_ssize_t window_from, int saving, Py_ssize_t save_every) {
    Py_ssize_t end = s + CHUNK - 1;
    if (end > last) end = last;
    if (s < window_from && end >= window_from) end = window_from - 1;
    if (saving) { /* stop at the next saved step */
        const Py_ssize_t saved = s + (save_every - s % save_every) % save_every;
        if (end > saved) end = saved;
    }
    return (int)(end - s + 1);
}
#endif
