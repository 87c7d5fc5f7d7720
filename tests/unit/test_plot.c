/*
 * test_plot.c - runtime/plot_*.c and svg.c: the sampled paths against plan_eval
 * (read back from the SVG), poles cut, the sample budget, the projections, the
 * forward-mode derivatives against the scheme's own diff(), and the SVG's
 * structure (a small well-formedness checker below).
 */
/* cmocka.h needs these first, in this order */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
// clang-format on

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>

#include "codegen/lower.h"
#include "compiler/derive.h"
#include "runtime/eval.h"
#include "runtime/plot.h"

/* ---- fixtures ------------------------------------------------------------ */

typedef struct Fix {
    Plan *p;
    int dim;
    double *pts; // npoints * dim
    const double *ptr[8];
    double params[4], consts[4];
    PlotEnv env;
} Fix;

static void fix_init(Fix *f, const char *text, int dim, const double *pts)
{
    memset(f, 0, sizeof *f);
    Derived *d = derive_source("t.pcs", text, strlen(text), stderr, NULL);
    assert_non_null(d);
    f->p = lower_derived(d, stderr);
    derived_free(d);
    assert_non_null(f->p);
    f->dim = dim;
    size_t n = (size_t)f->p->npoints * (size_t)dim;
    f->pts = malloc(sizeof *f->pts * (n + 1));
    memcpy(f->pts, pts, sizeof *f->pts * n);
    for (int i = 0; i < f->p->npoints && i < 8; i++)
        f->ptr[i] = f->pts + (size_t)i * (size_t)dim;
    f->env.plan = f->p;
    f->env.param = 0;
    f->env.params = f->params;
    f->env.consts = f->consts;
    f->env.points = f->ptr;
    f->env.dim = dim;
}

static void fix_clear(Fix *f)
{
    plan_free(f->p);
    free(f->pts);
}

static const char desargues[] =
    "scheme desargues_arc\n"
    "point A, B, C, D\n"
    "param t in [0, 1]\n"
    "P = along(A, C, t)\nQ = along(C, B, t)\nK = along(B, D, t)\n"
    "N = along(P, Q, t)\nJ = along(Q, K, t)\n"
    "T = meet(line(P, Q), line(A, B))\nS = meet(line(Q, K), line(C, D))\n"
    "M = meet(line(S, N), line(T, J))\n"
    "dM = diff(M, t)\nd2M = diff(M, t, 2)\n"
    "output M, dM, d2M, T\n";
static const double desargues2[] = {0, 0, 4, 0, 1, 3, 5, 3};
static const double desargues3[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};

/* the SVG of spec s in memory */
static char *svg_of(const PlotSpec *s, PlotStats *st)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    assert_int_equal(plot_svg(m, s, st), 0);
    fclose(m);
    return buf;
}

/* ---- a small XML well-formedness checker --------------------------------- */

/* 1 when text is one well-formed element (prolog allowed): tags nest and
 * match, attributes are quoted and unique, entities known, no raw '<' or
 * '&' in text. */
