/* The elements of a network as the compiled step reads them: their kind codes
 * (SPRING .. LOCKING, the codes of the element modules of lumped.laws), the pieces of a
 * step graph (piece: free, f = a + b w on lo <= w <= hi, or rigid, w = a for
 * lo <= f <= hi), each kind's step graph (Element.step_graph), its state
 * update (Element.next_state) and the mode test (step._mode: which piece
 * holds z = f + sigma w), repeated here by kind code: change both together
 * (tests/test_network_kernel.py compares the compiled step with the Python
 * one).  Nothing here knows the network: one element at a time.
 *
 * Included by _network_forest.h (the one-step problem) and by
 * _network_kernel.c (the marching loop and its binding). */
#ifndef LUMPED_NETWORK_ELEMENTS_H
#define LUMPED_NETWORK_ELEMENTS_H

#include <math.h>
#include <stdint.h>

#include "_slip_curve.h" /* law_t, slip_curve, slip_speed: a Stribeck contact's branch */
#include "_stick.h"      /* sticks1: the stick test of every kernel */

#define MAX_PIECES 5
enum { SPRING = 0, STRING = 1, BINGHAM = 2, MAXWELL = 3, DASHPOT = 4, LOCKING = 5, FRICTION = 6, STRIBECK = 7 };
/* The largest kind code: STRIBECK + 2 (a Stribeck contact's codes are STRIBECK - 1 + its decay code). */
#define LAST_KIND (STRIBECK + 2)
/* FRICTION: a friction contact with a linear slip curve g(s) = a + b s (laws.step_graph.SlipGraph), its
 * parameters (static, a, b); only the sparse step (_network_sparse.h) is handed one.  Its modes are the
 * indices of its three pieces, SLIP_BACK 0, STICK 1, SLIP_FORWARD 2, picked by slip_rule. */
enum { SLIP_BACK = 0, STICK_PIECE = 1, SLIP_FORWARD = 2 };
/* STRIBECK .. STRIBECK + 2: a friction contact of lumped.laws.StribeckLaw with a fall (decay code 1, 2, 3 of
 * its kernel_form(), the kind STRIBECK - 1 + code), parameters (static, kinetic, v_s, viscous): its slip
 * branches are curves (laws.step_graph.CurveSlipGraph), which the sparse step linearises in each
 * iteration (_network_curve.h); its table of pieces holds the stick piece and, in a slip mode, the line
 * of that iteration.  Only the sparse step is handed one. */

/* True for a friction contact (its modes are the three of slip_rule). */
static int contact_kind(int64_t kind) { return kind >= FRICTION; }

/* A Stribeck contact's law from its kind and parameters. */
static law_t stribeck_law(int64_t kind, const double *p) {
    law_t l = {(int)(kind - STRIBECK + 1), p[0], p[1], p[2], p[3]};
    return l;
}

typedef struct {
    int rigid;
    double a, b, lo, hi;
} piece;

static piece free_piece(double a, double b, double lo, double hi) {
    piece p = {0, a, b, lo, hi};
    return p;
}

static piece rigid_piece(double w, double lo, double hi) {
    piece p = {1, w, 0.0, lo, hi};
    return p;
}

/* Bingham's band (elements._band): slip- on [lo, 0], stick, slip+ on [0, hi]. */
static int band(piece *g, double tau, double c, double lo, double hi) {
    g[0] = free_piece(-tau, c, lo, 0.0);
    g[1] = rigid_piece(0.0, -tau, tau);
    g[2] = free_piece(tau, c, 0.0, hi);
    return 3;
}

