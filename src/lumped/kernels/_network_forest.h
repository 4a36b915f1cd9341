/* The one-step problem of a network whose link graph is a forest (or a forest
 * and one more link, a chord: _network_loop.h), solved by elimination: the modes of the elements (which piece of its step graph each
 * is on) found by the active-set iteration of lumped.solvers.network_step
 * (step._iterate at the scales step.SIGMA_SCALES, then step._dual_sweeps;
 * read its docstring first), and for fixed modes the linear solve.
 *
 * Points are the masses and the ground; a *link* joins a point to its parent
 * in a spanning forest and carries every element between the two (parallel
 * elements).  Leaf to root, a free link adds its conductance K = sum b and
 * its load A = sum s a to the parent; a rigid link (one element on a rigid
 * piece: sticking, taut, locked) merges the child into the parent with the
 * fixed rate offset o, v_child = v_parent + o (exactly v_parent for a
 * sticking element).  Root to leaf, the velocities follow, then each free
 * force f = a + b w and each rigid force from the momentum balance of its
 * child's subtree.  O(points + elements) per solve, no fill-in; every pivot
 * D + K is positive (masses > 0, b >= 0).
 *
 * Holds net_t (the network's topology and the work arrays of one solve),
 * allocate and deallocate (those arrays) and the forest's linear solve
 * (eliminate, substitute); the active-set iteration around it, solve, is
 * _network_active_set.h.  Included by _network_kernel.c (the marching
 * loop and its binding); the elements' step graphs are _network_elements.h. */
#ifndef LUMPED_NETWORK_FOREST_H
#define LUMPED_NETWORK_FOREST_H

#include <Python.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "_network_elements.h" /* piece, MAX_PIECES, mode_of */

/* step.SIGMA_SCALES, step.DUAL_SWEEPS and step.default_bound's two numbers (the iterations per scale,
 * BOUND_BASE + BOUND_PER_ELEMENT elements): set from Python when the module is imported (network_settings
 * in _network_kernel.c, called by lumped.solvers.network_compiled), so that the two steps read one
 * definition; until then one scale, no sweeps and the bound 20 + 2 elements. */
#define MAX_SETTINGS 16
static double SCALES[MAX_SETTINGS] = {1.0};
static int N_SCALES = 1;
static int SWEEPS[MAX_SETTINGS] = {0};
static int N_SWEEPS = 0;
static int BOUND_BASE = 20, BOUND_PER_ELEMENT = 2;

/* The network: topology (read only), then the work arrays of one solve. */
typedef struct {
    Py_ssize_t n_mass, n_el, n_pt;
    const int64_t *kind, *first, *second, *order, *parent, *link_start, *link_el, *load_mass;
    const double *par, *sign, *inertia, *sigma;
    Py_ssize_t n_load;
    double dt;
    piece *graph;     /* n_el * MAX_PIECES */
    int *count;       /* pieces per element */
    int *mode, *guess, *next;
    int64_t *rig;     /* per point: the rigid element of its link, or -1 */
    double *D, *R, *num, *den, *K, *A, *off, *vall, *w, *f, *rhs, *z;
    uint64_t *seen;
    int bound;
    /* the chord (_network_loop.h): its elements link_el[chord_start:chord_end], its points */
    Py_ssize_t chord_start, chord_end;
    int64_t cp, cq, rc;
    double Kc, mu, *Ry, *numy, *vy;
    /* the last solve's rigid loop: its elements, their +-1 and particular forces */
    int rigid_loop;
    Py_ssize_t n_loop;
    int64_t *loop_el;
    double *loop_n, *loop_f0;
    /* the sparse step (_network_sparse.h): its arrays, or NULL for the forest's elimination; each
     * element's rate shift by a driven point (NULL: none); fallback set when a step needs the Python step */
    struct sparse_s *sp;
    double *delta;
    int fallback;
    double *gstate; /* the state each element's step graph was built from (the kernel's graphs()) */
    uint8_t *lazy;  /* the sparse step's one-piece graphs kept only in its arrays (sync_graphs), or NULL */
    uint8_t *driven; /* the sparse step's elements joined to driven points (graph built once a step), or NULL */
    double *stat;   /* a friction contact's static threshold (slip_rule), by element; the sparse step's */
    struct curve_s *cv; /* the Stribeck contacts (_network_curve.h), or NULL: none */
} net_t;

/* q's work arrays for n_mass masses and n_el elements: 0, or -1 if memory ran
 * out (deallocate frees what was taken either way). */
