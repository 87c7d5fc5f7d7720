/*
 * test_lower.c - codegen/lower.c: a Derived (exact weights) lowered to a
 * Plan.  Small schemes are derived with derive_source and lowered with
 * lower_derived; the tests check the Plan's names (params, consts, points,
 * outputs), kinds and weight slots, that plan_eval gives the values of the
 * weights computed here by hand from the constructions' definitions
 * (along(A, B, t) = A (1 - t) + B t, divide(A, B, k) = (A + k B)/(1 + k),
 * the Desargues arc of docs/api.md), what lower.h promises of the shape
 * (constant denominators folded, one common denominator, registers shared
 * across outputs, uniform weights), the statuses of plan.h (1 a pole, 2 an
 * overflow of the denominator, 4 a function's domain or a declared range
 * the derivation rested on, docs/eval.md), the lowering errors with their
 * exact located messages (a coefficient beyond or below the doubles, a
 * degree above 2^24, an unsolved unknown scalar), and lower_q_to_double's
 * rounding (to nearest, ties to even, subnormals included), and that
 * lowering stops at the thread's deadline (budget.h) with its error.
 *
 * The trick of most tests: with the base points the unit vectors of
 * R^npoints, coordinate j of a point output is the weight of point j.
 */
/* cmocka.h needs these first, in this order */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
// clang-format on

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <flint/flint.h>
#include <flint/fmpq.h>

#include "base/budget.h"
#include "codegen/lower.h"
#include "compiler/derive.h"
#include "compiler/print/format.h"
#include "runtime/eval.h"
#include "runtime/plan.h"
#include "tests/unit/slow_lower.h"

/* derives text (no error allowed) and lowers it (must succeed) */
static Plan *lower_text(const char *text)
{
    int nerr = -1;
    Derived *d = derive_source("x.pcs", text, strlen(text), stderr, &nerr);
    assert_non_null(d);
    assert_int_equal(nerr, 0);
    Plan *p = lower_derived(d, stderr);
    derived_free(d);
    assert_non_null(p);
    return p;
}

/* derives text (no error allowed), lowers it, which must fail: returns the
 * error text (free it) */
static char *lower_error(const char *text)
{
    char *msg = NULL;
    size_t len = 0;
    Derived *d = derive_source("x.pcs", text, strlen(text), stderr, NULL);
    assert_non_null(d);
    FILE *m = open_memstream(&msg, &len);
    Plan *p = lower_derived(d, m);
    fclose(m);
    assert_null(p);
    /* the same failure with err NULL: nothing written, still NULL */
    assert_null(lower_derived(d, NULL));
    derived_free(d);
    return msg;
}

/* Evaluates output o at n samples with the base points the unit vectors of
 * R^npoints (dim = npoints, at least 1): out[s*dim + j] is then the weight
 * of point j at sample s (a scalar output: out[s] is its value).  Returns
 * plan_eval's count. */
static size_t eval_units(const Plan *p, int o, size_t n,
                         const double *const *params, const double *consts,
                         double *out, unsigned char *status)
{
    int dim = p->npoints > 0 ? p->npoints : 1;
    double *e = calloc((size_t)dim * (size_t)dim, sizeof *e);
    const double **pts = calloc((size_t)dim, sizeof *pts);
    for (int i = 0; i < p->npoints; i++) {
        e[i * dim + i] = 1;
        pts[i] = e + i * dim;
    }
    size_t r = plan_eval(p, o, n, params, consts, pts, dim, out, status);
    free(pts);
    free(e);
    return r;
}

/* a and b agree to a few ulps (the Plan's order of operations is its own) */
static void assert_close(double a, double b)
{
    if (!(fabs(a - b) <= 4 * DBL_EPSILON * fmax(1.0, fabs(b))))
        fail_msg("%.17g is not %.17g", a, b);
}

static int count_op(const Plan *p, PlanOp op)
{
    int n = 0;
    for (int i = 0; i < p->nins; i++)
        n += p->ins[i].op == op;
    return n;
}

/* the slot of point pt in output o, or -1 */
static int slot_of(const Plan *p, int o, int pt)
{
    const PlanOutput *po = &p->outputs[o];
    for (int k = 0; k < po->nterms; k++)
        if (po->point[k] == pt)
            return k;
    return -1;
}

