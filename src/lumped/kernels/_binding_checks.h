/* Argument checks of the compiled kernels' bindings (_kernel.c, _network_kernel.c, _friction_kernel.c).
 *
 * The bindings are private (the drivers in timestepping and network.integrate
 * call them with arrays they built), but a wrong length, item type or count
 * would make the C loops read or write past a buffer; so every binding checks
 * what its loop relies on before it starts, and a failure raises ValueError
 * with one line that begins with the argument's name (the convention of
 * lumped.numerics.validate).  tests/test_bindings.py calls each binding with each bad
 * argument, in a child process, so that a crash shows as a failure.
 *
 * A binding takes its arrays into a `held` bag and releases them all at once. */
#ifndef LUMPED_BINDING_CHECKS_H
#define LUMPED_BINDING_CHECKS_H

#include <Python.h>
#include <math.h>
#include <string.h>

#define MAX_HELD 32

typedef struct {
    Py_buffer b[MAX_HELD];
    int n;
} held_t;

static void release_held(held_t *h) {
    for (int i = 0; i < h->n; i++) PyBuffer_Release(h->b + i);
    h->n = 0;
}

static const char *item_name(char type) {
    return type == 'd' ? "float64" : type == 'q' ? "int64" : "uint8";
}

/* The buffer's item type: 'd' (float64), 'q' (int64), 'B' (uint8), or 0. */
static char item_type(const Py_buffer *b) {
    const char *f = b->format ? b->format : "B";
    if (*f == '@' || *f == '=' || *f == (PY_LITTLE_ENDIAN ? '<' : '>')) f++;
    if (f[0] == '\0' || f[1] != '\0') return 0;
    if (b->itemsize == 8 && f[0] == 'd') return 'd';
    if (b->itemsize == 8 && (f[0] == 'q' || f[0] == 'l')) return 'q';
    if (b->itemsize == 1 && f[0] == 'B') return 'B';
    return 0;
}

/* Take obj's buffer into h: C-contiguous, items of `type`, `count` of them
 * (any number if count < 0), writable if asked.  NULL with ValueError if not. */
static Py_buffer *take(held_t *h, PyObject *obj, const char *name, char type, Py_ssize_t count, int writable) {
    Py_buffer *b = h->b + h->n;
    const int flags = PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0);
    if (h->n == MAX_HELD || PyObject_GetBuffer(obj, b, flags) < 0) {
        PyErr_Clear();
        PyErr_Format(PyExc_ValueError, "%s must be a %sC-contiguous array of %s", name, writable ? "writable " : "",
                     item_name(type));
        return NULL;
    }
    h->n++;
    if (item_type(b) != type) {
        PyErr_Format(PyExc_ValueError, "%s must hold %s items, got format '%s' of %zd bytes", name, item_name(type),
                     b->format ? b->format : "B", b->itemsize);
        return NULL;
    }
    if (count >= 0 && b->len / b->itemsize != count) {
        PyErr_Format(PyExc_ValueError, "%s must hold %zd %s values, got %zd", name, count, item_name(type),
                     b->len / b->itemsize);
        return NULL;
    }
    return b;
}

/* The number of items of a buffer taken by take(). */
static Py_ssize_t items(const Py_buffer *b) { return b->len / b->itemsize; }

/* The items of a tuple of `count` arrays, or NULL with ValueError naming it. */
static inline PyObject *const *tuple_items(PyObject *obj, const char *name, Py_ssize_t count) {
    if (!PyTuple_Check(obj) || PyTuple_GET_SIZE(obj) != count) {
        PyErr_Format(PyExc_ValueError, "%s must be a tuple of %zd arrays", name, count);
        return NULL;
    }
    return &PyTuple_GET_ITEM(obj, 0);
}

/* Take a tuple of n arrays of the given names, item types and counts (writable if asked) into h. */
static inline int take_tuple(held_t *h, PyObject *obj, const char *name, int n, const char *const *names, const char *types,
                             const Py_ssize_t *counts, int writable, Py_buffer **out) {
    PyObject *const *a = tuple_items(obj, name, n);
    if (a == NULL) return -1;
    for (int i = 0; i < n; i++)
        if (!(out[i] = take(h, a[i], names[i], types[i], counts[i], writable))) return -1;
    return 0;
}

/* 0 if lo <= x (lo < x if strict) and x is finite (or +inf if inf_ok); else -1 with ValueError. */
static int check_real(const char *name, double x, double lo, int strict, int inf_ok) {
    const int in_range = strict ? x > lo : x >= lo;
    if (in_range && (isfinite(x) || (inf_ok && x > 0))) return 0;
    PyObject *value = PyFloat_FromDouble(x), *bound = PyFloat_FromDouble(lo); /* PyErr_Format has no %g */
    if (value == NULL || bound == NULL) {
        Py_XDECREF(value);
        Py_XDECREF(bound);
        return -1;
    }
    if (isinf(lo))
        PyErr_Format(PyExc_ValueError, "%s must be finite, got %R", name, value);
    else
        PyErr_Format(PyExc_ValueError, "%s must be %s %R%s, got %R", name, strict ? ">" : ">=", bound,
                     inf_ok ? " (inf allowed)" : " and finite", value);
    Py_DECREF(value);
    Py_DECREF(bound);
    return -1;
}

/* 0 if the block n_first..n_last of a run of n_steps steps, saving every save_every-th, is consistent. */
static int check_steps(Py_ssize_t n_first, Py_ssize_t n_last, Py_ssize_t n_steps, Py_ssize_t save_every) {
    if (save_every < 1)
        PyErr_Format(PyExc_ValueError, "save_every must be >= 1, got %zd", save_every);
    else if (n_first < 0)
        PyErr_Format(PyExc_ValueError, "n_first must be >= 0, got %zd", n_first);
    else if (n_last < n_first)
        PyErr_Format(PyExc_ValueError, "n_last must be >= n_first = %zd, got %zd", n_first, n_last);
    else if (n_steps < n_last)
        PyErr_Format(PyExc_ValueError, "n_steps must be >= n_last = %zd, got %zd", n_last, n_steps);
    else
        return 0;
    return -1;
}

/* Rows that steps n_first..n_last save: every multiple of save_every, and n_steps. */
static Py_ssize_t rows_saved(Py_ssize_t n_first, Py_ssize_t n_last, Py_ssize_t n_steps, Py_ssize_t save_every) {
    const Py_ssize_t before = n_first / save_every + (n_first % save_every != 0); /* multiples < n_first */
    Py_ssize_t rows = n_last / save_every + 1 - before;
    if (n_first <= n_steps && n_steps <= n_last && n_steps % save_every != 0) rows++;
    return rows;
}

/* 0 if `row` is a valid row counter and `rows` rows hold it plus what the block saves. */
static int check_rows(const char *name, int64_t row, Py_ssize_t rows, Py_ssize_t n_first, Py_ssize_t n_last,
                      Py_ssize_t n_steps, Py_ssize_t save_every) {
    const Py_ssize_t need = rows_saved(n_first, n_last, n_steps, save_every);
    if (row < 0 || row > rows) {
        PyErr_Format(PyExc_ValueError, "counters[0] (the row) must be in 0..%zd, got %lld", rows, (long long)row);
        return -1;
    }
    if (need > rows - (Py_ssize_t)row) {
        PyErr_Format(PyExc_ValueError, "%s must have at least %lld rows (row %lld and %zd saved by steps %zd..%zd), got %zd",
                     name, (long long)row + need, (long long)row, need, n_first, n_last, rows);
        return -1;
    }
    return 0;
}

#endif
