/* A friction contact with a Stribeck fall (kinds STRIBECK .. STRIBECK + 2, _network_elements.h) in the
 * active-set iteration of the sparse step: lumped.laws.step_graph.CurveSlipGraph in C.
 *
 * Its mode is STICK_PIECE, or a slip direction (SLIP_BACK, SLIP_FORWARD) with the point (w, f) of that
 * branch last reached (in the contact's true rate, w + delta for a contact joined to a driven point) and
 * the points reached before it, at most CYCLE (step_graph._CYCLE; the binding checks the width of the
 * marching points against it).  In a slip mode the piece is the line of slope sigma through the point
 * (curve_pieces); the next point is the branch's resolvent point of z = f + sigma w, the root s of
 * g(s) + sigma s = |z| (slip_speed of _slip_curve.h, the one home of the curve in C), or the stick when
 * the branch has none (|z| at most static) or the rate changed sign (curve_next: step_graph._slip_rule);
 * the mode has settled when the points agree to 8 ulps term by term or the new point is one reached
 * before (curve_same: CurveSlipGraph.same).  The iteration then holds no cycle test (a mode vector does
 * not come back: network_step._iterate's `piecewise`), and the dual sweeps leave such a contact at its
 * initial mode.  The warm start of a step is the last step's settled mode, its point and history.
 * With tangent set (the Newton finish, CurveSlipGraph.newton) a slip mode's piece is the curve's tangent
 * (curve_slope), its next point the curve at the solve's rate, its mode the convexified graph's
 * resolvent (curve_fall), and it settles when the solve lies on the branch (curve_near).
 *
 * Included by _network_active_set.h, after _network_sparse.h (net_t, sparse_reread). */
#ifndef LUMPED_NETWORK_CURVE_H
#define LUMPED_NETWORK_CURVE_H

#include "_network_sparse.h" /* net_t, sparse_reread */

#define CYCLE 8                    /* step_graph._CYCLE: the points a mode remembers */
#define POINT_WIDTH (3 + 2 * CYCLE) /* a point in the marching array: w, f, count, the w's, the f's */

typedef struct {
    double w, f;
    int nb; /* the points before it, oldest first */
    double bw[CYCLE], bf[CYCLE];
    int near; /* the last solve in this mode lay on the branch to its rounding (curve_near) */
} slip_point;

typedef struct curve_s {
    Py_ssize_t n;             /* the Stribeck contacts */
    int64_t *el, *ix;         /* their elements; per element its index among them, or -1 */
    law_t *law;               /* each one's law */
    slip_point *pt, *warm;    /* the point of each one's mode, and of the step's warm start */
    double *nw, *nf;          /* the next iteration's point */
    const double *state;      /* the elements' states at the step's start (the dual sweeps' initial modes) */
    int tangent;              /* the finishing (Newton) form: CurveSlipGraph(tangent=True) */
    double df, dw;            /* the last solve's rounding (step._rounding), set by iterate */
} curve_t;

/* CurveSlipGraph.initial_mode: the stick, or the branch of the state's direction at (0, +-static). */
static int curve_initial(const net_t *q, Py_ssize_t k, double state) {
    const curve_t *c = q->cv;
    slip_point *p = c->pt + k;
    const double direction = state > 0 ? 1.0 : -1.0;
    p->w = 0.0, p->f = direction * c->law[k].stat, p->nb = 0;
    return state > 0 ? SLIP_FORWARD : state < 0 ? SLIP_BACK : STICK_PIECE;
}

/* g'(s) as StribeckLaw.slope computes it, operation for operation (so that the tangents of the Newton
 * finish, and with them its iterates, are the Python step's bit for bit). */
static double curve_slope(const law_t *l, double s) {
    const double x = s / l->vs;
    const double dd = l->code == 1 ? -exp(-x) : l->code == 2 ? -2.0 * x * exp(-x * x) : -1.0 / ((1.0 + x) * (1.0 + x));
    return l->visc + (l->stat - l->kin) / l->vs * dd;
}

