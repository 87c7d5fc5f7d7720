/*
 * test_natural.c - curves in natural parametrization (runtime/natural.h):
 * the quadrature against Fresnel's integrals, circles and Simpson's rule;
 * the G1 clothoid fit over a sweep of 1000 random configurations (success,
 * iterations, end point, end angle), its symmetries and known solutions;
 * the quadratic and cubic laws' joints; the article's Hooke-Jeeves search;
 * the evaluation table; the chord rule.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "libpointcalc.h"
#include "runtime/natural.h"
#include "runtime/plan.h"
#include "runtime/plot.h"

static uint64_t rng_state = 0x2545f4914f6cdd1dULL;
static double rnd(void) // xorshift64*, [0, 1)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (double)((rng_state * 0x2545f4914f6cdd1dULL) >> 11) /
           9007199254740992.0;
}

static NatSegment law(double x0, double y0, double phi0, int deg,
                      const double *k, double S)
{
    NatSegment g = {x0, y0, phi0, {0}, deg, S};
    for (int j = 0; j <= deg; j++)
        g.k[j] = k[j];
    return g;
}

/* Fresnel's integrals C(x) = int_0^x cos(pi t^2 / 2), S(x) likewise (A&S
 * table 7.7 values), as the clothoid k(s) = pi s from the origin */
static void test_fresnel(void **state)
{
    (void)state;
    static const double v[][3] = {
        {1.0, 0.77989340037682282947, 0.43825914739035476608},
        {2.0, 0.48825340607534075450, 0.34341567836369824220},
        {3.5, 0.53257243502800084533, 0.41524801197243752390},
    };
    double k[2] = {0, NAT_PI};
    NatSegment g = law(0, 0, 0, 1, k, 4);
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
        double x, y;
        nat_point(&g, v[i][0], &x, &y);
        assert_true(fabs(x - v[i][1]) < 2e-15);
        assert_true(fabs(y - v[i][2]) < 2e-15);
    }
}

/* a circle (constant curvature) and a line, in closed form */
static void test_circle_line(void **state)
{
    (void)state;
    double k[1] = {2};
    NatSegment g = law(1, -1, 0.4, 0, k, 40);
    for (double s = 0; s <= 40; s += 3.7) {
        double x, y;
        nat_point(&g, s, &x, &y);
        /* the phase is known to its rounding, eps |phi|, at each node */
        double tol = 1e-16 * (1 + s) * (1 + 2 * s);
        assert_true(fabs(x - (1 + (sin(0.4 + 2 * s) - sin(0.4)) / 2)) < tol);
        assert_true(fabs(y - (-1 - (cos(0.4 + 2 * s) - cos(0.4)) / 2)) < tol);
    }
    double z[1] = {0}, x, y;
    NatSegment l = law(0, 0, 1, 0, z, 5);
    nat_point(&l, 5, &x, &y);
    assert_true(fabs(x - 5 * cos(1)) < 1e-15 && fabs(y - 5 * sin(1)) < 1e-15);
}

/* a cubic law against composite Simpson on 200000 intervals */
static void test_cubic_simpson(void **state)
{
    (void)state;
    double k[4] = {0.7, -3.1, 2.2, 1.9};
    NatSegment g = law(0, 0, -0.3, 3, k, 2.3);
    int n = 200000;
    double h = g.length / n, sx = 0, sy = 0;
    for (int i = 0; i <= n; i++) {
        double w = i == 0 || i == n ? 1 : i % 2 ? 4 : 2, p = nat_phi(&g, i * h);
        sx += w * cos(p), sy += w * sin(p);
    }
    double x, y;
    nat_point(&g, g.length, &x, &y);
    assert_true(fabs(x - sx * h / 3) < 1e-13);
    assert_true(fabs(y - sy * h / 3) < 1e-13);
    /* and phi, k, k' as the polynomials they are */
    assert_true(fabs(nat_phi(&g, 2) -
                     (-0.3 + 1.4 - 3.1 * 2 + 2.2 * 8 / 3 + 1.9 * 4)) < 1e-13);
    assert_true(fabs(nat_kappa(&g, 2) - (0.7 - 6.2 + 8.8 + 15.2)) < 1e-13);
    assert_true(fabs(nat_dkappa(&g, 2) - (-3.1 + 8.8 + 22.8)) < 1e-13);
}

static double angle_diff(double a, double b)
{
    return fabs(remainder(a - b, 2 * NAT_PI));
}

