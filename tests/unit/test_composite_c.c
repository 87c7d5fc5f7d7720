/*
 * test_composite_c.c - composite curves (one formula in |t - t_k|, issue 19
 * item 6): the generated C and the runtime against exact values at the
 * knots, just left and right of them and between them, and the knots a
 * plot marks.
 *
 * Each case is a scheme (an example of examples/ or a formula of the
 * composite-curve text written with abs) and a reference written here
 * independently of pointcalc: the piecewise definition of the curve (a
 * polyline through its vertices, the C^1 and C^2 steps of (2.1.5) and
 * (2.1.6) piece by piece, the pieces of piecewise() and join()) or the defining
 * sum evaluated in exact rationals with |x| and sign(x) of fmpq.  The generated
 * code (NAME_M and NAME_M_batch, compiled with the contract's flags) and
 * plan_eval get the doubles t; the reference is taken at the exact value of the
 * same double, so the comparison measures the evaluation alone: |got - exact|
 * <= 1e-12 max(1, |exact|).  At a dyadic knot of a curve with dyadic pieces the
 * value must be exact (sign(0) = 0: the two pieces' mean, which for a
 * continuous curve is its value there).
 *
 * The generated per-sample code must be branch-free: no '?' and no 'if' in
 * the lines that compute registers (sign is (x > 0) - (x < 0)).
 *
 * The plot's knots: plot_curve_init puts a sample exactly on each knot of
 * the swept range, and plot_svg draws a mark (class "knot") at the curve's
 * point there; the expected marks are the vertices of the polygon, mapped
 * to pixels by the transform the SVG itself declares for its curves.
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
#include <flint/fmpq.h>

#include "codegen/emit_c.h"
#include "codegen/lower.h"
#include "compiler/derive.h"
#include "runtime/eval.h"
#include "runtime/plot.h"
#include "tests/unit/emit_harness.h"

#define TOL 1e-12

static int total_checks;

/* ---- exact references --------------------------------------------------- */

/* out[0..ncoords) = the curve at t, exactly */
typedef void (*RefFn)(fmpq *out, const fmpq_t t);

static int sgn(const fmpq_t x)
{
    return fmpq_sgn(x);
}

/* r = x/d */
static void div_si(fmpq_t r, const fmpq_t x, slong d)
{
    fmpz_t z;
    fmpz_init_set_si(z, d);
    fmpq_div_fmpz(r, x, z);
    fmpz_clear(z);
}

/* r = |x|^e */
static void abs_pow(fmpq_t r, const fmpq_t x, ulong e)
{
    fmpq_abs(r, x);
    fmpq_pow_si(r, r, (slong)e);
}

/* the closed polyline V[0] V[1] ... V[n-1] V[0] with V[j] at t = j:
 * V[0] before 0 and after n (each side a unit ramp, 2.2.2) */
static void polyline(fmpq *out, const fmpq_t t, const slong (*V)[2], int n)
{
    fmpq_t u;
    fmpq_init(u);
    slong j = -1; // the side [j, j + 1] holding t
    for (slong k = 0; k < n; k++)
        if (fmpq_cmp_si(t, k) >= 0 && fmpq_cmp_si(t, k + 1) <= 0)
            j = k;
    for (int c = 0; c < 2; c++) {
        if (j < 0) {
            fmpq_set_si(out + c, V[0][c], 1);
            continue;
        }
        slong a = V[j][c], b = V[(j + 1) % n][c];
        fmpq_sub_si(u, t, j); // a + (t - j)(b - a)
        fmpq_mul_si(out + c, u, b - a);
        fmpq_add_si(out + c, out + c, a);
    }
    fmpq_clear(u);
}

