/*
 * test_analyze.c - pointcalc analyze (compiler/analyze/, docs/analyze.md).
 *
 * Expectations are derived by hand (or by tests/oracle/sympy/
 * check_analyze.py, which finds every one of them again its own way):
 *   - real roots: (2t - 1)^2 (t^2 - 2)(t^3 - 3t + 1) has the roots 1/2
 *     (double), +-sqrt(2) and 2 cos(2 pi/9), 2 cos(4 pi/9), 2 cos(8 pi/9)
 *     (t = 2 cos x turns t^3 - 3t + 1 = 0 into 2 cos 3x + 1 = 0); the
 *     quadratic 2t^2 + 2t - 1 has (-1 +- sqrt(3))/2;
 *   - the Desargues arc (monograph 3.7): M(0) = A, M(1) = D, dM(0) = C - A,
 *     dM(1) = D - B, d2M(0) = 2B - 2A (not parallel: smoothness 1); T, S
 *     and R have the pole t = 1/2, M none;
 *   - its plane case C = B: barycentric (a, b, d) = ((1 - t)^3, t(1 - t),
 *     t^3), so b^3 = ad and ad(a + 3b + d) = ad (a + 3b + d = 1 here):
 *     F = B^3 - A^2 D - 3ABD - AD^2; d2M(0) = 2B - 2A is parallel to dM(0)
 *     = B - A, so both ends are inflections;
 *   - the contour arc of order k = 5 (3.6): derivatives 1..5 parallel to
 *     C - A at t = 0, to B - C at t = 1;
 *   - bezier(t^2, A, C, B) on [-1, 1]: the parabola traced twice (index
 *     2, order 2, stop point t = 0); (a, c, b) = ((1 - s)^2, 2s(1 - s),
 *     s^2) gives c^2 = 4ab;
 *   - along(A, B, t/(1 - t)) on [0, 1]: to infinity at t = 1 in the
 *     direction B - A; (A + B t + C t^2)/(1 + t + t^2) without a range:
 *     C at t -> oo, d/ds = B - C (s = 1/t);
 *   - what is not analysed, and why; consts given values (--set);
 *   - with coordinates, the curvature and the arc length of the parabola
 *     y = x^2 over [0, 1];
 *   - the time budget (analyze_derived_within), measured first.
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
#include <time.h>

#include <flint/fmpz_poly.h>

#include "base/budget.h"
#include "compiler/analyze/analyze.h"
#include "compiler/derive.h"

static Derived *derive_text(const char *text)
{
    DeriveOptions opt = {.max_seconds = 60, .keep_steps = 1};
    int nerr = 0;
    Derived *d =
        derive_source_ex("a.pcs", text, strlen(text), stderr, &nerr, &opt);
    if (!d)
        fail_msg("derive failed:\n%s", text);
    return d;
}

static const AnCurve *curve(const Analysis *a, const char *name)
{
    for (slong i = 0; i < a->ncurves; i++)
        if (strcmp(a->curves[i].name, name) == 0)
            return a->curves + i;
    fail_msg("no curve %s", name);
    return NULL;
}

/* the weights w as "A:1 C:-1" (zero weights left out) */
static void assert_combo(const fmpq *w, const Derived *d, const char *want)
{
    char buf[256] = "";
    for (slong i = 0; i < d->npoints; i++) {
        if (fmpq_is_zero(w + i))
            continue;
        char *s = fmpq_get_str(NULL, 10, w + i);
        snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "%s%s:%s",
                 buf[0] ? " " : "", d->points[i], s);
        flint_free(s);
    }
    assert_string_equal(buf, want);
}

/* r's roots as "text|value" joined by ", " (exact text when there is
 * one, else the value to 16 digits) */
static void assert_roots(const AnRoots *r, const char *want)
{
    char buf[512] = "";
    for (slong i = 0; i < r->n; i++) {
        size_t n = strlen(buf);
        if (r->v[i].exact)
            snprintf(buf + n, sizeof buf - n, "%s%s", i ? ", " : "",
                     r->v[i].exact);
        else
            snprintf(buf + n, sizeof buf - n, "%s%.15f", i ? ", " : "",
                     r->v[i].value);
    }
    assert_string_equal(buf, want);
}

