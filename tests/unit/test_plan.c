/*
 * test_plan.c - the Plan builder and the interpreter, without FLINT:
 * hash-consing, folding, shared powers, uniformity, pruning, the dump, and
 * plan_eval against direct evaluation (seeded random DAGs, poles, blocks,
 * every dimension).
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

#include "runtime/eval.h"
#include "runtime/plan.h"

static const char *const params[] = {"t", "u"};
static const char *const consts[] = {"k"};
static const char *const points[] = {"A", "B", "C"};

static Plan *new_plan(void)
{
    return plan_new("p", 2, params, 1, consts, 3, points);
}

static void test_plan_node_hash_conses_and_commutes(void **state)
{
    (void)state;
    Plan *p = new_plan();
    int t = plan_input(p, 0), u = plan_input(p, 1);
    assert_int_equal(plan_input(p, 0), t);
    int a = plan_add(p, t, u);
    assert_int_equal(plan_add(p, u, t), a);
    assert_int_equal(plan_mul(p, t, u), plan_mul(p, u, t));
    assert_int_not_equal(plan_sub(p, t, u), plan_sub(p, u, t));
    assert_int_equal(plan_const(p, 2.5), plan_const(p, 2.5));
    assert_int_equal(plan_const(p, 0.0), plan_const(p, -0.0));
    int n = p->nins;
    plan_add(p, u, t);
    assert_int_equal(p->nins, n); // nothing new
    plan_free(p);
}

static void test_plan_node_folds_and_simplifies(void **state)
{
    (void)state;
    Plan *p = new_plan();
    int t = plan_input(p, 0);
    int two = plan_const(p, 2), three = plan_const(p, 3);
    int five = plan_add(p, two, three);
    assert_int_equal(p->ins[five].op, PLAN_CONST);
    assert_true(p->k[p->ins[five].a] == 5);
    assert_int_equal(plan_mul(p, t, plan_const(p, 1)), t);
    assert_int_equal(plan_add(p, plan_const(p, 0), t), t);
    assert_int_equal(plan_neg(p, plan_neg(p, t)), t);
    int s = plan_add(p, t, plan_neg(p, three));
    assert_int_equal(p->ins[s].op, PLAN_SUB);
    assert_int_equal(plan_add(p, t, plan_const(p, -3)), s);
    assert_int_equal(plan_sub(p, t, plan_const(p, -2)), plan_add(p, t, two));
    int pole = plan_pole(p, plan_const(p, 0));
    assert_true(p->k[p->ins[pole].a] == 1);
    plan_free(p);
}

static void test_plan_pow_shares_chains(void **state)
{
    (void)state;
    Plan *p = new_plan();
    int t = plan_input(p, 0);
    int t2 = plan_pow(p, t, 2);
    int t4 = plan_pow(p, t, 4);
    assert_int_equal(p->ins[t4].op, PLAN_MUL);
    assert_int_equal(p->ins[t4].a, t2);
    assert_int_equal(p->ins[t4].b, t2);
    int t3 = plan_pow(p, t, 3);
    assert_true(p->ins[t3].a == t2 || p->ins[t3].b == t2);
    /* up to PLAN_POW_CHAIN a chain: t^20 = (t^10)^2, t^10 = (t^5)^2 */
    int t20 = plan_pow(p, t, 20);
    int t10 = plan_pow(p, t, 10);
    assert_int_equal(p->ins[t20].op, PLAN_MUL);
    assert_int_equal(p->ins[t20].a, t10);
    assert_int_equal(p->ins[t20].b, t10);
    int big = plan_pow(p, t, PLAN_POW_CHAIN + 1);
    assert_int_equal(p->ins[big].op, PLAN_POWI);
    assert_int_equal(p->ins[big].b, PLAN_POW_CHAIN + 1);
    assert_int_equal(plan_pow(p, t, 1), t);
    plan_free(p);
}