static const char lw[] = "scheme lw\n"           // 1
                         "point A, B, C\n"       // 2
                         "param t\n"             // 3
                         "const k\n"             // 4
                         "M = along(A, B, t)\n"  // 5
                         "D = divide(A, C, k)\n" // 6
                         "V = B - A\n"           // 7
                         "s = t*k + 1\n"         // 8
                         "output M, D, V, s\n";  // 9

static void test_lower_names_kinds_and_slots(void **state)
{
    (void)state;
    Plan *p = lower_text(lw);
    assert_string_equal(p->name, "lw");
    assert_int_equal(p->nparams, 1);
    assert_string_equal(p->params[0], "t");
    assert_int_equal(p->nconsts, 1);
    assert_string_equal(p->consts[0], "k");
    assert_int_equal(p->npoints, 3);
    assert_string_equal(p->points[0], "A");
    assert_string_equal(p->points[1], "B");
    assert_string_equal(p->points[2], "C");
    assert_int_equal(p->noutputs, 4);
    static const char *const names[] = {"M", "D", "V", "s"};
    static const Kind kinds[] = {KIND_POINT, KIND_POINT, KIND_VECTOR,
                                 KIND_SCALAR};
    static const int lines[] = {5, 6, 7, 8};
    for (int o = 0; o < 4; o++) {
        assert_string_equal(p->outputs[o].name, names[o]);
        assert_int_equal(p->outputs[o].kind, kinds[o]);
        assert_int_equal(p->outputs[o].line, lines[o]);
        assert_int_equal(plan_find_output(p, names[o]), o);
    }
    assert_int_equal(plan_find_output(p, "N"), -1);
    /* M on A, B; D on A, C; V on A, B; s one slot of point -1 */
    assert_int_equal(p->outputs[0].nterms, 2);
    assert_true(slot_of(p, 0, 0) >= 0 && slot_of(p, 0, 1) >= 0);
    assert_int_equal(slot_of(p, 0, 2), -1);
    assert_int_equal(p->outputs[1].nterms, 2);
    assert_true(slot_of(p, 1, 0) >= 0 && slot_of(p, 1, 2) >= 0);
    assert_int_equal(p->outputs[2].nterms, 2);
    assert_true(slot_of(p, 2, 0) >= 0 && slot_of(p, 2, 1) >= 0);
    assert_int_equal(p->outputs[3].nterms, 1);
    assert_int_equal(p->outputs[3].point[0], -1);
    assert_false(plan_output_uses_point(p, 0, 2));
    assert_true(plan_output_uses_point(p, 1, 2));
    assert_false(plan_output_uses_point(p, 1, 1));
    /* polynomial weights have no pole register; 1/(1 + k) has one */
    assert_int_equal(p->outputs[0].bad, -1);
    assert_int_equal(p->outputs[2].bad, -1);
    assert_int_equal(p->outputs[3].bad, -1);
    assert_true(p->outputs[1].bad >= 0);
    /* nothing was assumed of a bound */
    assert_null(p->bound);
    plan_free(p);
}

static void test_lower_values_are_the_exact_weights(void **state)
{
    (void)state;
    Plan *p = lower_text(lw);
    enum { N = 5 };
    const double t[N] = {-2, 0, 0.25, 1, 3.5};
    const double *params[1] = {t};
    const double k[1] = {0.5};
    double out[N * 3];
    unsigned char st[N];
    /* M = A (1 - t) + B t */
    assert_int_equal(eval_units(p, 0, N, params, k, out, st), 0);
    for (int i = 0; i < N; i++) {
        assert_close(out[3 * i], 1 - t[i]);
        assert_close(out[3 * i + 1], t[i]);
        assert_true(out[3 * i + 2] == 0);
        assert_int_equal(st[i], 0);
    }
    /* D = (A + k C)/(1 + k): 2/3 A + 1/3 C at k = 1/2 */
    assert_int_equal(eval_units(p, 1, N, params, k, out, st), 0);
    for (int i = 0; i < N; i++) {
        assert_close(out[3 * i], 2.0 / 3.0);
        assert_true(out[3 * i + 1] == 0);
        assert_close(out[3 * i + 2], 1.0 / 3.0);
        assert_int_equal(st[i], 0);
    }
    /* V = B - A, whatever t and k */
    assert_int_equal(eval_units(p, 2, N, params, k, out, st), 0);
    for (int i = 0; i < N; i++) {
        assert_true(out[3 * i] == -1);
        assert_true(out[3 * i + 1] == 1);
        assert_true(out[3 * i + 2] == 0);
    }
    /* s = t k + 1, one value per sample */
    double sv[N];
    assert_int_equal(eval_units(p, 3, N, params, k, sv, st), 0);
    for (int i = 0; i < N; i++)
        assert_close(sv[i], t[i] * 0.5 + 1);
    /* another k: D = (A + 3 C)/4 */
    const double k3[1] = {3};
    eval_units(p, 1, 1, params, k3, out, st);
    assert_close(out[0], 0.25);
    assert_close(out[2], 0.75);
    plan_free(p);
}