static void test_roots(void **state)
{
    (void)state;
    fmpz_poly_t p, q, e;
    fmpz_poly_init(p);
    fmpz_poly_init(q);
    fmpz_poly_init(e);
    fmpz_poly_set_str(p, "2  -1 2");   /* 2t - 1 */
    fmpz_poly_mul(p, p, p);            /* (2t - 1)^2 */
    fmpz_poly_set_str(q, "3  -2 0 1"); /* t^2 - 2 */
    fmpz_poly_mul(p, p, q);
    fmpz_poly_set_str(q, "4  1 -3 0 1"); /* t^3 - 3t + 1 */
    fmpz_poly_mul(p, p, q);
    AnRoots r;
    roots_init(&r);
    roots_real(&r, p, NULL, NULL, NULL);
    assert_int_equal(r.n, 6);
    const double pi = 3.14159265358979323846;
    double c[3] = {2 * cos(8 * pi / 9), 2 * cos(4 * pi / 9),
                   2 * cos(2 * pi / 9)};
    slong at[3] = {0, 2, 5};
    for (int i = 0; i < 3; i++) {
        assert_null(r.v[at[i]].exact);
        assert_true(fabs(r.v[at[i]].value - c[i]) <= 2e-15);
    }
    assert_string_equal(r.v[1].exact, "-sqrt(2)");
    assert_string_equal(r.v[3].exact, "1/2");
    assert_int_equal(r.v[3].mult, 2);
    assert_string_equal(r.v[4].exact, "sqrt(2)");
    roots_clear(&r);
    /* a range, and the factors of excl left out */
    fmpq_t lo, hi;
    fmpq_init(lo);
    fmpq_init(hi);
    fmpq_set_si(lo, 0, 1);
    fmpq_set_si(hi, 3, 2);
    roots_init(&r);
    roots_real(&r, p, lo, hi, NULL);
    assert_roots(&r, "0.347296355333861, 1/2, sqrt(2)");
    roots_clear(&r);
    fmpz_poly_set_str(e, "3  -2 0 1");
    roots_init(&r);
    roots_real(&r, p, lo, hi, e);
    assert_roots(&r, "0.347296355333861, 1/2");
    roots_clear(&r);
    /* the ends of the range count: 1/2 in [1/2, 1] */
    fmpq_set_si(lo, 1, 2);
    fmpq_set_si(hi, 1, 1);
    roots_init(&r);
    roots_real(&r, p, lo, hi, NULL);
    assert_roots(&r, "1/2");
    roots_clear(&r);
    /* square-root forms: (-1 +- sqrt(3))/2, +-2 sqrt(3), (1 +- sqrt(7))/3 */
    const char *polys[3] = {"3  -1 2 2", "3  -12 0 1", "3  -2 -2 3"};
    const char *want[3] = {"(-1 - sqrt(3))/2, (-1 + sqrt(3))/2",
                           "-2*sqrt(3), 2*sqrt(3)",
                           "(1 - sqrt(7))/3, (1 + sqrt(7))/3"};
    for (int i = 0; i < 3; i++) {
        fmpz_poly_set_str(q, polys[i]);
        roots_init(&r);
        roots_real(&r, q, NULL, NULL, NULL);
        assert_roots(&r, want[i]);
        roots_clear(&r);
    }
    /* no real root */
    fmpz_poly_set_str(q, "3  1 0 1");
    roots_init(&r);
    roots_real(&r, q, NULL, NULL, NULL);
    assert_int_equal(r.n, 0);
    roots_clear(&r);
    fmpq_clear(hi);
    fmpq_clear(lo);
    fmpz_poly_clear(e);
    fmpz_poly_clear(q);
    fmpz_poly_clear(p);
}

static const char desargues[] = "scheme desargues_arc\n"
                                "point A, B, C, D\n"
                                "param t in [0, 1]\n"
                                "P = along(A, C, t)\n"
                                "Q = along(C, B, t)\n"
                                "K = along(B, D, t)\n"
                                "N = along(P, Q, t)\n"
                                "J = along(Q, K, t)\n"
                                "T = meet(line(P, Q), line(A, B))\n"
                                "S = meet(line(Q, K), line(C, D))\n"
                                "M = meet(line(S, N), line(T, J))\n"
                                "M_CB = subst(M, C, B)\n"
                                "output M, M_CB\n";

