/*
 * test_steps.c - `derive --steps` (Derived.steps, compiler/steps.c).
 *
 * The steps of the Desargues arc (examples/desargues_arc.pcs) are compared
 * symbolically with the intermediate equations of the article
 * (seeds/article-desargues-contour-arc.txt): P, Q, K, N, J, T, S, R and M,
 * the Menelaus ratio ABT = -t^2/tb^2, and the meet of SN and TJ as the
 * article solves it (J in the simplex S, N, T with p_j = 2t - 1 and
 * q_j = tb/t, lambda = q_j/(p_j + q_j)).  The article's forms are written
 * as pointcalc definitions and derived by pointcalc's own front end, in the
 * same scheme, so that both sides live in one ring.  Also: the meet
 * identities on every meet step (lambda, mu, a + b), a V-theorem meet,
 * subst and diff steps, solve steps, an unknown no solve determines, the
 * parallel-lines error with steps on, and that keeping steps changes no
 * output.  The binary ($PC_BIN) is run for the --steps flag.
 */
/* cmocka.h needs these first, in this order */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
// clang-format on

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "compiler/derive.h"
#include "compiler/print/format.h"
#include "compiler/print/latexbreak.h"
#include "compiler/print/steps.h"

static char tmpdir[64];
static const char *bin;

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    size_t n = 0;
    FILE *m = open_memstream(&buf, &n);
    int c;
    while (f && (c = fgetc(f)) != EOF)
        fputc(c, m);
    fclose(m);
    if (f)
        fclose(f);
    if (len)
        *len = n;
    return buf;
}

static Derived *derive_text(const char *text, int keep, char **err)
{
    DeriveOptions opt = {.max_seconds = 60, .keep_steps = keep};
    size_t elen = 0;
    char *ebuf = NULL;
    FILE *e = open_memstream(&ebuf, &elen);
    int nerr = 0;
    Derived *d = derive_source_ex("s.pcs", text, strlen(text), e, &nerr, &opt);
    fclose(e);
    if (err)
        *err = ebuf;
    else
        free(ebuf);
    return d;
}

static const DerivedStep *step(const Derived *d, const char *name)
{
    for (slong i = 0; i < d->nsteps; i++)
        if (strcmp(d->steps[i].value.name, name) == 0)
            return &d->steps[i];
    fail_msg("no step '%s'", name);
    return NULL;
}

/* the two named steps have the same point equation */
static void same_point(const Derived *d, const char *x, const char *y)
{
    const DerivedStep *a = step(d, x), *b = step(d, y);
    if (!pteq_equal(a->value.eq, b->value.eq, &d->ring)) {
        char *sa = format_output_rhs(d, &a->value, FMT_TEXT, -1);
        char *sb = format_output_rhs(d, &b->value, FMT_TEXT, -1);
        fail_msg("%s = %s\n  but %s = %s", x, sa, y, sb);
    }
}

/* the scalar x equals step y's value */
static void same_scalar(const Derived *d, const RatFun x, const char *y)
{
    const DerivedStep *b = step(d, y);
    assert_int_equal(b->value.kind, KIND_SCALAR);
    if (!ratfun_equal(x, b->value.scalar, &d->ring)) {
        char *sa = ratfun_get_str(x, &d->ring);
        char *sb = ratfun_get_str(b->value.scalar, &d->ring);
        fail_msg("%s, but %s = %s", sa, y, sb);
    }
}

/* x equals the expression text (ratfun_set_str) */
static void scalar_is(const Derived *d, const RatFun x, const char *text)
{
    RatFun e;
    ratfun_init(e, &d->ring);
    assert_int_equal(ratfun_set_str(e, text, &d->ring), 0);
    if (!ratfun_equal(x, e, &d->ring)) {
        char *sa = ratfun_get_str(x, &d->ring);
        fail_msg("%s, expected %s", sa, text);
    }
    ratfun_clear(e, &d->ring);
}

/* ---- the meet identities ------------------------------------------------- */

/* the first point (not a direction) of args[lo..hi-1] */
static slong origin_of(const DerivedStep *s, slong lo, slong hi)
{
    for (slong j = lo; j < hi; j++)
        if (s->args[j].kind != KIND_VECTOR)
            return j;
    fail_msg("a flat of %s without a point", s->value.name);
    return lo;
}

/* res = args[j] as a direction from args[o] (a direction is itself) */
static void direction(PointEq res, const DerivedStep *s, slong j, slong o,
                      const Ring *r)
{
    if (s->args[j].kind == KIND_VECTOR)
        pteq_set(res, s->args[j].eq, r);
    else
        pteq_sub(res, s->args[j].eq, s->args[o].eq, r);
}

