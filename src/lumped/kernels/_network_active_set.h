/* The active-set iteration of the one-step problem (lumped.solvers.network_step:
 * step._iterate at the scales step.SIGMA_SCALES, then step._dual_sweeps; read its
 * docstring first) around the linear solve with the modes fixed: the forest's
 * elimination (_network_forest.h) or the sparse step's envelope LDL^T
 * (_network_sparse.h), with the Stribeck contacts' points (_network_curve.h).
 * One home for both steps; it sits above the three, which do not call it.
 * Holds solve (one step problem from the warm start in q->mode). */
#ifndef LUMPED_NETWORK_ACTIVE_SET_H
#define LUMPED_NETWORK_ACTIVE_SET_H

#include "_network_forest.h" /* net_t, chosen, eliminate, substitute */
#include "_network_sparse.h" /* sparse_linear, sync_graphs */
#include "_network_curve.h"  /* curve_pieces, curve_next, curve_same, curve_commit */

/* The mode after an iteration (StepGraph.next_mode): a friction contact's rule, in its true rate
 * w + delta (step_graph.Shifted), or the piece holding z = f + sigma w. */
static int next_mode(net_t *q, Py_ssize_t e, double sigma) {
    if (q->cv && q->cv->ix[e] >= 0) return curve_next(q, e, sigma);
    if (contact_kind(q->kind[e]) && q->count[e] == 3) {
        const double d = q->delta ? q->delta[e] : 0.0;
        return slip_rule(q->mode[e], d != 0.0 ? q->w[e] + d : q->w[e], q->f[e], q->stat[e]);
    }
    if (q->count[e] == 1) return 0; /* Pieces.mode of one piece: that piece */
    return mode_of(q->graph + e * MAX_PIECES, q->count[e], q->f[e] + sigma * q->w[e], sigma);
}

/* StepGraph.mode (the dual sweeps' choice): a shifted contact asks its own graph with z + sigma delta. */
static int resolvent_mode(const net_t *q, Py_ssize_t e, double z, double sigma) {
    const double d = q->delta ? q->delta[e] : 0.0;
    if (contact_kind(q->kind[e]) && q->count[e] == 3 && d != 0.0) {
        piece g[3];
        for (int k = 0; k < 3; k++) g[k] = shift_piece(q->graph[e * MAX_PIECES + k], -d);
        return mode_of(g, 3, z + sigma * d, sigma);
    }
    return mode_of(q->graph + e * MAX_PIECES, q->count[e], z, sigma);
}


/* One linear solve with the modes fixed: 0 if the sparse step met what it leaves to Python. */
static int linear(net_t *q, const int *mode) {
    if (q->sp) return sparse_linear(q, mode);
    eliminate(q, mode);
    substitute(q, mode);
    return 1;
}

static uint64_t hash_modes(const int *m, Py_ssize_t n) {
    uint64_t h = 1469598103934665603ULL; /* FNV-1a */
    for (Py_ssize_t i = 0; i < n; i++) {
        h ^= (uint64_t)(m[i] + 1);
        h *= 1099511628211ULL;
    }
    return h;
}

/* step.on_pieces: 1 if every element's (w, f) lies on its piece up to the
 * rounding of the linear solve (the bounds df, dw derived there). */
/* step._rounding: the bounds df, dw on the rounding of the last linear solve's forces and rates. */
static void rounding(const net_t *q, double *df, double *dw) {
    const double eps = 2.220446049250313e-16, n = (double)(q->n_mass + q->n_el + 1);
    double forces = 0.0, rates = 0.0;
    for (Py_ssize_t i = 0; i < q->n_mass; i++) {
        forces += fabs(q->rhs[i]) + q->inertia[i] * fabs(q->vall[i]);
        rates += fabs(q->vall[i]);
    }
    for (Py_ssize_t e = 0; e < q->n_el; e++) forces += fabs(q->f[e]), rates += fabs(q->w[e]);
    *df = n * eps * forces, *dw = n * eps * rates;
}