static void test_desargues(void **state)
{
    (void)state;
    Derived *d = derive_text(desargues);
    Analysis *a = analyze_derived(d, NULL, 0, NULL);
    const AnCurve *m = curve(a, "M");
    assert_null(m->skip);
    assert_int_equal(m->degree, 3);
    assert_int_equal(m->order, 3);
    assert_int_equal(m->index, 1);
    assert_int_equal(m->dim, 3);
    assert_int_equal(m->poles.n, 0);
    assert_int_equal(m->stops.n, 0);
    assert_false(m->has_infl);
    assert_null(m->implicit);
    assert_int_equal(m->nends, 2);
    assert_string_equal(m->ends[0].t, "0");
    assert_combo(m->ends[0].point, d, "A:1");
    assert_int_equal(m->ends[0].first, 1);
    assert_combo(m->ends[0].tangent, d, "A:-1 C:1");
    assert_int_equal(m->ends[0].parallel, 1);
    assert_combo(m->ends[1].point, d, "D:1");
    assert_combo(m->ends[1].tangent, d, "B:-1 D:1");
    assert_int_equal(m->ends[1].parallel, 1);
    assert_int_equal(m->npass, 2);
    assert_string_equal(d->points[m->pass[0].point], "A");
    assert_roots(&m->pass[0].t, "0");
    assert_string_equal(d->points[m->pass[1].point], "D");
    assert_roots(&m->pass[1].t, "1");
    /* the plane case */
    const AnCurve *p = curve(a, "M_CB");
    assert_int_equal(p->dim, 2);
    assert_int_equal(p->order, 3);
    assert_true(p->has_infl);
    assert_roots(&p->infl, "0, 1");
    assert_int_equal(p->ends[0].parallel, 2);
    assert_int_equal(p->ends[1].parallel, 2);
    assert_string_equal(p->implicit, "B^3 - A^2*D - 3*A*B*D - A*D^2");
    /* the definitions: T, S have the pole t = 1/2, nothing else does */
    int seen = 0;
    for (slong i = 0; i < a->ndefs; i++) {
        const AnDef *f = a->defs + i;
        if (!strcmp(f->name, "T") || !strcmp(f->name, "S")) {
            assert_roots(&f->poles, "1/2");
            seen++;
        } else
            assert_int_equal(f->poles.n, 0);
    }
    assert_int_equal(seen, 2);
    analysis_free(a);
    derived_free(d);
}

static void test_contour_arc(void **state)
{
    (void)state;
    Derived *d = derive_file("examples/contour_arcs.pcs", stderr, NULL);
    assert_non_null(d);
    Analysis *a = analyze_derived(d, NULL, 0, NULL);
    const AnCurve *m = curve(a, "M");
    assert_int_equal(m->degree, 6);
    assert_int_equal(m->order, 6);
    assert_int_equal(m->ends[0].first, 1);
    assert_int_equal(m->ends[0].parallel, 5);
    assert_combo(m->ends[0].tangent, d, "A:-2 C:2");
    assert_int_equal(m->ends[1].parallel, 5);
    assert_combo(m->ends[1].tangent, d, "B:2 C:-2");
    assert_int_equal(m->poles.n, 0);
    analysis_free(a);
    derived_free(d);
}

static void test_traced_twice(void **state)
{
    (void)state;
    Derived *d = derive_text("point A, B, C\nparam t in [-1, 1]\n"
                             "M = bezier(t^2, A, C, B)\n");
    Analysis *a = analyze_derived(d, NULL, 0, NULL);
    const AnCurve *m = curve(a, "M");
    assert_int_equal(m->degree, 4);
    assert_int_equal(m->index, 2);
    assert_int_equal(m->order, 2);
    assert_roots(&m->stops, "0");
    assert_int_equal(m->ends[0].first, 1);
    assert_string_equal(m->implicit, "4*A*B - C^2");
    assert_int_equal(m->npass, 2);
    assert_roots(&m->pass[0].t, "0");     /* A */
    assert_roots(&m->pass[1].t, "-1, 1"); /* B */
    analysis_free(a);
    derived_free(d);
}

static void test_infinity(void **state)
{
    (void)state;
    Derived *d = derive_text("point A, B, C\nparam t in [0, 1]\nparam u\n"
                             "M = along(A, B, t/(1 - t))\n"
                             "N = (A + B*u + C*u^2)/(1 + u + u^2)\n"
                             "output M, N\n");
    Analysis *a = analyze_derived(d, NULL, 0, NULL);
    const AnCurve *m = curve(a, "M");
    assert_int_equal(m->ends[1].infinite, 1);
    assert_combo(m->ends[1].point, d, "A:-1 B:1");
    assert_null(m->ends[1].tangent);
    assert_roots(&m->poles, "1");
    assert_int_equal(m->ends[0].parallel, -1); /* a straight line */
    const AnCurve *n = curve(a, "N");
    assert_int_equal(n->nends, 1);
    assert_false(n->bounded);
    assert_string_equal(n->ends[0].t, "oo");
    assert_combo(n->ends[0].point, d, "C:1");
    assert_combo(n->ends[0].tangent, d, "B:1 C:-1");
    assert_int_equal(n->poles.n, 0);
    analysis_free(a);
    derived_free(d);
}

