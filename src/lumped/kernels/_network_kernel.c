/* Backward Euler for a network of piecewise-linear elements whose link graph
 * is a forest, or a forest and one chord (_network_loop.h): the compiled marching loop of lumped.solvers.network_compiled,
 * and its binding.
 *
 * The one-step problem, its modes, its mode test and its cycle handling are
 * those of lumped.solvers.network_step (read its docstring first), solved by
 * elimination on the forest (_network_forest.h); the element step graphs and
 * state updates are those of lumped.laws.*_elements, repeated by kind code
 * (_network_elements.h).  Change both together: tests/test_network_kernel.py
 * compares this loop with the Python step.  What differs is the linear solve
 * with the modes fixed.
 *
 * One call advances steps n_first..n_last (the driver calls it block by
 * block, with the loads of the block tabulated).  counters = (row,
 * bad_step, bad_kind, most_iterations); bad_kind 1: the active-set iteration
 * did not settle, 2: a velocity or force is not finite; that step is not
 * saved.  Uses only the CPython buffer API. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "_binding_checks.h"
#include "_network_elements.h" /* piece, step_graph, next_state: the elements by kind code */
#include "_network_forest.h"     /* net_t, allocate: the network; the forest's linear solve */
#include "_network_sparse.h"     /* sparse_linear: the linear solve of any network */
#include "_network_active_set.h" /* solve: the one-step problem, the active set around either solve */

typedef struct {
    double *x, *v, *state;
    int64_t *modes, *rest, *counters;
    double *points; /* the Stribeck contacts' points (_network_curve.h), POINT_WIDTH per element; NULL: none */
} march_t;

typedef struct {
    double *t, *x, *v, *force, *state;
    uint8_t *rigid;
    double *low, *high; /* NULL: no intervals kept (no chord) */
} record_t;

static void save(const net_t *q, const march_t *m, const record_t *o, double t, int64_t row) {
    const Py_ssize_t n = q->n_mass, ne = q->n_el;
    o->t[row] = t;
    memcpy(o->x + row * n, m->x, n * sizeof(double));
    memcpy(o->v + row * n, m->v, n * sizeof(double));
    memcpy(o->force + row * ne, q->f, ne * sizeof(double));
    memcpy(o->state + row * ne, m->state, ne * sizeof(double));
    for (Py_ssize_t e = 0; e < ne; e++) o->rigid[row * ne + e] = (uint8_t)(q->sp ? q->sp->rig[e] : chosen(q, e, q->mode)->rigid);
    if (o->low) loop_intervals(q, o->low + row * ne, o->high + row * ne);
}

/* The elements joined to driven points (the sparse step only), an entry per element and driver it is
 * joined to (Network.driven, in its order): the element, the driver, the sign; n_drivers columns of
 * the drivers' mean velocities per step. */
typedef struct {
    Py_ssize_t n, n_drivers;
    const int64_t *el, *driver;
    const double *sign;
} driven_t;

/* Every step graph of the step: those whose state changed (stateful: a spring's force) and those of
 * the elements joined to driven points; the others are the ones built before, unchanged. */
static void graphs(net_t *q, const double *state, const driven_t *dv) {
    for (Py_ssize_t e = 0; e < q->n_el; e++) /* a driven element's graph: once, below */
        if (state[e] != q->gstate[e] && stateful(q->kind[e]) && !(q->driven && q->driven[e])) graph_of(q, e, state[e]);
    for (Py_ssize_t k = 0; k < dv->n; k++) graph_of(q, dv->el[k], state[dv->el[k]]);
}

/* One step to t = n dt with the loads `load` and the drivers' rate shifts `shift`: 0 on success, else
 * the bad kind (3: the sparse step met a rigid loop, the step is left to Python). */
static int step(net_t *q, const march_t *m, const double *load, const driven_t *dv, const double *shift,
                int *iterations) {
    for (Py_ssize_t k = 0; k < dv->n; k++) q->delta[dv->el[k]] = 0.0;
    for (Py_ssize_t k = 0; k < dv->n; k++) /* backward_euler_network._shifts: 0 + the sum, in its order */
        q->delta[dv->el[k]] += dv->sign[k] * shift[dv->driver[k]];
    graphs(q, m->state, dv);
    if (q->cv) q->cv->state = m->state;
    for (Py_ssize_t i = 0; i < q->n_mass; i++) q->rhs[i] = q->inertia[i] * m->v[i] + 0.0;
    for (Py_ssize_t k = 0; k < q->n_load; k++) q->rhs[q->load_mass[k]] = q->inertia[q->load_mass[k]] * m->v[q->load_mass[k]] + load[k];
    if (!solve(q, iterations)) return q->fallback ? 3 : 1;
    int finite = 1;
    for (Py_ssize_t i = 0; i < q->n_mass; i++) finite &= isfinite(q->vall[i]);
    for (Py_ssize_t e = 0; e < q->n_el; e++) finite &= isfinite(q->f[e]);
    if (!finite) return 2;
    for (Py_ssize_t i = 0; i < q->n_mass; i++) {
        m->v[i] = q->vall[i];
        m->x[i] = m->x[i] + q->dt * m->v[i];
    }
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        const int rigid = q->sp ? q->sp->rig[e] : chosen(q, e, q->mode)->rigid;
        const double w = q->delta ? q->w[e] + q->delta[e] : q->w[e]; /* the true rate */
        m->state[e] = next_state(q->kind[e], q->par + 4 * e, m->state[e], q->dt, w, q->f[e], rigid);
        m->modes[e] = q->mode[e];
    }
    return 0;
}