/* Element.step_graph for each kind; p holds the kind's parameters in field order. */
static int step_graph(int64_t kind, const double *p, double s, double dt, piece *g) {
    switch (kind) {
    case SPRING:
        g[0] = free_piece(s, dt * p[0], -INFINITY, INFINITY);
        return 1;
    case STRING: {
        const double k = p[0], reach = (p[1] - s) / dt;
        g[0] = free_piece(k * s, dt * k, -INFINITY, reach);
        g[1] = rigid_piece(reach, k * p[1], INFINITY);
        return 2;
    }
    case BINGHAM:
        return band(g, p[0], p[1], -INFINITY, INFINITY);
    case MAXWELL: {
        const double kdt = dt * p[0], tau = p[1], c = p[2];
        const double lo = (-tau - s) / kdt, hi = (tau - s) / kdt, slope = c * kdt / (c + kdt);
        g[0] = free_piece((c * s - kdt * tau) / (c + kdt), slope, -INFINITY, lo);
        g[1] = free_piece(s, kdt, lo, hi);
        g[2] = free_piece((c * s + kdt * tau) / (c + kdt), slope, hi, INFINITY);
        return 3;
    }
    case DASHPOT:
        g[0] = free_piece(0.0, p[0], -INFINITY, INFINITY);
        return 1;
    case FRICTION: /* SlipGraph: slip back, stick, slip forward */
        g[0] = free_piece(-p[1], p[2], -INFINITY, 0.0);
        g[1] = rigid_piece(0.0, -p[0], p[0]);
        g[2] = free_piece(p[1], p[2], 0.0, INFINITY);
        return 3;
    case STRIBECK:
    case STRIBECK + 1:
    case STRIBECK + 2: /* the stick piece; the slip pieces are each iteration's lines (_network_curve.h) */
        g[0] = free_piece(-p[1], p[3], -INFINITY, INFINITY);
        g[1] = rigid_piece(0.0, -p[0], p[0]);
        g[2] = free_piece(p[1], p[3], -INFINITY, INFINITY);
        return 3;
    case LOCKING: { /* tau, c, v_lock */
        const double lock = p[2], edge = p[0] + p[1] * p[2];
        g[0] = rigid_piece(-lock, -INFINITY, -edge);
        band(g + 1, p[0], p[1], -lock, lock);
        g[4] = rigid_piece(lock, edge, INFINITY);
        return 5;
    }
    }
    return 0; /* not reached: the bindings refuse any other code (take_topology) */
}

/* True if the kind's step graph depends on its state (step_graph reads s), so is built every step. */
static int stateful(int64_t kind) { return kind == SPRING || kind == STRING || kind == MAXWELL; }

/* Element.next_state for each kind. */
static double next_state(int64_t kind, const double *p, double s, double dt, double w, double f, int rigid) {
    switch (kind) {
    case SPRING:
    case MAXWELL:
        return f;
    case STRING:
        return rigid ? p[1] : s + dt * w;
    case FRICTION: /* SlipElement.next_state: the direction the step ends in */
    case STRIBECK:
    case STRIBECK + 1:
    case STRIBECK + 2:
        return rigid || w == 0.0 ? 0.0 : copysign(1.0, w);
    default:
        return 0.0;
    }
}

/* step._mode: the piece whose range of z = f + sigma w holds z.  A rigid
 * piece holds the closed band [lo + sigma a, hi + sigma a]: sticks1 of
 * _stick.h (lumped.laws.sticks in C), Algorithm 1's test, so a Bingham element sticks
 * on both edges of its band (tests/test_band_edge.py runs both steps there);
 * a rigid piece of zero width (a threshold 0) is never taken. */
static int mode_of(const piece *g, int n, double z, double sigma) {
    for (int k = 0; k < n; k++)
        if (g[k].rigid && g[k].lo < g[k].hi && sticks1(z, g[k].lo + sigma * g[k].a, g[k].hi + sigma * g[k].a))
            return k;
    for (int k = 0; k < n - 1; k++)
        if (!g[k].rigid && z <= g[k].a + (g[k].b + sigma) * g[k].hi) return k;
    return n - 1;
}

/* step_graph._slip_rule: a stuck contact stays stuck while |f| <= static and slips the way it is
 * pulled beyond; a slipping one slips while its (true) rate keeps its direction, else sticks. */
static int slip_rule(int old, double w, double f, double stat) {
    if (old == STICK_PIECE) return f > stat ? SLIP_FORWARD : f < -stat ? SLIP_BACK : STICK_PIECE;
    if (old == SLIP_FORWARD) return w > 0 ? SLIP_FORWARD : STICK_PIECE;
    return w < 0 ? SLIP_BACK : STICK_PIECE;
}

/* StepGraph.initial_mode: the middle piece, or a contact's piece from its state (its direction). */
static int initial_mode(int64_t kind, double state, int count) {
    if (contact_kind(kind) && count == 3) return state > 0 ? SLIP_FORWARD : state < 0 ? SLIP_BACK : STICK_PIECE;
    return count / 2;
}

/* step_graph._shift_piece: p in the rate w of an element whose true rate is w + delta. */
static piece shift_piece(piece p, double delta) {
    if (p.rigid) return rigid_piece(p.a - delta, p.lo, p.hi);
    return free_piece(p.a + p.b * delta, p.b, p.lo - delta, p.hi - delta);
}
#endif