/* w_i = c_i * ... : a constant denominator is folded into c_i, so no DIV
 * and no pole register; the constants are exact: (A + B)/2 and A/3 + 2B/3 */
static void test_lower_folds_constant_denominators(void **state)
{
    (void)state;
    Plan *p = lower_text("point A, B\nparam t\nM = (A + B)/2\n"
                         "N = A/3 + 2*B/3 + (B - A)*t/4\noutput M, N\n");
    assert_int_equal(p->outputs[0].bad, -1);
    assert_int_equal(p->outputs[1].bad, -1);
    assert_int_equal(count_op(p, PLAN_DIV), 0);
    assert_int_equal(count_op(p, PLAN_POLE), 0);
    const double t[2] = {0, 2};
    const double *params[1] = {t};
    double out[4];
    eval_units(p, 0, 2, params, NULL, out, NULL);
    assert_true(out[0] == 0.5 && out[1] == 0.5);
    assert_true(out[2] == 0.5 && out[3] == 0.5);
    /* N = A (1/3 - t/4) + B (2/3 + t/4) */
    eval_units(p, 1, 2, params, NULL, out, NULL);
    assert_close(out[0], 1.0 / 3.0);
    assert_close(out[1], 2.0 / 3.0);
    assert_close(out[2], 1.0 / 3.0 - 0.5);
    assert_close(out[3], 2.0 / 3.0 + 0.5);
    plan_free(p);
}

/* the Plan builder hash-conses across outputs: the weight 1 - t of A in
 * along(A, B, t) and in along(A, C, t) is one register; a weight of
 * consts only is uniform, one of a param is not */
static void test_lower_shares_registers_across_outputs(void **state)
{
    (void)state;
    Plan *p = lower_text("point A, B, C\nparam t\nconst k\n"
                         "M = along(A, B, t)\nN = along(A, C, t)\n"
                         "D = divide(B, C, k)\noutput M, N, D\n");
    int wm = p->outputs[0].reg[slot_of(p, 0, 0)];
    int wn = p->outputs[1].reg[slot_of(p, 1, 0)];
    assert_int_equal(wm, wn);
    /* t itself is the weight of B in M and of C in N */
    assert_int_equal(p->outputs[0].reg[slot_of(p, 0, 1)],
                     p->outputs[1].reg[slot_of(p, 1, 2)]);
    assert_int_equal(p->ins[wm].uniform, 0);
    const PlanOutput *d = &p->outputs[2];
    for (int k = 0; k < d->nterms; k++)
        assert_int_equal(p->ins[d->reg[k]].uniform, 1);
    assert_int_equal(p->ins[d->bad].uniform, 1);
    plan_free(p);
}

/* The Desargues arc (docs/api.md): four weights over the one denominator
 * 2t^2 - 2t + 1, lowered as one 1/L (a single DIV), and its values
 * (1 - t)^3, t^2 (1 - t), t (1 - t)^2, t^3 over it; no pole at t = 1/2,
 * where its auxiliary points T and S have one. */