static int allocate(net_t *q, Py_ssize_t n_mass, Py_ssize_t n_el) {
    const Py_ssize_t n_pt = n_mass + 1;
    q->n_mass = n_mass, q->n_el = n_el, q->n_pt = n_pt;
    q->bound = BOUND_BASE + BOUND_PER_ELEMENT * (int)n_el;
    q->graph = malloc((n_el * MAX_PIECES + 1) * sizeof(piece));
    q->count = malloc((4 * n_el + 1) * sizeof(int));
    q->rig = malloc(n_pt * sizeof(int64_t));
    q->D = malloc((12 * n_pt + 6 * n_el) * sizeof(double));
    q->seen = malloc(q->bound * sizeof(uint64_t));
    q->loop_el = malloc((n_el + 1 + n_pt) * sizeof(int64_t)); /* and hold_chord's scratch */
    if (!q->graph || !q->count || !q->rig || !q->D || !q->seen || !q->loop_el) return -1;
    q->mode = q->count + n_el, q->guess = q->mode + n_el, q->next = q->guess + n_el;
    q->R = q->D + n_pt, q->num = q->R + n_pt, q->den = q->num + n_pt, q->K = q->den + n_pt;
    q->A = q->K + n_pt, q->off = q->A + n_pt, q->vall = q->off + n_pt, q->rhs = q->vall + n_pt;
    q->w = q->rhs + n_pt, q->f = q->w + n_el, q->z = q->f + n_el;
    q->Ry = q->z + n_el, q->numy = q->Ry + n_pt, q->vy = q->numy + n_pt;
    q->loop_n = q->vy + n_pt, q->loop_f0 = q->loop_n + n_el, q->gstate = q->loop_f0 + n_el;
    q->n_loop = 0, q->rigid_loop = 0;
    return 0;
}

static void deallocate(net_t *q) {
    free(q->graph), free(q->count), free(q->rig), free(q->D), free(q->seen), free(q->loop_el);
}

static const piece *chosen(const net_t *q, Py_ssize_t e, const int *mode) {
    return q->graph + e * MAX_PIECES + mode[e];
}

#include "_network_loop.h"  /* the chord: chord_loads, chord_velocities, chord_forces, loop_intervals */

/* Leaf to root: fold each point's subtree into its parent. */
static void eliminate(net_t *q, const int *mode) {
    for (Py_ssize_t i = 0; i < q->n_pt; i++) {
        q->D[i] = i < q->n_mass ? q->inertia[i] : 0.0;
        q->R[i] = i < q->n_mass ? q->rhs[i] : 0.0;
    }
    if (q->chord_end > q->chord_start) chord_loads(q, mode);
    for (Py_ssize_t idx = q->n_pt - 1; idx >= 0; idx--) {
        const int64_t c = q->order[idx], p = q->parent[c];
        if (p < 0) continue;
        int64_t r = -1;
        double num = q->R[c], den = q->D[c], K = 0.0, A = 0.0;
        for (int64_t k = q->link_start[c]; k < q->link_start[c + 1]; k++) {
            const int64_t e = q->link_el[k];
            const piece *pc = chosen(q, e, mode);
            if (pc->rigid) {
                r = e;
                continue;
            }
            num -= q->sign[e] * pc->a;
            A += q->sign[e] * pc->a;
            den += pc->b;
            K += pc->b;
        }
        q->rig[c] = r;
        if (r >= 0) {
            const double o = q->sign[r] * chosen(q, r, mode)->a;
            q->off[c] = o;
            q->R[p] += q->R[c] - q->D[c] * o;
            q->D[p] += q->D[c];
        } else {
            q->num[c] = num, q->den[c] = den, q->K[c] = K, q->A[c] = A;
            q->R[p] += A + K * num / den;
            q->D[p] += K * q->D[c] / den;
        }
    }
}

/* The force of a rigid link's rigid element: the subtree's momentum balance
 * gives the link's tension T, less the parallel free elements' share. */
static void rigid_force(net_t *q, int64_t c, const int *mode) {
    const int64_t r = q->rig[c];
    double free = 0.0;
    for (int64_t k = q->link_start[c]; k < q->link_start[c + 1]; k++) {
        const int64_t e = q->link_el[k];
        if (e != r) free += q->sign[e] * q->f[e];
    }
    q->f[r] = q->sign[r] * ((q->R[c] - q->D[c] * q->vall[c]) - free);
    q->w[r] = chosen(q, r, mode)->a;
}

/* Root to leaf: velocities, then every element's rate and force. */
static void substitute(net_t *q, const int *mode) {
    const Py_ssize_t ground = q->n_mass;
    for (Py_ssize_t idx = 0; idx < q->n_pt; idx++) {
        const int64_t c = q->order[idx], p = q->parent[c];
        if (p < 0)
            q->vall[c] = c == ground ? 0.0 : q->R[c] / q->D[c];
        else if (q->rig[c] >= 0)
            q->vall[c] = q->vall[p] + q->off[c];
        else
            q->vall[c] = (q->num[c] + q->K[c] * q->vall[p]) / q->den[c];
    }
    if (q->chord_end > q->chord_start) chord_velocities(q, mode);
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        const piece *pc = chosen(q, e, mode);
        if (pc->rigid) continue;
        q->w[e] = q->vall[q->second[e]] - q->vall[q->first[e]];
        q->f[e] = pc->a + pc->b * q->w[e];
    }
    for (Py_ssize_t c = 0; c < q->n_pt; c++)
        if (q->parent[c] >= 0 && q->rig[c] >= 0) rigid_force(q, c, mode);
    if (q->chord_end > q->chord_start) chord_forces(q, mode);
}

#endif
