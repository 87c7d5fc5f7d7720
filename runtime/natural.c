/*
 * natural.c - natural-parametrization curves: the phase integrals and the
 * evaluation table (natural.h).
 *
 * Quadrature.  int exp(i psi) over an interval with psi a polynomial: the
 * interval is cut into n equal panels with n = ceil(V / NAT_PHASE_PER_PANEL),
 * V a bound of the phase's variation (the interval's length times a bound
 * of |psi'| on it), and each panel gets the 16-point Gauss-Legendre rule.
 * On a panel the integrand is exp(i psi) with psi turning by at most 8
 * radians: the rule's error for such an entire function is below 1e-30 of
 * the panel (the Bernstein-ellipse bound; tests/unit/test_natural.c checks
 * the result against Fresnel's integrals, circles and 4x the panels).
 *
 * The table.  [0, S] is cut into uniform panels; on each the point is
 * interpolated at the 21 Chebyshev points (values by the quadrature above,
 * from the panel's start, whose point is accumulated panel by panel) and
 * kept as its Chebyshev coefficients; the panels are doubled until the
 * last two coefficients of every panel are below 1e-16 of S.  Evaluating
 * is one Clenshaw recurrence per coordinate.
 */
#include "runtime/natural.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"

/* the positive half of the 16-point Gauss-Legendre rule on [-1, 1]: node,
 * weight (computed to 21 digits by Newton on P16 in decimal arithmetic) */
static const double gl16[8][2] = {
    {0.095012509837637440185, 0.189450610455068496285},
    {0.281603550779258913230, 0.182603415044923588867},
    {0.458016777657227386342, 0.169156519395002538189},
    {0.617876244402643748447, 0.149595988816576732082},
    {0.755404408355003033895, 0.124628971255533872052},
    {0.865631202387831743880, 0.095158511682492784810},
    {0.944575023073232576078, 0.062253523938647892863},
    {0.989400934991649932596, 0.027152459411754094852},
};

double nat_reduce_angle(double a)
{
    double r = remainder(a, 2 * NAT_PI);
    return r <= -NAT_PI ? r + 2 * NAT_PI : r;
}

double nat_kappa(const NatSegment *g, double s)
{
    double v = 0;
    for (int j = g->degree; j >= 0; j--)
        v = v * s + g->k[j];
    return v;
}

double nat_dkappa(const NatSegment *g, double s)
{
    double v = 0;
    for (int j = g->degree; j >= 1; j--)
        v = v * s + j * g->k[j];
    return v;
}

/* the phase's coefficients: ph[0] = phi0, ph[j+1] = k[j] / (j+1) */
static int phase_coef(const NatSegment *g, double *ph)
{
    ph[0] = g->phi0;
    for (int j = 0; j <= g->degree; j++)
        ph[j + 1] = g->k[j] / (j + 1);
    return g->degree + 1;
}

static double horner(const double *p, int deg, double s)
{
    double v = 0;
    for (int j = deg; j >= 0; j--)
        v = v * s + p[j];
    return v;
}

double nat_phi(const NatSegment *g, double s)
{
    double ph[NAT_MAX_DEGREE + 2];
    return horner(ph, phase_coef(g, ph), s);
}

/* a bound of |psi'| on [a, b]: exact for deg <= 2 (psi' linear), else
 * the sum of the terms' bounds */
static double rate_bound(const double *p, int deg, double a, double b)
{
    if (deg <= 1)
        return deg == 1 ? fabs(p[1]) : 0;
    if (deg == 2)
        return fmax(fabs(p[1] + 2 * p[2] * a), fabs(p[1] + 2 * p[2] * b));
    double m = fmax(fabs(a), fabs(b)), v = 0, mj = 1;
    for (int j = 1; j <= deg; j++, mj *= m)
        v += j * fabs(p[j]) * mj;
    return v;
}

static int panels_for(double variation)
{
    double n = ceil(variation / NAT_PHASE_PER_PANEL);
    if (!(n >= 1))
        return 1;
    return n > NAT_MAX_PANELS ? NAT_MAX_PANELS : (int)n;
}