/* The line of each slipping contact's mode at this scale (CurveSlipGraph.piece, then Shifted), into the
 * table of pieces, and the sparse step told to read it again. */
static void curve_pieces(net_t *q, double scale) {
    const curve_t *c = q->cv;
    for (Py_ssize_t k = 0; k < c->n; k++) {
        const int64_t e = c->el[k];
        if (q->mode[e] == STICK_PIECE) continue;
        double slope = q->sigma[e] * scale; /* the line of slope sigma, or the tangent (CurveSlipGraph.piece) */
        if (c->tangent && c->pt[k].w != 0.0) slope = curve_slope(c->law + k, fabs(c->pt[k].w));
        piece p = free_piece(c->pt[k].f - slope * c->pt[k].w, slope, -INFINITY, INFINITY);
        if (q->delta && q->delta[e] != 0.0) p = shift_piece(p, q->delta[e]);
        q->graph[e * MAX_PIECES + q->mode[e]] = p;
        if (q->sp) sparse_reread(q, e);
    }
}

/* StribeckLaw.fall: the steepest fall max(0, (static - kinetic)/v_s max(-d') - viscous), operation for operation. */
static double curve_fall(const law_t *l) {
    const double steepest = l->code == 2 ? sqrt(2.0 / M_E) : 1.0;
    const double fall = (l->stat - l->kin) / l->vs * steepest - l->visc;
    return fall > 0.0 ? fall : 0.0;
}

/* CurveSlipGraph.near: 1 if (w, f) (the true rate, direction w > 0) lies on the branch to the solve's
 * rounding, |f - direction g(|w|)| <= df + |g'| dw + 8 eps |g| (the bound derived there). */
static int curve_near(const curve_t *c, Py_ssize_t k, double direction, double w, double f, double dw) {
    double unused;
    const double g = slip_curve(c->law + k, direction * w, &unused);
    return fabs(f - direction * g) <= c->df + fabs(curve_slope(c->law + k, direction * w)) * dw + 8 * DBL_EPSILON * fabs(g);
}

/* CurveSlipGraph.next_mode: the mode after an iteration that gave (w, f) in the contact's mode; a slip
 * mode's point into c->nw, c->nf (the old point itself when the tangent form has settled). */
static int curve_next(net_t *q, Py_ssize_t e, double sigma) {
    curve_t *c = q->cv;
    const Py_ssize_t k = c->ix[e];
    const law_t *l = c->law + k;
    const double f = q->f[e];
    double direction, z, guess = -1.0;
    if (q->mode[e] == STICK_PIECE) {
        if (slip_rule(STICK_PIECE, 0.0, f, l->stat) == STICK_PIECE) return STICK_PIECE;
        direction = copysign(1.0, f), z = f;
    } else {
        const double d = q->delta ? q->delta[e] : 0.0, w = d != 0.0 ? q->w[e] + d : q->w[e];
        const double old = q->mode[e] == SLIP_FORWARD ? 1.0 : -1.0;
        const double dw = d != 0.0 ? c->dw + DBL_EPSILON * fabs(w) : c->dw; /* Shifted.next_mode */
        c->pt[k].near = 0;
        if (c->tangent) { /* CurveSlipGraph._convex_mode (a Stribeck graph is one: g(0+) = static) */
            z = f + (curve_fall(l) + sigma) * w;
            if (fabs(z) <= l->stat) return STICK_PIECE;
            direction = copysign(1.0, z);
            if (direction == old && direction * w > 0) { /* on: Newton's next point, or settled */
                double slope;
                const int near = c->pt[k].near = curve_near(c, k, direction, w, f, dw);
                c->nw[k] = near ? c->pt[k].w : w;
                c->nf[k] = near ? c->pt[k].f : direction * slip_curve(l, direction * w, &slope);
                return q->mode[e];
            } /* else the resolvent point of z on the branch `direction`, as from the stick */
        } else {
            direction = old;
            if (direction * w <= 0) return STICK_PIECE;
            c->pt[k].near = curve_near(c, k, direction, w, f, dw);
            z = f + sigma * w, guess = fabs(c->pt[k].w);
        }
    }
    if (direction * z <= l->stat) return STICK_PIECE; /* the slip limit of a falling law: static */
    double slope;
    const double s = slip_speed(l, direction * z, sigma, guess);
    c->nw[k] = direction * s, c->nf[k] = direction * slip_curve(l, s, &slope);
    return direction > 0 ? SLIP_FORWARD : SLIP_BACK;
}