static void test_skipped(void **state)
{
    (void)state;
    Derived *d = derive_text("point A, B\nparam t, u\nconst k\n"
                             "s = t^2\nM = along(A, B, k*t)\n"
                             "N = along(A, B, t*u)\nP = along(A, B, 1/3)\n"
                             "output s, M, N, P\n");
    Analysis *a = analyze_derived(d, NULL, 0, NULL);
    assert_string_equal(curve(a, "s")->skip, "a scalar, not a curve");
    /* k without --set: at its generic value 11/7 (analyze_generic_value) */
    assert_null(curve(a, "M")->skip);
    assert_int_equal(curve(a, "M")->degree, 1);
    assert_int_equal(a->cgiven[0], 0);
    assert_int_equal(a->cused[0], 1);
    assert_int_equal(fmpz_get_si(fmpq_numref(a->cvalue + 0)), 11);
    assert_int_equal(fmpz_get_si(fmpq_denref(a->cvalue + 0)), 7);
    assert_string_equal(curve(a, "N")->skip, "depends on more than one param");
    assert_string_equal(curve(a, "P")->skip, "a constant, not a curve");
    analysis_free(a);
    derived_free(d);
}

/* --set: along(A, B, t/(k - t)) at k = 1/2 has the pole t = 1/2; at k = 0
 * it is along(A, B, -1), a constant */
static void test_set(void **state)
{
    (void)state;
    Derived *d = derive_text("point A, B\nparam t in [0, 1]\nconst k\n"
                             "M = along(A, B, t/(k - t))\n");
    unsigned char given[1] = {1};
    fmpq value[1];
    fmpq_init(value);
    fmpq_set_si(value, 1, 2);
    AnSet set = {given, value, 0, NULL, NULL};
    Analysis *a = analyze_derived(d, NULL, 0, &set);
    assert_null(a->curves[0].skip);
    assert_roots(&a->curves[0].poles, "1/2");
    assert_int_equal(a->ndefs, 1);
    assert_roots(&a->defs[0].poles, "1/2");
    analysis_free(a);
    fmpq_zero(value);
    a = analyze_derived(d, NULL, 0, &set);
    assert_string_equal(a->curves[0].skip, "a constant, not a curve");
    analysis_free(a);
    fmpq_clear(value);
    derived_free(d);
}

/* --at: the parabola (t, t^2) = bezier(t, A, C, B) with A = (0, 0), C =
 * (1/2, 0), B = (1, 1): curvature 2/(1 + 4t^2)^(3/2), 2 at t = 0 (its
 * largest) and 2/5^(3/2) at t = 1 (its smallest); arc length
 * (2 sqrt(5) + asinh(2))/4 */