/* int_a^b u^m exp(i psi(u)) du for m = 0 .. nm - 1 (nm <= 6), into c
 * (cosine) and s (sine) */
static void integrate(const double *p, int deg, double a, double b, int nm,
                      double *c, double *s)
{
    for (int m = 0; m < nm; m++)
        c[m] = s[m] = 0;
    int n = panels_for(rate_bound(p, deg, a, b) * fabs(b - a));
    double h = (b - a) / n;
    for (int q = 0; q < n; q++) {
        double mid = a + (q + 0.5) * h, half = h / 2;
        for (int k = 0; k < 16; k++) {
            double x = gl16[k & 7][0] * (k < 8 ? -1 : 1);
            double u = mid + half * x, w = gl16[k & 7][1] * half;
            double ph = horner(p, deg, u), cs = cos(ph), sn = sin(ph);
            double um = w;
            for (int m = 0; m < nm; m++, um *= u) {
                c[m] += um * cs;
                s[m] += um * sn;
            }
        }
    }
}

void nat_moments(const double *p, int deg, int nm, double *c, double *s)
{
    integrate(p, deg, 0, 1, nm, c, s);
}

void nat_point(const NatSegment *g, double s, double *x, double *y)
{
    double ph[NAT_MAX_DEGREE + 2], c, sn;
    int deg = phase_coef(g, ph);
    integrate(ph, deg, 0, s, 1, &c, &sn);
    *x = g->x0 + c;
    *y = g->y0 + sn;
}

/* the phase of law k: ph[j + 1] = k[j] / (j + 1), ph[0] = 0; its degree */
static int law_phase(const double *k, double *ph)
{
    int deg = 1;
    ph[0] = 0;
    for (int j = 0; j <= NAT_MAX_DEGREE; j++) {
        ph[j + 1] = k[j] / (j + 1);
        if (k[j] != 0)
            deg = j + 1;
    }
    return deg;
}

double nat_law_phase(const double *k, double u)
{
    double ph[NAT_MAX_DEGREE + 2];
    return horner(ph, law_phase(k, ph), u);
}

double nat_law_kappa(const double *k, double u)
{
    return horner(k, NAT_MAX_DEGREE, u);
}

void nat_law_xy(const double *k, double u, double *x, double *y)
{
    double ph[NAT_MAX_DEGREE + 2];
    int deg = law_phase(k, ph);
    double turn = rate_bound(ph, deg, 0, u) * fabs(u);
    if (!(turn <= NAT_MAX_TURNING)) { /* also NaN: u or k not finite */
        *x = *y = NAN;
        return;
    }
    integrate(ph, deg, 0, u, 1, x, y);
}

/* ---- the table ----------------------------------------------------------- */

enum { NCHEB = NAT_CHEB_DEGREE + 1 };

/* the Chebyshev coefficients of panel [a, a + h] whose start point is
 * (xa, ya); returns the largest of its last two coefficients */
static double panel_fit(const double *ph, int deg, double a, double h,
                        double xa, double ya, double *cx, double *cy)
{
    double fx[NCHEB], fy[NCHEB];
    for (int k = 0; k < NCHEB; k++) {
        double t = cos(NAT_PI * (k + 0.5) / NCHEB), c, s;
        integrate(ph, deg, a, a + h * (1 + t) / 2, 1, &c, &s);
        fx[k] = c; // the offset from the panel's start: rounding ~ h
        fy[k] = s;
    }
    for (int j = 0; j < NCHEB; j++) {
        double sx = 0, sy = 0;
        for (int k = 0; k < NCHEB; k++) {
            double w = cos(NAT_PI * j * (k + 0.5) / NCHEB);
            sx += fx[k] * w;
            sy += fy[k] * w;
        }
        cx[j] = sx * (j ? 2.0 : 1.0) / NCHEB;
        cy[j] = sy * (j ? 2.0 : 1.0) / NCHEB;
    }
    cx[0] += xa;
    cy[0] += ya;
    return fmax(fmax(fabs(cx[NCHEB - 1]), fabs(cx[NCHEB - 2])),
                fmax(fabs(cy[NCHEB - 1]), fabs(cy[NCHEB - 2])));
}