static const slong square_v[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
static const double square_pts[] = {0, 0, 1, 0, 1, 1, 0, 1};

static void ref_square(fmpq *out, const fmpq_t t)
{
    polyline(out, t, square_v, 4);
}

static const slong hexagon_v[6][2] = {{2, 0},  {1, 2},   {-1, 2},
                                      {-2, 0}, {-1, -2}, {1, -2}};
static const double hexagon_pts[] = {2, 0, 1, 2, -1, 2, -2, 0, -1, -2, 1, -2};

static void ref_hexagon(fmpq *out, const fmpq_t t)
{
    polyline(out, t, hexagon_v, 6);
}

/* the steps piece by piece, u = (t - a)/w: 0 for u <= 0, 1 for u >= 1,
 * between: 3u^2 - 2u^3 (P_1^3, 2.1.5) or 10u^3 - 15u^4 + 6u^5 (P_2^5,
 * 2.1.6) */
static void step(fmpq_t r, const fmpq_t t, slong a, int smooth)
{
    fmpq_t u, v;
    fmpq_init(u);
    fmpq_init(v);
    fmpq_sub_si(u, t, a);
    if (fmpq_sgn(u) <= 0) {
        fmpq_zero(r);
    } else if (fmpq_cmp_si(u, 1) >= 0) {
        fmpq_one(r);
    } else if (smooth == 1) { // u^2 (3 - 2u)
        fmpq_mul_si(v, u, -2);
        fmpq_add_si(v, v, 3);
        fmpq_mul(v, v, u);
        fmpq_mul(r, v, u);
    } else { // u^3 (10 - 15u + 6u^2)
        fmpq_mul_si(v, u, 6);
        fmpq_sub_si(v, v, 15);
        fmpq_mul(v, v, u);
        fmpq_add_si(v, v, 10);
        fmpq_mul(v, v, u);
        fmpq_mul(v, v, u);
        fmpq_mul(r, v, u);
    }
    fmpq_clear(v);
    fmpq_clear(u);
}

/* 2.1 example 5: x = P_2^5(t,0,1) - P_2^5(t,2,1), y = P_2^5(t,1,1) -
 * P_2^5(t,3,1) */
static void ref_square_c2(fmpq *out, const fmpq_t t)
{
    fmpq_t s;
    fmpq_init(s);
    step(out + 0, t, 0, 2);
    step(s, t, 2, 2);
    fmpq_sub(out + 0, out + 0, s);
    step(out + 1, t, 1, 2);
    step(s, t, 3, 2);
    fmpq_sub(out + 1, out + 1, s);
    fmpq_clear(s);
}

/* 2.1 example 4: x = P_1^3(t,0,1) - P_1^3(t,1,1), y = P_1^3(t,1,1) -
 * P_1^3(t,2,1) */
static void ref_triangle_c1(fmpq *out, const fmpq_t t)
{
    fmpq_t s;
    fmpq_init(s);
    step(out + 0, t, 0, 1);
    step(s, t, 1, 1);
    fmpq_sub(out + 0, out + 0, s);
    step(out + 1, t, 1, 1);
    step(s, t, 2, 1);
    fmpq_sub(out + 1, out + 1, s);
    fmpq_clear(s);
}

/* ten knots, three of them not dyadic */
static const char *const spline_knots[] = {"0", "1/3", "1/2", "1",   "3/2",
                                           "2", "7/3", "3",   "7/2", "4"};
enum { NSPLINE = 10 };

/* S = 1/2 + t/5 + sum_k c_k |t - t_k|^3, c_k = (-1)^k (k + 1)/7;
 * F = sum_k d_k (t - t_k)|t - t_k|, d_k = (k - 4)/3;
 * J = t + t^2 sign(t - 1/2) + 2 sign(t - 2) (a jump: sign(0) = 0) */
static void ref_spline(fmpq *out, const fmpq_t t)
{
    fmpq_t x, y, k;
    fmpq_init(x);
    fmpq_init(y);
    fmpq_init(k);
    div_si(out + 0, t, 5);
    fmpq_set_si(x, 1, 2);
    fmpq_add(out + 0, out + 0, x);
    fmpq_zero(out + 1);
    for (int i = 0; i < NSPLINE; i++) {
        assert_int_equal(fmpq_set_str(k, spline_knots[i], 10), 0);
        fmpq_sub(x, t, k);
        abs_pow(y, x, 3);
        fmpq_mul_si(y, y, (i % 2 ? -1 : 1) * (i + 1));
        div_si(y, y, 7);
        fmpq_add(out + 0, out + 0, y);
        fmpq_abs(y, x);
        fmpq_mul(y, y, x);
        fmpq_mul_si(y, y, i - 4);
        div_si(y, y, 3);
        fmpq_add(out + 1, out + 1, y);
    }
    fmpq_set_si(k, 1, 2);
    fmpq_sub(x, t, k);
    fmpq_mul(y, t, t);
    fmpq_mul_si(y, y, sgn(x));
    fmpq_add(out + 2, t, y);
    fmpq_sub_si(x, t, 2);
    fmpq_add_si(out + 2, out + 2, 2 * sgn(x));
    /* Q = |t^2 - 1/4|: a kernel whose argument is not linear */
    fmpq_mul(x, t, t);
    fmpq_set_si(k, 1, 4);
    fmpq_sub(x, x, k);
    fmpq_abs(out + 3, x);
    fmpq_clear(k);
    fmpq_clear(y);
    fmpq_clear(x);
}

/* the join of the four sides (the square again), the piecewise P = t^2,
 * 2t - 1, 5 - t, 2 with knots 1, 2, 3, and L = the infinite polyline
 * O->A (through A at t = 0), A->B, B->C (at B for t = 1) of Theorem 3 */
static void ref_join(fmpq *out, const fmpq_t t)
{
    polyline(out, t, square_v, 4);
    if (fmpq_cmp_si(t, 1) <= 0) {
        fmpq_mul(out + 2, t, t);
    } else if (fmpq_cmp_si(t, 2) <= 0) {
        fmpq_mul_si(out + 2, t, 2);
        fmpq_sub_si(out + 2, out + 2, 1);
    } else if (fmpq_cmp_si(t, 3) <= 0) {
        fmpq_neg(out + 2, t);
        fmpq_add_si(out + 2, out + 2, 5);
    } else {
        fmpq_set_si(out + 2, 2, 1);
    }
    if (fmpq_sgn(t) <= 0) { // (1 + t, 0)
        fmpq_add_si(out + 3, t, 1);
        fmpq_zero(out + 4);
    } else if (fmpq_cmp_si(t, 1) <= 0) { // (1, t)
        fmpq_one(out + 3);
        fmpq_set(out + 4, t);
    } else { // (2 - t, 1)
        fmpq_neg(out + 3, t);
        fmpq_add_si(out + 3, out + 3, 2);
        fmpq_one(out + 4);
    }
}

/* ---- the cases ---------------------------------------------------------- */

typedef struct Case {
    const char *path; // an example, or
    const char *text; // the scheme
    const double *pts;
    int dim;
    int ncoords; // of all outputs together
    RefFn ref;
    const char *const *knots;
    int nknots;
    int exact_knots; // the value at a dyadic knot is exact
} Case;

static const char *const int_knots[] = {"0", "1", "2", "3", "4", "5", "6"};

static const char square_c2[] =
    "scheme square_c2\nparam t\n"
    "X = ((6*t^2 - 15*t + 10)*abs(t)^3 - (6*t^2 + 3*t + 1)*abs(t - 1)^3 - "
    "(6*t^2 - 39*t + 64)*abs(t - 2)^3 + (6*t^2 - 21*t + 19)*abs(t - 3)^3)/2\n"
    "Y = ((6*t^2 - 27*t + 31)*abs(t - 1)^3 - (6*t^2 - 9*t + 4)*abs(t - 2)^3 - "
    "(6*t^2 - 51*t + 109)*abs(t - 3)^3 + (6*t^2 - 33*t + 46)*abs(t - 4)^3)/2\n"
    "output X, Y\n";

static const char triangle_c1[] =
    "scheme triangle_c1\nparam t\n"
    "X = ((-2*t + 3)*t*abs(t) + 4*(t - 1)^2*abs(t - 1) - "
    "(2*t - 1)*(t - 2)*abs(t - 2))/2\n"
    "Y = ((-2*t + 5)*(t - 1)*abs(t - 1) + 4*(t - 2)^2*abs(t - 2) - "
    "(2*t - 3)*(t - 3)*abs(t - 3))/2\n"
    "output X, Y\n";

static const char spline[] =
    "scheme spline10\nparam t\n"
    "S = 1/2 + t/5 + abs(t)^3/7 - 2*abs(t - 1/3)^3/7 + 3*abs(t - 1/2)^3/7 - "
    "4*abs(t - 1)^3/7 + 5*abs(t - 3/2)^3/7 - 6*abs(t - 2)^3/7 + "
    "7*abs(t - 7/3)^3/7 - 8*abs(t - 3)^3/7 + 9*abs(t - 7/2)^3/7 - "
    "10*abs(t - 4)^3/7\n"
    "F = (-4*t*abs(t) - 3*(t - 1/3)*abs(t - 1/3) - 2*(t - 1/2)*abs(t - 1/2) "
    "- (t - 1)*abs(t - 1) + (t - 2)*abs(t - 2) + 2*(t - 7/3)*abs(t - 7/3) + "
    "3*(t - 3)*abs(t - 3) + 4*(t - 7/2)*abs(t - 7/2) + "
    "5*(t - 4)*abs(t - 4))/3\n"
    "J = t + t^2*sign(t - 1/2) + 2*sign(t - 2)\n"
    "Q = abs(t^2 - 1/4)\n"
    "output S, F, J, Q\n";

/* written with the composite forms of docs/language.md */
static const char joined[] =
    "scheme joined\npoint O, A, B, C\nparam t\n"
    "def g1(u) = along(O, A, u)\ndef g2(u) = along(A, B, u)\n"
    "def g3(u) = along(B, C, u)\ndef g4(u) = along(C, O, u)\n"
    "R = join(t, 0, g1[0..1], 1, g2[0..1], 2, g3[0..1], 3, g4[0..1], 4)\n"
    "P = piecewise(t, t^2, 1, 2*t - 1, 2, 5 - t, 3, 2)\n"
    "def h0(u) = O + (A - O)*u\ndef h1(u) = along(A, B, u)\n"
    "def h2(u) = B + (C - B)*u\n"
    "L = join(t, h0[-inf..1], 0, h1[0..1], 1, h2[0..inf])\n"
    "output R, P, L\n";

static const char *const q_knots[] = {"-1/2", "1/2", "2"};

static const Case cases[] = {
    {"examples/composite_square.pcs", NULL, square_pts, 2, 2, ref_square,
     int_knots, 5, 1},
    {"examples/composite_hexagon.pcs", NULL, hexagon_pts, 2, 2, ref_hexagon,
     int_knots, 7, 1},
    {NULL, square_c2, NULL, 1, 2, ref_square_c2, int_knots, 5, 1},
    {NULL, triangle_c1, NULL, 1, 2, ref_triangle_c1, int_knots, 4, 1},
    {NULL, spline, NULL, 1, 4, ref_spline, spline_knots, NSPLINE, 0},
    {NULL, spline, NULL, 1, 4, ref_spline, q_knots, 3, 0},
    {NULL, joined, square_pts, 2, 5, ref_join, int_knots, 5, 1},
};
enum { NCASES = sizeof cases / sizeof *cases };

/* ---- compiling --------------------------------------------------------- */

/* w1_O(t, pts, dim, out) and wb_O(n, t, pts, dim, out): the one param t,
 * no consts */
static char *wrapper(const Plan *p)
{
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    fputs("#include <stddef.h>\n#include \"gen.h\"\n", m);
    for (int o = 0; o < p->noutputs; o++) {
        const char *nm = p->outputs[o].name;
        for (int batch = 0; batch < 2; batch++) {
            const char *head =
                batch ? "void wb_%d(size_t n, const double *t, const double "
                        "*const *pts, int dim, double *out)"
                      : "void w1_%d(double t, const double *const *pts, int "
                        "dim, double *out)";
            fprintf(m, head, o);
            fputs(";\n", m);
            fprintf(m, head, o);
            fprintf(m, "\n{\n    (void)pts;\n    pcx_%s%s(%st, ", nm,
                    batch ? "_batch" : "", batch ? "n, " : "");
            for (int i = 0; i < p->npoints; i++)
                fprintf(m, "pts[%d], ", i);
            fputs("dim, out);\n}\n", m);
        }
    }
    fclose(m);
    return text;
}

typedef void (*one_fn)(double, const double *const *, int, double *);
typedef void (*batch_fn)(size_t, const double *, const double *const *, int,
                         double *);

/* every line of the generated C that computes a register: no branch */
static void check_branch_free(const char *src)
{
    int regs = 0;
    for (const char *l = src; l && *l;) {
        const char *e = strchr(l, '\n');
        size_t n = e ? (size_t)(e - l) : strlen(l);
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)(n < 1000 ? n : 1000), l);
        if (strstr(line, "const double r") && strstr(line, "/* line")) {
            regs++;
            if (strchr(line, '?') || strstr(line, "if (")) {
                fprintf(stderr, "a branch per sample: %s\n", line);
                fail();
            }
        }
        l = e ? e + 1 : NULL;
    }
    assert_true(regs > 0);
}