/* the sweep: unit chord, angles uniform in (-0.95 pi, 0.95 pi) */
static void test_g1_sweep(void **state)
{
    (void)state;
    int hist[8] = {0};
    double worst = 0;
    for (int i = 0; i < 1000; i++) {
        double t0 = (2 * rnd() - 1) * 0.95 * NAT_PI;
        double t1 = (2 * rnd() - 1) * 0.95 * NAT_PI;
        double rot = 2 * NAT_PI * rnd(), c = cos(rot), s = sin(rot);
        double x0 = 3 * rnd() - 1, y0 = 3 * rnd() - 1;
        NatSegment g;
        NatStats st;
        /* the chord turned by rot and moved: the same problem */
        assert_int_equal(
            nat_fit_g1(x0, y0, t0 + rot, x0 + c, y0 + s, t1 + rot, &g, &st), 0);
        assert_true(st.iterations <= 4);
        hist[st.iterations]++;
        assert_true(st.error <= 1e-12);
        worst = fmax(worst, st.error);
        assert_true(angle_diff(nat_phi(&g, g.length), t1 + rot) <= 1e-13);
        assert_true(g.length > 0);
    }
    /* "<= 4 iterations typical": most take 2 */
    assert_true(hist[2] > 600);
    assert_true(worst < 1e-13);
}

/* reflecting the configuration in the chord negates k (both
 * coefficients) and keeps S; reversing it gives k_rev(s) = -k(S - s) */
static void test_g1_symmetry(void **state)
{
    (void)state;
    for (int i = 0; i < 200; i++) {
        double t0 = (2 * rnd() - 1) * 0.9 * NAT_PI;
        double t1 = (2 * rnd() - 1) * 0.9 * NAT_PI, L = 0.5 + 2 * rnd();
        NatSegment g, m, r;
        assert_int_equal(nat_fit_g1(0, 0, t0, L, 0, t1, &g, NULL), 0);
        assert_int_equal(nat_fit_g1(0, 0, -t0, L, 0, -t1, &m, NULL), 0);
        assert_int_equal(
            nat_fit_g1(L, 0, t1 + NAT_PI, 0, 0, t0 + NAT_PI, &r, NULL), 0);
        double tol = 1e-12 * (1 + fabs(g.k[0]) + fabs(g.k[1]));
        assert_true(fabs(m.length - g.length) < 1e-12 * g.length);
        assert_true(fabs(m.k[0] + g.k[0]) < tol && fabs(m.k[1] + g.k[1]) < tol);
        assert_true(fabs(r.length - g.length) < 1e-12 * g.length);
        assert_true(fabs(r.k[1] - g.k[1]) < tol);
        assert_true(fabs(r.k[0] + nat_kappa(&g, g.length)) < tol);
    }
}

/* known solutions: the line, a circular arc (the minimal winding: the
 * short arc, not the long one) */
static void test_g1_known(void **state)
{
    (void)state;
    NatSegment g;
    assert_int_equal(nat_fit_g1(0, 0, 0, 2, 0, 0, &g, NULL), 0);
    assert_true(fabs(g.length - 2) < 1e-15 && fabs(g.k[0]) < 1e-15 &&
                fabs(g.k[1]) < 1e-15);
    for (double a = 0.1; a < 3.0; a += 0.3) { // chord 1, angles a and -a
        assert_int_equal(nat_fit_g1(0, 0, a, 1, 0, -a, &g, NULL), 0);
        double R = 1 / (2 * sin(a));
        assert_true(fabs(g.k[1]) < 1e-12);
        assert_true(fabs(g.k[0] + 1 / R) < 1e-12);
        assert_true(fabs(g.length - 2 * a * R) < 1e-12);
    }
    assert_int_equal(nat_fit_g1(1, 1, 0, 1, 1, 0, &g, NULL), -1);
    /* beyond double range: k1 ~ 1/chord^2 overflows; a failure, not an
     * infinite coefficient with a NaN end-point error */
    assert_int_equal(nat_fit_g1(0, 0, 0.3, 1e-300, 0, 0.5, &g, NULL), -1);
    assert_int_equal(nat_fit_g1(0, 0, 0.3, 1e300, 0, 0.5, &g, NULL), -1);
    /* an angle's winding is not the fit's: 7 is 7 - 2 pi */
    NatSegment h;
    assert_int_equal(nat_fit_g1(0, 0, 7, 1, 0, 0, &g, NULL), 0);
    assert_int_equal(nat_fit_g1(0, 0, 7 - 2 * NAT_PI, 1, 0, 0, &h, NULL), 0);
    assert_true(fabs(g.length - h.length) < 1e-14 &&
                fabs(g.k[1] - h.k[1]) < 1e-12);
}