static int xml_ok(const char *s)
{
    const char *stack[64];
    size_t slen[64];
    int depth = 0, roots = 0;
    if (strncmp(s, "<?xml", 5) == 0) {
        s = strstr(s, "?>");
        if (!s)
            return 0;
        s += 2;
    }
    while (*s) {
        if (*s == '<') {
            if (s[1] == '/') {
                const char *n = s + 2;
                size_t k = strcspn(n, ">");
                if (depth == 0 || n[k] != '>' || k != slen[depth - 1] ||
                    strncmp(n, stack[depth - 1], k) != 0)
                    return 0;
                depth--;
                s = n + k + 1;
                continue;
            }
            const char *n = s + 1;
            size_t k = strcspn(n, " \t\n/>");
            if (k == 0)
                return 0;
            const char *a = n + k;
            char names[32][32];
            int nn = 0;
            for (;;) {
                while (*a == ' ' || *a == '\n' || *a == '\t')
                    a++;
                if (*a == '/' && a[1] == '>') {
                    a += 2;
                    if (depth == 0)
                        roots++;
                    break;
                }
                if (*a == '>') {
                    if (depth == 64)
                        return 0;
                    if (depth == 0)
                        roots++;
                    stack[depth] = n;
                    slen[depth++] = k;
                    a++;
                    break;
                }
                size_t an = strcspn(a, "= \t\n/>");
                if (an == 0 || an >= 32 || a[an] != '=' || a[an + 1] != '"')
                    return 0;
                for (int i = 0; i < nn; i++)
                    if (strlen(names[i]) == an && strncmp(names[i], a, an) == 0)
                        return 0;
                if (nn < 32) {
                    memcpy(names[nn], a, an);
                    names[nn++][an] = '\0';
                }
                const char *v = a + an + 2;
                size_t vn = strcspn(v, "\"<");
                if (v[vn] != '"')
                    return 0;
                a = v + vn + 1;
            }
            s = a;
        } else if (*s == '&') {
            static const char *ent[] = {"&amp;", "&lt;", "&gt;", "&quot;",
                                        "&apos;"};
            int found = 0;
            for (int i = 0; i < 5 && !found; i++)
                if (strncmp(s, ent[i], strlen(ent[i])) == 0) {
                    s += strlen(ent[i]);
                    found = 1;
                }
            if (!found)
                return 0;
        } else {
            if (depth == 0 && !(*s == ' ' || *s == '\n'))
                return 0;
            s++;
        }
    }
    return depth == 0 && roots == 1;
}

static void test_xml_checker_can_fail(void **state)
{
    (void)state;
    assert_true(xml_ok("<a b=\"1\"><c/>x &amp; y</a>\n"));
    assert_false(xml_ok("<a><b></a></b>"));
    assert_false(xml_ok("<a b=\"1\" b=\"2\"/>"));
    assert_false(xml_ok("<a>x & y</a>"));
    assert_false(xml_ok("<a>"));
    assert_false(xml_ok("<a/><b/>"));
}

/* ---- reading paths back -------------------------------------------------- */

typedef struct Path {
    int n; // vertices
    double *x, *y;
    int *move; // 1: the vertex starts a subpath (M)
    int subpaths;
} Path;

/* the d attribute of the path with id="curve-NAME" */
static Path read_path(const char *svg, const char *name)
{
    Path P;
    memset(&P, 0, sizeof P);
    char key[64];
    snprintf(key, sizeof key, "id=\"curve-%s\"", name);
    const char *s = strstr(svg, key);
    assert_non_null(s);
    s = strstr(s, " d=\"");
    assert_non_null(s);
    s += 4;
    int cap = 16;
    P.x = malloc(sizeof *P.x * (size_t)cap);
    P.y = malloc(sizeof *P.y * (size_t)cap);
    P.move = malloc(sizeof *P.move * (size_t)cap);
    int mv = 0;
    while (*s && *s != '"') {
        if (*s == 'M') {
            mv = 1;
            s++;
            continue;
        }
        if (*s == 'L' || *s == ' ') {
            s++;
            continue;
        }
        char *e;
        double x = strtod(s, &e);
        assert_true(e != s);
        while (*e == ' ')
            e++;
        const char *s2 = e;
        double y = strtod(s2, &e);
        assert_true(e != s2);
        s = e;
        if (P.n == cap) {
            cap *= 2;
            P.x = realloc(P.x, sizeof *P.x * (size_t)cap);
            P.y = realloc(P.y, sizeof *P.y * (size_t)cap);
            P.move = realloc(P.move, sizeof *P.move * (size_t)cap);
        }
        P.x[P.n] = x;
        P.y[P.n] = y;
        P.move[P.n++] = mv;
        P.subpaths += mv;
        mv = 0;
    }
    return P;
}

static void path_clear(Path *P)
{
    free(P->x);
    free(P->y);
    free(P->move);
}

/* ---- tests --------------------------------------------------------------- */

/* Every vertex of the SVG path is a sample, and every sample agrees with
 * plan_eval at its t to the printed precision. */