/* fills t for t->npanels; returns the largest tail */
static double table_fill(NatTable *t, const double *ph, int deg)
{
    double S = t->seg.length, h = S / t->npanels, tail = 0;
    double xa = t->seg.x0, ya = t->seg.y0;
    for (int q = 0; q < t->npanels; q++) {
        double a = q * h, c, s;
        double *cx = t->cx + (size_t)q * NCHEB, *cy = t->cy + (size_t)q * NCHEB;
        tail = fmax(tail, panel_fit(ph, deg, a, h, xa, ya, cx, cy));
        integrate(ph, deg, a, a + h, 1, &c, &s);
        xa += c;
        ya += s;
    }
    return tail;
}

/* drops the top coefficients that are below 1e-16 of the length in every
 * panel: fewer steps of Clenshaw's recurrence */
static void trim(NatTable *t)
{
    double eps = 1e-16 * fmax(t->seg.length, 1e-300);
    while (t->ncoef > 2) {
        int j = t->ncoef - 1;
        for (int q = 0; q < t->npanels; q++)
            if (fabs(t->cx[(size_t)q * NCHEB + j]) > eps ||
                fabs(t->cy[(size_t)q * NCHEB + j]) > eps)
                return;
        t->ncoef--;
    }
}

int nat_table_build(NatTable *t, const NatSegment *seg)
{
    memset(t, 0, sizeof *t);
    t->seg = *seg;
    double S = seg->length;
    if (!isfinite(S) || S < 0)
        return -1;
    double ph[NAT_MAX_DEGREE + 2];
    int deg = phase_coef(seg, ph);
    /* at most half a radian of turning a panel to start with: the
     * coefficients then fall below 1e-16 of S by about the 12th */
    double n0 = ceil(rate_bound(ph, deg, 0, S) * S / 0.5);
    int n = !(n0 >= 1) ? 1 : n0 > NAT_MAX_PANELS ? NAT_MAX_PANELS : (int)n0;
    t->ncoef = NCHEB;
    for (;; n *= 2) {
        t->npanels = n;
        t->scale = S > 0 ? n / S : 0;
        t->cx = pc_xrealloc(t->cx, sizeof(double) * NCHEB * (size_t)n);
        t->cy = pc_xrealloc(t->cy, sizeof(double) * NCHEB * (size_t)n);
        double tail = table_fill(t, ph, deg);
        if (tail <= 1e-15 * fmax(S, 1e-300)) {
            trim(t);
            return 0;
        }
        if (n * 2 > NAT_MAX_PANELS)
            return -1;
    }
}

void nat_table_free(NatTable *t)
{
    pc_free(t->cx);
    pc_free(t->cy);
    t->cx = t->cy = NULL;
}

void nat_table_eval(const NatTable *t, double s, double *x, double *y)
{
    double u = s * t->scale;
    int q = (int)u;
    if (!(u > 0))
        q = 0, u = 0;
    if (q >= t->npanels)
        q = t->npanels - 1, u = t->npanels;
    double z = 2 * (u - q) - 1, z2 = 2 * z;
    const double *cx = t->cx + (size_t)q * NCHEB,
                 *cy = t->cy + (size_t)q * NCHEB;
    double bx1 = 0, bx2 = 0, by1 = 0, by2 = 0;
    for (int j = t->ncoef - 1; j >= 1; j--) {
        double bx = z2 * bx1 - bx2 + cx[j], by = z2 * by1 - by2 + cy[j];
        bx2 = bx1, bx1 = bx, by2 = by1, by1 = by;
    }
    *x = z * bx1 - bx2 + cx[0];
    *y = z * by1 - by2 + cy[0];
}