/* the quadratic and cubic laws keep the start curvature (and its
 * derivative), reach the end point and the end angle exactly; the start
 * values within 0.5 of the clothoid's own, as at a composite's joints (far
 * from them, e.g. of the opposite sign, the segment must loop: the
 * continuation from the clothoid reports a failure, docs/natural.md) */
static void test_law_g2_g3(void **state)
{
    (void)state;
    for (int i = 0; i < 200; i++) {
        double t0 = (2 * rnd() - 1) * 0.6 * NAT_PI;
        double t1 = (2 * rnd() - 1) * 0.6 * NAT_PI;
        NatSegment q, c, g;
        NatStats sq, sc;
        assert_int_equal(nat_fit_g1(0, 0, t0, 1, 0, t1, &g, NULL), 0);
        double k0 = g.k[0] + rnd() - 0.5, dk0 = g.k[1] + rnd() - 0.5;
        assert_int_equal(
            nat_fit_law(NAT_QUADRATIC, 0, 0, t0, 1, 0, t1, k0, 0, &q, &sq), 0);
        assert_int_equal(q.degree, 2);
        assert_true(q.k[0] == k0);
        assert_true(sq.error <= 1e-12);
        assert_true(angle_diff(nat_phi(&q, q.length), t1) < 1e-12);
        assert_int_equal(
            nat_fit_law(NAT_CUBIC, 0, 0, t0, 1, 0, t1, k0, dk0, &c, &sc), 0);
        assert_true(c.k[0] == k0 && c.k[1] == dk0);
        assert_true(sc.error <= 1e-12);
        assert_true(angle_diff(nat_phi(&c, c.length), t1) < 1e-12);
    }
}

/* Errata N1/N2: the article's (14) as printed,
 *   a = 3/S ((phi2 - phi1)/S^2 - b S/2 - c),
 * misses the end angle by radians where the corrected form is exact */
static void test_erratum_14(void **state)
{
    (void)state;
    NatSegment q;
    assert_int_equal(
        nat_fit_law(NAT_QUADRATIC, 0, 0, 0.5, 1, 0, -0.5, 1.5, 0, &q, NULL), 0);
    double S = q.length, b = q.k[1], c = q.k[0], D = -1.0;
    double printed = 3 / S * (D / (S * S) - b * S / 2 - c);
    NatSegment p = q;
    p.k[2] = printed;
    assert_true(angle_diff(nat_phi(&q, S), -0.5) < 1e-13);
    assert_true(angle_diff(nat_phi(&p, S), -0.5) > 0.5);
}

/* the article's search finds the same clothoid, with far more integrals */
static void test_hooke_jeeves(void **state)
{
    (void)state;
    NatSegment h, n;
    NatStats sh, sn;
    assert_int_equal(
        nat_fit_hj(0, 0, 0.3, 1, 0.2, -0.4, 1e-12, 100000, &h, &sh), 0);
    assert_int_equal(nat_fit_g1(0, 0, 0.3, 1, 0.2, -0.4, &n, &sn), 0);
    assert_true(fabs(h.length - n.length) < 1e-9);
    assert_true(fabs(h.k[0] - n.k[0]) < 1e-8 && fabs(h.k[1] - n.k[1]) < 1e-8);
    assert_true(sh.integrals > 50 * sn.integrals);
    /* a budget too small: not reached, reported */
    assert_int_equal(nat_fit_hj(0, 0, 0.3, 1, 0.2, -0.4, 1e-12, 20, &h, &sh),
                     1);
    assert_true(sh.error > 1e-12);
}

/* the table agrees with the quadrature to 1e-14 of the length */
static void test_table(void **state)
{
    (void)state;
    for (int i = 0; i < 30; i++) {
        double k[4] = {8 * rnd() - 4, 8 * rnd() - 4, 6 * rnd() - 3,
                       4 * rnd() - 2};
        NatSegment g = law(rnd(), rnd(), 6 * rnd(), i % 4, k, 0.2 + 3 * rnd());
        NatTable t;
        assert_int_equal(nat_table_build(&t, &g), 0);
        for (int j = 0; j <= 97; j++) {
            double s = g.length * j / 97, x, y, u, v;
            nat_point(&g, s, &x, &y);
            nat_table_eval(&t, s, &u, &v);
            assert_true(hypot(x - u, y - v) < 1e-14 * fmax(1, g.length));
        }
        nat_table_free(&t);
    }
}

