/* The linear solve of the one-step problem for any network (loops through the
 * ground, friction between masses): the merged system of
 * lumped.solvers.merged_system in a fixed ordering of the masses, factorised
 * as a variable band (skyline, envelope) LDL^T.  The active-set iteration
 * around it is _network_active_set.h's (iterate, solve): one home for both steps.
 *
 * With the modes fixed (read lumped.solvers.network_step first):
 *  1. clusters: the points joined by rigid pieces, found breadth first from
 *     the ground, then from each mass in the ordering; each point's offset
 *     from its cluster's root (network_step._clusters).  A rigid element
 *     that joins two points already in one cluster closes a rigid loop,
 *     whose forces the Python step splits (loop_forces): sparse_linear
 *     returns 0 and the step is left to Python.
 *  2. unknowns: one per cluster not holding the ground, numbered in the
 *     order of its first mass in the ordering (file order for a chain,
 *     reverse Cuthill-McKee for a general network:
 *     lumped.solvers.network_sparse.plan).
 *  3. the envelope: row r holds the columns first[r]..r, first[r] the
 *     smallest unknown a free piece of nonzero slope joins to r; merged
 *     clusters widen it where they join far apart masses (a chain's stuck
 *     neighbours: a contiguous cluster keeps it tridiagonal).
 *  4. assembly (merged_system.assemble, terms in the same order), LDL^T of
 *     the envelope (no pivoting: the matrix is the inertias plus a weighted
 *     Laplacian, symmetric positive definite, every pivot >= the smallest
 *     m/dt), forward and back substitution.
 *  5. velocities, each free element's rate and force, and each rigid
 *     element's force from the momentum balance of its masses, leaf to root
 *     of the rigid forest (network_step._rigid_forces).
 * Each pass is O(masses + elements + envelope): O(N) for a chain.  Steps 1 to 3 are kept from the
 * last solve until a piece changes what they read (sparse_piece sets dirty: a rigid flag, a rigid
 * piece's a, whether a free piece's b is 0), and the factors of step 4 until, besides, a free
 * piece's b changes (refactor): most iterations of a marching chain change a few modes or none,
 * and what is kept is what would be computed again, so the numbers are the same bit for bit.
 *
 * Includes _network_forest.h (net_t); included by _network_active_set.h and _network_kernel.c. */
#ifndef LUMPED_NETWORK_SPARSE_H
#define LUMPED_NETWORK_SPARSE_H

#include "_network_forest.h" /* net_t, chosen */

typedef struct sparse_s {
    const int64_t *at_pos;               /* n_mass: the mass at each place of the ordering */
    const int64_t *inc_start, *inc_el;   /* the elements at each point: inc_el[inc_start[p]:inc_start[p+1]] */
    int64_t *root, *col, *first, *start, *stack, *deg;
    uint8_t *used;                       /* per element: its rigid force is known */
    uint8_t *rig;                        /* per element: on a rigid piece in this solve */
    double *pa, *pb;                     /* per element: the chosen piece's a and b, read once per solve */
    int *cmode;                          /* per element: the mode rig, pa, pb were read for (-1: read again) */
    double *val, *diag, *load, *u, *gap; /* the envelope's values (cap), and per unknown / point */
    Py_ssize_t cap;
    /* steps 1 to 3 kept from the last solve while no piece changes what they read (a rigid flag, a
     * rigid piece's a, whether a free piece's b is 0): dirty says they must be done again */
    int dirty;
    Py_ssize_t m; /* the unknowns (envelope's count) */
    /* the factors of step 4 kept while, besides, no free piece's slope b changes (its bits) */
    int refactor;
} sparse_t;

static void sparse_free(sparse_t *s) {
    if (!s) return;
    free(s->root), free(s->val), free(s->diag), free(s->used), free(s->pa), free(s->cmode);
}

/* s's arrays for q (allocated): 0, or -1 if memory ran out (sparse_free frees what was taken). */
static int sparse_allocate(sparse_t *s, const net_t *q) {
    const Py_ssize_t n_pt = q->n_pt;
    s->root = malloc(6 * (n_pt + 1) * sizeof(int64_t));
    s->diag = malloc(5 * (n_pt + 1) * sizeof(double));
    s->used = malloc(2 * (q->n_el + 1));
    s->pa = malloc(2 * (q->n_el + 1) * sizeof(double));
    s->cmode = malloc((q->n_el + 1) * sizeof(int));
    s->cap = 2 * n_pt + 16;
    s->val = malloc(s->cap * sizeof(double));
    if (!s->root || !s->diag || !s->used || !s->val || !s->pa || !s->cmode) return -1;
    for (Py_ssize_t e = 0; e < q->n_el; e++) s->cmode[e] = -1;
    s->dirty = 1, s->refactor = 1;
    s->rig = s->used + (q->n_el + 1), s->pb = s->pa + (q->n_el + 1);
    s->col = s->root + (n_pt + 1), s->first = s->col + (n_pt + 1), s->start = s->first + (n_pt + 1);
    s->stack = s->start + (n_pt + 1), s->deg = s->stack + (n_pt + 1);
    s->load = s->diag + (n_pt + 1), s->u = s->load + (n_pt + 1), s->gap = s->u + (n_pt + 1);
    return 0;
}