static int on_pieces(const net_t *q, const int *mode) {
    double df, dw;
    rounding(q, &df, &dw);
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        const piece *p = chosen(q, e, mode);
        if (p->rigid ? !(p->lo - df <= q->f[e] && q->f[e] <= p->hi + df && fabs(q->w[e] - p->a) <= dw)
                     : !(p->lo - dw <= q->w[e] && q->w[e] <= p->hi + dw))
            return 0;
    }
    return 1;
}

/* step._iterate at one scale: 1 if settled (mode holds the modes), 0 if it
 * cycles or reaches the bound.  A cycle is a repeated hash of the mode
 * vector (a collision, odds 2^-64, only costs a restart at the next scale);
 * it is gone round once, and its first iterate on its pieces up to rounding
 * (on_pieces: a corner) is the solution, its rigid forces clipped to their bands. */
/* step._least_index: every change of mode after the first one undone (a curve keeps its point). */
static void least_index(net_t *q) {
    int changed = 0;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        if (q->next[e] == q->mode[e]) continue;
        if (changed) {
            q->next[e] = q->mode[e];
            const Py_ssize_t k = q->cv ? q->cv->ix[e] : -1;
            if (k >= 0) q->cv->nw[k] = q->cv->pt[k].w, q->cv->nf[k] = q->cv->pt[k].f, q->cv->pt[k].near = 0;
        }
        changed = 1;
    }
}

/* step._points_first: while a Stribeck contact's point still moves on its branch (its discrete mode kept, the
 * point not settled: curve_same), no contact that is not monotone changes its discrete mode; the rule acts on
 * the solve of the pieces chosen, not on an iterate on the way to it (issue 41: coupled(12) at step 215). */
static void points_first(net_t *q, double scale) {
    int moving = 0;
    for (Py_ssize_t k = 0; k < q->cv->n && !moving; k++) {
        const Py_ssize_t e = q->cv->el[k];
        moving = q->next[e] == q->mode[e] && q->mode[e] != STICK_PIECE && !curve_same(q, e, q->sigma[e] * scale);
    }
    if (!moving) return;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        const Py_ssize_t k = q->cv->ix[e];
        if (q->next[e] == q->mode[e] || !(k >= 0 || (contact_kind(q->kind[e]) && q->count[e] == 3))) continue;
        q->next[e] = q->mode[e];
        if (k >= 0) q->cv->nw[k] = q->cv->pt[k].w, q->cv->nf[k] = q->cv->pt[k].f, q->cv->pt[k].near = 0;
    }
}

static int iterate(net_t *q, double scale, int *iterations) {
    int seen = 0, cycling = 0, round = 0, single = 0;
    uint64_t first = 0;
    const int curves = q->cv && q->cv->n; /* a mode with a point: no cycle test (step._iterate's piecewise) */
    for (int it = 1; it <= q->bound; it++) {
        if (curves) curve_pieces(q, scale);
        if (!linear(q, q->mode)) {
            q->fallback = 1;
            return 0;
        }
        int settled = 1;
        if (curves) rounding(q, &q->cv->df, &q->cv->dw);
        for (Py_ssize_t e = 0; e < q->n_el; e++) {
            q->next[e] = next_mode(q, e, q->sigma[e] * scale);
            settled &= curves && q->cv->ix[e] >= 0 ? curve_same(q, e, q->sigma[e] * scale) : q->next[e] == q->mode[e];
        }
        if (settled) {
            *iterations = it;
            return 1;
        }
        if (curves) points_first(q, scale);
        /* step._iterate's one_at_a_time: the Newton finish.  step._pinned_rule has no twin here: a contact
         * held at rest by stuck ones that stops closes a rigid loop, which linear() hands to Python (and both
         * compiled steps refuse parallel elements that can be rigid: ineligible). */
        if (curves && q->cv->tangent) {
            const uint64_t h = hash_modes(q->next, q->n_el);
            for (int j = 0; j < seen && !single; j++) single = q->seen[j] == h;
            if (seen < q->bound) q->seen[seen++] = h;
            if (single) least_index(q);
        }
        if (curves) {
            for (Py_ssize_t k = 0; k < q->cv->n; k++) curve_commit(q, q->cv->el[k]);
            memcpy(q->mode, q->next, q->n_el * sizeof(int));
            continue;
        }
        const uint64_t h = hash_modes(q->next, q->n_el);
        for (int j = 0; j < seen && !cycling; j++) cycling = q->seen[j] == h;
        if (cycling) {
            sync_graphs(q);
            if (on_pieces(q, q->mode)) {
                for (Py_ssize_t e = 0; e < q->n_el; e++) {
                    const piece *p = chosen(q, e, q->mode);
                    if (p->rigid) q->f[e] = q->f[e] < p->lo ? p->lo : q->f[e] > p->hi ? p->hi : q->f[e];
                }
                *iterations = it;
                return 1;
            }
            const uint64_t here = hash_modes(q->mode, q->n_el);
            if (round && first == here) return 0; /* round the cycle, no iterate on its pieces */
            if (!round) first = here, round = 1;
        } else {
            q->seen[seen++] = h;
        }
        memcpy(q->mode, q->next, q->n_el * sizeof(int));
    }
    return 0;
}