/* Every meet step: M = O1 + D1*lambda = O2 + sum D2_j*mu_j (O the flat's
 * first point, D the others' directions from it), det = a + b, lambda =
 * b/det, and W = a*P + b*Q + c*V... (a direction V stands for O + V).
 * Returns the number of meets. */
static int check_meets(const Derived *d)
{
    const Ring *r = &d->ring;
    int nmeets = 0;
    PointEq x, y;
    RatFun l;
    pteq_init(x, r);
    pteq_init(y, r);
    ratfun_init(l, r);
    for (slong i = 0; i < d->nsteps; i++) {
        const DerivedStep *s = &d->steps[i];
        if (s->op != STEP_MEET || s->pending)
            continue;
        nmeets++;
        assert_int_equal(s->nfirst, 2);
        assert_int_equal(s->nparams, s->nargs - s->nfirst);
        /* on the first line */
        slong o = origin_of(s, 0, 2);
        direction(x, s, 1 - o, o, r);
        pteq_scalar_mul(x, x, s->params, r);
        pteq_add(x, x, s->args[o].eq, r);
        assert_true(pteq_equal(x, s->value.eq, r));
        /* on the second flat */
        o = origin_of(s, 2, s->nargs);
        pteq_set(x, s->args[o].eq, r);
        for (slong j = 2, k = 1; j < s->nargs; j++) {
            if (j == o)
                continue;
            direction(y, s, j, o, r);
            pteq_scalar_mul(y, y, s->params + k++, r);
            pteq_add(x, x, y, r);
        }
        assert_true(pteq_equal(x, s->value.eq, r));
        /* the S/V-theorem form */
        assert_true(s->has_sv);
        ratfun_add(l, s->sv_coord, s->sv_coord + 1, r);
        assert_true(ratfun_equal(l, s->det, r));
        assert_int_equal(ratfun_div(l, s->sv_coord + 1, s->det, r), 0);
        assert_true(ratfun_equal(l, s->params, r));
        PointEq v[5];
        for (slong j = 0; j < s->nargs; j++) {
            pteq_init(v[j], r);
            pteq_set(v[j], s->args[j].eq, r);
            if (s->args[j].kind == KIND_VECTOR)
                pteq_add(v[j], v[j],
                         s->args[j < 2 ? origin_of(s, 0, 2)
                                       : origin_of(s, 2, s->nargs)]
                             .eq,
                         r);
        }
        pteq_zero(x, r);
        for (slong k = 0, j = 0; k <= s->nparams; k++, j++) {
            if (j == s->sv_w)
                j++;
            pteq_scalar_mul(y, v[j], s->sv_coord + k, r);
            pteq_add(x, x, y, r);
        }
        assert_true(pteq_equal(x, v[s->sv_w], r));
        for (slong j = 0; j < s->nargs; j++)
            pteq_clear(v[j], r);
    }
    ratfun_clear(l, r);
    pteq_clear(y, r);
    pteq_clear(x, r);
    return nmeets;
}

/* the identities on the meets of examples: directions, planes, consts,
 * solves */
static void test_steps_meet_identities_examples(void **state)
{
    (void)state;
    static const char *const files[] = {
        "examples/parabola_improper_point.pcs",
        "examples/curve_3d_one_ratio.pcs",
        "examples/conic_five_points.pcs",
        "examples/closed_cubics.pcs",
        "examples/interpolation_desargues.pcs",
        "examples/ellipse_conjugate_diameters_2.pcs",
    };
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        DeriveOptions opt = {.max_seconds = 60, .keep_steps = 1};
        int nerr = 0;
        Derived *d = derive_file_ex(files[i], stderr, &nerr, &opt);
        if (!d)
            fail_msg("%s does not derive", files[i]);
        if (check_meets(d) == 0)
            fail_msg("%s: no meet", files[i]);
        derived_free(d);
    }
}

/* ---- the Desargues arc and the article ----------------------------------- */