static void test_metric(void **state)
{
    (void)state;
    Derived *d = derive_text("point A, B, C\nparam t in [0, 1]\n"
                             "M = bezier(t, A, C, B)\n");
    const double a[2] = {0, 0}, b[2] = {1, 1}, c[2] = {0.5, 0};
    const double *pt[3] = {a, b, c};
    AnSet set = {NULL, NULL, 2, pt, NULL};
    Analysis *an = analyze_derived(d, NULL, 0, &set);
    const AnCurve *m = an->curves;
    assert_true(m->has_metric);
    double k1 = 2 / pow(5, 1.5), len = (2 * sqrt(5) + asinh(2)) / 4;
    assert_true(fabs(m->kappa_end[0] - 2) < 1e-14);
    assert_true(fabs(m->kappa_end[1] - k1) < 1e-14);
    assert_true(fabs(m->kappa_ext[0] - 2) < 1e-14 && m->kappa_ext_t[0] == 0);
    assert_true(fabs(m->kappa_ext[1] - k1) < 1e-14 && m->kappa_ext_t[1] == 1);
    assert_true(fabs(m->length - len) < 1e-12 * len);
    analysis_free(an);
    /* a point without coordinates: nothing, and said */
    pt[2] = NULL;
    an = analyze_derived(d, NULL, 0, &set);
    assert_false(an->curves[0].has_metric);
    assert_true(an->curves[0].metric_missing);
    analysis_free(an);
    derived_free(d);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* 24 plane curves of degree 9 to 11 over A, B, C, each with its implicit
 * equation (a resultant and a factorisation: milliseconds each) */
static char *many_curves(void)
{
    char *text = malloc(8192), *p = text;
    p += sprintf(p, "point A, B, C\nparam t in [0, 1]\n");
    for (int i = 1; i <= 24; i++)
        p += sprintf(p,
                     "M%d = along(along(A, B, t^%d + %d*t - 1), C, "
                     "(t^%d + 3*t + %d)/(t^2 + %d))\n",
                     i, 9 + i % 3, i, 7 + i % 2, i, i);
    p += sprintf(p, "output M1");
    for (int i = 2; i <= 24; i++)
        p += sprintf(p, ", M%d", i);
    sprintf(p, "\n");
    return text;
}

/* what err received (closed here) */
static char *taken(FILE *m, char **buf)
{
    fclose(m);
    return *buf;
}

/* The time budget of analyze_derived_within, counted from the call.  The
 * whole analysis is timed first (budget 0: none; the fastest of three);
 * with an eighth of that it stops, at the next step past the deadline,
 * well before the whole would have ended,
 * NULL with the located message at the output it was analysing; with
 * 1 ns, at the first output.  analyze_derived under a deadline the caller
 * set keeps what it found before it: the curve it stopped in is skipped
 * (AN_LATE), none after it is listed. */
static void test_budget(void **state)
{
    (void)state;
    char *text = many_curves(), *msg = NULL;
    Derived *d = derive_text(text);
    double full = 1e9, t0; /* the fastest of three: a loaded machine */
    Analysis *an;
    for (int k = 0; k < 3; k++) {
        t0 = now_s();
        an = analyze_derived_within(d, NULL, 0, NULL, 0, stderr);
        full = fmin(full, now_s() - t0);
        assert_non_null(an);
        assert_int_equal(an->ncurves, 24);
        assert_false(an->late);
        for (slong i = 0; i < 24; i++)
            assert_non_null(an->curves[i].implicit);
        analysis_free(an);
    }

    size_t len;
    FILE *m = open_memstream(&msg, &len);
    t0 = now_s();
    an = analyze_derived_within(d, NULL, 0, NULL, full / 8, m);
    double took = now_s() - t0;
    assert_null(an);
    assert_true(took < 0.75 * full);
    taken(m, &msg);
    assert_true(strncmp(msg, "a.pcs:", 6) == 0);
    assert_non_null(strstr(msg, ":1: error: the time budget of "));
    assert_non_null(strstr(msg, " s ran out while analysing this; raise it "
                                "with --max-seconds\nM"));
    free(msg);

    m = open_memstream(&msg, &len);
    assert_null(analyze_derived_within(d, NULL, 0, NULL, 1e-9, m));
    taken(m, &msg);
    assert_string_equal(msg, "a.pcs:3:1: error: the time budget of 1e-09 s "
                             "ran out while analysing this; raise it with "
                             "--max-seconds\nM1 = along(along(A, B, t^10 + "
                             "1*t - 1), C, (t^8 + 3*t + 1)/(t^2 + 1))\n"
                             "^~\n");
    free(msg);

    budget_deadline_set(1e-9);
    an = analyze_derived(d, NULL, 0, NULL);
    budget_deadline_set(0);
    assert_true(an->late);
    assert_int_equal(an->ncurves, 1);
    assert_string_equal(an->curves[0].skip, AN_LATE);
    m = open_memstream(&msg, &len);
    analyze_print_text(m, an);
    taken(m, &msg);
    assert_non_null(strstr(msg, "M1: not analysed: " AN_LATE "\n"));
    assert_null(strstr(msg, "M2"));
    free(msg);
    m = open_memstream(&msg, &len); /* the other reports of it */
    analyze_print_json(m, an);
    analyze_print_latex(m, an);
    taken(m, &msg);
    assert_non_null(strstr(msg, "\"skipped\": \"" AN_LATE "\""));
    assert_null(strstr(msg, "M2"));
    free(msg);
    analysis_free(an);
    derived_free(d);
    free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_roots),       cmocka_unit_test(test_desargues),
        cmocka_unit_test(test_contour_arc), cmocka_unit_test(test_traced_twice),
        cmocka_unit_test(test_infinity),    cmocka_unit_test(test_skipped),
        cmocka_unit_test(test_set),         cmocka_unit_test(test_metric),
        cmocka_unit_test(test_budget),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    flint_cleanup_master();
    return rc;
}