static void test_plan_uniform_and_prune(void **state)
{
    (void)state;
    Plan *p = new_plan();
    int t = plan_input(p, 0), k = plan_input(p, 2);
    int kk = plan_mul(p, k, k);
    assert_true(p->ins[kk].uniform);
    assert_false(p->ins[t].uniform);
    int dead = plan_mul(p, t, plan_input(p, 1));
    (void)dead;
    int kkt = plan_mul(p, kk, t);
    int c1 = plan_const(p, 1);
    int w = plan_add(p, kkt, c1);
    int one = plan_sub(p, c1, w);
    int pt[2] = {0, 1}, rg[2] = {one, w};
    plan_add_output(p, "M", KIND_POINT, 4, 2, pt, rg, -1);
    int before = p->nins;
    plan_prune(p);
    assert_true(p->nins < before);
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    plan_dump(m, p);
    fclose(m);
    assert_string_equal(text, "plan p: params t u; consts k; points A B C;\n"
                              "  r0 = input t  # line 0\n"
                              "  r1 = input k uniform  # line 0\n"
                              "  r2 = mul r1 r1 uniform  # line 0\n"
                              "  r3 = mul r0 r2  # line 0\n"
                              "  r4 = const 1 uniform  # line 0\n"
                              "  r5 = add r3 r4  # line 0\n"
                              "  r6 = sub r4 r5  # line 0\n"
                              "  output M point line 4: A=r6 B=r5\n");
    free(text);
    plan_free(p);
}

/* M = A*(1 - w) + B*w, w = t/(t - k): pole at t = k */
static void test_plan_eval_poles_blocks_dims(void **state)
{
    (void)state;
    Plan *p = new_plan();
    int t = plan_input(p, 0), k = plan_input(p, 2);
    int den = plan_sub(p, t, k);
    int bad = plan_pole(p, den);
    int w = plan_div(p, t, den);
    int v = plan_sub(p, plan_const(p, 1), w);
    int pt[2] = {0, 1}, rg[2] = {v, w};
    plan_add_output(p, "M", KIND_POINT, 1, 2, pt, rg, bad);
    int sl[1] = {-1}, sr[1] = {w};
    plan_add_output(p, "w", KIND_SCALAR, 2, 1, sl, sr, bad);
    const size_t n = 1000; // several blocks and a tail
    double *tv = malloc(sizeof *tv * n), *uv = calloc(n, sizeof *uv);
    for (size_t i = 0; i < n; i++)
        tv[i] = -2 + 4.0 * (double)i / 999; // hits t = k below?
    double kval = tv[500];                  // yes: exactly one sample
    const double *prm[2] = {tv, uv};
    for (int dim = 1; dim <= 7; dim++) {
        double A[7], B[7];
        for (int c = 0; c < dim; c++) {
            A[c] = c + 1;
            B[c] = -2.5 * c;
        }
        const double *pts[3] = {A, B, NULL}; // C unused: may be NULL
        double *out = malloc(sizeof *out * n * (size_t)dim);
        unsigned char *st = malloc(n);
        size_t nb = plan_eval(p, 0, n, prm, &kval, pts, dim, out, st);
        assert_int_equal(nb, 1);
        for (size_t i = 0; i < n; i++) {
            assert_int_equal(st[i], i == 500);
            double ww = tv[i] / (tv[i] - kval);
            for (int c = 0; c < dim; c++) {
                double got = out[i * (size_t)dim + (size_t)c];
                if (i == 500)
                    assert_true(isnan(got));
                else
                    assert_true(got == (1 - ww) * A[c] + ww * B[c]);
            }
        }
        free(st);
        free(out);
    }
    double *sv = malloc(sizeof *sv * n);
    assert_int_equal(plan_eval(p, 1, n, prm, &kval, NULL, 0, sv, NULL), 1);
    assert_true(isnan(sv[500]));
    assert_true(sv[3] == tv[3] / (tv[3] - kval));
    assert_int_equal(plan_output_uses_point(p, 0, 1), 1);
    assert_int_equal(plan_output_uses_point(p, 0, 2), 0);
    free(sv);
    free(uv);
    free(tv);
    plan_free(p);
}

/* ---- random DAGs: plan_eval == direct evaluation ------------------------ */

typedef struct Node {
    int op, a, b; // op: 0 input t, 1 input u, 2 input k, 3 const, 4.. ops
    double c;
} Node;

static double direct(const Node *g, int i, const double *in)
{
    const Node *x = &g[i];
    switch (x->op) {
    case 0:
    case 1:
    case 2:
        return in[x->op];
    case 3:
        return x->c;
    case 4:
        return direct(g, x->a, in) + direct(g, x->b, in);
    case 5:
        return direct(g, x->a, in) - direct(g, x->b, in);
    case 6:
        return direct(g, x->a, in) * direct(g, x->b, in);
    case 7: { // a / (1 + b^2): never a pole
        double b = direct(g, x->b, in);
        return direct(g, x->a, in) / (1 + b * b);
    }
    case 8:
        return -direct(g, x->a, in);
    default: {
        double r = 1, v = direct(g, x->a, in);
        for (int e = 0; e < x->b; e++)
            r *= v;
        return r;
    }
    }
}