/* The article's intermediate equations (section "Моделирование дуги
 * обвода"), re-derived by hand and agreeing with the article:
 *   AP/AC = CQ/CB = BK/BD = PN/PQ = QJ/QK = t, tb = 1 - t;
 *   N = A tb^2 + 2C tb t + B t^2,  J = C tb^2 + 2B tb t + D t^2;
 *   Menelaus in ACB cut by PQT: ACP*CBQ*BAT = -1, ACP = CBQ = t/tb, so
 *   ABT = 1/BAT = -t^2/tb^2 and T = (A + ABT*B)/(1 + ABT)
 *     = (A tb^2 - B t^2)/(tb^2 - t^2), tb^2 - t^2 = 1 - 2t;
 *   likewise S = (C tb^2 - D t^2)/(1 - 2t); R = T tb + S t;
 *   J = (S - T) p_j + (N - T) q_j + T with p_j = 2t - 1, q_j = tb/t;
 *   M = S (1 - lambda) + N lambda, the S-theorem determinant
 *   |p_j q_j 1-p_j-q_j; 1-lambda lambda 0; 0 0 1| = 0 gives
 *   lambda = q_j/(p_j + q_j) = tb/(2t^2 - 2t + 1);
 *   M = S t(2t - 1)/(2t^2 - 2t + 1) + N tb/(2t^2 - 2t + 1)
 *     = (A tb^3 + B t^2 tb + C tb^2 t + D t^3)/(2t^2 - 2t + 1)  (2);
 *   C = B, A = D (the closed arc, 1 - 3t tb = 3t^2 - 3t + 1), t = 1/2 (the
 *   centroid), dM/dt and d2M/dt2 as printed, expanded numerators. */
static const char article[] =
    "\n# the article's forms\n"
    "tb = 1 - t\n"
    "P_a = A*tb + C*t\n"
    "Q_a = (B - C)*t + C\n"
    "K_a = B*tb + D*t\n"
    "N_a = A*tb^2 + 2*C*tb*t + B*t^2\n"
    "J_a = C*tb^2 + 2*B*tb*t + D*t^2\n"
    "ABT = -t^2/tb^2\n"
    "T_m = divide(A, B, ABT)\n"
    "T_a = (A*tb^2 - B*t^2)/(1 - 2*t)\n"
    "S_a = (C*tb^2 - D*t^2)/(1 - 2*t)\n"
    "R_a = (A*tb^3 - B*t^2*tb + C*tb^2*t - D*t^3)/(1 - 2*t)\n"
    "p_j = 2*t - 1\n"
    "q_j = tb/t\n"
    "J_snt = (S - T)*p_j + (N - T)*q_j + T\n"
    "J_p = Q + (S - Q)*p_j\n"
    "J_q = R + (N - R)*q_j\n"
    "lam = q_j/(p_j + q_j)\n"
    "pq = p_j + q_j\n"
    "mu_T = ABT/(1 + ABT)\n"
    "M_l = S*(1 - lam) + N*lam\n"
    "M_t = S*t*(2*t - 1)/(2*t^2 - 2*t + 1) + N*tb/(2*t^2 - 2*t + 1)\n"
    "M_a = (A*tb^3 + B*t^2*tb + C*tb^2*t + D*t^3)/(2*t^2 - 2*t + 1)\n"
    "M_half_a = (A + B + C + D)/4\n"
    "M_CB_a = (A*tb^3 + B*t*tb + D*t^3)/(2*t^2 - 2*t + 1)\n"
    "M_DA_a = (A*(1 - 3*t*tb) + B*t^2*tb + C*tb^2*t)/(2*t^2 - 2*t + 1)\n"
    "dM_a = ((-2*t^4 + 4*t^3 - 3*t^2 + 2*t - 1)*A"
    " + (-2*t^4 + 4*t^3 - 5*t^2 + 2*t)*B"
    " + (2*t^4 - 4*t^3 + 5*t^2 - 4*t + 1)*C"
    " + (2*t^4 - 4*t^3 + 3*t^2)*D)/(2*t^2 - 2*t + 1)^2\n"
    "d2M_a = ((-4*t^3 + 6*t - 2)*A + (4*t^3 - 6*t + 2)*B"
    " + (-4*t^3 + 12*t^2 - 6*t)*C + (4*t^3 - 12*t^2 + 6*t)*D)"
    "/(2*t^2 - 2*t + 1)^3\n";

static Derived *derive_desargues(int keep)
{
    size_t len;
    char *src = slurp("examples/desargues_arc.pcs", &len);
    assert_true(len > 0);
    char *text = malloc(len + sizeof article);
    memcpy(text, src, len);
    memcpy(text + len, article, sizeof article);
    char *err = NULL;
    Derived *d = derive_text(text, keep, &err);
    if (!d)
        fail_msg("%s", err);
    free(err);
    free(text);
    free(src);
    return d;
}