static void check_path_against_eval(Fix *f, const PlotSpec *s, int o,
                                    const char *svg, const PlotCurve *c,
                                    int digits)
{
    Path P = read_path(svg, f->p->outputs[o].name);
    assert_true(P.n >= 2);
    assert_true(digits >= 4 && digits <= 17);
    size_t j = 0;
    int matched = 0;
    double *pv = malloc(sizeof *pv * 1);
    double *pos = malloc(sizeof *pos * (size_t)f->dim);
    unsigned char stt;
    for (int v = 0; v < P.n; v++) {
        /* the next drawable sample with this position */
        int found = 0;
        for (; j < c->n && !found; j++) {
            /* the printed precision: a unit in the last digit */
            double tol =
                fmax(fabs(P.x[v]), fabs(P.y[v])) * pow(10, 1 - digits) + 1e-300;
            if (fabs(c->x[j] - P.x[v]) <= tol && fabs(c->y[j] - P.y[v]) <= tol)
                found = 1;
            else
                continue;
            pv[0] = c->t[j];
            const double *cols[1] = {pv};
            plan_eval(f->p, o, 1, cols, f->consts, f->env.points, f->dim, pos,
                      &stt);
            assert_int_equal(stt, 0);
            double x, y;
            plot_project(&s->view, pos, f->dim, &x, &y);
            assert_true(fabs(x - P.x[v]) <= tol);
            assert_true(fabs(y - P.y[v]) <= tol);
            matched++;
        }
        assert_true(found);
    }
    assert_int_equal(matched, P.n);
    free(pv);
    free(pos);
    path_clear(&P);
}

static void test_plot_desargues_2d_path_is_eval(void **state)
{
    (void)state;
    Fix f;
    fix_init(&f, desargues, 2, desargues2);
    PlotSpec s;
    plot_spec_default(&s);
    s.env = f.env;
    int curves[1] = {plan_find_output(f.p, "M")};
    s.curves = curves;
    s.ncurves = 1;
    s.lo = 0;
    s.hi = 1;
    PlotMark marks[4];
    const char *names[4] = {"A", "B", "C", "D"};
    for (int i = 0; i < 4; i++) {
        marks[i].name = names[i];
        marks[i].at = f.ptr[i];
        marks[i].kind = PLOT_BASE;
        marks[i].curve = -1;
    }
    s.marks = marks;
    s.nmarks = 4;
    PlotStats st;
    memset(&st, 0, sizeof st);
    st.keep_curves = 1;
    char *svg = svg_of(&s, &st);
    assert_true(xml_ok(svg));
    assert_non_null(strstr(svg, "<svg xmlns=\"http://www.w3.org/2000/svg\""));
    assert_non_null(strstr(svg, ">A</text>"));
    assert_non_null(strstr(svg, ">D</text>"));
    assert_int_equal(st.subpaths, 1);
    /* the arc runs from A to D */
    assert_true(st.curves[0].n > 10 && st.curves[0].n < 1000);
    assert_true(fabs(st.curves[0].x[0] - 0) < 1e-12);
    assert_true(fabs(st.curves[0].x[st.curves[0].n - 1] - 5) < 1e-12);
    check_path_against_eval(&f, &s, curves[0], svg, &st.curves[0], st.digits);
    /* small: a few KB */
    assert_true(strlen(svg) < 20000);
    plot_curve_clear(&st.curves[0]);
    free(st.curves);
    free(svg);
    fix_clear(&f);
}

