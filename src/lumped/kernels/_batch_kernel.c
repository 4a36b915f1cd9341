/* Algorithm 1 (backward Euler, Bingham or Coulomb dashpot) over many
 * parameter sets at once, keeping per-trajectory summaries: the compiled twin
 * of lumped.kernels.batched._numpy_batch.
 *
 * Each trajectory takes exactly the operations of the single-run kernel
 * (_kernel.c), in the same order, compiled without floating-point
 * contraction, with the same sine (the project's own, _sine.h, not the C
 * library's), so v and F_s are bit-identical to one run of
 * lumped.solvers.backward_euler.backward_euler.  The dashpot force F_d does not feed
 * back into the step (only v and F_s do), so it is not formed.  One
 * difference, in a value not kept: with a zero forcing amplitude the force is
 * +0.0 without evaluating amp*sin(...), which could be -0.0; that only ever
 * changes the sign of a zero predictor, hence of a zero F_d.  Blocks with
 * no forcing skip the forcing and the addition of that +0.0 altogether, for
 * the same reason.
 *
 * Layout: the trajectories are cut into blocks of BLOCK (_batch_block.h); the
 * blocks are shared among the threads (OpenMP); within a block the time loop
 * is outside, in chunks of CHUNK steps, and the loop over the block's
 * trajectories inside, written in vector lanes (_batch_lanes.h) with the
 * stick test, the switch of the forcing and the sine's quadrant as blends:
 * GROUP vectors at a time,
 * their state kept in registers over the chunk and their independent chains
 * interleaved.  Four variants (forced or not, window bookkeeping or not) are
 * compiled; the window's is used from the block's first window step on.  The
 * loop is compiled for AVX-512 (8 lanes), AVX2 (4 lanes) and the baseline
 * SSE2 (2 lanes); "auto" runs the widest the CPU has, the optional last
 * argument path picks one.  All give the same bits.  Counters are kept as
 * doubles (exact integers below 2^53) so that the inner loop is all double
 * lanes.
 *
 * One call advances steps first..last of the grid 1..n_steps; with first > 1
 * it resumes from the summaries that a call ending at step first-1 wrote
 * (v_N and F_s,N are the state, the rest are running counts), so the caller
 * can bound the work of each call and see signals between calls.
 *
 * Arguments: dt, first, last, n_steps, save_every (0: keep nothing), then
 * C-contiguous buffers of doubles
 *   par   (read)  double[10][n]: m, k, tau, c, x0, v0, amp, omega, phase, until
 *   nw    (read)  double[n]: first step of the summary window (n_steps+1: none)
 *   sums  (write; read too when first > 1) double[7][n]: v, F_s, rest_start,
 *                 stops, window stops, max |F_s| over steps >= 1, max |F_s|
 *                 over window steps >= 1 (after step last)
 *   xs    (write) double[rows][n]: x = F_s/k at the saved steps of first..last
 *                 (multiples of save_every, and n_steps): exactly rows*n
 *   path  (optional str) "auto" (default), "avx512", "avx2" or "default" */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "_batch_block.h" /* BLOCK, NPAR, NSUM; first, so that its helpers are compiled for the baseline */

/* The same loop compiled three times: for AVX-512 (eight lanes in one
 * register), AVX2 (four) and the baseline x86-64 (two, SSE2); all give the
 * same bits (IEEE operations on each lane, no contraction, the same sine).
 * "auto" runs the widest the CPU has. */
#pragma GCC push_options
#pragma GCC target("avx512f")
#define LANES 8
#define GROUP 4
#include "_batch_lanes.h"
#undef GROUP
#undef LANES
#pragma GCC pop_options
#pragma GCC push_options
#pragma GCC target("avx2")
#define LANES 4
#define GROUP 4
#include "_batch_lanes.h"
#undef GROUP
#undef LANES
#pragma GCC pop_options
#define LANES 2
#define GROUP 4
#include "_batch_lanes.h"
#undef GROUP
#undef LANES

typedef void (*RunBlock)(const double *, const double *, double *, double *, Py_ssize_t, Py_ssize_t, double,
                         Py_ssize_t, Py_ssize_t, Py_ssize_t, Py_ssize_t);
typedef void (*SineBuffer)(double *, Py_ssize_t);