static void test_steps_desargues_match_article(void **state)
{
    (void)state;
    Derived *d = derive_desargues(1);
    const Ring *r = &d->ring;
    /* one step per definition, in source order */
    static const char *const order[] = {"P", "Q", "K", "N",      "J",   "T",
                                        "S", "R", "M", "M_half", "M_CB"};
    for (size_t i = 0; i < sizeof order / sizeof order[0]; i++)
        assert_string_equal(d->steps[i].value.name, order[i]);
    assert_int_equal(d->nsteps, 15 + 27);
    assert_int_equal(step(d, "P")->op, STEP_ALONG);
    assert_int_equal(step(d, "T")->op, STEP_MEET);
    assert_int_equal(step(d, "T")->value.line, 40);
    assert_string_equal(step(d, "T")->expr, "meet(line(P, Q), line(A, B))");
    assert_int_equal(step(d, "tb")->op, STEP_EXPR);

    same_point(d, "P", "P_a");
    same_point(d, "Q", "Q_a");
    same_point(d, "K", "K_a");
    same_point(d, "N", "N_a");
    same_point(d, "J", "J_a");
    same_point(d, "J", "J_snt");
    same_point(d, "T", "T_a");
    same_point(d, "T", "T_m");
    same_point(d, "S", "S_a");
    same_point(d, "R", "R_a");
    same_point(d, "M", "M_l");
    same_point(d, "M", "M_t");
    same_point(d, "M", "M_a");
    /* the article's ratios p_j = (J - Q)/(S - Q), q_j = (J - R)/(N - R) */
    same_point(d, "J", "J_p");
    same_point(d, "J", "J_q");
    /* subst and diff: the special cases and derivatives it prints */
    same_point(d, "M_half", "M_half_a");
    same_point(d, "M_CB", "M_CB_a");
    same_point(d, "M_DA", "M_DA_a");
    same_point(d, "dM", "dM_a");
    same_point(d, "d2M", "d2M_a");
    assert_int_equal(step(d, "dM")->op, STEP_DIFF);
    assert_int_equal(step(d, "d2M")->order, 2);
    assert_int_equal(step(d, "M_CB")->op, STEP_SUBST);
    scalar_is(d, step(d, "M_half")->scalar, "1/2");

    /* along: its points and ratio */
    const DerivedStep *n = step(d, "N");
    assert_int_equal(n->nargs, 2);
    assert_string_equal(n->args[0].name, "P");
    assert_string_equal(n->args[1].name, "Q");
    assert_true(pteq_equal(n->args[0].eq, step(d, "P")->value.eq, r));
    scalar_is(d, n->scalar, "t");

    /* M = SN x TJ as the article solves it: J in the simplex S, N, T */
    const DerivedStep *m = step(d, "M");
    assert_true(m->has_sv);
    assert_int_equal(m->nargs, 4);
    assert_int_equal(m->sv_w, 3);
    assert_string_equal(m->args[m->sv_w].name, "J");
    assert_string_equal(m->args[0].name, "S");
    assert_string_equal(m->args[1].name, "N");
    assert_string_equal(m->args[2].name, "T");
    same_scalar(d, m->sv_coord, "p_j");
    same_scalar(d, m->sv_coord + 1, "q_j");
    same_scalar(d, m->params, "lam");
    same_scalar(d, m->det, "pq");
    scalar_is(d, m->params, "(1-t)/(2*t^2-2*t+1)");
    scalar_is(d, m->det, "(2*t^2-2*t+1)/t");
    scalar_is(d, m->params + 1, "t/(2*t^2-2*t+1)"); /* mu along TJ */

    /* T: on AB at the Menelaus ratio, mu = ABT/(1 + ABT); on PQ at
     * t/(2t - 1); parallel at t = 1/2 */
    const DerivedStep *t = step(d, "T");
    same_scalar(d, t->params + 1, "mu_T");
    scalar_is(d, t->params, "t/(2*t-1)");
    scalar_is(d, t->det, "(2*t-1)/t^2");
    const DerivedStep *s = step(d, "S");
    scalar_is(d, s->params, "t/(2*t-1)");
    scalar_is(d, s->params + 1, "t^2/(2*t-1)");

    assert_int_equal(check_meets(d), 3);
    derived_free(d);
}

/* a step's point equation differs from a wrong form: the comparison can
 * fail (the article's T with A and B swapped) */
static void test_steps_compare_can_fail(void **state)
{
    (void)state;
    static const char text[] = "point A, B, C, D\nparam t\n"
                               "P = along(A, C, t)\nQ = along(C, B, t)\n"
                               "T = meet(line(P, Q), line(A, B))\n"
                               "T_w = (B*(1-t)^2 - A*t^2)/(1 - 2*t)\n";
    Derived *d = derive_text(text, 1, NULL);
    assert_non_null(d);
    assert_false(
        pteq_equal(step(d, "T")->value.eq, step(d, "T_w")->value.eq, &d->ring));
    derived_free(d);
}