static int march(net_t *q, march_t *m, const record_t *o, const double *table, const driven_t *dv,
                 const double *shifts, Py_ssize_t n_first, Py_ssize_t n_last, Py_ssize_t n_steps,
                 Py_ssize_t save_every) {
    int64_t *cnt = m->counters;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        q->count[e] = step_graph(q->kind[e], q->par + 4 * e, m->state[e], q->dt, q->graph + e * MAX_PIECES);
        q->gstate[e] = m->state[e];
        q->mode[e] = m->modes[e] < 0 ? initial_mode(q->kind[e], m->state[e], q->count[e]) : (int)m->modes[e];
    }
    if (q->cv) {
        curve_load(q->cv, m->points);
        for (Py_ssize_t k = 0; k < q->cv->n; k++)
            if (m->modes[q->cv->el[k]] < 0) curve_initial(q, k, m->state[q->cv->el[k]]);
    }
    for (Py_ssize_t n = n_first; n <= n_last; n++) {
        int iterations = 0;
        const int bad = step(q, m, table + (n - n_first) * q->n_load, dv, dv->n ? shifts + (n - n_first) * dv->n_drivers : NULL, &iterations);
        if (bad) {
            cnt[1] = n, cnt[2] = bad;
            if (q->cv) curve_store(q->cv, m->points);
            return bad;
        }
        if (iterations > cnt[3]) cnt[3] = iterations;
        for (Py_ssize_t i = 0; i < q->n_mass; i++)
            if (m->v[i] != 0.0) m->rest[i] = n + 1;
        if (n % save_every == 0 || n == n_steps) save(q, m, o, (double)n * q->dt, cnt[0]++);
    }
    if (q->cv) curve_store(q->cv, m->points);
    return 0;
}

/* ---- the Python binding ------------------------------------------------ */

/* Every argument is checked before the loop runs (_binding_checks.h): the
 * lengths and item types of the arrays against the counts (elements from
 * `kind`, masses from `inertia`, rows from `t`), the kind codes, every index
 * (points, elements, masses, modes) within range and the forest's order. */

static const char *const TOPOLOGY[] = {
    "topology[0] (kind)",  "topology[1] (par)",    "topology[2] (first)",      "topology[3] (second)",
    "topology[4] (order)", "topology[5] (parent)", "topology[6] (link_start)", "topology[7] (link_el)",
    "topology[8] (sign)",  "topology[9] (inertia)", "topology[10] (sigma)",    "topology[11] (load_mass)"};

/* -1 with ValueError unless lo <= values[i] < hi for every i. */
static int check_indices(const char *name, const Py_buffer *b, int64_t lo, int64_t hi) {
    const int64_t *values = b->buf;
    for (Py_ssize_t i = 0; i < items(b); i++)
        if (values[i] < lo || values[i] >= hi) {
            PyErr_Format(PyExc_ValueError, "%s must hold values in %lld..%lld, got %lld at %zd", name, (long long)lo,
                         (long long)hi - 1, (long long)values[i], i);
            return -1;
        }
    return 0;
}

/* -1 with ValueError unless order lists every point once, each point's parent before it, the ground a root. */
static int check_forest(const int64_t *order, const int64_t *parent, Py_ssize_t n_pt) {
    Py_ssize_t *place = malloc(n_pt * sizeof(Py_ssize_t));
    if (place == NULL) {
        PyErr_NoMemory();
        return -1;
    }
    for (Py_ssize_t p = 0; p < n_pt; p++) place[p] = -1;
    const char *bad = NULL;
    for (Py_ssize_t i = 0; i < n_pt && !bad; i++) {
        if (place[order[i]] >= 0) bad = "topology[4] (order) must list every point once";
        place[order[i]] = i;
    }
    for (Py_ssize_t p = 0; p < n_pt && !bad; p++)
        if (parent[p] >= 0 && place[parent[p]] > place[p])
            bad = "topology[5] (parent) must come before each point in topology[4] (order)";
    if (!bad && parent[n_pt - 1] != -1) bad = "topology[5] (parent) of the ground must be -1 (a root)";
    free(place);
    if (bad) PyErr_SetString(PyExc_ValueError, bad);
    return bad ? -1 : 0;
}

/* The chord (_network_loop.h): the elements of link_el after the forest's links, all between one
 * pair of points; -1 with ValueError if they are not. */
static int take_chord(net_t *q, Py_ssize_t n_link_el) {
    q->chord_start = q->link_start[q->n_pt], q->chord_end = n_link_el;
    if (q->chord_end == q->chord_start) return 0;
    const int64_t first = q->link_el[q->chord_start];
    q->cp = q->first[first], q->cq = q->second[first];
    for (Py_ssize_t k = q->chord_start; k < q->chord_end; k++) {
        const int64_t e = q->link_el[k];
        const int same = q->first[e] == q->cp && q->second[e] == q->cq, reversed = q->first[e] == q->cq && q->second[e] == q->cp;
        if (!same && !reversed) {
            PyErr_Format(PyExc_ValueError, "topology[7] (link_el) after the forest's links must join one pair of points, got element %lld", (long long)e);
            return -1;
        }
    }
    return 0;
}