static void test_lower_desargues_one_common_denominator(void **state)
{
    (void)state;
    Plan *p = lower_text("point A, B, C, D\nparam t in [0, 1]\n"
                         "P = along(A, C, t)\nQ = along(C, B, t)\n"
                         "K = along(B, D, t)\nN = along(P, Q, t)\n"
                         "J = along(Q, K, t)\n"
                         "T = meet(line(P, Q), line(A, B))\n"
                         "S = meet(line(Q, K), line(C, D))\n"
                         "M = meet(line(S, N), line(T, J))\n");
    assert_int_equal(p->noutputs, 1);
    assert_string_equal(p->outputs[0].name, "M");
    assert_int_equal(p->outputs[0].kind, KIND_POINT);
    assert_int_equal(p->outputs[0].nterms, 4);
    assert_int_equal(count_op(p, PLAN_DIV), 1);
    enum { N = 6 };
    const double t[N] = {0, 0.25, 0.5, 0.75, 1, 2};
    const double *params[1] = {t};
    double out[N * 4];
    unsigned char st[N];
    assert_int_equal(eval_units(p, 0, N, params, NULL, out, st), 0);
    for (int i = 0; i < N; i++) {
        double u = t[i], v = 1 - u, den = 2 * u * u - 2 * u + 1;
        assert_close(out[4 * i], v * v * v / den);
        assert_close(out[4 * i + 1], u * u * v / den);
        assert_close(out[4 * i + 2], u * v * v / den);
        assert_close(out[4 * i + 3], u * u * u / den);
        assert_int_equal(st[i], PLAN_STATUS_OK);
    }
    /* M(1/2) is the centroid */
    assert_close(out[8], 0.25);
    plan_free(p);
}

/* a function's value (a kernel) is computed once and shared by every
 * output that uses it (docs/codegen.md); a kernel in a denominator has
 * its pole check; diff of a point is a vector output */
static void test_lower_kernels_shared_and_diff(void **state)
{
    (void)state;
    Plan *p = lower_text("point A, B\nparam t\na = sin(t)\n"
                         "b = 2*sin(t) + t\nc = 1/sin(t)\n"
                         "M = along(A, B, t^2)\nW = diff(M, t)\n"
                         "output a, b, c, W\n");
    assert_int_equal(count_op(p, PLAN_FN), 1);
    assert_int_equal(p->outputs[3].kind, KIND_VECTOR);
    assert_string_equal(p->outputs[3].name, "W");
    const double t[3] = {0.5, 0, -1};
    const double *params[1] = {t};
    double v[6];
    unsigned char st[3];
    assert_int_equal(eval_units(p, 0, 3, params, NULL, v, st), 0);
    assert_close(v[0], sin(0.5));
    assert_true(v[1] == 0);
    assert_close(v[2], -sin(1.0));
    assert_int_equal(eval_units(p, 1, 3, params, NULL, v, st), 0);
    assert_close(v[0], 2 * sin(0.5) + 0.5);
    assert_close(v[2], -2 * sin(1.0) - 1);
    assert_int_equal(eval_units(p, 2, 3, params, NULL, v, st), 1);
    assert_close(v[0], 1 / sin(0.5));
    assert_int_equal(st[0], PLAN_STATUS_OK);
    assert_int_equal(st[1], PLAN_STATUS_POLE);
    assert_true(isnan(v[1]));
    /* d/dt (A (1 - t^2) + B t^2) = 2t (B - A) */
    assert_int_equal(eval_units(p, 3, 3, params, NULL, v, st), 0);
    assert_close(v[0], -1);
    assert_close(v[1], 1);
    assert_true(v[2] == 0 && v[3] == 0);
    assert_close(v[4], 2);
    assert_close(v[5], -2);
    plan_free(p);
}

/* divide(A, B, t) = (A + t B)/(1 + t): a pole at t = -1 (status 1, NaN),
 * counted in plan_eval's result */
static void test_lower_pole_status(void **state)
{
    (void)state;
    Plan *p = lower_text("point A, B\nparam t\nD = divide(A, B, t)\n");
    const double t[3] = {1, -1, 3};
    const double *params[1] = {t};
    double out[6];
    unsigned char st[3];
    assert_int_equal(eval_units(p, 0, 3, params, NULL, out, st), 1);
    assert_int_equal(st[0], PLAN_STATUS_OK);
    assert_close(out[0], 0.5);
    assert_close(out[1], 0.5);
    assert_int_equal(st[1], PLAN_STATUS_POLE);
    assert_true(isnan(out[2]) && isnan(out[3]));
    assert_int_equal(st[2], PLAN_STATUS_OK);
    assert_close(out[4], 0.25);
    assert_close(out[5], 0.75);
    plan_free(p);
}

/* divide(A, B, t^2) at t = 1e200: 1 + t^2 is not finite, 1/L is 0 and the
 * weights would be finite and wrong: status 2, NaN */
