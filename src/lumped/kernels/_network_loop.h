/* The one loop of links that the compiled step also solves: a *chord*, one
 * link (its elements link_el[chord_start:chord_end]) between the points cp and
 * cq that the spanning forest of _network_forest.h leaves out (a ring of
 * masses through the ground; lumped.solvers.network_compiled.plan).
 *
 * With the modes fixed, the chord's free elements add their conductance Kc
 * between cp and cq (a rank-one term Kc u u^T, u = e_cq - e_cp) and a rigid
 * element fixes u^T v = o.  Both are one more solve on the forest: with x0
 * the forest's solution (the chord's loads a included) and y the forest's
 * solution for the load u (no loads, no offsets: fold_unit, unit_velocities),
 * the chord's tension along u beyond its loads is
 *
 *     mu = Kc s0 / (1 + Kc sy)      (free),     mu = (s0 - o) / sy      (rigid),
 *
 * s0 = u^T x0, sy = u^T y >= 0, and v = x0 - mu y (Sherman-Morrison, or the
 * bordered system of the constraint); the forest's subtree balances, which
 * give its rigid links' forces, take the load -mu u the same way.
 *
 * sy = 0 exactly when cp and cq are merged by rigid links: with a rigid chord
 * the loop is then rigid all round and its forces are not unique
 * (lumped.solvers.loop_forces).  The chord's element carries 0 (mu = Kc o),
 * the forest's rigid links on the loop carry the rest (f0), and the
 * circulation c around the loop, f = f0 + n c with n = +-1, is the one of
 * least norm that keeps every element of the loop in its band: the clipped
 * vertex of a parabola (loop_forces._one_loop, in C).  loop_intervals gives
 * each element's admissible interval from the same data.  The plan accepts a
 * chord only where every element on the loop that can be rigid is a Bingham
 * element (rate 0 when rigid), so a rigid loop's rates always agree.
 *
 * Included by _network_forest.h (after net_t). */
#ifndef LUMPED_NETWORK_LOOP_H
#define LUMPED_NETWORK_LOOP_H

/* The chord's loads: a free element's a, as a forest link's (eliminate). */
static void chord_loads(net_t *q, const int *mode) {
    for (Py_ssize_t k = q->chord_start; k < q->chord_end; k++) {
        const int64_t e = q->link_el[k];
        const piece *pc = q->graph + e * MAX_PIECES + mode[e];
        if (pc->rigid) continue;
        q->R[q->cq] -= q->sign[e] * pc->a;
        q->R[q->cp] += q->sign[e] * pc->a;
    }
}

/* y: the forest's velocities under the load u, with eliminate's pivots. */
static void unit_solve(net_t *q) {
    const Py_ssize_t ground = q->n_mass;
    for (Py_ssize_t i = 0; i < q->n_pt; i++) q->Ry[i] = 0.0;
    q->Ry[q->cq] += 1.0;
    q->Ry[q->cp] -= 1.0;
    for (Py_ssize_t idx = q->n_pt - 1; idx >= 0; idx--) {
        const int64_t c = q->order[idx], p = q->parent[c];
        if (p < 0) continue;
        if (q->rig[c] >= 0) {
            q->Ry[p] += q->Ry[c];
        } else {
            q->numy[c] = q->Ry[c];
            q->Ry[p] += q->K[c] * q->numy[c] / q->den[c];
        }
    }
    for (Py_ssize_t idx = 0; idx < q->n_pt; idx++) {
        const int64_t c = q->order[idx], p = q->parent[c];
        if (p < 0)
            q->vy[c] = c == ground ? 0.0 : q->Ry[c] / q->D[c];
        else if (q->rig[c] >= 0)
            q->vy[c] = q->vy[p];
        else
            q->vy[c] = (q->numy[c] + q->K[c] * q->vy[p]) / q->den[c];
    }
}