/* step._dual_sweeps: modes from Gauss-Seidel on the dual (into q->guess). */
static void dual_sweeps(net_t *q, int sweeps) {
    double *inv = q->D, *v = q->vall, *f = q->z; /* scratch */
    for (Py_ssize_t i = 0; i < q->n_pt; i++) {
        inv[i] = i < q->n_mass ? 1.0 / q->inertia[i] : 0.0;
        v[i] = i < q->n_mass ? q->rhs[i] * inv[i] : 0.0;
    }
    for (Py_ssize_t e = 0; e < q->n_el; e++) f[e] = 0.0, q->guess[e] = q->count[e] / 2;
    const curve_t *c = q->cv;
    for (Py_ssize_t k = 0; c && k < c->n; k++) /* not piecewise: left at its initial mode */
        q->guess[c->el[k]] = curve_initial(q, k, c->state[c->el[k]]);
    for (int s = 0; s < sweeps; s++) {
        for (Py_ssize_t e = 0; e < q->n_el; e++) {
            if (c && c->ix[e] >= 0) continue;
            const int64_t i = q->first[e], j = q->second[e];
            const double sigma = 1.0 / (inv[i] + inv[j]);
            const double z = f[e] + sigma * (v[j] - v[i]);
            const int k = q->guess[e] = resolvent_mode(q, e, z, sigma);
            const piece *p = q->graph + e * MAX_PIECES + k;
            const double fresh = p->rigid ? z - sigma * p->a : p->a + p->b * (z - p->a) / (p->b + sigma);
            const double delta = fresh - f[e];
            f[e] = fresh;
            v[j] -= delta * inv[j];
            v[i] += delta * inv[i];
            v[q->n_mass] = 0.0;
        }
    }
}

/* step.solve_step from the warm start in q->mode: 1 if settled. */
static int solve(net_t *q, int *iterations) {
    memcpy(q->guess, q->mode, q->n_el * sizeof(int));
    q->fallback = 0;
    if (q->cv && q->cv->n) curve_keep(q->cv, 0);
    for (int s = 0; s < N_SCALES; s++) {
        memcpy(q->mode, q->guess, q->n_el * sizeof(int));
        if (s && q->cv && q->cv->n) curve_keep(q->cv, 1);
        if (iterate(q, SCALES[s], iterations)) return 1;
        if (q->fallback) return 0;
        if (s == 0 && q->cv && q->cv->n) { /* a curve's fixed-point iteration failed: Newton (step.solve_step) */
            memcpy(q->mode, q->guess, q->n_el * sizeof(int));
            curve_keep(q->cv, 1);
            q->cv->tangent = 1;
            const int done = iterate(q, 1.0, iterations);
            q->cv->tangent = 0;
            if (done || q->fallback) return done;
        }
    }
    if (N_SWEEPS) sync_graphs(q);
    for (int s = 0; s < N_SWEEPS; s++) {
        dual_sweeps(q, SWEEPS[s]);
        memcpy(q->mode, q->guess, q->n_el * sizeof(int));
        if (iterate(q, 1.0, iterations)) return 1;
        if (q->fallback) return 0;
    }
    return 0;
}
#endif
