/* Backward Euler for one mass with a friction contact: the compiled loop of
 * lumped.solvers.friction_compiled, and its binding.
 *
 * The system: one mass; linear springs (state: the force) and linear
 * dashpots, each between the mass and the ground or a driven point at a
 * constant velocity; and one friction contact of lumped.laws.StribeckLaw (its
 * kernel_form(): code 0 no fall, 1 exponential, 2 gaussian, 3 rational
 * decay; law = (static, kinetic, v_s, viscous)), also to the ground or a
 * driven point.  An element joined to a driven point sees the problem's rate
 * plus `delta` (lumped.laws.step_graph.Shifted): its pieces are shifted as
 * _shift_piece shifts them.
 *
 * One step is lumped.solvers.network_step.solve_step for this system, with
 * the contact's rule of lumped.laws.step_graph._slip_rule: a stuck contact
 * stays stuck while |f| <= static and slips the way it is pulled beyond; a
 * slipping one slips while its rate keeps its sign, else sticks (and is then
 * tested against static again).  The linear solve with the modes fixed is the
 * Python step's for one mass, operation for operation and in element order
 * (merged_system.assemble, network_step._rigid_forces), so that with a
 * linear slip curve (code 0) the numbers are the Python step's bit for bit.
 * On a Stribeck branch (codes 1 to 3) the slip speed s of the whole step
 * solves g(s) + E s = y (E the mass's m/dt plus its springs' k dt and
 * dashpots' c, y the contact's resolvent variable), unique when E exceeds the
 * curve's steepest fall (lumped.solvers.uniqueness.check_step), by Newton's
 * method safeguarded by bisection on the bracket (0, y/E]; the Python step
 * reaches the same root by its resolvent iteration, so the two agree to the
 * root solves' tolerance.  tests/test_friction_kernel.py holds them together.
 *
 * One call advances steps n_first..n_last (the driver calls it block by
 * block, with the block's loads tabulated, or none).  counters = (row,
 * bad_step, bad_kind, most_iterations); bad_kind 1: the rule did not settle,
 * 2: a velocity or force is not finite; that step is not saved.  Uses only
 * the CPython buffer API. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <float.h>
#include <math.h>
#include <stdint.h>

#include "_binding_checks.h"
#include "_slip_curve.h" /* law_t, slip_curve, slip_speed: the Stribeck slip curve and its root */

enum { SPRING = 0, DASHPOT = 1, CONTACT = 2 }; /* the roles of friction_compiled.plan */
enum { STICK = 0 };                             /* the contact's mode: -1, 0 (stuck), +1 */
#define MAX_RULE 8 /* the rule settles in at most 3 solves (stick, slip, stick); more is a failure */

typedef struct {
    Py_ssize_t n_el, contact;
    const int64_t *role;
    const double *par, *sign, *delta;
    law_t law;
    double inertia, dt;
    double *a, *b, *w, *f; /* each element's piece f = a + b w and its rate and force (n_el each) */
    double speed[3];       /* the contact's last slip speeds on a Stribeck branch, newest first */
    int known;             /* how many of them follow one another (0 after a stick) */
} sys_t;

/* ---- one step ------------------------------------------------------------- */

/* The pieces of the springs and dashpots (Element.step_graph, shifted by delta). */
static void free_pieces(sys_t *q, const double *state) {
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        if (q->role[e] == SPRING) q->a[e] = state[e], q->b[e] = q->dt * q->par[e];
        else if (q->role[e] == DASHPOT) q->a[e] = 0.0, q->b[e] = q->par[e];
        else continue;
        if (q->delta[e] != 0.0) q->a[e] = q->a[e] + q->b[e] * q->delta[e];
    }
}

/* The rate of element e at the mass velocity v: v_second - v_first, the ground (or driver) at 0. */
static double rate(const sys_t *q, Py_ssize_t e, double v) { return q->sign[e] > 0 ? v - 0.0 : 0.0 - v; }

/* The contact stuck (its rigid piece w = -delta): the mass moves with the point it is stuck to; the
 * contact's force from the mass's momentum balance (network_step._rigid_forces). */
static double stuck(sys_t *q, double rhs) {
    const Py_ssize_t c = q->contact;
    const double a = q->delta[c] != 0.0 ? 0.0 - q->delta[c] : 0.0;
    const double v = q->sign[c] > 0 ? 0.0 + a : 0.0 + -a;
    double pushed = 0.0;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        if (e == c) continue;
        q->w[e] = rate(q, e, v);
        q->f[e] = q->a[e] + q->b[e] * q->w[e];
        pushed = q->sign[e] > 0 ? pushed + q->f[e] : pushed - q->f[e];
    }
    const double gap = (rhs - q->inertia * v) - pushed;
    q->w[c] = a;
    q->f[c] = q->sign[c] * gap;
    return v;
}