/* The top of the cluster (points joined by rigid forest links) holding `start`. */
static int64_t cluster_top(const net_t *q, int64_t start) {
    while (q->parent[start] >= 0 && q->rig[start] >= 0) start = q->parent[start];
    return start;
}

/* A rigid chord between two clusters holds v_cq = v_cp + o only to rounding after v = x0 - mu y;
 * make it exact as a forest link is: one cluster's velocities again from the other's, through
 * the chord and then the cluster's own offsets (a sticking element's two points then move with
 * one velocity, bit for bit).  The cluster moved is cq's, or cp's if cq's holds the ground. */
static void hold_chord(net_t *q, double o) {
    int64_t start = q->cq, top = cluster_top(q, q->cq);
    double target = q->vall[q->cp] + o;
    if (top == q->n_mass) start = q->cp, top = cluster_top(q, q->cp), target = q->vall[q->cq] - o;
    int64_t *mark = q->loop_el + q->n_el + 1; /* scratch: 2 on start's path to the top, 1 in the cluster */
    for (Py_ssize_t i = 0; i < q->n_pt; i++) mark[i] = 0;
    q->vall[start] = target;
    for (int64_t node = start;; node = q->parent[node]) {
        mark[node] = 2;
        if (node == top) break;
        q->vall[q->parent[node]] = q->vall[node] - q->off[node];
    }
    for (Py_ssize_t idx = 0; idx < q->n_pt; idx++) {
        const int64_t c = q->order[idx], p = q->parent[c];
        if (p < 0 || q->rig[c] < 0 || mark[c] || !mark[p]) continue;
        mark[c] = 1;
        q->vall[c] = q->vall[p] + q->off[c];
    }
}

/* After the forest's velocities: the chord's tension mu, the velocities and balances with it. */
static void chord_velocities(net_t *q, const int *mode) {
    double Kc = 0.0;
    q->rc = -1;
    for (Py_ssize_t k = q->chord_start; k < q->chord_end; k++) {
        const int64_t e = q->link_el[k];
        const piece *pc = q->graph + e * MAX_PIECES + mode[e];
        if (pc->rigid)
            q->rc = e;
        else
            Kc += pc->b;
    }
    unit_solve(q);
    const double s0 = q->vall[q->cq] - q->vall[q->cp], sy = q->vy[q->cq] - q->vy[q->cp];
    q->Kc = Kc, q->n_loop = 0;
    if (q->rc < 0) {
        q->mu = Kc * s0 / (1.0 + Kc * sy);
    } else {
        const double o = q->sign[q->rc] * q->graph[q->rc * MAX_PIECES + mode[q->rc]].a;
        q->rigid_loop = !(sy > 0.0);
        q->mu = q->rigid_loop ? Kc * o : (s0 - o) / sy;
    }
    if (q->rc < 0) q->rigid_loop = 0;
    if (q->mu != 0.0)
        for (Py_ssize_t i = 0; i < q->n_pt; i++) {
            q->vall[i] -= q->mu * q->vy[i];
            q->R[i] -= q->mu * q->Ry[i];
        }
    if (q->rc >= 0 && !q->rigid_loop) hold_chord(q, q->sign[q->rc] * q->graph[q->rc * MAX_PIECES + mode[q->rc]].a);
}

/* c's interval from element j: lo <= f0 + n c <= hi (n = +-1). */
static void c_bounds(double f0, double n, double lo, double hi, double *low, double *high) {
    if (n > 0)
        *low = lo - f0, *high = hi - f0;
    else
        *low = f0 - hi, *high = f0 - lo;
}

/* The rigid loop's forces: the chord's element at 0 and the forest's rigid links (f0), then
 * the least-norm circulation c (loop_forces._one_loop). */