/* the chord rule is exact on a circle: points at equal arcs */
static void test_chord_rule(void **state)
{
    (void)state;
    NatPoint p[5];
    for (int i = 0; i < 5; i++) {
        double a = 0.3 + 0.4 * i;
        p[i] = (NatPoint){2 * cos(a), 2 * sin(a), 0, 0};
    }
    nat_chord_angles(p, 5);
    for (int i = 0; i < 5; i++)
        assert_true(angle_diff(p[i].th, 0.3 + 0.4 * i + NAT_PI / 2) < 1e-14);
    /* and the composite through them is that circle: k = 1/2 */
    NatCurve c;
    int bad;
    assert_int_equal(
        nat_composite(p, 5, &(NatChain){.law = NAT_LINEAR}, &c, &bad), 0);
    for (int i = 0; i < 4; i++) {
        assert_true(fabs(c.seg[i].k[0] - 0.5) < 1e-12 &&
                    fabs(c.seg[i].k[1]) < 1e-12);
        assert_true(fabs(c.seg[i].length - 0.8) < 1e-12);
    }
    nat_curve_free(&c);
}

/* composite G2 and G3 chains: the joints keep what the law promises */
static void test_composite_joints(void **state)
{
    (void)state;
    NatPoint p[5] = {{0, 0, 0.2, 1},
                     {1, 0.3, 0, 0},
                     {2, 0.1, 0, 0},
                     {3, -0.4, 0, 0},
                     {4, 0, 0.3, 1}};
    for (NatLaw l = NAT_LINEAR; l <= NAT_CUBIC; l++) {
        NatCurve c;
        int bad;
        NatPoint q[5];
        memcpy(q, p, sizeof q);
        assert_int_equal(nat_composite(q, 5, &(NatChain){.law = l}, &c, &bad),
                         0);
        assert_true(c.stats.error < 1e-12);
        for (int j = 0; j < 3; j++) {
            assert_true(fabs(c.joint[j].dphi) < 1e-13);
            if (l >= NAT_QUADRATIC)
                assert_true(fabs(c.joint[j].dk) < 1e-12);
            else
                assert_true(fabs(c.joint[j].dk) > 1e-3); // G1 only
            if (l == NAT_CUBIC)
                assert_true(fabs(c.joint[j].ddk) < 1e-12);
        }
        nat_curve_free(&c);
    }
}

/* the C library's entry points: the circle through five points, the
 * chord rule by flags, the errors */
static void test_api(void **state)
{
    (void)state;
    double pts[15];
    unsigned char given[5] = {0, 0, 0, 0, 0};
    for (int i = 0; i < 5; i++) {
        double a = 0.3 + 0.4 * i;
        pts[3 * i] = 2 * cos(a), pts[3 * i + 1] = 2 * sin(a),
                pts[3 * i + 2] = 99;
    }
    pc_natural_segment seg[4];
    int bad = 7;
    assert_int_equal(pc_natural_fit(pts, given, 5, PC_NATURAL_CUBIC, seg, &bad),
                     PC_OK);
    assert_int_equal(bad, -1);
    for (int i = 0; i < 4; i++) { // a circle: every law's k is 1/2
        assert_true(fabs(seg[i].k[0] - 0.5) < 1e-12);
        assert_true(fabs(seg[i].length - 0.8) < 1e-12);
        double xy[2];
        pc_natural_point(&seg[i], seg[i].length, xy);
        assert_true(hypot(xy[0] - pts[3 * i + 3], xy[1] - pts[3 * i + 4]) <
                    1e-12);
    }
    assert_int_equal(seg[0].degree, 1);
    assert_int_equal(seg[1].degree, 3);
    /* every angle given (has_angle NULL): 99 is taken as it is */
    assert_int_equal(pc_natural_fit(pts, NULL, 2, PC_NATURAL_LINEAR, seg, NULL),
                     PC_OK);
    assert_true(fabs(remainder(seg[0].phi0 - 99, 2 * NAT_PI)) < 1e-12);
    assert_int_equal(pc_natural_fit(pts, NULL, 1, PC_NATURAL_LINEAR, seg, NULL),
                     PC_EINVAL);
    assert_int_equal(pc_natural_fit(pts, NULL, 3, 4, seg, NULL), PC_EINVAL);
    double same[6] = {1, 1, 0, 1, 1, 0.5};
    assert_int_equal(
        pc_natural_fit(same, NULL, 2, PC_NATURAL_LINEAR, seg, NULL), PC_EINVAL);
    double nan6[6] = {0, 0, 0, NAN, 1, 0};
    assert_int_equal(
        pc_natural_fit(nan6, NULL, 2, PC_NATURAL_LINEAR, seg, NULL), PC_EINVAL);
    /* a zigzag the cubic law cannot follow from the G3 joint */
    double zig[15] = {0, 0, 0, 1, 1, 0, 2, -1, 0, 3, 1, 0, 4, 0, 0};
    unsigned char ends[5] = {1, 0, 0, 0, 1};
    assert_int_equal(pc_natural_fit(zig, ends, 5, PC_NATURAL_CUBIC, seg, &bad),
                     PC_ENOFIT);
    assert_int_equal(bad, 1);
}