static void test_plot_pole_is_cut(void **state)
{
    (void)state;
    Fix f;
    /* M = (t, 1/(3t - 1)): a hyperbola with its pole at t = 1/3 */
    static const char text[] = "point A, B, C\nparam t in [-1, 1]\n"
                               "U = (B - A)*t + A\n"
                               "M = U + (C - A)*(1/(3*t - 1))\n"
                               "output M\n";
    static const double pts[] = {0, 0, 1, 0, 0, 1};
    fix_init(&f, text, 2, pts);
    PlotSpec s;
    plot_spec_default(&s);
    s.env = f.env;
    int curves[1] = {0};
    s.curves = curves;
    s.ncurves = 1;
    s.lo = -1;
    s.hi = 1;
    double win[4] = {-1.5, -10, 1.5, 10};
    s.window = win;
    PlotStats st;
    memset(&st, 0, sizeof st);
    st.keep_curves = 1;
    char *svg = svg_of(&s, &st);
    assert_true(xml_ok(svg));
    const PlotCurve *c = &st.curves[0];
    assert_int_equal(st.subpaths, 2);
    assert_int_equal(plot_curve_subpaths(c), 2);
    /* no drawn segment across t = 1/3, and the samples come close to it */
    double below = -1, above = 1;
    for (size_t i = 1; i < c->n; i++) {
        if (!c->cut[i])
            assert_false(c->t[i - 1] < 1.0 / 3 && c->t[i] > 1.0 / 3);
        if (c->t[i] < 1.0 / 3 && c->ok[i])
            below = fmax(below, c->t[i]);
        if (c->t[i] > 1.0 / 3 && c->ok[i])
            above = fmin(above, c->t[i]);
    }
    assert_true(1.0 / 3 - below < 1e-4);
    assert_true(above - 1.0 / 3 < 1e-4);
    /* the SVG has two subpaths (the clipped branches each start with M) */
    Path P = read_path(svg, "M");
    assert_int_equal(P.subpaths, 2);
    for (int v = 1; v < P.n; v++)
        if (!P.move[v]) /* a drawn segment never spans the asymptote */
            assert_false(P.x[v - 1] * P.x[v] < 0 &&
                         fabs(P.y[v] - P.y[v - 1]) > 10);
    path_clear(&P);
    plot_curve_clear(&st.curves[0]);
    free(st.curves);
    free(svg);
    /* no budget to refine: the sign change of the denominator's factor
     * alone still cuts the segment across the pole */
    PlotLimits lim = {8, PLOT_MAX_DEPTH, 9};
    PlotCurve c2;
    plot_curve_init(&c2, &f.env, 0, -1, 1, &s.view, &lim);
    plot_curve_refine(&c2, &f.env, &s.view, win, &lim);
    assert_int_equal(c2.n, 9);
    assert_true(c2.nfac >= 1);
    assert_int_equal(plot_curve_subpaths(&c2), 2);
    for (size_t i = 1; i < c2.n; i++)
        assert_int_equal(c2.cut[i], c2.t[i - 1] < 1.0 / 3 && c2.t[i] > 1.0 / 3);
    plot_curve_clear(&c2);
    fix_clear(&f);
}

/* the budget is a hard cap, whatever the curve does */
static void test_plot_budget(void **state)
{
    (void)state;
    static const char text[] = "point A, B, C\nparam t in [0, 1]\n"
                               "const k\n"
                               "M = A + (B - A)*cos(k*t) + (C - A)*sin(k*t)\n"
                               "output M\n";
    static const double pts[] = {0, 0, 1, 0, 0, 1};
    Fix f;
    fix_init(&f, text, 2, pts);
    f.consts[0] = 5000; /* ~800 turns around the circle */
    PlotLimits lim = {16, PLOT_MAX_DEPTH, 300};
    PlotView v;
    plot_view_default(&v, 2);
    PlotCurve c;
    plot_curve_init(&c, &f.env, 0, 0, 1, &v, &lim);
    assert_int_equal(c.n, 17);
    double box[4] = {-1, -1, 1, 1};
    plot_curve_refine(&c, &f.env, &v, box, &lim);
    assert_true(c.n <= 300);
    assert_true(c.n > 17);
    plot_curve_clear(&c);
    /* a generous budget on the circle itself (k = 2 pi): few samples */
    f.consts[0] = 6.283185307179586;
    lim.max_samples = 100000;
    plot_curve_init(&c, &f.env, 0, 0, 1, &v, &lim);
    plot_curve_refine(&c, &f.env, &v, box, &lim);
    assert_true(c.n > 50 && c.n < 2000);
    /* every drawn sample on the unit circle */
    for (size_t i = 0; i < c.n; i++)
        assert_true(fabs(hypot(c.x[i], c.y[i]) - 1) < 1e-12);
    assert_int_equal(plot_curve_subpaths(&c), 1);
    plot_curve_clear(&c);
    fix_clear(&f);
}

/* a domain: sqrt(1 - t^2) over [-2, 2] is drawn on [-1, 1] only, its ends
 * located by bisection; a jump (sign) is cut */
