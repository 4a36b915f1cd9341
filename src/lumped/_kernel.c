/* Algorithm 1 (backward Euler) for a Bingham or Coulomb dashpot: the compiled
 * twin of lumped.timestepping._bingham_loop.  Same operations in the same
 * order, compiled without floating-point contraction, so the numbers are
 * bit-identical to the pure-Python loop.  Uses only the CPython buffer API. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>

static PyObject *bingham_loop(PyObject *self, PyObject *args) {
    double m, k, dt, tau, c, x0, v0, amp, omega, phase, until;
    Py_ssize_t n_steps, save_every;
    Py_buffer table, out;
    if (!PyArg_ParseTuple(args, "dddddddnnddddy*w*", &m, &k, &dt, &tau, &c, &x0, &v0,
                          &n_steps, &save_every, &amp, &omega, &phase, &until, &table, &out))
        return NULL;
    const double *force_values = (const double *)table.buf;
    double *o = (double *)out.buf;
    const int tabulated = table.len > 0;
    Py_BEGIN_ALLOW_THREADS
    const double eta = m / dt + k * dt;
    double f_s = k * x0, v = v0, f, f_d = 0.0;
    Py_ssize_t row = 1;
    for (Py_ssize_t n = 1; n <= n_steps; n++) {
        const double t = (double)n * dt;
        if (tabulated) f = force_values[n];
        else if (t <= until) f = amp * sin(omega * t + phase);
        else f = 0.0;
        const double predictor = (m / dt) * v + f - f_s;
        if (fabs(predictor) <= tau) {
            v = 0.0;
            f_d = predictor;
        } else {
            const double signed_tau = copysign(tau, predictor);
            f_d = (eta * signed_tau + c * predictor) / (eta + c);
            v = (predictor - signed_tau) / (eta + c);
        }
        f_s = f_s + dt * k * v;
        if (n % save_every == 0 || n == n_steps) {
            double *r = o + 6 * row;
            r[0] = t; r[1] = f_s / k; r[2] = v; r[3] = f_s; r[4] = f_d; r[5] = f;
            row++;
        }
    }
    Py_END_ALLOW_THREADS
    PyBuffer_Release(&table);
    PyBuffer_Release(&out);
    Py_RETURN_NONE;
}

static PyMethodDef methods[] = {
    {"bingham_loop", bingham_loop, METH_VARARGS, "Algorithm 1 for the Bingham law."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_kernel", NULL, -1, methods};

PyMODINIT_FUNC PyInit__kernel(void) { return PyModule_Create(&module); }