/* line and plane: the V-theorem (4 x 4 determinant) */
static void test_steps_v_theorem(void **state)
{
    (void)state;
    static const char text[] = "point A, B, C, D\nparam t\n"
                               "P = along(A, C, t)\nK = along(B, D, 1 - t)\n"
                               "X = meet(line(P, K), plane(A, B, (C + D)/2))\n"
                               "Y = meet(line(A, C), plane(B, D, P))\n";
    Derived *d = derive_text(text, 1, NULL);
    assert_non_null(d);
    const DerivedStep *x = step(d, "X");
    assert_int_equal(x->nargs, 5);
    assert_int_equal(x->nparams, 3);
    scalar_is(d, x->params, "t");
    assert_string_equal(x->args[4].name, "(C + D)/2");
    assert_int_equal(check_meets(d), 2);
    /* the plane through P meets AC in P: lambda = t */
    scalar_is(d, step(d, "Y")->params, "t");
    FILE *null = fopen("/dev/null", "w");
    steps_print(null, d, FMT_TEXT, -1);
    steps_print(null, d, FMT_LATEX, -1);
    steps_print(null, d, FMT_JSON, -1);
    fclose(null);
    derived_free(d);
}

/* subst and diff of points and scalars */
static void test_steps_subst_diff(void **state)
{
    (void)state;
    static const char text[] = "point A, B\nparam t, u\n"
                               "x = t^2*u\n"
                               "y = diff(x, t)\n"
                               "z = diff(x, t, 2)\n"
                               "w = subst(x, u, t + 1)\n"
                               "P = along(A, B, x)\n"
                               "Q = subst(P, A, B)\n"
                               "V = diff(P, t)\n"
                               "H = subst(P, t, 1/2)\n";
    Derived *d = derive_text(text, 1, NULL);
    assert_non_null(d);
    assert_int_equal(d->nsteps, 8);
    const DerivedStep *y = step(d, "y"), *z = step(d, "z");
    assert_int_equal(y->op, STEP_DIFF);
    assert_string_equal(y->var, "t");
    assert_int_equal(y->order, 1);
    scalar_is(d, y->value.scalar, "2*t*u");
    assert_int_equal(z->order, 2);
    scalar_is(d, z->value.scalar, "2*u");
    const DerivedStep *w = step(d, "w");
    assert_int_equal(w->op, STEP_SUBST);
    assert_string_equal(w->var, "u");
    assert_int_equal(w->nargs, 0);
    scalar_is(d, w->scalar, "t+1");
    scalar_is(d, w->value.scalar, "t^3+t^2");
    const DerivedStep *q = step(d, "Q");
    assert_int_equal(q->op, STEP_SUBST);
    assert_string_equal(q->var, "A");
    assert_int_equal(q->nargs, 1);
    assert_string_equal(q->args[0].name, "B");
    assert_int_equal(q->value.kind, KIND_POINT);
    assert_int_equal(q->value.eq->len, 1); /* B */
    const DerivedStep *v = step(d, "V");
    assert_int_equal(v->value.kind, KIND_VECTOR);
    assert_int_equal(v->value.eq->len, 2);
    scalar_is(d, &v->value.w[1], "2*t*u"); /* B */
    scalar_is(d, &v->value.w[0], "-2*t*u");
    const DerivedStep *h = step(d, "H");
    scalar_is(d, h->scalar, "1/2");
    scalar_is(d, &h->value.w[1], "u/4");
    /* the printed forms */
    char *out = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&out, &len);
    steps_print(f, d, FMT_TEXT, -1);
    fclose(f);
    assert_non_null(strstr(out, "y = diff(x, t)  =  2*t*u\n"));
    assert_non_null(strstr(out, "Q = subst(P, A, B)  =  B\n"));
    assert_non_null(strstr(out, "    (vector)\n"));
    free(out);
    derived_free(d);
}

/* solve: the unknowns are steps, and earlier definitions show the solution */
static void test_steps_solve(void **state)
{
    (void)state;
    static const char text[] = "point A, B\nparam t\nunknown C\n"
                               "X = along(A, C, t)\n"
                               "solve subst(X, t, 1/2) = B for C\n"
                               "output X\n";
    Derived *d = derive_text(text, 1, NULL);
    assert_non_null(d);
    assert_int_equal(d->nsteps, 2);
    const DerivedStep *c = step(d, "C"), *x = step(d, "X");
    assert_int_equal(c->op, STEP_SOLVE);
    assert_string_equal(c->expr, "solve subst(X, t, 1/2) = B for C");
    scalar_is(d, &c->value.w[0], "-1"); /* C = 2B - A */
    scalar_is(d, &c->value.w[1], "2");
    assert_false(x->pending);
    assert_true(pteq_equal(x->value.eq, d->outputs[0].eq, &d->ring));
    assert_true(pteq_equal(x->args[1].eq, c->value.eq, &d->ring));
    derived_free(d);
}

