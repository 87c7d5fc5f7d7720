/*
 * natural_path.c - the article's Hooke-Jeeves search, for comparison, and
 * composite curves through points (natural.h).
 */
#include "runtime/natural.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"

/* ---- Hooke-Jeeves (the article's method) --------------------------------- */

typedef struct HjCtx {
    double x0, y0, th0, x1, y1, D;
    int evals;
} HjCtx;

/* (16): the end point's distance from the target, the linear law with a
 * from (13) */
static double hj_f(HjCtx *h, const double *v)
{
    double b = v[0], S = v[1];
    if (!(S > 0) || !isfinite(b))
        return INFINITY;
    double a = 2 / S * (h->D / S - b), p[3] = {h->th0, b, a / 2}, c, s;
    h->evals++;
    /* int_0^S e^{i phi(s)} ds = S int_0^1 e^{i phi(S tau)} dtau */
    double q[3] = {p[0], p[1] * S, p[2] * S * S};
    nat_moments(q, 2, 1, &c, &s);
    return hypot(h->x0 + S * c - h->x1, h->y0 + S * s - h->y1);
}

/* one exploratory round around x (value *fx) with steps st */
static void hj_explore(HjCtx *h, double *x, double *fx, const double *st)
{
    for (int i = 0; i < 2; i++) {
        double keep = x[i];
        x[i] = keep + st[i];
        double f = hj_f(h, x);
        if (f < *fx) {
            *fx = f;
            continue;
        }
        x[i] = keep - st[i];
        f = hj_f(h, x);
        if (f < *fx) {
            *fx = f;
            continue;
        }
        x[i] = keep;
    }
}

int nat_fit_hj(double x0, double y0, double th0, double x1, double y1,
               double th1, double tol, int max_evals, NatSegment *seg,
               NatStats *st)
{
    NatStats local;
    if (!st)
        st = &local;
    memset(st, 0, sizeof *st);
    double r = hypot(x1 - x0, y1 - y0), phi = atan2(y1 - y0, x1 - x0);
    HjCtx h = {x0, y0, th0, x1, y1, 0, 0};
    h.D = nat_reduce_angle(th1 - phi) - nat_reduce_angle(th0 - phi);
    double base[2] = {0, r}, fb = hj_f(&h, base), step[2] = {0.5 / r, 0.25 * r};
    while (fb > tol * r && h.evals < max_evals && step[1] > 1e-17 * r) {
        double x[2] = {base[0], base[1]}, fx = fb;
        hj_explore(&h, x, &fx, step);
        st->iterations++;
        if (!(fx < fb)) {
            step[0] /= 2, step[1] /= 2;
            continue;
        }
        while (fx < fb && h.evals < max_evals) { // pattern moves
            double p[2] = {2 * x[0] - base[0], 2 * x[1] - base[1]};
            base[0] = x[0], base[1] = x[1], fb = fx;
            double fp = hj_f(&h, p);
            hj_explore(&h, p, &fp, step);
            st->iterations++;
            x[0] = p[0], x[1] = p[1], fx = fp;
        }
    }
    memset(seg, 0, sizeof *seg);
    seg->x0 = x0, seg->y0 = y0, seg->phi0 = th0, seg->degree = 1;
    seg->length = base[1];
    seg->k[0] = base[0];
    seg->k[1] = 2 / base[1] * (h.D / base[1] - base[0]);
    st->integrals = h.evals;
    st->error = fb;
    return fb <= tol * r ? 0 : 1;
}

/* ---- composite curves ---------------------------------------------------- */

void nat_chord_angles(NatPoint *p, int n)
{
    if (n < 2)
        return;
    if (n == 2) {
        double d = atan2(p[1].y - p[0].y, p[1].x - p[0].x);
        for (int i = 0; i < 2; i++)
            if (!p[i].has_th)
                p[i].th = d;
        return;
    }
    for (int i = 1; i < n - 1; i++)
        if (!p[i].has_th)
            p[i].th = atan2(p[i + 1].y - p[i - 1].y, p[i + 1].x - p[i - 1].x);
    if (!p[0].has_th)
        p[0].th = 2 * atan2(p[1].y - p[0].y, p[1].x - p[0].x) - p[1].th;
    if (!p[n - 1].has_th)
        p[n - 1].th =
            2 * atan2(p[n - 1].y - p[n - 2].y, p[n - 1].x - p[n - 2].x) -
            p[n - 2].th;
}

void nat_curve_free(NatCurve *c)
{
    pc_free(c->seg);
    pc_free(c->joint);
    c->seg = NULL;
    c->joint = NULL;
    c->nseg = 0;
}

static void add_stats(NatStats *sum, const NatStats *s)
{
    sum->iterations += s->iterations;
    sum->integrals += s->integrals;
    sum->error = fmax(sum->error, s->error);
}

/* segment i of the chain from a (start angle th0, curvature k0 and its
 * derivative dk0 there) to b */
static int fit_segment(const NatChain *ch, int i, const NatPoint *a, double th0,
                       double k0, double dk0, const NatPoint *b, NatSegment *g,
                       NatStats *st)
{
    if (ch->hooke_jeeves)
        return nat_fit_hj(a->x, a->y, th0, b->x, b->y, b->th, 1e-12,
                          NAT_HJ_MAX_EVALS, g, st) != 0
                   ? -1
                   : 0;
    int lawful = ch->law != NAT_LINEAR && (i > 0 || ch->has_kstart);
    if (lawful)
        return nat_fit_law(ch->law, a->x, a->y, th0, b->x, b->y, b->th, k0, dk0,
                           g, st);
    return nat_fit_g1(a->x, a->y, th0, b->x, b->y, b->th, g, st);
}

int nat_composite(NatPoint *pts, int n, const NatChain *ch, NatCurve *c,
                  int *bad)
{
    memset(c, 0, sizeof *c);
    *bad = -1;
    if (n < 2 || n > NAT_MAX_POINTS)
        return -1;
    nat_chord_angles(pts, n);
    for (int i = 0; i < n; i++) // directions: the winding is the fit's
        pts[i].th = nat_reduce_angle(pts[i].th);
    c->nseg = n - 1;
    c->seg = pc_xcalloc((size_t)n, sizeof *c->seg);
    c->joint = pc_xcalloc((size_t)n, sizeof *c->joint);
    for (int i = 0; i < n - 1; i++) {
        const NatPoint *a = &pts[i];
        NatSegment *g = &c->seg[i];
        NatStats st;
        double th0 = a->th, k0 = ch->kstart, dk0 = ch->dkstart;
        if (i > 0) { // continue the previous end: its angle, unwound
            const NatSegment *p = &c->seg[i - 1];
            double end = nat_phi(p, p->length);
            th0 = end + nat_reduce_angle(a->th - end);
            k0 = nat_kappa(p, p->length);
            dk0 = nat_dkappa(p, p->length);
        }
        int rc = fit_segment(ch, i, a, th0, k0, dk0, &pts[i + 1], g, &st);
        add_stats(&c->stats, &st);
        if (rc != 0) {
            *bad = i;
            return -1;
        }
        if (i > 0) {
            const NatSegment *p = &c->seg[i - 1];
            NatJoint *j = &c->joint[i - 1];
            j->dphi = nat_reduce_angle(nat_phi(g, 0) - nat_phi(p, p->length));
            j->dk = nat_kappa(g, 0) - nat_kappa(p, p->length);
            j->ddk = nat_dkappa(g, 0) - nat_dkappa(p, p->length);
        }
    }
    return 0;
}
