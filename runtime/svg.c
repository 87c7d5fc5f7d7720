/*
 * svg.c - the SVG writer of a plot (plot.h says what is drawn and how):
 * the figure's window fitted to the curves, the curves as clipped paths,
 * the construction lines and marks, tangent vectors and the curvature
 * comb.  The curves come from plot_sample.c, the derivatives from
 * plot_jet.c, the projection from plot_view.c.
 */
#include "runtime/plot_int.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"
#include "runtime/eval.h"

void plot_spec_default(PlotSpec *s)
{
    memset(s, 0, sizeof *s);
    plot_view_default(&s->view, 2);
    plot_limits_default(&s->lim);
    s->tangent_scale = 1;
    s->width = 720;
}

static const char *const palette[] = {"#d62728", "#1f77b4", "#2ca02c",
                                      "#9467bd", "#ff7f0e", "#8c564b"};
enum { NPALETTE = sizeof palette / sizeof palette[0] };

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* xs[n] sorted in place; the q-quantile */
static double quantile(double *xs, size_t n, double q)
{
    qsort(xs, n, sizeof *xs, cmp_double);
    size_t k = (size_t)(q * (double)(n - 1) + 0.5);
    return xs[k < n ? k : n - 1];
}

static void box_add(double *B, double x, double y)
{
    if (!isfinite(x) || !isfinite(y))
        return;
    B[0] = fmin(B[0], x);
    B[1] = fmin(B[1], y);
    B[2] = fmax(B[2], x);
    B[3] = fmax(B[3], y);
}

static int box_empty(const double *B)
{
    return !(B[0] <= B[2] && B[1] <= B[3]);
}

static double box_diag(const double *B)
{
    return hypot(B[2] - B[0], B[3] - B[1]);
}

/* The window: everything, unless the curves run far beyond the points and
 * the middle of the curves (poles, a long param range): then the core,
 * enlarged by a quarter each side.  Never degenerate; a 6% margin. */