/* Element e's chosen piece pc (in mode) as the solve reads it: rigid flag, a, b. */
static inline void sparse_piece(sparse_t *s, Py_ssize_t e, const piece *pc, int mode) {
    const uint8_t rig = (uint8_t)pc->rigid; /* a's bits compared: an offset 0 and -0 may sum differently */
    if (rig != s->rig[e] || (rig ? memcmp(&pc->a, s->pa + e, sizeof(double)) != 0 : (pc->b == 0.0) != (s->pb[e] == 0.0)))
        s->dirty = 1;
    if (!rig && memcmp(&pc->b, s->pb + e, sizeof(double)) != 0) s->refactor = 1;
    s->rig[e] = rig, s->pa[e] = pc->a, s->pb[e] = pc->b;
    s->cmode[e] = mode;
}

/* Each spring's slope dt k into pb (graph_of's spring reads it there): after q->dt is set. */
static void sparse_springs(net_t *q) {
    for (Py_ssize_t e = 0; e < q->n_el; e++)
        if (q->kind[e] == SPRING) q->sp->pb[e] = q->dt * q->par[4 * e];
}

/* Element e's piece to be read again from the table at the next solve (a Stribeck contact's new line). */
static void sparse_reread(net_t *q, Py_ssize_t e) { q->sp->cmode[e] = -1; }

/* Element e's step graph from its state, shifted by its rate shift (backward_euler_network._graphs):
 * into the table of pieces, and the chosen piece into the sparse step's arrays; a one-piece graph (a
 * spring: rebuilt whenever its force changes) only into those arrays, the table filled when a rare
 * path reads it (sync_graphs). */
static void graph_of(net_t *q, Py_ssize_t e, double state) {
    if (q->lazy && q->count[e] == 1 && q->kind[e] == SPRING) {
        /* the same numbers as below without the table; a spring's slope dt k is in pb from the start
         * (sparse_springs) and every piece of its graph has it */
        const double b = q->sp->pb[e], d = q->delta ? q->delta[e] : 0.0;
        q->gstate[e] = state;
        q->sp->rig[e] = 0, q->sp->pa[e] = d != 0.0 ? state + b * d : state;
        q->sp->cmode[e] = q->mode[e], q->lazy[e] = 1;
        return;
    }
    piece local[MAX_PIECES];
    const int lazy = q->lazy && q->count[e] == 1;
    piece *g = lazy ? local : q->graph + e * MAX_PIECES;
    q->gstate[e] = state;
    q->count[e] = step_graph(q->kind[e], q->par + 4 * e, state, q->dt, g);
    if (q->delta && q->delta[e] != 0.0)
        for (int k = 0; k < q->count[e]; k++) g[k] = shift_piece(g[k], q->delta[e]);
    if (q->sp) sparse_piece(q->sp, e, g + q->mode[e], q->mode[e]); /* while the piece is in cache */
    if (q->lazy) q->lazy[e] = (uint8_t)lazy;
}

/* The table of pieces brought up to date for the paths that read it (cycles, dual sweeps). */
static void sync_graphs(net_t *q) {
    if (!q->lazy) return;
    for (Py_ssize_t e = 0; e < q->n_el; e++)
        if (q->lazy[e]) {
            q->lazy[e] = 0;
            q->count[e] = 0; /* not lazy: graph_of writes the table */
            graph_of(q, e, q->gstate[e]);
        }
}

/* Each element's piece in mode read into s (those whose mode changed); the number of rigid elements. */
static Py_ssize_t refresh(net_t *q, sparse_t *s, const int *mode) {
    Py_ssize_t rigid = 0;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        if (s->cmode[e] != mode[e]) sparse_piece(s, e, chosen(q, e, mode), mode[e]); /* a new mode */
        rigid += s->rig[e];
    }
    return rigid;
}

/* Step 1: each point's cluster root (s->root) and offset (q->off), given the number of rigid elements;
 * that number, or -1 if one closes a rigid loop. */