/* an unknown that no solve determines, in a definition no output uses */
static void test_steps_pending(void **state)
{
    (void)state;
    static const char text[] = "point A, B\nunknown X\n"
                               "Y = along(A, X, 1/2)\n"
                               "Z = along(A, B, 1/2)\noutput Z\n";
    char *err = NULL;
    Derived *d = derive_text(text, 1, &err);
    if (!d) { /* sema may refuse an unknown without solve: then no steps */
        assert_true(strlen(err) > 0);
        free(err);
        return;
    }
    free(err);
    assert_true(step(d, "Y")->pending);
    assert_false(step(d, "Z")->pending);
    char *out = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&out, &len);
    steps_print(f, d, FMT_TEXT, -1);
    steps_print(f, d, FMT_LATEX, -1);
    steps_print(f, d, FMT_JSON, -1);
    fclose(f);
    assert_non_null(strstr(out, "no solve determines"));
    assert_non_null(strstr(out, "\"pending\": true"));
    free(out);
    derived_free(d);
}

/* parallel lines: the same error with steps on as off, no Derived */
static void test_steps_parallel_error(void **state)
{
    (void)state;
    static const char text[] = "point A, B, C\n"
                               "P = meet(line(A, B), line(C, C + B - A))\n";
    char *e0 = NULL, *e1 = NULL;
    assert_null(derive_text(text, 0, &e0));
    assert_null(derive_text(text, 1, &e1));
    assert_string_equal(e0, e1);
    assert_non_null(strstr(e1, "s.pcs:2:5: error: lines in meet() are "
                               "parallel: no intersection"));
    free(e0);
    free(e1);
}

static char *print_derived(const Derived *d, FormatStyle st)
{
    char *out = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&out, &len);
    format_derived(f, d, st, -1);
    fclose(f);
    return out;
}

/* keeping steps changes no output; without it there are none */
static void test_steps_off_changes_nothing(void **state)
{
    (void)state;
    Derived *d0 = derive_desargues(0), *d1 = derive_desargues(1);
    assert_int_equal(d0->nsteps, 0);
    assert_null(d0->steps);
    assert_true(d1->nsteps > 0);
    for (int st = FMT_TEXT; st <= FMT_JSON; st++) {
        char *a = print_derived(d0, (FormatStyle)st);
        char *b = print_derived(d1, (FormatStyle)st);
        assert_string_equal(a, b);
        free(a);
        free(b);
    }
    derived_free(d1);
    derived_free(d0);
}

/* the printed steps of the Desargues arc, text, LaTeX and JSON */
static void test_steps_print_desargues(void **state)
{
    (void)state;
    Derived *d = derive_desargues(1);
    char *out = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&out, &len);
    steps_print(f, d, FMT_TEXT, -1);
    fclose(f);
    assert_non_null(strstr(out, "P = along(A, C, t)  =  A*(1 - t) + C*t\n"));
    assert_non_null(strstr(out, "M = meet(line(S, N), line(T, J))\n"
                                "    S-theorem in the simplex S, N, T:  "
                                "J = a*S + b*N + c*T\n"));
    assert_non_null(strstr(out, "lambda = b/(a + b) = "));
    assert_non_null(strstr(out, "(zero: the lines are parallel)"));
    free(out);
    f = open_memstream(&out, &len);
    steps_print(f, d, FMT_LATEX, -1);
    fclose(f);
    assert_non_null(strstr(out, "\\begin{align*}\n"));
    assert_non_null(strstr(out, "\\begin{vmatrix} a & b & c \\\\ 1 - "
                                "\\lambda & \\lambda & 0 \\\\ 0 & 0 & 1 "
                                "\\end{vmatrix}"));
    assert_non_null(strstr(out, "M_{CB} &= \\texttt{subst(M, C, B)}"));
    assert_non_null(strstr(out, "\\end{align*}\n"));
    free(out);
    f = open_memstream(&out, &len);
    steps_print(f, d, FMT_JSON, -1);
    fclose(f);
    char *plain = print_derived(d, FMT_JSON);
    /* derive's object, with "steps" before its closing brace */
    size_t n = strlen(plain);
    assert_true(n > 3 && strncmp(out, plain, n - 3) == 0);
    assert_non_null(strstr(out, ",\n \"steps\": [{\"name\": \"P\", \"line\": "
                                "16, \"op\": \"along\""));
    assert_non_null(strstr(out, "\"lambda\": \"(1-t)/(2*t^2-2*t+1)\""));
    assert_string_equal(out + strlen(out) - 3, "]}\n");
    free(plain);
    free(out);
    derived_free(d);
}