/* Take the topology tuple's 12 arrays into h, checked; set q's counts and topology.  q is zeroed. */
static int take_topology(held_t *h, PyObject *obj, net_t *q) {
    memset(q, 0, sizeof *q);
    PyObject *const *a = tuple_items(obj, "topology", 12);
    const Py_buffer *b[12];
    if (a == NULL || !(b[0] = take(h, a[0], TOPOLOGY[0], 'q', -1, 0)) || !(b[9] = take(h, a[9], TOPOLOGY[9], 'd', -1, 0)))
        return -1;
    const Py_ssize_t n_el = items(b[0]), n_mass = items(b[9]), n_pt = n_mass + 1;
    const Py_ssize_t count[12] = {n_el, 4 * n_el, n_el, n_el, n_pt, n_pt, n_pt + 1, -1, n_el, n_mass, n_el, -1};
    for (int i = 1; i < 12; i++)
        if (i != 9 && !(b[i] = take(h, a[i], TOPOLOGY[i], i == 1 || i == 8 || i == 10 ? 'd' : 'q', count[i], 0)))
            return -1;
    const int64_t *link_start = b[6]->buf;
    if (check_indices(TOPOLOGY[0], b[0], 0, 6) < 0 || check_indices(TOPOLOGY[2], b[2], 0, n_pt) < 0 ||
        check_indices(TOPOLOGY[3], b[3], 0, n_pt) < 0 || check_indices(TOPOLOGY[4], b[4], 0, n_pt) < 0 ||
        check_indices(TOPOLOGY[5], b[5], -1, n_pt) < 0 || check_indices(TOPOLOGY[6], b[6], 0, items(b[7]) + 1) < 0 ||
        check_indices(TOPOLOGY[7], b[7], 0, n_el) < 0 || check_indices(TOPOLOGY[11], b[11], 0, n_mass) < 0 ||
        check_forest(b[4]->buf, b[5]->buf, n_pt) < 0)
        return -1;
    for (Py_ssize_t p = 0; p < n_pt; p++)
        if (link_start[p + 1] < link_start[p]) {
            PyErr_Format(PyExc_ValueError, "%s must not decrease, got %lld after %lld", TOPOLOGY[6],
                         (long long)link_start[p + 1], (long long)link_start[p]);
            return -1;
        }
    q->kind = b[0]->buf, q->par = b[1]->buf, q->first = b[2]->buf, q->second = b[3]->buf, q->order = b[4]->buf;
    q->parent = b[5]->buf, q->link_start = link_start, q->link_el = b[7]->buf, q->sign = b[8]->buf;
    q->inertia = b[9]->buf, q->sigma = b[10]->buf, q->load_mass = b[11]->buf;
    q->n_mass = n_mass, q->n_el = n_el, q->n_pt = n_pt, q->n_load = items(b[11]);
    return take_chord(q, items(b[7]));
}

/* -1 with ValueError unless every warm-start mode is -1 or a piece of its element's graph. */
static int check_modes(const char *name, const int64_t *modes, const int *pieces, Py_ssize_t n_el) {
    for (Py_ssize_t e = 0; e < n_el; e++)
        if (modes[e] < -1 || modes[e] >= pieces[e]) {
            PyErr_Format(PyExc_ValueError, "%s must be -1 or in 0..%d for element %zd, got %lld", name, pieces[e] - 1,
                         e, (long long)modes[e]);
            return -1;
        }
    return 0;
}

/* The one-step problem of network_solve and sparse_solve (the tests' entry points): the step graphs
 * from their rows (rigid, b, a, lo, hi; MAX_PIECES per element), the warm start (-1: the middle piece) and
 * the right-hand side into q, one solve, then v, w, f, the modes and the rigid flags into the solution's
 * buffers.  The iterations it took if settled, else 0. */
static int solve_one(net_t *q, const double *pc, const int64_t *warm, const double *r, Py_buffer *const *sb) {
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        for (int k = 0; k < q->count[e]; k++) {
            const double *row = pc + (e * MAX_PIECES + k) * 5;
            q->graph[e * MAX_PIECES + k] = row[0] != 0.0 ? rigid_piece(row[1], row[3], row[4]) : free_piece(row[1], row[2], row[3], row[4]);
        }
        q->mode[e] = warm[e] < 0 ? q->count[e] / 2 : (int)warm[e];
    }
    for (Py_ssize_t i = 0; i < q->n_mass; i++) q->rhs[i] = r[i];
    int iterations = 0;
    const int ok = solve(q, &iterations);
    double *v = sb[0]->buf, *w = sb[1]->buf, *f = sb[2]->buf;
    int64_t *modes = sb[3]->buf;
    uint8_t *rigid = sb[4]->buf;
    for (Py_ssize_t i = 0; i < q->n_mass; i++) v[i] = q->vall[i];
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        w[e] = q->w[e], f[e] = q->f[e], modes[e] = q->mode[e];
        rigid[e] = (uint8_t)chosen(q, e, q->mode)->rigid;
    }
    return ok ? iterations : 0;
}

/* network_solve(topology, pieces, counts, rhs, solution) -> iterations (0: did not settle).
 * One step problem with the given graphs: pieces (elements, 5, 5) rows (rigid, a, b, lo, hi),
 * counts (elements,) in 1..5; solution = (v, w, f, modes, rigid) written in place; the warm start is
 * modes (-1: the middle piece). */