static Py_ssize_t clusters(net_t *q, sparse_t *s, Py_ssize_t rigid) {
    const Py_ssize_t ground = q->n_mass;
    Py_ssize_t merged = 0;
    for (Py_ssize_t p = 0; p < q->n_pt; p++) s->root[p] = -1;
    for (Py_ssize_t k = -1; k < q->n_mass; k++) {
        const int64_t begin = k < 0 ? ground : s->at_pos[k];
        if (s->root[begin] >= 0) continue;
        s->root[begin] = begin, q->off[begin] = 0.0;
        if (rigid == 0) continue;
        Py_ssize_t top = 0;
        s->stack[top++] = begin;
        while (top) {
            const int64_t node = s->stack[--top];
            for (int64_t j = s->inc_start[node]; j < s->inc_start[node + 1]; j++) {
                const int64_t e = s->inc_el[j];
                if (!s->rig[e]) continue;
                const int forward = q->first[e] == node;
                const int64_t next = forward ? q->second[e] : q->first[e];
                if (s->root[next] >= 0) continue;
                s->root[next] = begin;
                q->off[next] = q->off[node] + (forward ? s->pa[e] : -s->pa[e]);
                s->stack[top++] = next;
                merged++;
            }
        }
    }
    return merged == rigid ? rigid : -1;
}

/* Steps 2 and 3: the unknowns (s->col per point, -1 in the ground's cluster) and the envelope
 * (s->first, s->start); the unknown count, or -1 if memory ran out. */
static Py_ssize_t envelope(net_t *q, sparse_t *s, const int *mode) {
    const Py_ssize_t ground = q->n_mass;
    Py_ssize_t m = 0;
    for (Py_ssize_t p = 0; p < q->n_pt; p++) s->col[p] = -2;
    s->col[ground] = -1;
    for (Py_ssize_t k = 0; k < q->n_mass; k++) {
        const int64_t p = s->at_pos[k], r = s->root[p];
        if (r == ground) {
            s->col[p] = -1;
            continue;
        }
        if (s->col[r] == -2) s->col[r] = m++;
        s->col[p] = s->col[r];
    }
    for (Py_ssize_t u = 0; u < m; u++) s->first[u] = u;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        if (s->rig[e] || s->pb[e] == 0.0) continue;
        const int64_t ci = s->col[q->first[e]], cj = s->col[q->second[e]];
        if (ci < 0 || cj < 0 || ci == cj) continue;
        const int64_t r = ci > cj ? ci : cj, c = ci > cj ? cj : ci;
        if (c < s->first[r]) s->first[r] = c;
    }
    s->start[0] = 0;
    for (Py_ssize_t u = 0; u < m; u++) s->start[u + 1] = s->start[u] + (u - s->first[u]);
    if (s->start[m] > s->cap) {
        const Py_ssize_t cap = 2 * s->start[m];
        double *val = realloc(s->val, cap * sizeof(double));
        if (!val) return -1;
        s->val = val, s->cap = cap;
    }
    return m;
}

/* Step 4a: the merged matrix (merged_system.assemble's inertias and slopes, in its order) into the
 * envelope, and its LDL^T in place (val: L below the diagonal, diag: D). */
static void factorise(net_t *q, sparse_t *s, Py_ssize_t m) {
    double *val = s->val, *diag = s->diag;
    const int64_t *col = s->col, *first = s->first, *start = s->start;
    for (Py_ssize_t k = 0; k < m; k++) diag[k] = 0.0;
    memset(val, 0, start[m] * sizeof(double));
    for (Py_ssize_t i = 0; i < q->n_mass; i++)
        if (col[i] >= 0) diag[col[i]] += q->inertia[i];
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        const int64_t ci = col[q->first[e]], cj = col[q->second[e]];
        const double b = s->pb[e];
        if (s->rig[e] || ci == cj || b == 0.0) continue;
        if (cj >= 0) diag[cj] += b;
        if (ci >= 0) diag[ci] += b;
        if (ci >= 0 && cj >= 0) {
            const int64_t r = ci > cj ? ci : cj, c = ci > cj ? cj : ci;
            val[start[r] + (c - first[r])] -= b;
        }
    }
    for (Py_ssize_t i = 0; i < m; i++) { /* row i of L (over D), L_ij = g_j / D_j */
        const int64_t fi = first[i];
        double *row = val + start[i] - fi; /* row[j], j in fi..i-1 */
        for (int64_t j = fi; j < i; j++) {
            const int64_t fj = first[j];
            const double *other = val + start[j] - fj;
            double g = row[j];
            for (int64_t k = fi > fj ? fi : fj; k < j; k++) g -= row[k] * other[k];
            row[j] = g;
        }
        double d = diag[i];
        for (int64_t j = fi; j < i; j++) {
            const double l = row[j] / diag[j];
            d -= row[j] * l;
            row[j] = l;
        }
        diag[i] = d;
    }
}

/* Step 4b: merged_system.assemble's load (its terms in its order), then forward and back substitution
 * through the factors of factorise (into s->u). */