static void test_plot_domain_and_jump(void **state)
{
    (void)state;
    static const char text[] = "point A, B, C\nparam t in [-2, 2]\n"
                               "M = A + (B - A)*t + (C - A)*sqrt(1 - t^2)\n"
                               "N = A + (B - A)*t + (C - A)*sign(t - 1/3)\n"
                               "output M, N\n";
    static const double pts[] = {0, 0, 1, 0, 0, 1};
    Fix f;
    fix_init(&f, text, 2, pts);
    PlotLimits lim;
    plot_limits_default(&lim);
    PlotView v;
    plot_view_default(&v, 2);
    double box[4] = {-2, -1.5, 2, 1.5};
    PlotCurve c;
    plot_curve_init(&c, &f.env, 0, -2, 2, &v, &lim);
    plot_curve_refine(&c, &f.env, &v, box, &lim);
    assert_int_equal(plot_curve_subpaths(&c), 1);
    double lo = 2, hi = -2;
    for (size_t i = 0; i < c.n; i++)
        if (c.ok[i]) {
            lo = fmin(lo, c.t[i]);
            hi = fmax(hi, c.t[i]);
            assert_true(c.t[i] >= -1 && c.t[i] <= 1);
            assert_true(fabs(hypot(c.x[i], c.y[i]) - 1) < 1e-12);
        }
    assert_true(lo < -1 + 1e-4 && hi > 1 - 1e-4);
    plot_curve_clear(&c);
    plot_curve_init(&c, &f.env, 1, -2, 2, &v, &lim);
    plot_curve_refine(&c, &f.env, &v, box, &lim);
    assert_int_equal(plot_curve_subpaths(&c), 2);
    for (size_t i = 1; i < c.n; i++)
        if (!c.cut[i]) /* no drawn segment joins y = -1 and y = 1 */
            assert_true(fabs(c.y[i] - c.y[i - 1]) < 0.5);
    plot_curve_clear(&c);
    fix_clear(&f);
}

/* the forward-mode derivatives agree with the scheme's diff() */
static void test_plot_jet_matches_diff(void **state)
{
    (void)state;
    Fix f;
    fix_init(&f, desargues, 3, desargues3);
    int oM = plan_find_output(f.p, "M"), o1 = plan_find_output(f.p, "dM"),
        o2 = plan_find_output(f.p, "d2M");
    for (int i = 0; i <= 20; i++) {
        double t = -0.5 + 2.0 * i / 20, pos[3], d1[3], d2[3], e1[3], e2[3];
        assert_int_equal(plot_jet(&f.env, oM, t, pos, d1, d2), 0);
        assert_int_equal(plot_jet(&f.env, o1, t, e1, NULL, NULL), 0);
        assert_int_equal(plot_jet(&f.env, o2, t, e2, NULL, NULL), 0);
        for (int c = 0; c < 3; c++) {
            assert_true(fabs(d1[c] - e1[c]) <= 1e-12 * (1 + fabs(e1[c])));
            assert_true(fabs(d2[c] - e2[c]) <= 1e-11 * (1 + fabs(e2[c])));
        }
    }
    /* functions: the chain rule of every kernel kind */
    static const char fns[] =
        "point A, B\nparam t\n"
        "M = A + (B - A)*(sin(t)*exp(t) + sqrt(t + 2) + ln(t + 3) + "
        "atan(t) + asin(t/2) + cosh(t)*tanh(t))\n"
        "dM = diff(M, t)\nd2M = diff(M, t, 2)\noutput M, dM, d2M\n";
    Fix g;
    static const double pts[] = {0, 1};
    fix_init(&g, fns, 1, pts);
    for (int i = 0; i <= 10; i++) {
        double t = -1 + 0.2 * i, pos, d1, d2, e1, e2;
        assert_int_equal(plot_jet(&g.env, 0, t, &pos, &d1, &d2), 0);
        assert_int_equal(plot_jet(&g.env, 1, t, &e1, NULL, NULL), 0);
        assert_int_equal(plot_jet(&g.env, 2, t, &e2, NULL, NULL), 0);
        assert_true(fabs(d1 - e1) <= 1e-10 * (1 + fabs(e1)));
        assert_true(fabs(d2 - e2) <= 1e-9 * (1 + fabs(e2)));
    }
    fix_clear(&g);
    fix_clear(&f);
}