static PyObject *network_solve(PyObject *self, PyObject *args) {
    static const char *const names[] = {"solution[0] (v)", "solution[1] (w)", "solution[2] (f)",
                                        "solution[3] (modes)", "solution[4] (rigid)"};
    PyObject *topo_obj, *pieces_obj, *counts_obj, *rhs_obj, *sol_obj;
    if (!PyArg_ParseTuple(args, "OOOOO", &topo_obj, &pieces_obj, &counts_obj, &rhs_obj, &sol_obj)) return NULL;
    held_t h = {.n = 0};
    net_t q;
    Py_buffer *sb[5];
    const Py_buffer *pieces, *counts, *rhs;
    if (take_topology(&h, topo_obj, &q) < 0 || !(pieces = take(&h, pieces_obj, "pieces", 'd', q.n_el * MAX_PIECES * 5, 0)) ||
        !(counts = take(&h, counts_obj, "counts", 'q', q.n_el, 0)) || !(rhs = take(&h, rhs_obj, "rhs", 'd', q.n_mass, 0)))
        goto fail;
    const Py_ssize_t sizes[] = {q.n_mass, q.n_el, q.n_el, q.n_el, q.n_el};
    if (take_tuple(&h, sol_obj, "solution", 5, names, "dddqB", sizes, 1, sb) < 0 ||
        check_indices("counts", counts, 1, MAX_PIECES + 1) < 0)
        goto fail;
    const Py_ssize_t n_el = q.n_el;
    if (allocate(&q, q.n_mass, n_el) < 0) {
        PyErr_NoMemory();
        goto fail_alloc;
    }
    const double *pc = pieces->buf, *r = rhs->buf;
    const int64_t *cnt = counts->buf, *warm = sb[3]->buf;
    for (Py_ssize_t e = 0; e < n_el; e++) q.count[e] = (int)cnt[e];
    if (check_modes(names[3], warm, q.count, n_el) < 0) goto fail_alloc;
    const int ok = solve_one(&q, pc, warm, r, sb);
    deallocate(&q);
    release_held(&h);
    return PyLong_FromLong(ok);
fail_alloc:
    deallocate(&q);
fail:
    release_held(&h);
    return NULL;
}

/* network_block(topology, marching, record, table, dt, n_first, n_last, n_steps, save_every)
 * topology = (kind, par, first, second, order, parent, link_start, link_el, sign, inertia, sigma, load_mass)
 * marching = (x, v, state, modes, rest, counters); record = (t, x, v, force, state, rigid, low, high),
 * low and high (the admissible forces, _network_loop.h) empty unless the topology has a chord. */
static PyObject *network_block(PyObject *self, PyObject *args) {
    static const char *const march_names[] = {"marching[0] (x)",     "marching[1] (v)",    "marching[2] (state)",
                                              "marching[3] (modes)", "marching[4] (rest)", "marching[5] (counters)"};
    static const char *const record_names[] = {"record[0] (t)",     "record[1] (x)",     "record[2] (v)",
                                               "record[3] (force)", "record[4] (state)", "record[5] (rigid)",
                                               "record[6] (low)",   "record[7] (high)"};
    PyObject *topo_obj, *march_obj, *rec_obj, *table_obj;
    double dt;
    Py_ssize_t n_first, n_last, n_steps, save_every;
    if (!PyArg_ParseTuple(args, "OOOOdnnnn", &topo_obj, &march_obj, &rec_obj, &table_obj, &dt, &n_first, &n_last,
                          &n_steps, &save_every))
        return NULL;
    held_t h = {.n = 0};
    net_t q;
    Py_buffer *mb[6], *rb[8];
    const Py_buffer *table;
    PyObject *const *r;
    if (check_real("dt", dt, 0.0, 1, 0) < 0 || check_steps(n_first, n_last, n_steps, save_every) < 0 ||
        take_topology(&h, topo_obj, &q) < 0)
        goto fail;
    const Py_ssize_t nm = q.n_mass, ne = q.n_el;
    const Py_ssize_t march_sizes[] = {nm, nm, ne, ne, nm, 4};
    if (take_tuple(&h, march_obj, "marching", 6, march_names, "dddqqq", march_sizes, 1, mb) < 0 ||
        !(table = take(&h, table_obj, "table", 'd', (n_last - n_first + 1) * q.n_load, 0)) ||
        !(r = tuple_items(rec_obj, "record", 8)) || !(rb[0] = take(&h, r[0], record_names[0], 'd', -1, 1)))
        goto fail;
    const Py_ssize_t rows = items(rb[0]);
    const Py_ssize_t kept = q.link_start[q.n_pt] < q.chord_end ? rows * ne : 0; /* intervals: with a chord only */
    const Py_ssize_t record_sizes[] = {rows, rows * nm, rows * nm, rows * ne, rows * ne, rows * ne, kept, kept};
    for (int i = 1; i < 8; i++)
        if (!(rb[i] = take(&h, r[i], record_names[i], "ddddBdd"[i - 1], record_sizes[i], 1))) goto fail;
    int64_t *counters = mb[5]->buf;
    if (check_rows(record_names[0], counters[0], rows, n_first, n_last, n_steps, save_every) < 0) goto fail;
    if (allocate(&q, nm, ne) < 0) {
        PyErr_NoMemory();
        goto fail_alloc;
    }
    const double *state = mb[2]->buf;
    for (Py_ssize_t e = 0; e < ne; e++)
        q.count[e] = step_graph(q.kind[e], q.par + 4 * e, state[e], dt, q.graph + e * MAX_PIECES);
    if (check_modes(march_names[3], mb[3]->buf, q.count, ne) < 0) goto fail_alloc;
    q.dt = dt;
    march_t m = {mb[0]->buf, mb[1]->buf, mb[2]->buf, mb[3]->buf, mb[4]->buf, counters, NULL};
    record_t o = {rb[0]->buf, rb[1]->buf, rb[2]->buf, rb[3]->buf, rb[4]->buf, rb[5]->buf,
                  kept ? rb[6]->buf : NULL, kept ? rb[7]->buf : NULL};
    const driven_t none = {0, 0, NULL, NULL, NULL};
    Py_BEGIN_ALLOW_THREADS
    march(&q, &m, &o, table->buf, &none, NULL, n_first, n_last, n_steps, save_every);
    Py_END_ALLOW_THREADS
    deallocate(&q);
    release_held(&h);
    Py_RETURN_NONE;
fail_alloc:
    deallocate(&q);
fail:
    release_held(&h);
    return NULL;
}