static void assemble_solve(net_t *q, sparse_t *s, Py_ssize_t m) {
    double *load = s->load, *u = s->u;
    const double *val = s->val, *diag = s->diag;
    const int64_t *col = s->col, *first = s->first, *start = s->start;
    for (Py_ssize_t k = 0; k < m; k++) load[k] = 0.0;
    for (Py_ssize_t i = 0; i < q->n_mass; i++) {
        const int64_t c = col[i];
        if (c < 0) continue;
        load[c] += q->rhs[i] - q->inertia[i] * q->off[i];
    }
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        const int64_t i = q->first[e], j = q->second[e], ci = col[i], cj = col[j];
        if (s->rig[e] || ci == cj) continue;
        const double known = s->pa[e] + s->pb[e] * (q->off[j] - q->off[i]);
        if (cj >= 0) load[cj] -= known;
        if (ci >= 0) load[ci] += known;
    }
    for (Py_ssize_t i = 0; i < m; i++) {
        const int64_t fi = first[i];
        const double *row = val + start[i] - fi;
        double y = load[i];
        for (int64_t k = fi; k < i; k++) y -= row[k] * u[k];
        u[i] = y;
    }
    for (Py_ssize_t i = 0; i < m; i++) u[i] /= diag[i];
    for (Py_ssize_t i = m - 1; i >= 0; i--) {
        const int64_t fi = first[i];
        const double *row = val + start[i] - fi;
        for (int64_t k = fi; k < i; k++) u[k] -= row[k] * u[i];
    }
}

/* Step 5, the rigid elements: leaf to root of the rigid forest, each takes what balances its leaf. */
static void peel(net_t *q, sparse_t *s, const int *mode) {
    const Py_ssize_t ground = q->n_mass;
    double *gap = s->gap, *pushed = q->R; /* pushed and deg: summed by sparse_linear's last pass */
    for (Py_ssize_t i = 0; i < q->n_mass; i++) gap[i] = q->rhs[i] - q->inertia[i] * q->vall[i];
    gap[ground] = 0.0;
    Py_ssize_t top = 0;
    for (Py_ssize_t i = 0; i < q->n_pt; i++) {
        gap[i] = gap[i] - pushed[i];
        if (i != ground && s->deg[i] == 1) s->stack[top++] = i;
    }
    while (top) {
        const int64_t i = s->stack[--top];
        if (s->deg[i] != 1) continue;
        int64_t e = -1;
        for (int64_t k = s->inc_start[i]; k < s->inc_start[i + 1] && e < 0; k++) {
            const int64_t c = s->inc_el[k];
            if (!s->used[c] && s->rig[c]) e = c;
        }
        const int64_t j = q->second[e] == i ? q->first[e] : q->second[e];
        s->used[e] = 1;
        q->f[e] = q->second[e] == i ? gap[i] : -gap[i];
        gap[j] -= q->second[e] == j ? q->f[e] : -q->f[e];
        s->deg[i]--, s->deg[j]--;
        if (j != ground && s->deg[j] == 1) s->stack[top++] = j;
    }
}

/* The linear solve with the modes fixed (see the top): 1, or 0 if a rigid loop (or memory) leaves the
 * step to Python. */
static int sparse_linear(net_t *q, const int *mode) {
    sparse_t *s = q->sp;
    const Py_ssize_t ground = q->n_mass;
    const Py_ssize_t rigid = refresh(q, s, mode);
    if (s->dirty) {
        if (clusters(q, s, rigid) < 0 || (s->m = envelope(q, s, mode)) < 0) return 0;
        s->dirty = 0, s->refactor = 1;
    }
    const Py_ssize_t m = s->m;
    if (s->refactor) factorise(q, s, m), s->refactor = 0;
    assemble_solve(q, s, m);
    for (Py_ssize_t p = 0; p < q->n_pt; p++) q->vall[p] = s->col[p] < 0 ? q->off[p] : s->u[s->col[p]] + q->off[p];
    q->vall[ground] = 0.0;
    double *pushed = q->R; /* the free forces' sum at each point, and the rigid elements there: for peel */
    if (rigid)
        for (Py_ssize_t p = 0; p < q->n_pt; p++) pushed[p] = 0.0, s->deg[p] = 0;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        const int64_t i = q->first[e], j = q->second[e];
        if (s->rig[e]) {
            q->w[e] = s->pa[e], q->f[e] = 0.0;
            if (rigid) s->used[e] = 0, s->deg[i]++, s->deg[j]++;
        } else {
            q->w[e] = q->vall[j] - q->vall[i];
            q->f[e] = s->pa[e] + s->pb[e] * q->w[e];
            if (rigid) pushed[j] += q->f[e], pushed[i] -= q->f[e];
        }
    }
    if (rigid) peel(q, s, mode);
    return 1;
}
#endif