/* ---- the test ----------------------------------------------------------- */

static Plan *plan_of(const Case *c, char **text)
{
    const char *name = c->path ? c->path : "composite.pcs";
    Derived *d;
    if (c->path) {
        d = derive_file(c->path, stderr, NULL);
    } else {
        d = derive_source(name, c->text, strlen(c->text), stderr, NULL);
    }
    assert_non_null(d);
    Plan *p = lower_derived(d, stderr);
    derived_free(d);
    assert_non_null(p);
    if (text)
        *text = harness_emit(p, 0, "composite.pcs");
    return p;
}

/* the test points: every knot, +- 1e-9 and +- 2^-30 of it, and points not
 * dyadic in between and beyond; returns how many */
static size_t test_points(const Case *c, double *t, size_t cap)
{
    static const double between[] = {
        1.0 / 3, 2.0 / 7, 5.0 / 3, 22.0 / 7, 3.79,  -0.6,    4.3,      0.1,
        2.9,     -1e-17,  1e-17,   -1e-300,  -3.25, 6.0 / 7, 13.0 / 3, 5.9};
    size_t n = 0;
    fmpq_t k;
    fmpq_init(k);
    for (int i = 0; i < c->nknots; i++) {
        assert_int_equal(fmpq_set_str(k, c->knots[i], 10), 0);
        double kd = fmpq_get_d(k); // within an ulp of the knot
        const double off[] = {
            0, 1e-9, -1e-9, ldexp(1, -30), -ldexp(1, -30), 1.0 / 3};
        for (size_t j = 0; j < sizeof off / sizeof *off && n < cap; j++)
            t[n++] = kd + off[j];
    }
    fmpq_clear(k);
    for (size_t j = 0; j < sizeof between / sizeof *between && n < cap; j++)
        t[n++] = between[j];
    return n;
}