/* ---- the sparse step's bindings (_network_sparse.h) ---------------------- */

static const char *const SPARSE[] = {
    "topology[0] (kind)",      "topology[1] (par)",    "topology[2] (first)",   "topology[3] (second)",
    "topology[4] (at_pos)",    "topology[5] (inc_start)", "topology[6] (inc_el)", "topology[7] (inertia)",
    "topology[8] (sigma)",     "topology[9] (load_mass)", "topology[10] (driven_el)", "topology[11] (driven_driver)",
    "topology[12] (driven_sign)"};

/* -1 with ValueError unless at_pos lists every mass once and the incidence lists each element once
 * at its first point and once at its second. */
static int check_sparse(const net_t *q, const sparse_t *s, Py_ssize_t n_inc) {
    const Py_ssize_t n = q->n_mass > q->n_el ? q->n_mass : q->n_el;
    uint8_t *seen = calloc(2 * n + 2, 1);
    if (seen == NULL) {
        PyErr_NoMemory();
        return -1;
    }
    const char *bad = NULL;
    for (Py_ssize_t k = 0; k < q->n_mass && !bad; k++)
        if (seen[s->at_pos[k]]++) bad = "topology[4] (at_pos) must list every mass once";
    memset(seen, 0, 2 * n + 2);
    if (!bad && (s->inc_start[0] != 0 || s->inc_start[q->n_pt] != n_inc || n_inc != 2 * q->n_el))
        bad = "topology[5] (inc_start) must run from 0 to the length of topology[6] (inc_el), twice the elements";
    for (Py_ssize_t p = 0; p < q->n_pt && !bad; p++) {
        if (s->inc_start[p + 1] < s->inc_start[p]) bad = "topology[5] (inc_start) must not decrease";
        for (int64_t k = s->inc_start[p]; k < s->inc_start[p + 1] && !bad; k++) {
            const int64_t e = s->inc_el[k];
            const int at = q->first[e] == p ? 0 : q->second[e] == p ? 1 : -1;
            if (at < 0 || seen[2 * e + at]++) bad = "topology[6] (inc_el) must list each element once at each of its points";
        }
    }
    free(seen);
    if (bad) PyErr_SetString(PyExc_ValueError, bad);
    return bad ? -1 : 0;
}

/* -1 with ValueError unless each Stribeck contact's parameters are a StribeckLaw's with a fall. */
static int check_laws(const net_t *q) {
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        const double *p = q->par + 4 * e;
        if (q->kind[e] >= STRIBECK &&
            (check_real("topology[1] (par) static", p[0], 0.0, 1, 0) < 0 ||
             check_real("topology[1] (par) kinetic", p[1], 0.0, 0, 0) < 0 ||
             check_real("topology[1] (par) static - kinetic", p[0] - p[1], 0.0, 1, 0) < 0 ||
             check_real("topology[1] (par) stribeck_velocity", p[2], 0.0, 1, 0) < 0 ||
             check_real("topology[1] (par) viscous", p[3], 0.0, 0, 0) < 0))
            return -1;
    }
    return 0;
}

/* Take the sparse topology tuple's 13 arrays into h, checked; set q's counts and arrays, s's, and dv
 * (its driver count: n_drivers). */