/* ---- robustness -----------------------------------------------------------
 */

static uint64_t rng = 1;

static uint32_t rnd(uint32_t n)
{
    rng ^= rng >> 12; /* xorshift64* */
    rng ^= rng << 25;
    rng ^= rng >> 27;
    return (uint32_t)((rng * 2685821657736338717ULL) >> 33) % n;
}

/* a derivation with steps, printed three ways: success XOR errors */
static int probe_steps(const char *buf, size_t len)
{
    DeriveOptions opt = {.max_seconds = 10, .keep_steps = 1};
    int nerr = -1;
    Derived *d = derive_source_ex("m.pcs", buf, len, NULL, &nerr, &opt);
    int ok = (d != NULL) == (nerr == 0);
    if (d) {
        char *out = NULL;
        size_t n = 0;
        FILE *f = open_memstream(&out, &n);
        steps_print(f, d, FMT_TEXT, -1);
        steps_print(f, d, FMT_LATEX, -1);
        steps_print(f, d, FMT_JSON, -1);
        if (d->npoints > 0)
            steps_print(f, d, FMT_TEXT, 0);
        fclose(f);
        free(out);
        ok = ok && d->nsteps > 0;
    }
    derived_free(d);
    return ok;
}

/* seeded mutations of schemes with meets, solves, directions, subst and
 * diff: no crash, no leak, success exactly when there is no error */
static void test_steps_mutations_never_crash(void **state)
{
    (void)state;
    static const char *const files[] = {
        "examples/desargues_arc.pcs", "examples/parabola_improper_point.pcs",
        "examples/curve_3d_one_ratio.pcs", "examples/interpolation_bezier.pcs",
        "examples/ellipse_central_angle.pcs"};
    static const char *const tokens[] = {
        "(",     ")",        ",",      "=",      "+",      "-",       "*",
        "/",     "^",        "\n",     "0",      "1",      "t",       "A",
        "B",     "meet(",    "line(",  "plane(", "along(", "divide(", "subst(",
        "diff(", "unknown ", "solve ", " for ",  "1/2",    "A - B",   "sin("};
    const char *env = getenv("PC_FUZZ_MUTATIONS");
    int muts = env ? atoi(env) / 5 + 1 : 300;
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        size_t len;
        char *text = slurp(files[i], &len);
        assert_true(probe_steps(text, len));
        rng = 0x9e3779b97f4a7c15ULL ^ (uint64_t)len;
        char *b = malloc(len * 2 + 64);
        for (int m = 0; m < muts; m++) {
            size_t n = len, cap = len * 2 + 64;
            memcpy(b, text, len);
            for (int e = 1 + (int)rnd(3); e > 0; e--) {
                size_t at = n ? rnd((uint32_t)n) : 0;
                if (rnd(3) == 0 && n) { /* delete a short range */
                    size_t l = 1 + rnd(6);
                    l = at + l > n ? n - at : l;
                    memmove(b + at, b + at + l, n - at - l);
                    n -= l;
                } else { /* insert a token */
                    const char *t = tokens[rnd(sizeof tokens / sizeof *tokens)];
                    size_t l = strlen(t);
                    if (n + l >= cap)
                        continue;
                    memmove(b + at + l, b + at, n - at);
                    memcpy(b + at, t, l);
                    n += l;
                }
            }
            if (!probe_steps(b, n))
                fail_msg("%s: inconsistent result for\n%.*s", files[i], (int)n,
                         b);
        }
        free(b);
        free(text);
    }
}

/* ---- the command line ---------------------------------------------------- */

typedef struct Run {
    int rc;
    char *out, *err;
} Run;

static Run run(const char *args)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "%s %s >%s/out 2>%s/err", bin, args, tmpdir,
             tmpdir);
    int st = system(cmd);
    Run r;
    r.rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    snprintf(cmd, sizeof cmd, "%s/out", tmpdir);
    r.out = slurp(cmd, NULL);
    snprintf(cmd, sizeof cmd, "%s/err", tmpdir);
    r.err = slurp(cmd, NULL);
    return r;
}

static void run_free(Run *r)
{
    free(r->out);
    free(r->err);
}