static void check_value(double got, const fmpq_t exact, const char *what,
                        int ci, double t, int coord)
{
    fmpq_t g;
    fmpq_init(g);
    fmpq_set_double(g, got);
    fmpq_sub(g, g, exact);
    double err = fabs(fmpq_get_d(g)), ex = fmpq_get_d(exact);
    total_checks++;
    if (!(err <= TOL * fmax(1, fabs(ex)))) {
        fprintf(stderr,
                "case %d %s: t = %.17g coord %d: got %.17g, exact %.17g "
                "(error %.3g)\n",
                ci, what, t, coord, got, ex, err);
        fail();
    }
    fmpq_clear(g);
}

static void check_case(int ci)
{
    const Case *c = &cases[ci];
    char *src;
    Plan *p = plan_of(c, &src);
    check_branch_free(src);
    char *hdr = harness_emit(p, 1, "composite.pcs"), *wrap = wrapper(p);
    Compiled cc;
    harness_compile(&cc, "comp", src, hdr, wrap);
    free(src);
    free(hdr);
    free(wrap);

    const double *ptr[8] = {NULL};
    for (int i = 0; i < p->npoints && i < 8; i++)
        ptr[i] = c->pts + (size_t)i * (size_t)c->dim;
    double t[200];
    size_t n = test_points(c, t, 200);
    fmpq *exact = _fmpq_vec_init(c->ncoords);
    fmpq_t tq;
    fmpq_init(tq);
    int off = 0; // the output's first coordinate among ncoords
    for (int o = 0; o < p->noutputs; o++) {
        int nco = p->outputs[o].kind == KIND_SCALAR ? 1 : c->dim;
        char sym[32];
        snprintf(sym, sizeof sym, "w1_%d", o);
        one_fn one = (one_fn)(uintptr_t)dlsym(cc.so, sym);
        snprintf(sym, sizeof sym, "wb_%d", o);
        batch_fn bat = (batch_fn)(uintptr_t)dlsym(cc.so, sym);
        assert_non_null(one);
        assert_non_null(bat);
        double *ob = malloc(sizeof *ob * n * (size_t)nco);
        double *orun = malloc(sizeof *orun * n * (size_t)nco);
        bat(n, t, ptr, c->dim, ob);
        const double *prm[1] = {t};
        plan_eval(p, o, n, prm, NULL, ptr, c->dim, orun, NULL);
        for (size_t i = 0; i < n; i++) {
            double o1[8];
            one(t[i], ptr, c->dim, o1);
            fmpq_set_double(tq, t[i]);
            c->ref(exact, tq);
            int dyadic_knot = 0;
            for (int k = 0; k < c->nknots && c->exact_knots; k++)
                dyadic_knot |= t[i] == (double)atoi(c->knots[k]);
            for (int q = 0; q < nco; q++) {
                const fmpq *e = exact + off + q;
                check_value(o1[q], e, "NAME_M", ci, t[i], off + q);
                check_value(ob[i * (size_t)nco + (size_t)q], e, "NAME_M_batch",
                            ci, t[i], off + q);
                check_value(orun[i * (size_t)nco + (size_t)q], e, "plan_eval",
                            ci, t[i], off + q);
                if (dyadic_knot) { // exact at the knot
                    fmpq_t g;
                    fmpq_init(g);
                    fmpq_set_double(g, o1[q]);
                    if (!fmpq_equal(g, e)) {
                        fprintf(stderr,
                                "case %d: t = %g coord %d: %.17g not "
                                "exact at the knot\n",
                                ci, t[i], off + q, o1[q]);
                        fail();
                    }
                    fmpq_set_double(g, orun[i * (size_t)nco + (size_t)q]);
                    assert_true(fmpq_equal(g, e));
                    fmpq_clear(g);
                }
            }
        }
        off += nco;
        free(ob);
        free(orun);
    }
    assert_int_equal(off, c->ncoords);
    fmpq_clear(tq);
    _fmpq_vec_clear(exact, c->ncoords);
    compiled_clear(&cc);
    plan_free(p);
}