static int cpu_has(const char *feature) {
    __builtin_cpu_init();
    return !strcmp(feature, "avx512f") ? __builtin_cpu_supports("avx512f") : __builtin_cpu_supports("avx2");
}

/* The widest path the CPU runs. */
static const char *best(void) { return cpu_has("avx512f") ? "avx512" : cpu_has("avx2") ? "avx2" : "default"; }

/* The path named (auto: the best), or NULL with a ValueError set. */
static const char *resolve_path(const char *who, const char *path) {
    if (!strcmp(path, "auto")) return best();
    if (strcmp(path, "avx512") && strcmp(path, "avx2") && strcmp(path, "default")) {
        PyErr_Format(PyExc_ValueError, "%s: path must be 'auto', 'avx512', 'avx2' or 'default', got '%.40s'", who,
                     path);
        return NULL;
    }
    if ((!strcmp(path, "avx512") && !cpu_has("avx512f")) || (!strcmp(path, "avx2") && !cpu_has("avx2"))) {
        PyErr_Format(PyExc_ValueError, "%s: path '%s' requested but this CPU does not have it", who, path);
        return NULL;
    }
    return path;
}

/* A C-contiguous buffer of doubles (writable if asked), or -1 with a ValueError naming it. */
static int doubles(PyObject *obj, Py_buffer *view, int writable, const char *name) {
    if (PyObject_GetBuffer(obj, view, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0)) < 0) {
        PyErr_Clear();
        PyErr_Format(PyExc_ValueError, "bingham_batch: %s must be a C-contiguous%s buffer of doubles", name,
                     writable ? " writable" : "");
        return -1;
    }
    if (view->itemsize != (Py_ssize_t)sizeof(double) || view->format == NULL || strcmp(view->format, "d")) {
        PyBuffer_Release(view);
        PyErr_Format(PyExc_ValueError, "bingham_batch: %s must hold doubles (format 'd'), got format '%s'", name,
                     view->format == NULL ? "B" : view->format);
        return -1;
    }
    return 0;
}

/* Saved steps in first..last: the multiples of save_every, and n_steps. */
static Py_ssize_t saved_rows(Py_ssize_t first, Py_ssize_t last, Py_ssize_t n_steps, Py_ssize_t save_every) {
    if (save_every < 1 || last < first) return 0;
    return last / save_every - (first - 1) / save_every + (last == n_steps && n_steps % save_every != 0);
}

/* The arguments' problem, or NULL; n is the trajectories (nw's length). */
static const char *check(double dt, Py_ssize_t first, Py_ssize_t last, Py_ssize_t n_steps, Py_ssize_t save_every,
                         Py_ssize_t n, const Py_buffer *par, const Py_buffer *sums, const Py_buffer *xs) {
    const Py_ssize_t d = (Py_ssize_t)sizeof(double);
    if (!(dt > 0.0 && isfinite(dt))) return "dt must be > 0 and finite";
    if (n_steps < 0) return "n_steps must be >= 0";
    if (first < 1 || last > n_steps || first > last + 1) return "steps must satisfy 1 <= first <= last + 1 <= n_steps + 1";
    if (save_every < 0) return "save_every must be >= 0 (0: keep nothing)";
    if (n > PY_SSIZE_T_MAX / (NPAR * d)) return "too many trajectories";
    if (par->len != NPAR * n * d) return "par must hold 10 rows of n doubles (n = len(nw))";
    if (sums->len != NSUM * n * d) return "sums must hold 7 rows of n doubles (n = len(nw))";
    const Py_ssize_t rows = saved_rows(first, last, n_steps, save_every);
    if (save_every == 0 && xs->len != 0) return "xs must be empty when save_every is 0";
    if (n > 0 && rows > PY_SSIZE_T_MAX / (n * d)) return "xs would be too large";
    if (xs->len != rows * n * d) return "xs must hold exactly rows*n doubles (rows: the saved steps of first..last)";
    return NULL;
}