static void test_steps_cli(void **state)
{
    (void)state;
    Run plain = run("derive examples/desargues_arc.pcs");
    Run steps = run("derive examples/desargues_arc.pcs --steps");
    assert_int_equal(plain.rc, 0);
    assert_int_equal(steps.rc, 0);
    assert_string_equal(steps.err, "");
    /* the steps, a blank line, then derive's own output */
    size_t np = strlen(plain.out), ns = strlen(steps.out);
    assert_true(ns > np + 1);
    assert_string_equal(steps.out + ns - np, plain.out);
    assert_int_equal(steps.out[ns - np - 1], '\n');
    assert_non_null(strstr(steps.out, "T = meet(line(P, Q), line(A, B))\n"));
    run_free(&steps);
    run_free(&plain);

    Run tex = run("derive --steps --format latex examples/desargues_arc.pcs");
    assert_int_equal(tex.rc, 0);
    assert_non_null(strstr(tex.out, "\\end{align*}\n"));
    run_free(&tex);
    Run json = run("derive examples/desargues_arc.pcs --format json --steps");
    assert_int_equal(json.rc, 0);
    assert_non_null(strstr(json.out, "\"steps\": ["));
    run_free(&json);

    /* an error: nothing on stdout, exit 1 */
    char path[128];
    snprintf(path, sizeof path, "%s/bad.pcs", tmpdir);
    FILE *f = fopen(path, "w");
    fputs("point A, B, C\nP = meet(line(A, B), line(C, C + B - A))\n", f);
    fclose(f);
    char args[256];
    snprintf(args, sizeof args, "derive --steps %s", path);
    Run bad = run(args);
    assert_int_equal(bad.rc, 1);
    assert_string_equal(bad.out, "");
    assert_non_null(strstr(bad.err, "lines in meet() are parallel"));
    run_free(&bad);

    Run help = run("derive --help");
    assert_non_null(strstr(help.out, "--steps"));
    run_free(&help);
}

static int setup(void **state)
{
    (void)state;
    bin = getenv("PC_BIN");
    if (!bin)
        bin = "build/pointcalc";
    strcpy(tmpdir, "/tmp/pc_steps_XXXXXX");
    return mkdtemp(tmpdir) ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    int rc = system(cmd);
    flint_cleanup_master();
    return rc;
}

/* --steps LaTeX within the page (latexbreak.h): the square of the
 * composite-curve text, whose source line and value are each wider than
 * the page, continues its row under the alignment point ("&\qquad"),
 * every line balanced and within the width */
static void test_steps_latex_rows_fit(void **state)
{
    (void)state;
    Derived *d = derive_text("point O, A, B, C\nparam t\n"
                             "R = O + (A - O)*(1 + abs(t) - abs(t - 1))/2"
                             " + (B - A)*(1 + abs(t - 1) - abs(t - 2))/2"
                             " + (C - B)*(1 + abs(t - 2) - abs(t - 3))/2"
                             " + (O - C)*(1 + abs(t - 3) - abs(t - 4))/2\n",
                             1, NULL);
    assert_non_null(d);
    char *out = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&out, &len);
    steps_print(f, d, FMT_LATEX, -1);
    fclose(f);
    assert_non_null(strstr(out, "  R &= \\texttt{O + (A - O)*"));
    assert_non_null(strstr(out, " \\\\\n  &\\qquad \\texttt{"));
    assert_non_null(strstr(out, " \\\\\n  &\\qquad = \\frac{1}{2} \\Bigl( "));
    int lines = 0;
    for (char *p = out, *e; (e = strchr(p, '\n')); p = e + 1, lines++) {
        size_t n = (size_t)(e - p);
        assert_true(latex_width(p, n) <= LATEX_LINE_UNITS + 4);
        int lr = 0;
        for (char *q = p; q < e; q++) {
            if (strncmp(q, "\\left", 5) == 0)
                lr++;
            else if (strncmp(q, "\\right", 6) == 0)
                lr--;
        }
        assert_int_equal(lr, 0);
    }
    assert_true(lines > 8);
    free(out);
    derived_free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_steps_desargues_match_article),
        cmocka_unit_test(test_steps_compare_can_fail),
        cmocka_unit_test(test_steps_v_theorem),
        cmocka_unit_test(test_steps_meet_identities_examples),
        cmocka_unit_test(test_steps_subst_diff),
        cmocka_unit_test(test_steps_solve),
        cmocka_unit_test(test_steps_pending),
        cmocka_unit_test(test_steps_parallel_error),
        cmocka_unit_test(test_steps_off_changes_nothing),
        cmocka_unit_test(test_steps_mutations_never_crash),
        cmocka_unit_test(test_steps_print_desargues),
        cmocka_unit_test(test_steps_cli),
        cmocka_unit_test(test_steps_latex_rows_fit),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