static int take_sparse(held_t *h, PyObject *obj, net_t *q, sparse_t *s, driven_t *dv, Py_ssize_t n_drivers) {
    memset(q, 0, sizeof *q);
    memset(s, 0, sizeof *s);
    PyObject *const *a = tuple_items(obj, "topology", 13);
    const Py_buffer *b[13];
    if (a == NULL || !(b[0] = take(h, a[0], SPARSE[0], 'q', -1, 0)) || !(b[7] = take(h, a[7], SPARSE[7], 'd', -1, 0)) ||
        !(b[10] = take(h, a[10], SPARSE[10], 'q', -1, 0)))
        return -1;
    const Py_ssize_t n_el = items(b[0]), n_mass = items(b[7]), n_pt = n_mass + 1, n_dv = items(b[10]);
    const Py_ssize_t count[13] = {n_el, 4 * n_el, n_el, n_el, n_mass, n_pt + 1, -1, n_mass, n_el, -1, n_dv, n_dv, n_dv};
    for (int i = 1; i < 13; i++)
        if (i != 7 && i != 10 && !(b[i] = take(h, a[i], SPARSE[i], i == 1 || i == 8 || i == 12 ? 'd' : 'q', count[i], 0)))
            return -1;
    if (check_indices(SPARSE[0], b[0], 0, LAST_KIND + 1) < 0 || check_indices(SPARSE[2], b[2], 0, n_pt) < 0 ||
        check_indices(SPARSE[3], b[3], 0, n_pt) < 0 || check_indices(SPARSE[4], b[4], 0, n_mass) < 0 ||
        check_indices(SPARSE[5], b[5], 0, items(b[6]) + 1) < 0 || check_indices(SPARSE[6], b[6], 0, n_el) < 0 ||
        check_indices(SPARSE[9], b[9], 0, n_mass) < 0 || check_indices(SPARSE[10], b[10], 0, n_el) < 0 ||
        check_indices(SPARSE[11], b[11], 0, n_drivers) < 0)
        return -1;
    q->kind = b[0]->buf, q->par = b[1]->buf, q->first = b[2]->buf, q->second = b[3]->buf;
    q->inertia = b[7]->buf, q->sigma = b[8]->buf, q->load_mass = b[9]->buf;
    q->n_mass = n_mass, q->n_el = n_el, q->n_pt = n_pt, q->n_load = items(b[9]);
    s->at_pos = b[4]->buf, s->inc_start = b[5]->buf, s->inc_el = b[6]->buf;
    dv->n = n_dv, dv->el = b[10]->buf, dv->driver = b[11]->buf, dv->sign = b[12]->buf, dv->n_drivers = n_drivers;
    return check_sparse(q, s, items(b[6])) < 0 || check_laws(q) < 0 ? -1 : 0;
}

/* The Stribeck contacts' arrays (_network_curve.h), if q has any: 0, or -1 if memory ran out. */
static int allocate_curves(net_t *q) {
    Py_ssize_t n = 0;
    for (Py_ssize_t e = 0; e < q->n_el; e++) n += q->kind[e] >= STRIBECK;
    if (n == 0) return 0;
    curve_t *c = q->cv = calloc(1, sizeof(curve_t));
    if (!c) return -1;
    c->n = n;
    c->el = malloc((n + q->n_el) * sizeof(int64_t));
    c->law = malloc(n * sizeof(law_t));
    c->pt = malloc(2 * n * sizeof(slip_point));
    c->nw = malloc(2 * n * sizeof(double));
    if (!c->el || !c->law || !c->pt || !c->nw) return -1;
    c->ix = c->el + n, c->warm = c->pt + n, c->nf = c->nw + n;
    for (Py_ssize_t e = 0, k = 0; e < q->n_el; e++) {
        c->ix[e] = q->kind[e] >= STRIBECK ? k : -1;
        if (q->kind[e] >= STRIBECK) c->el[k] = e, c->law[k] = stribeck_law(q->kind[e], q->par + 4 * e), k++;
    }
    return 0;
}

static void free_curves(net_t *q) {
    if (!q->cv) return;
    free(q->cv->el), free(q->cv->law), free(q->cv->pt), free(q->cv->nw), free(q->cv);
    q->cv = NULL;
}

/* q's and s's work arrays, and the rate shifts (zero): 0, or -1 with MemoryError. */
static int allocate_sparse(net_t *q, sparse_t *s) {
    if (allocate(q, q->n_mass, q->n_el) < 0 || sparse_allocate(s, q) < 0 ||
        !(q->delta = calloc(q->n_el + 1, sizeof(double)))) {
        PyErr_NoMemory();
        return -1;
    }
    q->sp = s;
    if (!(q->stat = malloc((q->n_el + 1) * sizeof(double)))) {
        PyErr_NoMemory();
        return -1;
    }
    for (Py_ssize_t e = 0; e < q->n_el; e++) q->stat[e] = q->par[4 * e]; /* contiguous, for slip_rule */
    if (!(q->lazy = calloc(2 * (q->n_el + 1), 1))) {
        PyErr_NoMemory();
        return -1;
    }
    q->driven = q->lazy + (q->n_el + 1);
    return 0;
}

static void deallocate_sparse(net_t *q, sparse_t *s) {
    deallocate(q);
    sparse_free(s);
    free_curves(q);
    free(q->delta), free(q->stat), free(q->lazy);
}

/* sparse_solve(topology, pieces, counts, rhs, delta, solution) -> iterations (0: did not settle, -1: a
 * rigid loop, left to Python).  network_solve for the sparse step: one step problem with the given
 * graphs, pieces (elements, 5, 5) as there, delta (elements,) each element's rate shift (a friction
 * contact's rule reads its true rate w + delta). */