static PyObject *bingham_batch(PyObject *self, PyObject *args) {
    double dt;
    Py_ssize_t first, last, n_steps, save_every;
    PyObject *objects[4];
    Py_buffer par, nw, sums, xs;
    const char *path = "auto";
    if (!PyArg_ParseTuple(args, "dnnnnOOOO|s", &dt, &first, &last, &n_steps, &save_every, &objects[0], &objects[1],
                          &objects[2], &objects[3], &path))
        return NULL;
    if (doubles(objects[0], &par, 0, "par") < 0) return NULL;
    if (doubles(objects[1], &nw, 0, "nw") < 0) goto release_par;
    if (doubles(objects[2], &sums, 1, "sums") < 0) goto release_nw;
    if (doubles(objects[3], &xs, 1, "xs") < 0) goto release_sums;
    const Py_ssize_t n = nw.len / (Py_ssize_t)sizeof(double);
    const char *problem = check(dt, first, last, n_steps, save_every, n, &par, &sums, &xs);
    const char *chosen = problem == NULL ? resolve_path("bingham_batch", path) : NULL;
    if (problem != NULL) PyErr_Format(PyExc_ValueError, "bingham_batch: %s", problem);
    if (chosen != NULL) {
        const RunBlock run = !strcmp(chosen, "avx512") ? run_block8 : !strcmp(chosen, "avx2") ? run_block4 : run_block2;
        const double *p = (const double *)par.buf, *w = (const double *)nw.buf;
        double *o = (double *)sums.buf, *x = save_every > 0 && xs.len > 0 ? (double *)xs.buf : NULL;
        const Py_ssize_t blocks = (n + BLOCK - 1) / BLOCK;
        Py_BEGIN_ALLOW_THREADS
#pragma omp parallel for schedule(dynamic, 1)
        for (Py_ssize_t i = 0; i < blocks; i++) run(p, w, o, x, n, i * BLOCK, dt, first, last, n_steps, save_every);
        Py_END_ALLOW_THREADS
    }
    PyBuffer_Release(&xs);
release_sums:
    PyBuffer_Release(&sums);
release_nw:
    PyBuffer_Release(&nw);
release_par:
    PyBuffer_Release(&par);
    if (PyErr_Occurred()) return NULL;
    Py_RETURN_NONE;
}

/* Test hook: the project's sine of a buffer of doubles, in place, in the lanes of one path. */
static PyObject *sine(PyObject *self, PyObject *args) {
    PyObject *obj;
    Py_buffer x;
    const char *path = "auto";
    if (!PyArg_ParseTuple(args, "O|s", &obj, &path)) return NULL;
    const char *chosen = resolve_path("sine", path);
    if (chosen == NULL) return NULL;
    if (doubles(obj, &x, 1, "x") < 0) return NULL;
    const SineBuffer f = !strcmp(chosen, "avx512") ? sine_buffer8 : !strcmp(chosen, "avx2") ? sine_buffer4 : sine_buffer2;
    f((double *)x.buf, x.len / (Py_ssize_t)sizeof(double));
    PyBuffer_Release(&x);
    Py_RETURN_NONE;
}

static PyObject *threads(PyObject *self, PyObject *unused) {
    int count = 1;
#ifdef _OPENMP
#pragma omp parallel
    {
#pragma omp single
        count = omp_get_num_threads();
    }
#endif
    return PyLong_FromLong(count);
}

static PyObject *best_path(PyObject *self, PyObject *unused) { return PyUnicode_FromString(best()); }

static PyObject *paths(PyObject *self, PyObject *unused) {
    if (cpu_has("avx512f") && cpu_has("avx2")) return Py_BuildValue("(sss)", "default", "avx2", "avx512");
    if (cpu_has("avx512f")) return Py_BuildValue("(ss)", "default", "avx512");
    if (cpu_has("avx2")) return Py_BuildValue("(ss)", "default", "avx2");
    return Py_BuildValue("(s)", "default");
}

static PyMethodDef methods[] = {
    {"bingham_batch", bingham_batch, METH_VARARGS, "Algorithm 1 over many parameter sets, summaries only."},
    {"threads", threads, METH_NOARGS, "Number of threads the batched kernel uses."},
    {"best_path", best_path, METH_NOARGS, "The loop 'auto' runs: 'avx512', 'avx2' or 'default' (SSE2)."},
    {"paths", paths, METH_NOARGS, "The paths this CPU runs, narrowest first."},
    {"sine", sine, METH_VARARGS, "The project's sine of a buffer of doubles in place, in one path's lanes (a test hook)."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_batch_kernel", NULL, -1, methods};

PyMODINIT_FUNC PyInit__batch_kernel(void) { return PyModule_Create(&module); }