static void test_lower_overflow_status(void **state)
{
    (void)state;
    Plan *p = lower_text("point A, B\nparam t\nD = divide(A, B, t^2)\n");
    const double t[2] = {1e200, 2};
    const double *params[1] = {t};
    double out[4];
    unsigned char st[2];
    assert_int_equal(eval_units(p, 0, 2, params, NULL, out, st), 1);
    assert_int_equal(st[0], PLAN_STATUS_OVERFLOW);
    assert_true(isnan(out[0]) && isnan(out[1]));
    assert_int_equal(st[1], PLAN_STATUS_OK);
    assert_close(out[2], 1.0 / 5.0);
    assert_close(out[3], 4.0 / 5.0);
    plan_free(p);
}

/* sqrt of a negative number, ln of a number <= 0, asin beyond [-1, 1]:
 * status 4 (docs/eval.md), NaN; inside the domains the values of libm */
static void test_lower_domain_status(void **state)
{
    (void)state;
    Plan *p = lower_text("param t\nq = sqrt(t)\nl = ln(t)\na = asin(t)\n"
                         "output q, l, a\n");
    enum { N = 5 };
    const double t[N] = {-1, 0, 0.25, 1, 2};
    const double *params[1] = {t};
    double v[N];
    unsigned char st[N];
    assert_int_equal(eval_units(p, 0, N, params, NULL, v, st), 1);
    assert_int_equal(st[0], PLAN_STATUS_DOMAIN);
    assert_true(isnan(v[0]));
    assert_true(v[1] == 0 && v[2] == 0.5 && v[3] == 1);
    assert_close(v[4], sqrt(2.0));
    for (int i = 1; i < N; i++)
        assert_int_equal(st[i], PLAN_STATUS_OK);

    assert_int_equal(eval_units(p, 1, N, params, NULL, v, st), 2);
    assert_int_equal(st[0], PLAN_STATUS_DOMAIN);
    assert_int_equal(st[1], PLAN_STATUS_DOMAIN);
    assert_true(isnan(v[0]) && isnan(v[1]));
    assert_close(v[2], -log(4.0));
    assert_true(v[3] == 0);
    assert_close(v[4], log(2.0));

    assert_int_equal(eval_units(p, 2, N, params, NULL, v, st), 1);
    assert_close(v[0], -asin(1.0));
    assert_true(v[1] == 0);
    assert_close(v[2], asin(0.25));
    assert_close(v[3], asin(1.0));
    assert_int_equal(st[3], PLAN_STATUS_OK);
    assert_int_equal(st[4], PLAN_STATUS_DOMAIN);
    assert_true(isnan(v[4]));
    plan_free(p);
}

/* abs(t) = t on [0, 1] rests on t >= 0 only: t = -1/2 is status 4, t =
 * 3/2 evaluates (docs/language.md, Declared ranges); the Plan records the
 * assumed end and the interval's text */
static void test_lower_declared_range_status(void **state)
{
    (void)state;
    Plan *p = lower_text("param t in [0, 1]\nr = abs(t)\n");
    assert_non_null(p->bound);
    assert_int_equal(p->bound[0].flags, PLAN_BOUND_LO);
    assert_string_equal(p->bound[0].text, "[0, 1]");
    assert_true(p->bound[0].lo == 0 && p->bound[0].hi == 1);
    assert_true(plan_out_of_bounds(p, 0, -0.5));
    assert_false(plan_out_of_bounds(p, 0, 1.5));
    const double t[4] = {-0.5, 0, 0.5, 1.5};
    const double *params[1] = {t};
    double v[4];
    unsigned char st[4];
    assert_int_equal(eval_units(p, 0, 4, params, NULL, v, st), 1);
    assert_int_equal(st[0], PLAN_STATUS_DOMAIN);
    assert_true(isnan(v[0]));
    assert_true(v[1] == 0 && v[2] == 0.5 && v[3] == 1.5);
    assert_int_equal(st[1] | st[2] | st[3], 0);
    plan_free(p);

    /* an open end: t = 0 itself is outside (0, 1] */
    p = lower_text("param t in (0, 1]\nr = abs(t)\n");
    assert_int_equal(p->bound[0].flags, PLAN_BOUND_LO | PLAN_BOUND_LO_OPEN);
    assert_string_equal(p->bound[0].text, "(0, 1]");
    eval_units(p, 0, 4, params, NULL, v, st);
    assert_int_equal(st[0], PLAN_STATUS_DOMAIN);
    assert_int_equal(st[1], PLAN_STATUS_DOMAIN);
    assert_int_equal(st[2], PLAN_STATUS_OK);
    assert_int_equal(st[3], PLAN_STATUS_OK);
    plan_free(p);

    /* a const's bound: sqrt(a^2) = a for a > 0; input 0 is the const */
    p = lower_text("const a > 0\nr = sqrt(a^2)\n");
    assert_int_equal(p->nparams, 0);
    assert_int_equal(p->bound[0].flags, PLAN_BOUND_LO | PLAN_BOUND_LO_OPEN);
    assert_string_equal(p->bound[0].text, "(0, inf)");
    const double a1[1] = {2}, a2[1] = {-2};
    eval_units(p, 0, 1, NULL, a1, v, st);
    assert_true(v[0] == 2);
    assert_int_equal(st[0], PLAN_STATUS_OK);
    assert_int_equal(eval_units(p, 0, 1, NULL, a2, v, st), 1);
    assert_int_equal(st[0], PLAN_STATUS_DOMAIN);
    plan_free(p);

    /* a range no simplification used changes nothing */
    p = lower_text("point A, B\nparam t in [0, 1]\nM = along(A, B, t)\n");
    assert_null(p->bound);
    assert_int_equal(p->outputs[0].bad, -1);
    const double t2[1] = {2};
    const double *params2[1] = {t2};
    eval_units(p, 0, 1, params2, NULL, v, st);
    assert_true(v[0] == -1 && v[1] == 2);
    assert_int_equal(st[0], PLAN_STATUS_OK);
    plan_free(p);
}