static PyObject *sparse_solve(PyObject *self, PyObject *args) {
    static const char *const names[] = {"solution[0] (v)", "solution[1] (w)", "solution[2] (f)",
                                        "solution[3] (modes)", "solution[4] (rigid)"};
    PyObject *topo_obj, *pieces_obj, *counts_obj, *rhs_obj, *delta_obj, *sol_obj;
    if (!PyArg_ParseTuple(args, "OOOOOO", &topo_obj, &pieces_obj, &counts_obj, &rhs_obj, &delta_obj, &sol_obj))
        return NULL;
    held_t h = {.n = 0};
    net_t q;
    sparse_t sp;
    driven_t dv;
    Py_buffer *sb[5];
    const Py_buffer *pieces, *counts, *rhs, *delta;
    if (take_sparse(&h, topo_obj, &q, &sp, &dv, PY_SSIZE_T_MAX) < 0 ||
        !(pieces = take(&h, pieces_obj, "pieces", 'd', q.n_el * MAX_PIECES * 5, 0)) ||
        !(counts = take(&h, counts_obj, "counts", 'q', q.n_el, 0)) || !(rhs = take(&h, rhs_obj, "rhs", 'd', q.n_mass, 0)) ||
        !(delta = take(&h, delta_obj, "delta", 'd', q.n_el, 0)))
        goto fail;
    const Py_ssize_t sizes[] = {q.n_mass, q.n_el, q.n_el, q.n_el, q.n_el};
    if (take_tuple(&h, sol_obj, "solution", 5, names, "dddqB", sizes, 1, sb) < 0 ||
        check_indices("counts", counts, 1, MAX_PIECES + 1) < 0)
        goto fail;
    const Py_ssize_t n_el = q.n_el;
    if (allocate_sparse(&q, &sp) < 0) goto fail_alloc;
    const double *pc = pieces->buf, *r = rhs->buf, *d = delta->buf;
    const int64_t *cnt = counts->buf, *warm = sb[3]->buf;
    for (Py_ssize_t e = 0; e < n_el; e++) q.count[e] = (int)cnt[e], q.delta[e] = d[e];
    if (check_modes(names[3], warm, q.count, n_el) < 0) goto fail_alloc;
    const int ok = solve_one(&q, pc, warm, r, sb);
    const int fallback = q.fallback;
    deallocate_sparse(&q, &sp);
    release_held(&h);
    return PyLong_FromLong(ok ? ok : fallback ? -1 : 0);
fail_alloc:
    deallocate_sparse(&q, &sp);
fail:
    release_held(&h);
    return NULL;
}

/* sparse_block(topology, marching, record, table, means, dt, n_first, n_last, n_steps, save_every)
 * network_block for the sparse step: topology = (kind, par, first, second, at_pos, inc_start, inc_el,
 * inertia, sigma, load_mass, driven_el, driven_driver, driven_sign), marching and record as there (no
 * intervals: a step whose forces are not unique is a rigid loop, left to Python with counters[2] = 3)
 * and marching[6] (points) the Stribeck contacts' points (_network_curve.h: POINT_WIDTH per element),
 * means (steps, drivers) each driver's mean velocity over each step of the block: a driven element's
 * rate shift is the sum of sign * mean over its entries. */
static PyObject *sparse_block(PyObject *self, PyObject *args) {
    static const char *const march_names[] = {"marching[0] (x)",     "marching[1] (v)",    "marching[2] (state)",
                                              "marching[3] (modes)", "marching[4] (rest)", "marching[5] (counters)",
                                              "marching[6] (points)"};
    static const char *const record_names[] = {"record[0] (t)",     "record[1] (x)",     "record[2] (v)",
                                               "record[3] (force)", "record[4] (state)", "record[5] (rigid)"};
    PyObject *topo_obj, *march_obj, *rec_obj, *table_obj, *shift_obj;
    double dt;
    Py_ssize_t n_first, n_last, n_steps, save_every, n_drivers;
    if (!PyArg_ParseTuple(args, "OOOOOdnnnnn", &topo_obj, &march_obj, &rec_obj, &table_obj, &shift_obj, &dt, &n_first,
                          &n_last, &n_steps, &save_every, &n_drivers))
        return NULL;
    held_t h = {.n = 0};
    net_t q;
    sparse_t sp;
    driven_t dv;
    Py_buffer *mb[7], *rb[6];
    const Py_buffer *table, *shifts;
    if (n_drivers < 0) {
        PyErr_Format(PyExc_ValueError, "n_drivers must be >= 0, got %zd", n_drivers);
        return NULL;
    }
    if (check_real("dt", dt, 0.0, 1, 0) < 0 || check_steps(n_first, n_last, n_steps, save_every) < 0 ||
        take_sparse(&h, topo_obj, &q, &sp, &dv, n_drivers) < 0)
        goto fail;
    const Py_ssize_t nm = q.n_mass, ne = q.n_el, steps = n_last - n_first + 1;
    const Py_ssize_t march_sizes[] = {nm, nm, ne, ne, nm, 4, ne * POINT_WIDTH};
    if (take_tuple(&h, march_obj, "marching", 7, march_names, "dddqqqd", march_sizes, 1, mb) < 0 ||
        !(table = take(&h, table_obj, "table", 'd', steps * q.n_load, 0)) ||
        !(shifts = take(&h, shift_obj, "means", 'd', steps * n_drivers, 0)) ||
        !(rb[0] = take(&h, PyTuple_Check(rec_obj) && PyTuple_GET_SIZE(rec_obj) == 6 ? PyTuple_GET_ITEM(rec_obj, 0) : rec_obj,
                       record_names[0], 'd', -1, 1)))
        goto fail;
    const Py_ssize_t rows = items(rb[0]);
    const Py_ssize_t record_sizes[] = {rows, rows * nm, rows * nm, rows * ne, rows * ne, rows * ne};
    if (take_tuple(&h, rec_obj, "record", 6, record_names, "dddddB", record_sizes, 1, rb) < 0) goto fail;
    int64_t *counters = mb[5]->buf;
    if (check_rows(record_names[0], counters[0], rows, n_first, n_last, n_steps, save_every) < 0) goto fail;
    if (allocate_sparse(&q, &sp) < 0) goto fail_alloc;
    if (allocate_curves(&q) < 0) {
        PyErr_NoMemory();
        goto fail_alloc;
    }
    for (Py_ssize_t k = 0; k < dv.n; k++) q.driven[dv.el[k]] = 1;
    const double *state = mb[2]->buf;
    for (Py_ssize_t e = 0; e < ne; e++)
        q.count[e] = step_graph(q.kind[e], q.par + 4 * e, state[e], dt, q.graph + e * MAX_PIECES);
    if (check_modes(march_names[3], mb[3]->buf, q.count, ne) < 0) goto fail_alloc;
    q.dt = dt;
    sparse_springs(&q);
    march_t m = {mb[0]->buf, mb[1]->buf, mb[2]->buf, mb[3]->buf, mb[4]->buf, counters, mb[6]->buf};
    record_t o = {rb[0]->buf, rb[1]->buf, rb[2]->buf, rb[3]->buf, rb[4]->buf, rb[5]->buf, NULL, NULL};
    Py_BEGIN_ALLOW_THREADS
    march(&q, &m, &o, table->buf, &dv, shifts->buf, n_first, n_last, n_steps, save_every);
    Py_END_ALLOW_THREADS
    deallocate_sparse(&q, &sp);
    release_held(&h);
    Py_RETURN_NONE;
fail_alloc:
    deallocate_sparse(&q, &sp);
fail:
    release_held(&h);
    return NULL;
}