static unsigned long rng_state = 12345;
static unsigned rnd(unsigned n)
{
    rng_state = rng_state * 6364136223846793005ul + 1442695040888963407ul;
    return (unsigned)(rng_state >> 33) % n;
}

static void test_plan_eval_random_dags_match_direct(void **state)
{
    (void)state;
    enum { NODES = 40, TRIALS = 200, N = 300 };
    for (int trial = 0; trial < TRIALS; trial++) {
        Node g[NODES];
        int reg[NODES];
        Plan *p = new_plan();
        for (int i = 0; i < NODES; i++) {
            Node *x = &g[i];
            x->op = i < 3 ? i : i < 5 ? 3 : 4 + (int)rnd(6);
            x->a = i ? (int)rnd((unsigned)i) : 0;
            x->b = i ? (int)rnd((unsigned)i) : 0;
            x->c = (double)((int)rnd(17) - 8) / 4;
            if (x->op == 9)
                x->b = 2 + (int)rnd(3); // small powers: stay finite
            switch (x->op) {
            case 0:
            case 1:
            case 2:
                reg[i] = plan_input(p, x->op);
                break;
            case 3:
                reg[i] = plan_const(p, x->c);
                break;
            case 4:
                reg[i] = plan_add(p, reg[x->a], reg[x->b]);
                break;
            case 5:
                reg[i] = plan_sub(p, reg[x->a], reg[x->b]);
                break;
            case 6:
                reg[i] = plan_mul(p, reg[x->a], reg[x->b]);
                break;
            case 7: {
                int b2 = plan_mul(p, reg[x->b], reg[x->b]);
                reg[i] =
                    plan_div(p, reg[x->a], plan_add(p, plan_const(p, 1), b2));
                break;
            }
            case 8:
                reg[i] = plan_neg(p, reg[x->a]);
                break;
            default:
                reg[i] = plan_pow(p, reg[x->a], x->b);
            }
        }
        /* output: the last three nodes as weights of A, B, C */
        int pt[3] = {0, 1, 2};
        int rg[3] = {reg[NODES - 3], reg[NODES - 2], reg[NODES - 1]};
        plan_add_output(p, "M", KIND_POINT, 1, 3, pt, rg, -1);
        plan_prune(p);
        double tv[N], uv[N], kval = (double)((int)rnd(9) - 4) / 8;
        for (int i = 0; i < N; i++) {
            tv[i] = (double)((int)rnd(33) - 16) / 16;
            uv[i] = (double)((int)rnd(33) - 16) / 8;
        }
        const double *prm[2] = {tv, uv};
        double A[2] = {1, 0}, B[2] = {0, 1}, C[2] = {1, 1};
        const double *pts[3] = {A, B, C};
        double out[2 * N];
        assert_int_equal(plan_eval(p, 0, N, prm, &kval, pts, 2, out, NULL), 0);
        for (int i = 0; i < N; i++) {
            double in[3] = {tv[i], uv[i], kval};
            double wa = direct(g, NODES - 3, in), wb = direct(g, NODES - 2, in),
                   wc = direct(g, NODES - 1, in);
            double x = wa * A[0] + wb * B[0] + wc * C[0];
            double y = wa * A[1] + wb * B[1] + wc * C[1];
            double tol = 1e-12 * (fabs(wa) + fabs(wb) + 2 * fabs(wc) + 1e-300);
            if (!(fabs(out[2 * i] - x) <= tol &&
                  fabs(out[2 * i + 1] - y) <= tol)) {
                fprintf(stderr, "trial %d sample %d: %g,%g vs %g,%g\n", trial,
                        i, out[2 * i], out[2 * i + 1], x, y);
                fail();
            }
        }
        plan_free(p);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plan_node_hash_conses_and_commutes),
        cmocka_unit_test(test_plan_node_folds_and_simplifies),
        cmocka_unit_test(test_plan_pow_shares_chains),
        cmocka_unit_test(test_plan_uniform_and_prune),
        cmocka_unit_test(test_plan_eval_poles_blocks_dims),
        cmocka_unit_test(test_plan_eval_random_dags_match_direct),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