/* natx and naty in the Plan (the language's natural curves): the value
 * is the segment's point, the constant fold agrees, and the jets that
 * plot's curvature combs read give |M'| = 1 and the law's curvature,
 * through the chain rule of u = 2s; a phase beyond reach is NaN and its
 * ISNAN flag 1 */
static void test_plan_natural(void **state)
{
    (void)state;
    const char *params[] = {"s"}, *points[] = {"O", "E1", "E2"};
    Plan *p = plan_new("nat", 1, params, 0, NULL, 3, points);
    const double k[4] = {0.5, -1.25, 0.75, 0.125};
    int s = plan_input(p, 0);
    int u = plan_mul(p, plan_const(p, 2), s);
    int x = plan_natural(p, 0, u, k), y = plan_natural(p, 1, u, k);
    assert_int_equal(plan_natural(p, 0, u, k), x); /* hash-consed */
    int wo = plan_sub(p, plan_sub(p, plan_const(p, 1), x), y);
    int pt[3] = {0, 1, 2}, reg[3] = {wo, x, y};
    plan_add_output(p, "M", KIND_POINT, 1, 3, pt, reg,
                    plan_mul(p, plan_isnan(p, x), plan_const(p, 1e6)));
    const double o[2] = {0, 0}, e1[2] = {1, 0}, e2[2] = {0, 1};
    const double *pts[3] = {o, e1, e2};
    PlotEnv env = {p, 0, NULL, NULL, pts, 2};
    for (double t = -0.75; t <= 1.5; t += 0.25) {
        double pos[2], d1[2], d2[2];
        assert_int_equal(plot_jet(&env, 0, t, pos, d1, d2), 0);
        NatSegment g = law(0, 0, 0, 3, k, 2 * t);
        double gx, gy;
        nat_point(&g, 2 * t, &gx, &gy);
        assert_true(fabs(pos[0] - gx) < 1e-15 && fabs(pos[1] - gy) < 1e-15);
        double sp = hypot(d1[0], d1[1]); /* |dM/ds| = |u'| = 2 */
        assert_true(fabs(sp - 2) < 1e-14);
        double kap = (d1[0] * d2[1] - d1[1] * d2[0]) / (sp * sp * sp);
        double want =
            k[0] + k[1] * 2 * t + k[2] * 4 * t * t + k[3] * 8 * t * t * t;
        assert_true(fabs(kap - want) < 1e-13);
        /* the fold of a constant argument: the same value */
        int c = plan_natural(p, 1, plan_const(p, 2 * t), k);
        assert_int_equal(p->ins[c].op, PLAN_CONST);
        assert_true(fabs(p->k[p->ins[c].a] - gy) < 1e-15);
    }
    double pos[2];
    assert_int_equal(plot_jet(&env, 0, 200, pos, NULL, NULL),
                     PLAN_STATUS_POLE); /* the flag: 1e6 < the domain's */
    assert_true(isnan(plan_natural_eval(0, k, 200)));
    assert_false(isnan(plan_natural_eval(0, k, 20)));
    plan_free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fresnel),
        cmocka_unit_test(test_circle_line),
        cmocka_unit_test(test_cubic_simpson),
        cmocka_unit_test(test_g1_sweep),
        cmocka_unit_test(test_g1_symmetry),
        cmocka_unit_test(test_g1_known),
        cmocka_unit_test(test_law_g2_g3),
        cmocka_unit_test(test_erratum_14),
        cmocka_unit_test(test_hooke_jeeves),
        cmocka_unit_test(test_table),
        cmocka_unit_test(test_chord_rule),
        cmocka_unit_test(test_composite_joints),
        cmocka_unit_test(test_api),
        cmocka_unit_test(test_plan_natural),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