/* network_settings(scales, sweeps, bound): the iteration's sigma scales (floats > 0) and dual sweep
 * counts (ints > 0), at most MAX_SETTINGS each, and the bound on iterations per scale as (base,
 * per_element), ints >= 0 with base + per_element >= 1: step.SIGMA_SCALES, step.DUAL_SWEEPS and
 * step.BOUND. */
static PyObject *network_settings(PyObject *self, PyObject *args) {
    PyObject *scales, *sweeps;
    int base, per_element;
    if (!PyArg_ParseTuple(args, "O!O!(ii)", &PyTuple_Type, &scales, &PyTuple_Type, &sweeps, &base, &per_element))
        return NULL;
    if (base < 0 || per_element < 0 || base + per_element < 1 || base > 1000000 || per_element > 1000) {
        PyErr_SetString(PyExc_ValueError, "bound must be (base, per_element), ints >= 0, base + per_element >= 1");
        return NULL;
    }
    const Py_ssize_t ns = PyTuple_GET_SIZE(scales), nw = PyTuple_GET_SIZE(sweeps);
    if (ns < 1 || ns > MAX_SETTINGS || nw > MAX_SETTINGS) {
        PyErr_Format(PyExc_ValueError, "scales must hold 1 to %d values and sweeps at most %d", MAX_SETTINGS, MAX_SETTINGS);
        return NULL;
    }
    double s[MAX_SETTINGS];
    long w[MAX_SETTINGS];
    for (Py_ssize_t i = 0; i < ns; i++) {
        s[i] = PyFloat_AsDouble(PyTuple_GET_ITEM(scales, i));
        if (PyErr_Occurred()) return NULL;
        if (!(s[i] > 0.0) || !isfinite(s[i])) {
            PyErr_Format(PyExc_ValueError, "scales[%zd] must be > 0 and finite", i);
            return NULL;
        }
    }
    for (Py_ssize_t i = 0; i < nw; i++) {
        w[i] = PyLong_AsLong(PyTuple_GET_ITEM(sweeps, i));
        if (PyErr_Occurred()) return NULL;
        if (w[i] < 1 || w[i] > 1000000) {
            PyErr_Format(PyExc_ValueError, "sweeps[%zd] must be in 1..1000000", i);
            return NULL;
        }
    }
    for (Py_ssize_t i = 0; i < ns; i++) SCALES[i] = s[i];
    for (Py_ssize_t i = 0; i < nw; i++) SWEEPS[i] = (int)w[i];
    N_SCALES = (int)ns, N_SWEEPS = (int)nw;
    BOUND_BASE = base, BOUND_PER_ELEMENT = per_element;
    Py_RETURN_NONE;
}

static PyMethodDef methods[] = {
    {"network_settings", network_settings, METH_VARARGS, "The iteration's sigma scales, dual sweep counts and bound on iterations."},
    {"network_block", network_block, METH_VARARGS, "Backward Euler for a forest network, one block of steps."},
    {"network_solve", network_solve, METH_VARARGS, "One step problem of a forest network with given graphs."},
    {"sparse_block", sparse_block, METH_VARARGS, "Backward Euler for any network (the sparse step), one block of steps."},
    {"sparse_solve", sparse_solve, METH_VARARGS, "One step problem of any network with given graphs (the sparse step)."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_network_kernel", NULL, -1, methods};

PyMODINIT_FUNC PyInit__network_kernel(void) { return PyModule_Create(&module); }