/* the refusals of lower.h, at the output's definition (FILE:LINE:COL,
 * the line, the caret under the defined name) */
static void test_lower_refuses_coefficients_beyond_doubles(void **state)
{
    (void)state;
    char *e = lower_error("param t\ns = 10^400*t\n");
    assert_string_equal(
        e, "x.pcs:2:1: error: s cannot be evaluated in double precision: "
           "scaled to integer coefficients, its equation has a coefficient "
           "of about 10^400, beyond the largest double\n"
           "s = 10^400*t\n"
           "^\n");
    free(e);
    e = lower_error("param t\ns = 1\nu = t/10^400\noutput s, u\n");
    assert_string_equal(
        e, "x.pcs:3:1: error: u cannot be evaluated in double precision: a "
           "coefficient of its equation (about 10^-400) is below the "
           "smallest double and would be 0\n"
           "u = t/10^400\n"
           "^\n");
    free(e);
    /* a point output: 10^400 in a weight's numerator */
    e = lower_error("point A, B\nparam t\nM = along(A, B, 10^400*t)\n");
    assert_non_null(strstr(e, "x.pcs:3:1: error: M cannot be evaluated in "
                              "double precision: scaled to integer "
                              "coefficients, its equation has a coefficient "
                              "of about 10^400"));
    free(e);
}

static void test_lower_refuses_degree_above_2_24(void **state)
{
    (void)state;
    /* (t^1000)^1000)^20 = t^(2*10^7) > 2^24 = 16777216 */
    char *e = lower_error("param t\nc = t^1000\nb = c^1000\na = b^20\n");
    assert_string_equal(e, "x.pcs:4:1: error: a cannot be evaluated "
                           "numerically: its equation has degree 20000000, "
                           "beyond the limit of 16777216\n"
                           "a = b^20\n"
                           "^\n");
    free(e);
    /* t^(10^6 * 16) = t^16000000 is below the limit: lowered */
    Plan *p = lower_text("param t\nc = t^1000\nb = c^1000\na = b^16\n");
    const double t[2] = {1, -1};
    const double *params[1] = {t};
    double v[2];
    eval_units(p, 0, 2, params, NULL, v, NULL);
    assert_true(v[0] == 1 && v[1] == 1);
    plan_free(p);
}

/* An output holding a ring variable that is neither a param nor a const
 * (an unknown scalar no solve determined).  derive itself refuses such
 * outputs, so the Derived is altered by hand: s = t becomes s = k, k the
 * solve's extra variable. */