/* The mass velocity with every piece free (merged_system.assemble for one unknown, in element order). */
static double free_solve(sys_t *q, double rhs) {
    double load = rhs, diag = q->inertia;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        load = q->sign[e] > 0 ? load - q->a[e] : load + q->a[e];
        if (q->b[e] != 0.0) diag = diag + q->b[e];
    }
    const double v = load / diag;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        q->w[e] = rate(q, e, v);
        q->f[e] = q->a[e] + q->b[e] * q->w[e];
    }
    return v;
}

/* The contact slipping in `direction` on a linear slip curve (code 0): its piece (SlipGraph), then
 * the free solve; the new mode by the rule (slipping while the true rate keeps its sign). */
static double slip_linear(sys_t *q, double rhs, int direction, int *mode) {
    const Py_ssize_t c = q->contact;
    q->a[c] = direction > 0 ? q->law.kin : -q->law.kin, q->b[c] = q->law.visc;
    if (q->delta[c] != 0.0) q->a[c] = q->a[c] + q->b[c] * q->delta[c];
    const double v = free_solve(q, rhs), u = q->w[c] + q->delta[c];
    *mode = direction > 0 ? (u > 0 ? 1 : STICK) : (u < 0 ? -1 : STICK);
    return v;
}

/* Newton's start: the last slip speeds extrapolated by the parabola through them (the step changes
 * s by O(dt); the parabola's error is O(dt^3), within the reach of one Newton step at dt = 1e-3 on the
 * belt: benchmarks/bench_belt.py), or -1 after a stick (slip_speed then starts from the tangent at 0). */
static double guess(const sys_t *q) {
    const double *s = q->speed;
    if (q->known == 3) return 3.0 * (s[0] - s[1]) + s[2];
    if (q->known == 2) return 2.0 * s[0] - s[1];
    return q->known == 1 ? s[0] : -1.0;
}

/* The contact slipping in `direction` on a Stribeck branch: the step's slip speed (slip_speed), or
 * STICK when the branch has no point (y at most g(0+) = static). */
static double slip_curve_step(sys_t *q, double rhs, int direction, int *mode) {
    const Py_ssize_t c = q->contact;
    double load = rhs, E = q->inertia;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        if (e == c) continue;
        load = q->sign[e] > 0 ? load - q->a[e] : load + q->a[e];
        E = E + q->b[e];
    }
    /* f_c + E u_c = sign_c load + E delta_c on the step, u_c the contact's true rate */
    const double y = direction * (q->sign[c] * load + E * q->delta[c]);
    if (!(y > q->law.stat)) {
        *mode = STICK;
        return 0.0;
    }
    double slope;
    const double s = slip_speed(&q->law, y, E, guess(q));
    q->speed[2] = q->speed[1], q->speed[1] = q->speed[0], q->speed[0] = s;
    q->known += q->known < 3;
    q->f[c] = direction * slip_curve(&q->law, s, &slope);
    const double v = (load - q->sign[c] * q->f[c]) / E;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        q->w[e] = rate(q, e, v);
        if (e != c) q->f[e] = q->a[e] + q->b[e] * q->w[e];
    }
    *mode = direction;
    return v;
}

/* One step from the mass velocity v and the element states: the new velocity, the contact's mode;
 * 0 if the rule did not settle within MAX_RULE solves (*iterations: the solves taken). */
static int step(sys_t *q, double rhs, const double *state, double *v, int *mode, int *iterations) {
    free_pieces(q, state);
    int old = state[q->contact] > 0 ? 1 : state[q->contact] < 0 ? -1 : STICK;
    for (int it = 1; it <= MAX_RULE; it++) {
        int next;
        if (old == STICK) {
            *v = stuck(q, rhs);
            const double f = q->f[q->contact];
            next = f > q->law.stat ? 1 : f < -q->law.stat ? -1 : STICK;
        } else if (q->law.code == 0) {
            *v = slip_linear(q, rhs, old, &next);
        } else {
            *v = slip_curve_step(q, rhs, old, &next);
        }
        if (next == old) {
            *mode = old, *iterations = it;
            return 1;
        }
        old = next;
    }
    return 0;
}

typedef struct {
    double *x, *v, *state;
    int64_t *rest, *counters;
} march_t;

typedef struct {
    double *t, *x, *v, *force, *state;
    uint8_t *rigid;
} record_t;