static void fit_box(double *box, const PlotSpec *s, const PlotCurve *cv,
                    const double *mx, const double *my)
{
    double F[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    double C[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    size_t n = 0;
    for (int i = 0; i < s->nmarks; i++) {
        box_add(F, mx[i], my[i]);
        box_add(C, mx[i], my[i]);
    }
    for (int k = 0; k < s->ncurves; k++)
        for (size_t i = 0; i < cv[k].n; i++)
            if (cv[k].ok[i]) {
                box_add(F, cv[k].x[i], cv[k].y[i]);
                n++;
            }
    if (n > 0) {
        double *xs = pc_xmalloc(sizeof *xs * n),
               *ys = pc_xmalloc(sizeof *ys * n);
        size_t j = 0;
        for (int k = 0; k < s->ncurves; k++)
            for (size_t i = 0; i < cv[k].n; i++)
                if (cv[k].ok[i]) {
                    xs[j] = cv[k].x[i];
                    ys[j++] = cv[k].y[i];
                }
        box_add(C, quantile(xs, n, 0.05), quantile(ys, n, 0.05));
        box_add(C, quantile(xs, n, 0.95), quantile(ys, n, 0.95));
        pc_free(xs);
        pc_free(ys);
    }
    if (box_empty(F)) {
        box[0] = box[1] = -1;
        box[2] = box[3] = 1;
        return;
    }
    double dc = box_diag(C), df = box_diag(F);
    if (!isfinite(dc)) { // coordinates beyond half the double range
        box[0] = box[1] = -1;
        box[2] = box[3] = 1;
        return;
    }
    if (!(df <= 8 * dc) && dc > 0) {
        double w = C[2] - C[0], h = C[3] - C[1];
        memcpy(box, C, sizeof C);
        box[0] -= w / 4;
        box[2] += w / 4;
        box[1] -= h / 4;
        box[3] += h / 4;
    } else {
        memcpy(box, F, sizeof F);
    }
    double w = box[2] - box[0], h = box[3] - box[1];
    if (!(w > 0) && !(h > 0)) {
        double e = fmax(fabs(box[0]), fabs(box[1])) * 0.2;
        w = h = e > 0 && isfinite(e) ? e : 1;
        box[0] -= w / 2;
        box[2] += w / 2;
        box[1] -= h / 2;
        box[3] += h / 2;
    } else if (!(w > h * 1e-6)) {
        box[0] -= h / 2;
        box[2] += h / 2;
    } else if (!(h > w * 1e-6)) {
        box[1] -= w / 2;
        box[3] += w / 2;
    }
    w = box[2] - box[0];
    h = box[3] - box[1];
    if (!(isfinite(w) && isfinite(h) && w > 0 && h > 0)) {
        box[0] = box[1] = -1;
        box[2] = box[3] = 1;
        return;
    }
    box[0] -= 0.06 * w;
    box[2] += 0.06 * w;
    box[1] -= 0.06 * h;
    box[3] += 0.06 * h;
}

/* Liang-Barsky: clips (x0,y0)-(x1,y1) to B; 0 when nothing is left;
 * *c0, *c1 say whether an end moved */
static int clip(const double *B, double *x0, double *y0, double *x1, double *y1,
                int *c0, int *c1)
{
    double dx = *x1 - *x0, dy = *y1 - *y0, u0 = 0, u1 = 1;
    double pq[4][2] = {{-dx, *x0 - B[0]},
                       {dx, B[2] - *x0},
                       {-dy, *y0 - B[1]},
                       {dy, B[3] - *y0}};
    for (int k = 0; k < 4; k++) {
        double p = pq[k][0], q = pq[k][1];
        if (p == 0) {
            if (q < 0)
                return 0;
        } else {
            double r = q / p;
            if (p < 0 && r > u0)
                u0 = r;
            else if (p > 0 && r < u1)
                u1 = r;
        }
    }
    if (!(u0 <= u1))
        return 0;
    double ax = *x0, ay = *y0;
    *c0 = u0 > 0;
    *c1 = u1 < 1;
    if (*c1) {
        *x1 = ax + u1 * dx;
        *y1 = ay + u1 * dy;
    }
    if (*c0) {
        *x0 = ax + u0 * dx;
        *y0 = ay + u0 * dy;
    }
    return 1;
}

typedef struct Fig {
    FILE *out;
    double s, tx, ty; // pixel = (tx + s x, ty - s y)
    int W, H;
    double clipw[4]; // the canvas in world coordinates, a little larger
    double clipp[4]; // the canvas in pixels, a little larger
    int digits;      // significant digits of world coordinates
} Fig;

/* a number in the C locale, %.*g, no "-0" */
static void put_num(FILE *out, double v, int digits)
{
    char buf[64];
    if (v == 0)
        v = 0; // -0 -> 0
    pc_snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (strcmp(buf, "-0") == 0)
        strcpy(buf, "0");
    fputs(buf, out);
}

static void put_px(FILE *out, double v)
{
    char buf[64];
    pc_snprintf(buf, sizeof buf, "%.1f", v);
    size_t n = strlen(buf);
    if (n >= 2 && strcmp(buf + n - 2, ".0") == 0)
        buf[n - 2] = '\0';
    if (strcmp(buf, "-0") == 0)
        strcpy(buf, "0");
    fputs(buf, out);
}

static void put_escaped(FILE *out, const char *s)
{
    for (; s && *s; s++) {
        switch (*s) {
        case '&':
            fputs("&amp;", out);
            break;
        case '<':
            fputs("&lt;", out);
            break;
        case '>':
            fputs("&gt;", out);
            break;
        case '"':
            fputs("&quot;", out);
            break;
        case '\'':
            fputs("&apos;", out);
            break;
        default:
            /* control characters are not allowed in XML 1.0 */
            if ((unsigned char)*s >= 0x20 || *s == '\t' || *s == '\n')
                fputc(*s, out);
            else
                fputc('?', out);
        }
    }
}

static void px_of(const Fig *g, double x, double y, double *px, double *py)
{
    *px = g->tx + g->s * x;
    *py = g->ty - g->s * y;
}

/* A pixel polyline: segments clipped to the canvas, joined where one
 * starts where the last one ended. */
typedef struct Pen {
    const Fig *g;
    int down; // the pen rests at (x, y)
    double x, y;
} Pen;

static void pen_move_to(const Fig *g, double x, double y)
{
    fputs("M", g->out);
    put_px(g->out, x);
    fputc(' ', g->out);
    put_px(g->out, y);
}

static void pen_line(Pen *P, double x0, double y0, double x1, double y1)
{
    const Fig *g = P->g;
    int c0, c1;
    if (!clip(g->clipp, &x0, &y0, &x1, &y1, &c0, &c1)) {
        P->down = 0;
        return;
    }
    if (!P->down || x0 != P->x || y0 != P->y)
        pen_move_to(g, x0, y0);
    fputs("L", g->out);
    put_px(g->out, x1);
    fputc(' ', g->out);
    put_px(g->out, y1);
    P->down = !c1;
    P->x = x1;
    P->y = y1;
}

static void pen_lift(Pen *P)
{
    P->down = 0;
}

/* one separate pixel segment, clipped */
static void px_segment(const Fig *g, double x0, double y0, double x1, double y1)
{
    Pen P = {g, 0, 0, 0};
    pen_line(&P, x0, y0, x1, y1);
}

static void write_curve(const Fig *g, const PlotCurve *c, const char *name,
                        const char *colour)
{
    FILE *out = g->out;
    fputs("<path class=\"curve\" id=\"curve-", out);
    put_escaped(out, name);
    fprintf(out, "\" stroke=\"%s\" stroke-width=\"", colour);
    put_num(out, 2 / g->s, 3);
    fputs("\" d=\"", out);
    long pen = -1; // sample the pen rests on, unclipped
    int cont = 0;  // the last command was L (more pairs continue it)
    for (size_t i = 1; i < c->n; i++) {
        if (c->cut[i])
            continue;
        double x0 = c->x[i - 1], y0 = c->y[i - 1], x1 = c->x[i], y1 = c->y[i];
        int c0, c1;
        if (!clip(g->clipw, &x0, &y0, &x1, &y1, &c0, &c1)) {
            pen = -1;
            continue;
        }
        if (c0 || pen != (long)i - 1) {
            fputs("M", out);
            put_num(out, x0, g->digits);
            fputc(' ', out);
            put_num(out, y0, g->digits);
            cont = 0;
        }
        fputs(cont ? " " : "L", out);
        put_num(out, x1, g->digits);
        fputc(' ', out);
        put_num(out, y1, g->digits);
        cont = 1;
        pen = c1 ? -1 : (long)i;
    }
    fputs("\"/>\n", out);
}

/* the forward-mode jet of output o at t, projected: position, r', r'' */
typedef struct Jet {
    const PlotEnv *env;
    const PlotView *view;
    unsigned char *live;
    double (*r)[3];
    double *buf; // 3 * dim
} Jet;

static void jet_init(Jet *J, const PlotEnv *env, const PlotView *view)
{
    J->env = env;
    J->view = view;
    J->live = pc_xmalloc((size_t)env->plan->nins + 1);
    J->r = pc_xmalloc(sizeof *J->r * (size_t)(env->plan->nins + 1));
    J->buf = pc_xmalloc(sizeof *J->buf * 3 * (size_t)env->dim);
}

static void jet_clear(Jet *J)
{
    pc_free(J->live);
    pc_free(J->r);
    pc_free(J->buf);
}

/* p[k] = (x, y) of the k-th derivative; 1 when all finite and no status */
static int jet_at(Jet *J, int o, double t, double p[3][2])
{
    const PlotEnv *env = J->env;
    const PlanOutput *po = &env->plan->outputs[o];
    int dim = env->dim;
    plan_live(env->plan, o, J->live);
    plot_jet_run(env, J->live, t, J->r);
    if (po->bad >= 0 && J->r[po->bad][0] != 0)
        return 0;
    int ok = 1;
    for (int k = 0; k < 3; k++) {
        double *P = J->buf + (size_t)k * (size_t)dim;
        for (int c = 0; c < dim; c++) {
            double v = 0;
            for (int j = 0; j < po->nterms; j++)
                v += J->r[po->reg[j]][k] * env->points[po->point[j]][c];
            P[c] = v;
        }
        plot_project(J->view, P, dim, &p[k][0], &p[k][1]);
        ok &= isfinite(p[k][0]) && isfinite(p[k][1]);
    }
    return ok;
}

static void write_tangents(const Fig *g, const PlotSpec *s, Jet *J)
{
    FILE *out = g->out;
    fputs("<g class=\"tangents\" stroke-width=\"1.5\">\n", out);
    for (int k = 0; k < s->ncurves; k++) {
        for (int i = 0; i < s->ntangents; i++) {
            double p[3][2];
            if (!jet_at(J, s->curves[k], s->tangents[i], p))
                continue;
            double x0, y0, x1, y1;
            px_of(g, p[0][0], p[0][1], &x0, &y0);
            px_of(g, p[0][0] + s->tangent_scale * p[1][0],
                  p[0][1] + s->tangent_scale * p[1][1], &x1, &y1);
            double dx = x1 - x0, dy = y1 - y0, l = hypot(dx, dy);
            if (!isfinite(l))
                continue;
            fprintf(out, "<path stroke=\"%s\" d=\"", palette[k % NPALETTE]);
            px_segment(g, x0, y0, x1, y1);
            /* the arrowhead, when the tip is on the canvas */
            if (l > 1 && x1 >= 0 && x1 <= g->W && y1 >= 0 && y1 <= g->H) {
                double ux = dx / l, uy = dy / l, a = l < 20 ? l / 2 : 10;
                px_segment(g, x1, y1, x1 - a * ux + 0.4 * a * uy,
                           y1 - a * uy - 0.4 * a * ux);
                px_segment(g, x1, y1, x1 - a * ux - 0.4 * a * uy,
                           y1 - a * uy + 0.4 * a * ux);
            }
            fputs("\"/>\n", out);
        }
    }
    fputs("</g>\n", out);
}

/* the curvature comb of the drawn (projected) curve: teeth along the
 * normal, away from the centre of curvature, length scale * curvature */
static void write_comb(const Fig *g, const PlotSpec *s, Jet *J,
                       const PlotCurve *cv)
{
    FILE *out = g->out;
    int n = s->comb;
    double *px = pc_xmalloc(sizeof *px * (size_t)(n + 1) * 4);
    double *kap = pc_xmalloc(sizeof *kap * (size_t)(n + 1));
    unsigned char *ok = pc_xmalloc((size_t)n + 1);
    double *fac = NULL;
    fputs("<g class=\"comb\" stroke-width=\"0.75\">\n", out);
    for (int k = 0; k < s->ncurves; k++) {
        const PlotCurve *c = &cv[k];
        int nf = c->nfac;
        fac =
            pc_xrealloc(fac, sizeof *fac * ((size_t)(n + 1) * (size_t)nf + 1));
        double kmax[2] = {0, 0};
        size_t nk = 0;
        for (int i = 0; i <= n; i++) {
            double t = n == 0 ? s->lo : mix(s->lo, s->hi, (double)i / n);
            double p[3][2];
            ok[i] = (unsigned char)jet_at(J, s->curves[k], t, p);
            for (int f = 0; f < nf; f++)
                fac[(size_t)i * (size_t)nf + (size_t)f] = J->r[c->facreg[f]][0];
            if (!ok[i]) /* p is not filled in */
                continue;
            double sp = hypot(p[1][0], p[1][1]);
            double kp =
                (p[1][0] * p[2][1] - p[1][1] * p[2][0]) / (sp * sp * sp);
            if (!(sp > 0) || !isfinite(kp))
                ok[i] = 0;
            if (!ok[i])
                continue;
            kap[i] = kp;
            px[4 * i] = p[0][0];
            px[4 * i + 1] = p[0][1];
            px[4 * i + 2] = -p[1][1] / sp; // left normal
            px[4 * i + 3] = p[1][0] / sp;
            nk++;
        }
        /* automatic scale: the 90% quantile of |curvature| makes a tooth
         * a tenth of the figure */
        double scale = s->comb_scale;
        if (!(scale > 0) && nk > 0) {
            double *a = pc_xmalloc(sizeof *a * nk);
            size_t j = 0;
            for (int i = 0; i <= n; i++)
                if (ok[i])
                    a[j++] = fabs(kap[i]);
            kmax[0] = quantile(a, nk, 0.9);
            pc_free(a);
            scale = kmax[0] > 0 ? 0.1 * (g->W + g->H) / 2 / g->s / kmax[0] : 0;
        }
        const char *col = palette[k % NPALETTE];
        fprintf(out, "<path stroke=\"%s\" stroke-opacity=\"0.5\" d=\"", col);
        for (int i = 0; i <= n; i++) {
            if (!ok[i])
                continue;
            double ax, ay, bx, by;
            px_of(g, px[4 * i], px[4 * i + 1], &ax, &ay);
            px_of(g, px[4 * i] - scale * kap[i] * px[4 * i + 2],
                  px[4 * i + 1] - scale * kap[i] * px[4 * i + 3], &bx, &by);
            px_segment(g, ax, ay, bx, by);
        }
        fputs("\"/>\n", out);
        /* the envelope through the teeth's ends, cut where the curve is */
        fprintf(out, "<path stroke=\"%s\" d=\"", col);
        Pen pen = {g, 0, 0, 0};
        for (int i = 1; i <= n; i++) {
            if (!ok[i] || !ok[i - 1]) {
                pen_lift(&pen);
                continue;
            }
            int pole = 0;
            for (int f = 0; f < nf && !pole; f++) {
                double u = fac[(size_t)(i - 1) * (size_t)nf + (size_t)f];
                double v = fac[(size_t)i * (size_t)nf + (size_t)f];
                pole = (u < 0 && v > 0) || (u > 0 && v < 0);
            }
            if (pole) {
                pen_lift(&pen);
                continue;
            }
            double ax, ay, bx, by;
            px_of(g, px[4 * (i - 1)] - scale * kap[i - 1] * px[4 * (i - 1) + 2],
                  px[4 * (i - 1) + 1] -
                      scale * kap[i - 1] * px[4 * (i - 1) + 3],
                  &ax, &ay);
            px_of(g, px[4 * i] - scale * kap[i] * px[4 * i + 2],
                  px[4 * i + 1] - scale * kap[i] * px[4 * i + 3], &bx, &by);
            pen_line(&pen, ax, ay, bx, by);
        }
        fputs("\"/>\n", out);
    }
    fputs("</g>\n", out);
    pc_free(px);
    pc_free(kap);
    pc_free(ok);
    pc_free(fac);
}

static void write_lines(const Fig *g, const PlotSpec *s, const double *mx,
                        const double *my)
{
    FILE *out = g->out;
    fputs("<path class=\"lines\" stroke=\"#888\" stroke-width=\"1\" d=\"", out);
    for (int i = 0; i < s->nlines; i++) {
        const PlotLine *L = &s->lines[i];
        double px[4], py[4];
        int n = 0;
        for (int k = 0; k < L->n && k < 4; k++) {
            int m = L->m[k];
            if (m < 0 || m >= s->nmarks || !isfinite(mx[m]) || !isfinite(my[m]))
                continue;
            px_of(g, mx[m], my[m], &px[n], &py[n]);
            n++;
        }
        /* the direction: the two points furthest apart */
        double best = 0;
        int a = 0, b = 0;
        for (int p = 0; p < n; p++)
            for (int q = p + 1; q < n; q++) {
                double d = hypot(px[q] - px[p], py[q] - py[p]);
                if (d > best) {
                    best = d;
                    a = p;
                    b = q;
                }
            }
        if (!(best > 0.5) || !isfinite(best))
            continue;
        double ux = (px[b] - px[a]) / best, uy = (py[b] - py[a]) / best;
        /* a little beyond both ends */
        px_segment(g, px[a] - 8 * ux, py[a] - 8 * uy, px[b] + 8 * ux,
                   py[b] + 8 * uy);
    }
    fputs("\"/>\n", out);
}

static void write_marks(const Fig *g, const PlotSpec *s, const double *mx,
                        const double *my)
{
    FILE *out = g->out;
    fputs("<g class=\"points\">\n", out);
    for (int i = 0; i < s->nmarks; i++) {
        const PlotMark *m = &s->marks[i];
        double x, y;
        px_of(g, mx[i], my[i], &x, &y);
        if (!(x >= 0 && x <= g->W && y >= 0 && y <= g->H))
            continue;
        const char *fill =
            m->kind == PLOT_BASE ? "#000"
            : m->kind == PLOT_AUX
                ? "#fff"
                : palette[(m->curve < 0 ? 0 : m->curve) % NPALETTE];
        fputs("<circle cx=\"", out);
        put_px(out, x);
        fputs("\" cy=\"", out);
        put_px(out, y);
        fprintf(out, "\" r=\"%s\" fill=\"%s\" stroke=\"#000\"/>",
                m->kind == PLOT_BASE ? "3" : "2.5", fill);
        if (!m->name) { // a point of the construction without a name
            fputc('\n', out);
            continue;
        }
        fputs("<text x=\"", out);
        put_px(out, x + 5);
        fputs("\" y=\"", out);
        put_px(out, y - 5);
        fprintf(out, "\"%s>", m->kind == PLOT_AUX ? " fill=\"#555\"" : "");
        put_escaped(out, m->name);
        fputs("</text>\n", out);
    }
    fputs("</g>\n", out);
}

/* point output o at t, projected (eval's numbers): 1 when drawable */
static int curve_point(const PlotSpec *s, int o, double t, double *x, double *y)
{
    const PlotEnv *env = &s->env;
    const Plan *p = env->plan;
    double *pv = pc_xmalloc(sizeof *pv * (size_t)(p->nparams + 1));
    const double **prm = pc_xmalloc(sizeof *prm * (size_t)(p->nparams + 1));
    double *pos = pc_xmalloc(sizeof *pos * (size_t)env->dim);
    for (int i = 0; i < p->nparams; i++) {
        pv[i] = i == env->param ? t : env->params[i];
        prm[i] = pv + i;
    }
    unsigned char st = 0;
    plan_eval(p, o, 1, (const double *const *)prm, env->consts, env->points,
              env->dim, pos, &st);
    int ok = st == 0;
    for (int c = 0; c < env->dim && ok; c++)
        ok = isfinite(pos[c]);
    if (ok)
        plot_project(&s->view, pos, env->dim, x, y);
    pc_free(pos);
    pc_free(prm);
    pc_free(pv);
    return ok && isfinite(*x) && isfinite(*y);
}

static void knot_mark(const Fig *g, double x, double y, const char *colour)
{
    double px, py;
    px_of(g, x, y, &px, &py);
    if (!(px >= 0 && px <= g->W && py >= 0 && py <= g->H))
        return;
    fputs("<circle class=\"knot\" cx=\"", g->out);
    put_px(g->out, px);
    fputs("\" cy=\"", g->out);
    put_px(g->out, py);
    fprintf(g->out, "\" r=\"5\" stroke=\"%s\"/>\n", colour);
}

/* A mark at each knot of the curves (plot_knots: where a sign kernel's
 * linear argument is 0) on the curve's point there; at a jump (the two
 * one-sided points more than a tenth of a pixel apart) one at each end
 * instead. */
static void write_knots(const Fig *g, const PlotSpec *s, const PlotCurve *cv)
{
    int any = 0;
    for (int k = 0; k < s->ncurves; k++)
        any |= cv[k].nknots > 0;
    if (!any)
        return;
    fputs("<g class=\"knots\" fill=\"none\" stroke-width=\"1.5\">\n", g->out);
    for (int k = 0; k < s->ncurves; k++) {
        const char *colour = palette[k % NPALETTE];
        for (size_t i = 0; i < cv[k].nknots; i++) {
            double t = cv[k].knots[i], x, y, xl, yl, xr, yr;
            int o = s->curves[k];
            int ok = curve_point(s, o, t, &x, &y);
            int okl = curve_point(s, o, nextafter(t, -INFINITY), &xl, &yl);
            int okr = curve_point(s, o, nextafter(t, INFINITY), &xr, &yr);
            if (okl && okr && hypot(xr - xl, yr - yl) * g->s > 0.1) {
                knot_mark(g, xl, yl, colour);
                knot_mark(g, xr, yr, colour);
            } else if (ok) {
                knot_mark(g, x, y, colour);
            }
        }
    }
    fputs("</g>\n", g->out);
}

/* the sampling limits of the figure's curves */
static PlotLimits limits(const PlotSpec *s, int nc)
{
    /* the budget: per curve, and PLOT_TOTAL_SAMPLES for all of them */
    PlotLimits lim = s->lim;
    if (nc > 0 && lim.max_samples > PLOT_TOTAL_SAMPLES / (size_t)nc)
        lim.max_samples = PLOT_TOTAL_SAMPLES / (size_t)nc;
    if (lim.max_samples < 2)
        lim.max_samples = 2;
    if (lim.initial < 1)
        lim.initial = 1;
    if ((size_t)lim.initial + 1 > lim.max_samples)
        lim.initial = (int)(lim.max_samples - 1);
    if (lim.max_depth > 60)
        lim.max_depth = 60;
    return lim;
}

/* the canvas: its size in pixels, the world-to-pixel map (scale s,
 * translation tx, ty), the clip windows and the digits of the coordinates */
static void canvas(Fig *g, FILE *out, const PlotSpec *s, const double box[4])
{
    g->out = out;
    double w = box[2] - box[0], h = box[3] - box[1];
    g->W = s->width > 0 ? s->width : 720;
    if (s->height > 0) {
        g->H = s->height;
    } else {
        double hh = g->W * h / w;
        g->H = !(hh >= g->W / 3.0) ? (g->W + 2) / 3
               : hh > 1.5 * g->W   ? g->W * 3 / 2
                                   : (int)(hh + 0.5);
    }
    g->s = fmin(g->W / w, g->H / h);
    double cx = (box[0] + box[2]) / 2, cy = (box[1] + box[3]) / 2;
    g->tx = g->W / 2.0 - g->s * cx;
    g->ty = g->H / 2.0 + g->s * cy;
    double ex = 4 / g->s; // 4 px beyond the canvas
    g->clipw[0] = (0 - g->tx) / g->s - ex;
    g->clipw[2] = (g->W - g->tx) / g->s + ex;
    g->clipw[1] = (g->ty - g->H) / g->s - ex;
    g->clipw[3] = g->ty / g->s + ex;
    g->clipp[0] = g->clipp[1] = -4;
    g->clipp[2] = g->W + 4;
    g->clipp[3] = g->H + 4;
    double maxabs = fmax(fmax(fabs(g->clipw[0]), fabs(g->clipw[2])),
                         fmax(fabs(g->clipw[1]), fabs(g->clipw[3])));
    double res = 0.02 / g->s; // a fiftieth of a pixel
    double lg = ceil(log10(maxabs / res));
    g->digits = !(lg >= 4) ? 4 : !(lg <= 17) ? 17 : (int)lg;
}

/* the legend: a stroke of each curve's colour and its name */
static void write_legend(FILE *out, const PlotSpec *s)
{
    const Plan *p = s->env.plan;
    int nc = s->ncurves;
    if (nc > 0) {
        fputs("<g class=\"legend\">\n", out);
        for (int k = 0; k < nc; k++) {
            fprintf(out,
                    "<path d=\"M10 %dh20\" stroke=\"%s\" stroke-width=\"2\"/>"
                    "<text x=\"36\" y=\"%d\">",
                    18 + 18 * k, palette[k % NPALETTE], 23 + 18 * k);
            put_escaped(out, p->outputs[s->curves[k]].name);
            fputs("</text>\n", out);
        }
        fputs("</g>\n", out);
    }
}

int plot_svg(FILE *out, const PlotSpec *s, PlotStats *st)
{
    const PlotEnv *env = &s->env;
    const Plan *p = env->plan;
    int nc = s->ncurves;
    PlotCurve *cv = pc_xcalloc((size_t)nc + 1, sizeof *cv);
    double *mx = pc_xmalloc(sizeof *mx * (size_t)(s->nmarks + 1));
    double *my = pc_xmalloc(sizeof *my * (size_t)(s->nmarks + 1));
    PlotStats local;
    if (!st) {
        memset(&local, 0, sizeof local);
        st = &local;
    }
    for (int i = 0; i < s->nmarks; i++)
        plot_project(&s->view, s->marks[i].at, env->dim, &mx[i], &my[i]);
    PlotLimits lim = limits(s, nc);
    for (int k = 0; k < nc; k++)
        plot_curve_init(&cv[k], env, s->curves[k], s->lo, s->hi, &s->view,
                        &lim);
    double box[4];
    const double *W = s->window;
    if (W && W[0] < W[2] && W[1] < W[3] && isfinite(W[2] - W[0]) &&
        isfinite(W[3] - W[1]))
        memcpy(box, W, sizeof box);
    else
        fit_box(box, s, cv, mx, my);
    for (int k = 0; k < nc; k++)
        plot_curve_refine(&cv[k], env, &s->view, box, &lim);
    /* the canvas */
    Fig g;
    canvas(&g, out, s, box);
    memcpy(st->box, box, sizeof box);
    st->digits = g.digits;

    fprintf(out,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" "
            "width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
            "font-family=\"sans-serif\" font-size=\"14\">\n",
            g.W, g.H, g.W, g.H);
    fputs("<title>", out);
    put_escaped(out, s->title ? s->title : p->name);
    fputs("</title>\n", out);
    fprintf(out, "<rect width=\"%d\" height=\"%d\" fill=\"#fff\"/>\n", g.W,
            g.H);
    fputs("<g fill=\"none\" stroke-linecap=\"round\" "
          "stroke-linejoin=\"round\">\n",
          out);
    if (s->nlines)
        write_lines(&g, s, mx, my);
    Jet J;
    jet_init(&J, env, &s->view);
    if (s->comb > 0)
        write_comb(&g, s, &J, cv);
    /* the curves in world coordinates (eval's numbers, projected) */
    fputs("<g transform=\"matrix(", out);
    put_num(out, g.s, 10);
    fputs(" 0 0 ", out);
    put_num(out, -g.s, 10);
    fputc(' ', out);
    put_num(out, g.tx, 10);
    fputc(' ', out);
    put_num(out, g.ty, 10);
    fputs(")\">\n", out);
    st->samples = 0;
    st->subpaths = 0;
    for (int k = 0; k < nc; k++) {
        write_curve(&g, &cv[k], p->outputs[s->curves[k]].name,
                    palette[k % NPALETTE]);
        st->samples += cv[k].n;
        st->subpaths += plot_curve_subpaths(&cv[k]);
    }
    fputs("</g>\n", out);
    if (s->ntangents > 0)
        write_tangents(&g, s, &J);
    jet_clear(&J);
    fputs("</g>\n", out);
    write_knots(&g, s, cv);
    write_marks(&g, s, mx, my);
    write_legend(out, s);
    fputs("</svg>\n", out);
    if (st->keep_curves) {
        st->curves = cv;
    } else {
        for (int k = 0; k < nc; k++)
            plot_curve_clear(&cv[k]);
        pc_free(cv);
        st->curves = NULL;
    }
    pc_free(mx);
    pc_free(my);
    return ferror(out) ? -1 : 0;
}