static void test_lower_refuses_unsolved_unknown_scalar(void **state)
{
    (void)state;
    static const char text[] = "point A, B\nparam t\nunknown scalar k\n"
                               "X = along(A, B, k)\n"
                               "solve X = divide(A, B, 2) for k\ns = t\n";
    Derived *d = derive_source("x.pcs", text, strlen(text), stderr, NULL);
    assert_non_null(d);
    assert_int_equal(d->nextra, 1);
    assert_string_equal(d->extra[0], "k");
    assert_int_equal(d->noutputs, 1);
    Plan *p = lower_derived(d, NULL); /* as derived: fine */
    assert_non_null(p);
    plan_free(p);
    ratfun_gen(d->outputs[0].scalar, d->nparams + d->nconsts, &d->ring);
    char *msg = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&msg, &len);
    assert_null(lower_derived(d, m));
    fclose(m);
    assert_string_equal(msg, "x.pcs:6:1: error: s depends on an unknown "
                             "scalar that no solve determined: emit-c and "
                             "eval cannot give it a value\n"
                             "s = t\n"
                             "^\n");
    free(msg);
    derived_free(d);
}

/* q as a double: the value, and the status */
static LowerError q_to_double(double *v, const char *num, const char *den)
{
    fmpq_t q;
    fmpq_init(q);
    fmpz_set_str(fmpq_numref(q), num, 10);
    fmpz_set_str(fmpq_denref(q), den, 10);
    fmpq_canonicalise(q);
    *v = -42;
    LowerError e = lower_q_to_double(v, q);
    fmpq_clear(q);
    return e;
}

/* 2^e + add as a decimal string (flint_free it), for the edges of the
 * doubles */
static char *pow2(ulong e, long add)
{
    fmpz_t z;
    fmpz_init(z);
    fmpz_one(z);
    fmpz_mul_2exp(z, z, e);
    if (add >= 0)
        fmpz_add_ui(z, z, (ulong)add);
    else
        fmpz_sub_ui(z, z, (ulong)-add);
    char *s = fmpz_get_str(NULL, 10, z);
    fmpz_clear(z);
    return s;
}

static void test_lower_q_to_double_rounds_to_nearest_even(void **state)
{
    (void)state;
    double v;
    assert_int_equal(q_to_double(&v, "0", "1"), LOWER_OK);
    assert_true(v == 0);
    assert_int_equal(q_to_double(&v, "1", "3"), LOWER_OK);
    assert_true(v == 1.0 / 3.0); /* IEEE division rounds to nearest */
    assert_int_equal(q_to_double(&v, "-2", "3"), LOWER_OK);
    assert_true(v == -2.0 / 3.0);
    assert_int_equal(q_to_double(&v, "3", "10"), LOWER_OK);
    assert_true(v == 0.3); /* the compiler's rounding of the literal */
    /* 2^53 + 1 is a tie between 2^53 and 2^53 + 2: to even, 2^53; 2^53 +
     * 3 between 2^53 + 2 and 2^53 + 4: to even, 2^53 + 4 (truncation, as
     * FLINT 2.9's fmpq_get_d, gives + 2) */
    char *s = pow2(53, 1);
    assert_int_equal(q_to_double(&v, s, "1"), LOWER_OK);
    assert_true(v == 9007199254740992.0);
    flint_free(s);
    s = pow2(53, 3);
    assert_int_equal(q_to_double(&v, s, "1"), LOWER_OK);
    assert_true(v == 9007199254740996.0);
    flint_free(s);
    /* 1/(2^1074): the smallest subnormal; 1/2^1075 is a tie with 0, to
     * even (0): underflow; 3/2^1076 rounds up to 2^-1074 */
    s = pow2(1074, 0);
    assert_int_equal(q_to_double(&v, "1", s), LOWER_OK);
    assert_true(v == 0x1p-1074);
    flint_free(s);
    s = pow2(1075, 0);
    assert_int_equal(q_to_double(&v, "1", s), LOWER_UNDERFLOW);
    flint_free(s);
    s = pow2(1076, 0);
    assert_int_equal(q_to_double(&v, "3", s), LOWER_OK);
    assert_true(v == 0x1p-1074);
    assert_int_equal(q_to_double(&v, "-3", s), LOWER_OK);
    assert_true(v == -0x1p-1074);
    flint_free(s);
    /* DBL_MAX = 2^1024 - 2^971; the midpoint 2^1024 - 2^970 rounds to
     * even, up to 2^1024: overflow; just below it, DBL_MAX */
    s = pow2(1024, 0);
    assert_int_equal(q_to_double(&v, s, "1"), LOWER_OVERFLOW);
    flint_free(s);
    fmpz_t z, h;
    fmpz_init(z);
    fmpz_init(h);
    fmpz_one(z);
    fmpz_mul_2exp(z, z, 1024);
    fmpz_one(h);
    fmpz_mul_2exp(h, h, 970);
    fmpz_sub(z, z, h); /* the midpoint */
    s = fmpz_get_str(NULL, 10, z);
    assert_int_equal(q_to_double(&v, s, "1"), LOWER_OVERFLOW);
    flint_free(s);
    fmpz_sub_ui(z, z, 1);
    s = fmpz_get_str(NULL, 10, z);
    assert_int_equal(q_to_double(&v, s, "1"), LOWER_OK);
    assert_true(v == DBL_MAX);
    flint_free(s);
    fmpz_clear(h);
    fmpz_clear(z);
    /* far out: 10^400 and 10^-400 */
    fmpq_t q;
    fmpq_init(q);
    fmpz_set_ui(fmpq_numref(q), 10);
    fmpz_pow_ui(fmpq_numref(q), fmpq_numref(q), 400);
    assert_int_equal(lower_q_to_double(&v, q), LOWER_OVERFLOW);
    fmpq_inv(q, q);
    assert_int_equal(lower_q_to_double(&v, q), LOWER_UNDERFLOW);
    fmpq_clear(q);
}