static void test_composite_c_matches_exact_at_knots(void **state)
{
    (void)state;
    for (int ci = 0; ci < NCASES; ci++)
        check_case(ci);
}

/* ---- the plot's knots --------------------------------------------------- */

/* the numbers of attribute name="..." in tag (NULL: missing) */
static int attr_num(const char *tag, const char *name, double *v)
{
    char key[32];
    snprintf(key, sizeof key, " %s=\"", name);
    const char *s = strstr(tag, key);
    if (!s)
        return 0;
    *v = strtod(s + strlen(key), NULL);
    return 1;
}

/* the square over [-1/2, 9/2]: knots at t = 0 .. 4; the curve's samples
 * include them exactly, and a knot mark sits on each vertex */
static void test_composite_plot_marks_knots(void **state)
{
    (void)state;
    Plan *p = plan_of(&cases[0], NULL);
    PlotSpec s;
    plot_spec_default(&s);
    s.env.plan = p;
    s.env.param = 0;
    double params[1] = {0};
    s.env.params = params;
    const double *ptr[4];
    for (int i = 0; i < 4; i++)
        ptr[i] = square_pts + 2 * i;
    s.env.points = ptr;
    s.env.dim = 2;
    int curves[1] = {0};
    s.curves = curves;
    s.ncurves = 1;
    s.lo = -0.5;
    s.hi = 4.5;
    /* the knots the plot finds */
    double *kn = NULL;
    size_t nk = plot_knots(&s.env, 0, s.lo, s.hi, &kn);
    assert_int_equal(nk, 5);
    for (size_t i = 0; i < nk; i++)
        assert_true(kn[i] == (double)i);
    free(kn);
    nk = plot_knots(&s.env, 0, 0.5, 2.5, &kn);
    assert_int_equal(nk, 2);
    assert_true(kn[0] == 1 && kn[1] == 2);
    free(kn);
    /* samples on the knots, at the vertices exactly */
    PlotLimits lim;
    plot_limits_default(&lim);
    PlotCurve cv;
    plot_curve_init(&cv, &s.env, 0, s.lo, s.hi, &s.view, &lim);
    double box[4] = {-0.1, -0.1, 1.1, 1.1};
    plot_curve_refine(&cv, &s.env, &s.view, box, &lim);
    int seen = 0;
    for (size_t i = 0; i < cv.n; i++)
        for (int k = 0; k < 5; k++)
            if (cv.t[i] == (double)k) {
                seen |= 1 << k;
                assert_true(cv.x[i] == (double)square_v[k % 4][0]);
                assert_true(cv.y[i] == (double)square_v[k % 4][1]);
            }
    assert_int_equal(seen, 31);
    plot_curve_clear(&cv);

    /* the SVG: a mark per distinct knot point (t = 0 and t = 4 are both
     * the vertex O: one mark each, at the same place) */
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    assert_int_equal(plot_svg(m, &s, NULL), 0);
    fclose(m);
    const char *g = strstr(buf, "<g transform=\"matrix(");
    assert_non_null(g);
    double a, b, c2, d, e, f;
    assert_int_equal(sscanf(g + strlen("<g transform=\"matrix("),
                            "%lf %lf %lf %lf %lf %lf", &a, &b, &c2, &d, &e, &f),
                     6);
    int found[5] = {0};
    int marks = 0;
    for (const char *q = strstr(buf, "class=\"knot\""); q;
         q = strstr(q + 1, "class=\"knot\"")) {
        const char *end = strchr(q, '>');
        assert_non_null(end);
        char tag[256];
        snprintf(tag, sizeof tag, " %.*s", (int)(end - q), q);
        double x, y;
        assert_true(attr_num(tag, "cx", &x) && attr_num(tag, "cy", &y));
        marks++;
        int hit = 0;
        for (int k = 0; k < 5; k++) {
            double px = a * (double)square_v[k % 4][0] +
                        c2 * (double)square_v[k % 4][1] + e;
            double py = b * (double)square_v[k % 4][0] +
                        d * (double)square_v[k % 4][1] + f;
            if (fabs(x - px) <= 0.051 && fabs(y - py) <= 0.051 && !found[k] &&
                !hit) {
                found[k] = hit = 1;
            }
        }
        assert_true(hit);
    }
    assert_int_equal(marks, 5);
    for (int k = 0; k < 5; k++)
        assert_true(found[k]);
    free(buf);

    /* no knots: a scheme without sign kernels has no marks */
    static const char plain[] = "point A, B\nparam t\nM = along(A, B, t^2)\n";
    Derived *dd = derive_source("t.pcs", plain, strlen(plain), stderr, NULL);
    assert_non_null(dd);
    Plan *q = lower_derived(dd, stderr);
    derived_free(dd);
    s.env.plan = q;
    nk = plot_knots(&s.env, 0, -1, 1, &kn);
    assert_int_equal(nk, 0);
    free(kn);
    buf = NULL;
    m = open_memstream(&buf, &len);
    assert_int_equal(plot_svg(m, &s, NULL), 0);
    fclose(m);
    assert_null(strstr(buf, "class=\"knot\""));
    free(buf);
    plan_free(q);
    plan_free(p);
}

