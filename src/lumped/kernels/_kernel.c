/* Algorithm 1 (backward Euler) for a Bingham or Coulomb dashpot: the compiled
 * twin of lumped.solvers.backward_euler._bingham_block.  Same operations in the same
 * order, compiled without floating-point contraction, so the numbers are
 * bit-identical to the pure-Python loop.  Uses only the CPython buffer API.
 *
 * The corrector (lines 5 to 10) below is necessarily a second copy, in C, of
 * lumped.laws.bingham_corrector, the one Python copy, which the Python loop
 * calls.  Change both together: tests/test_algorithm1.py compares this kernel
 * with the Python loop bit for bit (np.array_equal), and checks that the
 * Python loop goes through bingham_corrector at every step.
 *
 * One call advances steps n_first..n_last; the driver calls it block by block
 * (so that Ctrl-C is seen between blocks) and carries the state in two small
 * arrays: state = (F_s, v, F_d), counters = (row, rest_start, bad_step,
 * bad_quantity).  rest_start is the first step of the current run of v == 0;
 * a non-finite v, F_d or F_s stops the loop with bad_step and bad_quantity
 * (1: v, 2: F_d, 3: F_s) set and that step not saved.  The binding checks
 * every argument first (_binding_checks.h): a bad one raises ValueError. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>
#include <stdint.h>
#define SINE_LANES 1
#include "_sine.h" /* the project's sine, one lane: project_sine1 */

#include "_binding_checks.h"
#include "_stick.h" /* the stick test and the corrector, shared by every kernel */

/* The arguments' checks (see _binding_checks.h): -1 with ValueError if one is bad. */
static int check_block(held_t *h, const double *p, Py_ssize_t n_first, Py_ssize_t n_last, Py_ssize_t n_steps,
                       Py_ssize_t save_every, PyObject *const *arrays) {
    static const char *names[] = {"m", "k", "dt", "tau", "c", "amp", "omega", "phase", "until"};
    for (int i = 0; i < 9; i++) {
        const int positive = i < 3, non_negative = i == 3 || i == 4, time = i == 8;
        if (check_real(names[i], p[i], positive || non_negative || time ? 0.0 : -INFINITY, positive, time) < 0)
            return -1;
    }
    if (check_steps(n_first, n_last, n_steps, save_every) < 0) return -1;
    const Py_buffer *table = take(h, arrays[0], "force_values", 'd', -1, 0);
    if (table == NULL || !take(h, arrays[1], "state", 'd', 3, 1)) return -1;
    const Py_buffer *counters = take(h, arrays[2], "counters", 'q', 4, 1);
    const Py_buffer *out = counters ? take(h, arrays[3], "out", 'd', -1, 1) : NULL;
    if (out == NULL) return -1;
    if (items(table) != 0 && items(table) != n_last - n_first + 1) {
        PyErr_Format(PyExc_ValueError, "force_values must hold 0 or n_last - n_first + 1 = %zd float64 values, got %zd",
                     n_last - n_first + 1, items(table));
        return -1;
    }
    if (items(out) % 6 != 0) {
        PyErr_Format(PyExc_ValueError, "out must have 6 columns (t, x, v, F_s, F_d, F), got %zd values", items(out));
        return -1;
    }
    const int64_t row = ((const int64_t *)counters->buf)[0];
    return check_rows("out", row, items(out) / 6, n_first, n_last, n_steps, save_every);
}

static PyObject *bingham_block(PyObject *self, PyObject *args) {
    double m, k, dt, tau, c, amp, omega, phase, until;
    Py_ssize_t n_first, n_last, n_steps, save_every;
    PyObject *arrays[4];
    if (!PyArg_ParseTuple(args, "dddddnnnnddddOOOO", &m, &k, &dt, &tau, &c, &n_first, &n_last, &n_steps,
                          &save_every, &amp, &omega, &phase, &until, arrays, arrays + 1, arrays + 2, arrays + 3))
        return NULL;
    held_t h = {.n = 0};
    const double p[] = {m, k, dt, tau, c, amp, omega, phase, until};
    if (check_block(&h, p, n_first, n_last, n_steps, save_every, arrays) < 0) {
        release_held(&h);
        return NULL;
    }
    const Py_buffer *table = h.b, *state = h.b + 1, *counters = h.b + 2, *out = h.b + 3;
    const double *force_values = (const double *)table->buf;
    double *st = (double *)state->buf, *o = (double *)out->buf;
    int64_t *cnt = (int64_t *)counters->buf;
    const int tabulated = table->len > 0;
    Py_BEGIN_ALLOW_THREADS
    const double eta = m / dt + k * dt;
    double f_s = st[0], v = st[1], f_d = st[2], f;
    int64_t row = cnt[0], rest_start = cnt[1];
    for (Py_ssize_t n = n_first; n <= n_last; n++) {
        const double t = (double)n * dt;
        if (tabulated) f = force_values[n - n_first];
        else if (t <= until) f = amp * project_sine1((sine_vd1){omega * t + phase})[0];
        else f = 0.0;
        const double predictor = (m / dt) * v + f - f_s;
        bingham_corrector1(predictor, eta, tau, c, &f_d, &v); /* lines 5-10, _stick.h */
        f_s = f_s + dt * k * v;
        if (!(isfinite(v) && isfinite(f_d) && isfinite(f_s))) {
            cnt[2] = n;
            cnt[3] = !isfinite(v) ? 1 : !isfinite(f_d) ? 2 : 3;
            break;
        }
        if (v != 0.0) rest_start = n + 1;
        if (n % save_every == 0 || n == n_steps) {
            double *r = o + 6 * row;
            r[0] = t; r[1] = f_s / k; r[2] = v; r[3] = f_s; r[4] = f_d; r[5] = f;
            row++;
        }
    }
    st[0] = f_s; st[1] = v; st[2] = f_d;
    cnt[0] = row; cnt[1] = rest_start;
    Py_END_ALLOW_THREADS
    release_held(&h);
    Py_RETURN_NONE;
}

/* Test hook: the project's sine (one lane) of every double of a writable buffer, in place. */
static PyObject *sine(PyObject *self, PyObject *args) {
    Py_buffer values;
    if (!PyArg_ParseTuple(args, "w*", &values)) return NULL;
    if (values.itemsize != (Py_ssize_t)sizeof(double) || values.len % (Py_ssize_t)sizeof(double)) {
        PyBuffer_Release(&values);
        PyErr_SetString(PyExc_ValueError, "sine: the buffer must hold doubles");
        return NULL;
    }
    double *x = (double *)values.buf;
    for (Py_ssize_t i = 0; i < values.len / (Py_ssize_t)sizeof(double); i++) x[i] = project_sine1((sine_vd1){x[i]})[0];
    PyBuffer_Release(&values);
    Py_RETURN_NONE;
}

static PyMethodDef methods[] = {
    {"bingham_block", bingham_block, METH_VARARGS, "Algorithm 1 for the Bingham law, one block."},
    {"sine", sine, METH_VARARGS, "The project's sine of a buffer of doubles, in place (a test hook)."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_kernel", NULL, -1, methods};

PyMODINIT_FUNC PyInit__kernel(void) { return PyModule_Create(&module); }