static int teardown_group(void **state)
{
    (void)state;
    flint_cleanup_master();
    return 0;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* the thread's deadline (budget.h): what the fuzz targets give each
 * input after its derivation, and the C API each pc_compile.  40 outputs
 * that derive in milliseconds and lower for much longer (a factoring each
 * of degree about 60): with a deadline of an eighth of the lowering's
 * time (measured here first), lowering gives up at the next recursive
 * step with the located error and frees what it built (ASan, valgrind),
 * well before it would have ended; the printer with a deadline already
 * passed skips its search for short forms and still prints every output */
static void test_lower_stops_at_the_deadline(void **state)
{
    (void)state;
    char *text = slow_to_lower();
    int nerr = 0;
    Derived *d = derive_source("slow.pcs", text, strlen(text), NULL, &nerr);
    assert_non_null(d);
    double t0 = now_s();
    Plan *pl = lower_derived(d, NULL);
    double full = now_s() - t0;
    assert_non_null(pl);
    plan_free(pl);
    char *err = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&err, &len);
    budget_deadline_set(full / 8);
    t0 = now_s();
    pl = lower_derived(d, m);
    double cut = now_s() - t0;
    assert_true(budget_late());
    budget_deadline_set(0);
    assert_false(budget_late());
    fclose(m);
    assert_null(pl);
    assert_true(cut < full / 2);
    assert_true(strncmp(err, "slow.pcs:", 9) == 0);
    assert_non_null(strstr(err, ": error: the time budget of "));
    assert_non_null(strstr(err, " s ran out while lowering this to numbers; "
                                "raise it with --max-seconds\n"));
    free(err);
    m = open_memstream(&err, &len);
    budget_deadline_set(1e-9);
    format_derived(m, d, FMT_TEXT, -1);
    budget_deadline_set(0);
    fclose(m);
    assert_non_null(strstr(err, "M1 = "));
    assert_non_null(strstr(err, "M40 = "));
    free(err);
    derived_free(d);
    free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lower_names_kinds_and_slots),
        cmocka_unit_test(test_lower_values_are_the_exact_weights),
        cmocka_unit_test(test_lower_folds_constant_denominators),
        cmocka_unit_test(test_lower_shares_registers_across_outputs),
        cmocka_unit_test(test_lower_desargues_one_common_denominator),
        cmocka_unit_test(test_lower_kernels_shared_and_diff),
        cmocka_unit_test(test_lower_pole_status),
        cmocka_unit_test(test_lower_overflow_status),
        cmocka_unit_test(test_lower_domain_status),
        cmocka_unit_test(test_lower_declared_range_status),
        cmocka_unit_test(test_lower_refuses_coefficients_beyond_doubles),
        cmocka_unit_test(test_lower_refuses_degree_above_2_24),
        cmocka_unit_test(test_lower_refuses_unsolved_unknown_scalar),
        cmocka_unit_test(test_lower_q_to_double_rounds_to_nearest_even),
        cmocka_unit_test(test_lower_stops_at_the_deadline),
    };
    return cmocka_run_group_tests(tests, NULL, teardown_group);
}