/* a knot not dyadic (3t - 1: t = 1/3) is found to the double whose sign
 * argument is nearest 0; a jump (sign(t - 1/2)) is marked at both of its
 * one-sided ends, and a knot of a non-linear argument (t^2 - 1/4) is not
 * looked for */
static void test_composite_plot_knots_not_dyadic_and_jumps(void **state)
{
    (void)state;
    static const char text[] =
        "point A, B, C\nparam t\n"
        "M = A + (B - A)*(t + abs(3*t - 1)) + (C - A)*(sign(t - 1/2) + "
        "abs(t^2 - 1/4))\n";
    Derived *dd = derive_source("t.pcs", text, strlen(text), stderr, NULL);
    assert_non_null(dd);
    Plan *p = lower_derived(dd, stderr);
    derived_free(dd);
    assert_non_null(p);
    static const double pts[] = {0, 0, 1, 0, 0, 1};
    const double *ptr[3] = {pts, pts + 2, pts + 4};
    double params[1] = {0};
    PlotEnv env = {p, 0, params, NULL, ptr, 2};
    double *kn = NULL;
    size_t nk = plot_knots(&env, 0, -1, 1, &kn);
    assert_int_equal(nk, 2);
    assert_true(fabs(kn[0] - 1.0 / 3) <= 2e-16 && kn[1] == 0.5);
    free(kn);
    PlotSpec s;
    plot_spec_default(&s);
    s.env = env;
    int curves[1] = {0};
    s.curves = curves;
    s.ncurves = 1;
    s.lo = -1;
    s.hi = 1;
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    assert_int_equal(plot_svg(m, &s, NULL), 0);
    fclose(m);
    int marks = 0;
    for (const char *q = strstr(buf, "class=\"knot\""); q;
         q = strstr(q + 1, "class=\"knot\""))
        marks++;
    assert_int_equal(marks, 3); // 1/3 once, 1/2 at both ends of the jump
    free(buf);
    plan_free(p);
}

static int teardown(void **state)
{
    (void)state;
    flint_cleanup_master();
    return 0;
}

int main(void)
{
    (void)harness_batch_wrapper; // the harness's, not needed here
    (void)outside_assumed;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_composite_c_matches_exact_at_knots),
        cmocka_unit_test(test_composite_plot_marks_knots),
        cmocka_unit_test(test_composite_plot_knots_not_dyadic_and_jumps),
    };
    int rc = cmocka_run_group_tests(tests, NULL, teardown);
    fprintf(stderr, "test_composite_c: %d value comparisons\n", total_checks);
    return rc;
}