static void save(const sys_t *q, const march_t *m, const record_t *o, double t, int64_t row, int mode) {
    const Py_ssize_t ne = q->n_el;
    o->t[row] = t, o->x[row] = m->x[0], o->v[row] = m->v[0];
    for (Py_ssize_t e = 0; e < ne; e++) {
        o->force[row * ne + e] = q->f[e];
        o->state[row * ne + e] = m->state[e];
        o->rigid[row * ne + e] = (uint8_t)(e == q->contact && mode == STICK);
    }
}

static void march(sys_t *q, march_t *m, const record_t *o, const double *table, int tabulated, Py_ssize_t n_first,
                  Py_ssize_t n_last, Py_ssize_t n_steps, Py_ssize_t save_every) {
    int64_t *cnt = m->counters;
    for (Py_ssize_t n = n_first; n <= n_last; n++) {
        const double rhs = q->inertia * m->v[0] + (tabulated ? table[n - n_first] : 0.0);
        double v;
        int mode, iterations;
        if (!step(q, rhs, m->state, &v, &mode, &iterations)) {
            cnt[1] = n, cnt[2] = 1;
            return;
        }
        int finite = isfinite(v);
        for (Py_ssize_t e = 0; e < q->n_el; e++) finite &= isfinite(q->f[e]);
        if (!finite) {
            cnt[1] = n, cnt[2] = 2;
            return;
        }
        if (iterations > cnt[3]) cnt[3] = iterations;
        if (mode == STICK) q->known = 0;
        m->v[0] = v;
        m->x[0] = m->x[0] + q->dt * v;
        for (Py_ssize_t e = 0; e < q->n_el; e++) { /* Element.next_state */
            if (q->role[e] == SPRING) m->state[e] = q->f[e];
            else if (q->role[e] == DASHPOT) m->state[e] = 0.0;
            else {
                const double u = q->w[e] + q->delta[e];
                m->state[e] = mode == STICK || u == 0.0 ? 0.0 : copysign(1.0, u);
            }
        }
        if (v != 0.0) m->rest[0] = n + 1;
        if (n % save_every == 0 || n == n_steps) save(q, m, o, (double)n * q->dt, cnt[0]++, mode);
    }
}

/* ---- the Python binding ------------------------------------------------------ */

/* The system's checks: roles 0..2 with exactly one contact, signs +-1, finite parameters and shifts. */
static int check_plan(sys_t *q) {
    q->contact = -1;
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        const int64_t r = q->role[e];
        if (r < SPRING || r > CONTACT || (r == CONTACT && q->contact >= 0)) {
            PyErr_Format(PyExc_ValueError, "plan[0] (role) must be 0, 1 or 2 with one 2, got %lld at %zd", (long long)r, e);
            return -1;
        }
        if (r == CONTACT) q->contact = e;
    }
    if (q->contact < 0) {
        PyErr_SetString(PyExc_ValueError, "plan[0] (role) must name one contact (2)");
        return -1;
    }
    for (Py_ssize_t e = 0; e < q->n_el; e++) {
        if (q->sign[e] != 1.0 && q->sign[e] != -1.0) {
            PyErr_Format(PyExc_ValueError, "plan[2] (sign) must be +1 or -1, at %zd", e);
            return -1;
        }
        if (check_real("plan[1] (par)", q->par[e], 0.0, q->role[e] == SPRING, 0) < 0 ||
            check_real("plan[3] (delta)", q->delta[e], -INFINITY, 0, 0) < 0)
            return -1;
    }
    const law_t *l = &q->law;
    if (l->code < 0 || l->code > 3) {
        PyErr_Format(PyExc_ValueError, "code must be 0 to 3, got %d", l->code);
        return -1;
    }
    if (check_real("static", l->stat, 0.0, 1, 0) < 0 || check_real("kinetic", l->kin, 0.0, 0, 0) < 0 ||
        check_real("static - kinetic", l->stat - l->kin, 0.0, 0, 0) < 0 ||
        check_real("stribeck_velocity", l->vs, 0.0, l->code != 0, 0) < 0 || check_real("viscous", l->visc, 0.0, 0, 0) < 0)
        return -1;
    return 0;
}

/* friction_block(plan, law, marching, record, table, dt, inertia, n_first, n_last, n_steps, save_every)
 * plan = (role, par, sign, delta), one value per element; law = (code, static, kinetic, v_s, viscous);
 * marching = (x, v, state, rest, counters); record = (t, x, v, force, state, rigid); table: the load
 * on the mass at each step of the block, or empty (no load). */