static void loop_split(net_t *q, const int *mode) {
    Py_ssize_t m = 0;
    q->loop_el[m] = q->rc, q->loop_n[m] = q->sign[q->rc], m++;
    for (Py_ssize_t c = 0; c < q->n_pt; c++)
        if (q->parent[c] >= 0 && q->rig[c] >= 0 && q->Ry[c] != 0.0)
            q->loop_el[m] = q->rig[c], q->loop_n[m] = -q->sign[q->rig[c]] * q->Ry[c], m++;
    double c_lo = -INFINITY, c_hi = INFINITY, sum = 0.0;
    for (Py_ssize_t j = 0; j < m; j++) {
        const int64_t e = q->loop_el[j];
        const piece *pc = q->graph + e * MAX_PIECES + mode[e];
        double lo, hi;
        q->loop_f0[j] = q->f[e];
        c_bounds(q->f[e], q->loop_n[j], pc->lo, pc->hi, &lo, &hi);
        if (lo > c_lo) c_lo = lo;
        if (hi < c_hi) c_hi = hi;
        sum += q->loop_n[j] * q->f[e];
    }
    double c = -sum / (double)m;
    const int feasible = c_lo <= c_hi;
    if (feasible) c = c < c_lo ? c_lo : c > c_hi ? c_hi : c;
    for (Py_ssize_t j = 0; j < m; j++) {
        const int64_t e = q->loop_el[j];
        const piece *pc = q->graph + e * MAX_PIECES + mode[e];
        double value = q->loop_f0[j] + q->loop_n[j] * c;
        if (feasible) value = value < pc->lo ? pc->lo : value > pc->hi ? pc->hi : value;
        q->f[e] = value;
    }
    q->n_loop = m;
}

/* After the forest's forces: the chord's rigid element, and the rigid loop's split. */
static void chord_forces(net_t *q, const int *mode) {
    if (q->rc < 0) return;
    const piece *pc = q->graph + q->rc * MAX_PIECES + mode[q->rc];
    q->w[q->rc] = pc->a;
    q->f[q->rc] = q->sign[q->rc] * (q->mu - q->Kc * q->sign[q->rc] * pc->a);
    if (q->rigid_loop) loop_split(q, mode);
}

/* Each element's admissible force into low, high (elements): its force, and on a rigid loop the
 * band that the other elements of the loop leave it (loop_forces._one_loop). */
static void loop_intervals(const net_t *q, double *low, double *high) {
    memcpy(low, q->f, q->n_el * sizeof(double));
    memcpy(high, q->f, q->n_el * sizeof(double));
    double lo1 = -INFINITY, lo2 = -INFINITY, hi1 = INFINITY, hi2 = INFINITY;
    Py_ssize_t at_lo = -1, at_hi = -1;
    for (Py_ssize_t j = 0; j < q->n_loop; j++) {
        const int64_t e = q->loop_el[j];
        const piece *pc = q->graph + e * MAX_PIECES + q->mode[e];
        double lo, hi;
        c_bounds(q->loop_f0[j], q->loop_n[j], pc->lo, pc->hi, &lo, &hi);
        if (lo > lo1) lo2 = lo1, lo1 = lo, at_lo = j;
        else if (lo > lo2) lo2 = lo;
        if (hi < hi1) hi2 = hi1, hi1 = hi, at_hi = j;
        else if (hi < hi2) hi2 = hi;
    }
    for (Py_ssize_t j = 0; j < q->n_loop; j++) {
        const int64_t e = q->loop_el[j];
        const piece *pc = q->graph + e * MAX_PIECES + q->mode[e];
        const double others_lo = j == at_lo ? lo2 : lo1, others_hi = j == at_hi ? hi2 : hi1, f0 = q->loop_f0[j];
        const double a = q->loop_n[j] > 0 ? f0 + others_lo : f0 - others_hi;
        const double b = q->loop_n[j] > 0 ? f0 + others_hi : f0 - others_lo;
        low[e] = a > pc->lo ? a : pc->lo;
        high[e] = b < pc->hi ? b : pc->hi;
    }
}
#endif