/* 3D: the views project the eval coordinates */
static void test_plot_projection_3d(void **state)
{
    (void)state;
    Fix f;
    fix_init(&f, desargues, 3, desargues3);
    const char *views[] = {"xy", "xz", "yz", "iso", "30,20"};
    int oM = plan_find_output(f.p, "M");
    for (int k = 0; k < 5; k++) {
        PlotSpec s;
        plot_spec_default(&s);
        char msg[200];
        assert_int_equal(plot_view_parse(&s.view, views[k], msg, sizeof msg),
                         0);
        s.env = f.env;
        s.curves = &oM;
        s.ncurves = 1;
        s.lo = 0;
        s.hi = 1;
        PlotStats st;
        memset(&st, 0, sizeof st);
        st.keep_curves = 1;
        char *svg = svg_of(&s, &st);
        assert_true(xml_ok(svg));
        check_path_against_eval(&f, &s, oM, svg, &st.curves[0], st.digits);
        /* at t = 1/2 the arc passes the centroid (1/4, 1/4, 1/4) */
        const PlotCurve *c = &st.curves[0];
        double cx, cy, P[3] = {0.25, 0.25, 0.25};
        plot_project(&s.view, P, 3, &cx, &cy);
        int near = 0;
        for (size_t i = 0; i < c->n; i++)
            near |= c->t[i] == 0.5 && fabs(c->x[i] - cx) < 1e-12 &&
                    fabs(c->y[i] - cy) < 1e-12;
        assert_true(near);
        if (k == 1) { /* xz: x = M.1, y = M.3 */
            assert_true(fabs(c->x[c->n - 1] - 0) < 1e-12);
            assert_true(fabs(c->y[c->n - 1] - 1) < 1e-12);
        }
        plot_curve_clear(&st.curves[0]);
        free(st.curves);
        free(svg);
    }
    char msg[200];
    PlotView v;
    assert_int_equal(plot_view_parse(&v, "xw", msg, sizeof msg), -1);
    assert_int_equal(plot_view_parse(&v, "30", msg, sizeof msg), -1);
    assert_int_equal(plot_view_parse(&v, "30,100", msg, sizeof msg), -1);
    assert_int_equal(plot_view_parse(&v, "nan,0", msg, sizeof msg), -1);
    fix_clear(&f);
}

/* names are escaped; tangents, comb, lines and marks make valid XML */
static void test_plot_everything_is_wellformed(void **state)
{
    (void)state;
    Fix f;
    fix_init(&f, desargues, 2, desargues2);
    PlotSpec s;
    plot_spec_default(&s);
    s.env = f.env;
    int curves[1] = {plan_find_output(f.p, "M")};
    s.curves = curves;
    s.ncurves = 1;
    s.lo = -0.5;
    s.hi = 1.5;
    PlotMark marks[3] = {{"A<&>\"'", f.ptr[0], PLOT_BASE, -1},
                         {"B", f.ptr[1], PLOT_AUX, -1},
                         {"C", f.ptr[2], PLOT_CURRENT, 0}};
    PlotLine lines[1] = {{3, {0, 1, 2, 0}}};
    double tangents[3] = {0, 0.5, 1};
    s.marks = marks;
    s.nmarks = 3;
    s.lines = lines;
    s.nlines = 1;
    s.tangents = tangents;
    s.ntangents = 3;
    s.comb = 50;
    s.title = "a & b";
    char *svg = svg_of(&s, NULL);
    assert_true(xml_ok(svg));
    assert_non_null(strstr(svg, ">A&lt;&amp;&gt;&quot;&apos;</text>"));
    assert_non_null(strstr(svg, "<title>a &amp; b</title>"));
    assert_non_null(strstr(svg, "class=\"tangents\""));
    assert_non_null(strstr(svg, "class=\"comb\""));
    assert_non_null(strstr(svg, "class=\"lines\""));
    free(svg);
    fix_clear(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_xml_checker_can_fail),
        cmocka_unit_test(test_plot_desargues_2d_path_is_eval),
        cmocka_unit_test(test_plot_pole_is_cut),
        cmocka_unit_test(test_plot_budget),
        cmocka_unit_test(test_plot_domain_and_jump),
        cmocka_unit_test(test_plot_jet_matches_diff),
        cmocka_unit_test(test_plot_projection_3d),
        cmocka_unit_test(test_plot_everything_is_wellformed),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    flint_cleanup_master(); /* FLINT's caches: valgrind sees nothing left */
    return failed;
}