static PyObject *friction_block(PyObject *self, PyObject *args) {
    static const char *const plan_names[] = {"plan[0] (role)", "plan[1] (par)", "plan[2] (sign)", "plan[3] (delta)"};
    static const char *const march_names[] = {"marching[0] (x)", "marching[1] (v)", "marching[2] (state)",
                                              "marching[3] (rest)", "marching[4] (counters)"};
    static const char *const record_names[] = {"record[0] (t)",     "record[1] (x)",     "record[2] (v)",
                                               "record[3] (force)", "record[4] (state)", "record[5] (rigid)"};
    PyObject *plan_obj, *march_obj, *rec_obj, *table_obj, *first_plan;
    sys_t q = {0};
    Py_ssize_t n_first, n_last, n_steps, save_every;
    if (!PyArg_ParseTuple(args, "O(idddd)OOOddnnnn", &plan_obj, &q.law.code, &q.law.stat, &q.law.kin, &q.law.vs,
                          &q.law.visc, &march_obj, &rec_obj, &table_obj, &q.dt, &q.inertia, &n_first, &n_last,
                          &n_steps, &save_every))
        return NULL;
    held_t h = {.n = 0};
    Py_buffer *pb[4], *mb[5], *rb[6];
    const Py_buffer *table;
    PyObject *const *pa = tuple_items(plan_obj, "plan", 4);
    if (pa == NULL || check_real("dt", q.dt, 0.0, 1, 0) < 0 || check_real("inertia", q.inertia, 0.0, 1, 0) < 0 ||
        check_steps(n_first, n_last, n_steps, save_every) < 0)
        goto fail;
    first_plan = pa[0];
    if (!(pb[0] = take(&h, first_plan, plan_names[0], 'q', -1, 0))) goto fail;
    q.n_el = items(pb[0]);
    const Py_ssize_t ne = q.n_el, plan_sizes[] = {ne, ne, ne, ne}, march_sizes[] = {1, 1, ne, 1, 4};
    if (take_tuple(&h, plan_obj, "plan", 4, plan_names, "qddd", plan_sizes, 0, pb) < 0 ||
        take_tuple(&h, march_obj, "marching", 5, march_names, "dddqq", march_sizes, 1, mb) < 0 ||
        !(table = take(&h, table_obj, "table", 'd', -1, 0)))
        goto fail;
    const int tabulated = items(table) > 0;
    if (tabulated && items(table) != n_last - n_first + 1) {
        PyErr_Format(PyExc_ValueError, "table must hold 0 or n_last - n_first + 1 = %zd float64 values, got %zd",
                     n_last - n_first + 1, items(table));
        goto fail;
    }
    PyObject *const *r = tuple_items(rec_obj, "record", 6);
    if (r == NULL || !(rb[0] = take(&h, r[0], record_names[0], 'd', -1, 1))) goto fail;
    const Py_ssize_t rows = items(rb[0]), record_sizes[] = {rows, rows, rows, rows * ne, rows * ne, rows * ne};
    if (take_tuple(&h, rec_obj, "record", 6, record_names, "dddddB", record_sizes, 1, rb) < 0) goto fail;
    q.role = pb[0]->buf, q.par = pb[1]->buf, q.sign = pb[2]->buf, q.delta = pb[3]->buf;
    int64_t *counters = mb[4]->buf;
    if (check_plan(&q) < 0 || check_rows(record_names[0], counters[0], rows, n_first, n_last, n_steps, save_every) < 0)
        goto fail;
    double *work = PyMem_Malloc(4 * (size_t)ne * sizeof(double));
    if (work == NULL) {
        PyErr_NoMemory();
        goto fail;
    }
    q.a = work, q.b = work + ne, q.w = work + 2 * ne, q.f = work + 3 * ne;
    for (Py_ssize_t e = 0; e < 4 * ne; e++) work[e] = 0.0;
    march_t m = {mb[0]->buf, mb[1]->buf, mb[2]->buf, mb[3]->buf, counters};
    record_t o = {rb[0]->buf, rb[1]->buf, rb[2]->buf, rb[3]->buf, rb[4]->buf, rb[5]->buf};
    Py_BEGIN_ALLOW_THREADS
    march(&q, &m, &o, table->buf, tabulated, n_first, n_last, n_steps, save_every);
    Py_END_ALLOW_THREADS
    PyMem_Free(work);
    release_held(&h);
    Py_RETURN_NONE;
fail:
    release_held(&h);
    return NULL;
}

static PyMethodDef methods[] = {
    {"friction_block", friction_block, METH_VARARGS, "Backward Euler for one mass with a friction contact, one block."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_friction_kernel", NULL, -1, methods};

PyMODINIT_FUNC PyInit__friction_kernel(void) { return PyModule_Create(&module); }