/* CurveSlipGraph.same for the contact's mode and q->next[e] (the new point c->nw, c->nf). */
static int curve_same(const net_t *q, Py_ssize_t e, double sigma) {
    const curve_t *c = q->cv;
    const int old = q->mode[e], fresh = q->next[e];
    if (old == STICK_PIECE || fresh == STICK_PIECE || old != fresh) return old == fresh;
    const Py_ssize_t k = c->ix[e];
    const slip_point *p = c->pt + k;
    const double w0 = p->w, f0 = p->f, w1 = c->nw[k], f1 = c->nf[k];
    if (c->tangent) return p->near; /* the solve on the branch: CurveSlipGraph.same's `old is new` */
    const double scale = fabs(f1) + fabs(f0) + sigma * (fabs(w1) + fabs(w0)) + 1e-300;
    if (fabs(f1 - f0) + sigma * fabs(w1 - w0) <= 8 * DBL_EPSILON * scale) return 1;
    if (!p->near) return 0; /* reached from a solve off the branch: the new point's before is empty */
    if (w1 == w0 && f1 == f0) return 1; /* the new point's before: the old point and the last CYCLE - 1 of its */
    for (int j = p->nb > CYCLE - 1 ? p->nb - (CYCLE - 1) : 0; j < p->nb; j++)
        if (w1 == p->bw[j] && f1 == p->bf[j]) return 1;
    return 0;
}

/* The contact moves to q->next[e]: a slip mode reached from a slip mode remembers the old point. */
static void curve_commit(net_t *q, Py_ssize_t e) {
    curve_t *c = q->cv;
    const Py_ssize_t k = c->ix[e];
    slip_point *p = c->pt + k;
    if (q->next[e] == STICK_PIECE) return;
    if (q->mode[e] == STICK_PIECE || c->tangent || !p->near) {
        p->nb = 0; /* a first point, a Newton point, or one reached from a solve off the branch */
    } else {
        if (p->nb == CYCLE) {
            memmove(p->bw, p->bw + 1, (CYCLE - 1) * sizeof(double));
            memmove(p->bf, p->bf + 1, (CYCLE - 1) * sizeof(double));
            p->nb--;
        }
        p->bw[p->nb] = p->w, p->bf[p->nb] = p->f, p->nb++;
    }
    p->w = c->nw[k], p->f = c->nf[k];
}

/* The points of the warm start kept (at a step's start), or put back (at a restart). */
static void curve_keep(curve_t *c, int back) {
    if (back) memcpy(c->pt, c->warm, c->n * sizeof(slip_point));
    else memcpy(c->warm, c->pt, c->n * sizeof(slip_point));
}

/* The points to and from the marching array (POINT_WIDTH values per element). */
static void curve_load(curve_t *c, const double *points) {
    for (Py_ssize_t k = 0; k < c->n; k++) {
        const double *row = points + c->el[k] * POINT_WIDTH;
        slip_point *p = c->pt + k;
        p->w = row[0], p->f = row[1], p->nb = (int)row[2];
        for (int j = 0; j < CYCLE; j++) p->bw[j] = row[3 + j], p->bf[j] = row[3 + CYCLE + j];
    }
}

static void curve_store(const curve_t *c, double *points) {
    for (Py_ssize_t k = 0; k < c->n; k++) {
        double *row = points + c->el[k] * POINT_WIDTH;
        const slip_point *p = c->pt + k;
        row[0] = p->w, row[1] = p->f, row[2] = p->nb;
        for (int j = 0; j < CYCLE; j++) row[3 + j] = j < p->nb ? p->bw[j] : 0.0, row[3 + CYCLE + j] = j < p->nb ? p->bf[j] : 0.0;
    }
}
#endif
