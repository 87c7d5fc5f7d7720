/*
 * test_conics.c - the conics of chapter 2 (the examples) have the metric
 * property that defines them, evaluated by the runtime over their
 * parameter range (the library API, what `eval` runs):
 *
 *   ellipse    |MF1| + |MF2| = 2a
 *   hyperbola  ||MF1| - |MF2|| = 2a
 *   circle     |MO| = r
 *
 * The base points are placed in a plane of dimension 2, 3 and 7 (a random
 * orthonormal frame at a random origin), so the check also covers points
 * given in any dimension.  The properties and the placements are written
 * here from the geometry, independently of the derivations.
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

#include "libpointcalc.h"

/* the cases' tables leave their optional last field (D) out */
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

#define PI 3.14159265358979323846
#define NS 200 /* samples over the range */
#define MAXD 7

/* a plane in R^dim: origin o, orthonormal e1, e2 */
typedef struct Frame {
    int dim;
    double o[MAXD], e1[MAXD], e2[MAXD];
} Frame;

static double urand(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return ((*s >> 8) & 0xffff) / 65536.0 - 0.5;
}

static void frame_init(Frame *f, int dim, unsigned seed)
{
    f->dim = dim;
    double n1 = 0, d = 0, n2 = 0;
    for (int i = 0; i < dim; i++) {
        f->o[i] = 4 * urand(&seed);
        f->e1[i] = urand(&seed) + (i == 0);
        f->e2[i] = urand(&seed) + (i == 1);
    }
    for (int i = 0; i < dim; i++)
        n1 += f->e1[i] * f->e1[i];
    for (int i = 0; i < dim; i++)
        f->e1[i] /= sqrt(n1);
    for (int i = 0; i < dim; i++)
        d += f->e1[i] * f->e2[i];
    for (int i = 0; i < dim; i++)
        f->e2[i] -= d * f->e1[i];
    for (int i = 0; i < dim; i++)
        n2 += f->e2[i] * f->e2[i];
    for (int i = 0; i < dim; i++)
        f->e2[i] /= sqrt(n2);
}

/* the point (x, y) of the plane */
static void put(const Frame *f, double x, double y, double *p)
{
    for (int i = 0; i < f->dim; i++)
        p[i] = f->o[i] + x * f->e1[i] + y * f->e2[i];
}

static double dist(const Frame *f, const double *p, const double *q)
{
    double s = 0;
    for (int i = 0; i < f->dim; i++)
        s += (p[i] - q[i]) * (p[i] - q[i]);
    return sqrt(s);
}

typedef enum Prop { ELLIPSE, HYPERBOLA, CIRCLE } Prop;

/* One case: the example, the plane coordinates of its points A, B, C (and
 * the consts, in declaration order), the property's foci or centre, the
 * parameter range (open: both ends excluded). */
typedef struct Case {
    const char *file;
    double consts[8];
    double A[2], B[2], C[2];
    Prop prop;
    double f1[2], f2[2]; // foci (ELLIPSE, HYPERBOLA) or centre f1 (CIRCLE)
    double k;            // 2a, or the radius
    double lo, hi;       // the range of the first param
    double D[2];         // a fourth point D, where the scheme has one
} Case;

static void check_case(const Case *c)
{
    char *diag = NULL;
    pc_scheme *s = pc_scheme_load(c->file, &diag);
    if (!s)
        fprintf(stderr, "%s", diag ? diag : "");
    free(diag);
    assert_non_null(s);
    pc_plan *p = pc_compile(s, &diag);
    if (!p)
        fprintf(stderr, "%s", diag ? diag : "");
    free(diag);
    assert_non_null(p);
    int o = pc_find_output(s, "M");
    assert_true(o >= 0);
    int np = pc_nparams(s), npt = pc_npoints(s);
    double *prm[4];
    for (int i = 0; i < np; i++) {
        prm[i] = malloc(sizeof(double) * NS);
        for (int k = 0; k < NS; k++) /* the first param sweeps, others 0 */
            prm[i][k] = i ? 0.0 : c->lo + (c->hi - c->lo) * (k + 0.5) / NS;
    }
    static const int dims[] = {2, 3, 7};
    for (int di = 0; di < 3; di++) {
        Frame f;
        frame_init(&f, dims[di], 17u + (unsigned)di);
        double pts[8][MAXD];
        const double *pp[8] = {0};
        for (int i = 0; i < npt; i++) {
            const char *nm = pc_point_name(s, i);
            const double *xy = strcmp(nm, "A") == 0   ? c->A
                               : strcmp(nm, "B") == 0 ? c->B
                               : strcmp(nm, "C") == 0 ? c->C
                               : strcmp(nm, "D") == 0 ? c->D
                                                      : NULL;
            if (xy) {
                put(&f, xy[0], xy[1], pts[i]);
                pp[i] = pts[i];
            }
        }
        double f1[MAXD], f2[MAXD];
        put(&f, c->f1[0], c->f1[1], f1);
        put(&f, c->f2[0], c->f2[1], f2);
        double *out = malloc(sizeof(double) * NS * (size_t)f.dim);
        unsigned char st[NS];
        assert_int_equal(pc_eval(p, o, NS, (const double *const *)prm,
                                 c->consts, pp, f.dim, out, st, NULL),
                         PC_OK);
        double worst = 0;
        for (int k = 0; k < NS; k++) {
            assert_int_equal(st[k], 0);
            const double *m = out + (size_t)k * (size_t)f.dim;
            double d1 = dist(&f, m, f1), d2 = dist(&f, m, f2);
            double v = c->prop == ELLIPSE     ? d1 + d2
                       : c->prop == HYPERBOLA ? fabs(d1 - d2)
                                              : d1;
            double err = fabs(v - c->k) / fmax(1.0, fmax(d1, d2));
            worst = fmax(worst, err);
        }
        if (!(worst < 1e-11))
            fprintf(stderr, "%s, dim %d: property off by %g\n", c->file, f.dim,
                    worst);
        assert_true(worst < 1e-11);
        free(out);
    }
    for (int i = 0; i < np; i++)
        free(prm[i]);
    pc_plan_free(p);
    pc_scheme_free(s);
}

static void test_ellipses(void **state)
{
    (void)state;
    const double a = 3, b = 2, c = sqrt(a * a - b * b);
    const Case cases[] = {
        {"examples/ellipse_central_angle.pcs",
         {a, b},
         {a, 0},
         {0, b},
         {0, 0},
         ELLIPSE,
         {c, 0},
         {-c, 0},
         2 * a,
         0,
         2 * PI},
        {"examples/ellipse_central_radius.pcs",
         {a, b},
         {a, 0},
         {0, b},
         {0, 0},
         ELLIPSE,
         {c, 0},
         {-c, 0},
         2 * a,
         b,
         a},
        {"examples/ellipse_focus_angle.pcs",
         {a, b},
         {a, 0},
         {0, b},
         {0, 0},
         ELLIPSE,
         {c, 0},
         {-c, 0},
         2 * a,
         0,
         2 * PI},
        {"examples/ellipse_compression.pcs",
         {a, b},
         {a, 0},
         {0, b},
         {0, 0},
         ELLIPSE,
         {c, 0},
         {-c, 0},
         2 * a,
         0,
         2 * PI},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        check_case(&cases[i]);

    /* the ellipse with its axis at the angle theta to the line AB of a
     * general triangle (2.1.1.1): centre C, semi-axes m along CK, n; K on
     * AB with AK = b sin(pi - alpha - theta)/sin(theta) */
    const double A[2] = {0.2, -0.1}, B[2] = {4.1, 0.6}, C[2] = {1.3, 2.4};
    const double la = hypot(B[0] - C[0], B[1] - C[1]);
    const double lb = hypot(A[0] - C[0], A[1] - C[1]);
    const double lc = hypot(B[0] - A[0], B[1] - A[1]);
    const double al =
        acos(((B[0] - A[0]) * (C[0] - A[0]) + (B[1] - A[1]) * (C[1] - A[1])) /
             (lc * lb));
    const double ga =
        acos(((A[0] - C[0]) * (B[0] - C[0]) + (A[1] - C[1]) * (B[1] - C[1])) /
             (lb * la));
    const double th = 0.7, mm = 3, nn = 1.5;
    const double ak = lb * sin(PI - al - th) / sin(th);
    const double K[2] = {A[0] + (B[0] - A[0]) * ak / lc,
                         A[1] + (B[1] - A[1]) * ak / lc};
    const double ck = hypot(K[0] - C[0], K[1] - C[1]);
    const double f = sqrt(mm * mm - nn * nn);
    const Case tilted = {
        "examples/ellipse_axis_at_angle.pcs",
        {la, lb, lc, al, ga, th, mm, nn},
        {A[0], A[1]},
        {B[0], B[1]},
        {C[0], C[1]},
        ELLIPSE,
        {C[0] + f * (K[0] - C[0]) / ck, C[1] + f * (K[1] - C[1]) / ck},
        {C[0] - f * (K[0] - C[0]) / ck, C[1] - f * (K[1] - C[1]) / ck},
        2 * mm,
        0,
        2 * PI};
    check_case(&tilted);
}

static void test_hyperbolas(void **state)
{
    (void)state;
    const double a = 2, b = 1.5, c = sqrt(a * a + b * b);
    const double w = asin(b / c); /* the asymptotes' angle */
    const Case cases[] = {
        {"examples/hyperbola_central_angle.pcs",
         {a, b},
         {a, 0},
         {0, b},
         {0, 0},
         HYPERBOLA,
         {c, 0},
         {-c, 0},
         2 * a,
         -w + 1e-3,
         w - 1e-3},
        {"examples/hyperbola_central_radius.pcs",
         {a, b},
         {a, 0},
         {0, b},
         {0, 0},
         HYPERBOLA,
         {c, 0},
         {-c, 0},
         2 * a,
         a,
         10 * a},
        {"examples/hyperbola_focus_angle.pcs",
         {a, b},
         {a, 0},
         {0, b},
         {0, 0},
         HYPERBOLA,
         {c, 0},
         {-c, 0},
         2 * a,
         w + 1e-3,
         2 * PI - w - 1e-3},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        check_case(&cases[i]);
}

/* the hyperbola by the central angle runs off along its asymptotes
 * y = +-(b/a) x as phi nears +-asin(b/c): the direction of M - C there is
 * (a, +-b)/c (a separate property from the focal difference) */
static void test_hyperbola_asymptotes(void **state)
{
    (void)state;
    const double a = 2, b = 1.5, c = sqrt(a * a + b * b), w = asin(b / c);
    char *diag = NULL;
    pc_scheme *s =
        pc_scheme_load("examples/hyperbola_central_angle.pcs", &diag);
    free(diag);
    assert_non_null(s);
    pc_plan *p = pc_compile(s, NULL);
    assert_non_null(p);
    const double A[2] = {a, 0}, B[2] = {0, b}, C[2] = {0, 0};
    const double *pts[3];
    for (int i = 0; i < 3; i++) {
        const char *nm = pc_point_name(s, i);
        pts[i] = nm[0] == 'A' ? A : nm[0] == 'B' ? B : C;
    }
    const double phis[2] = {w - 1e-7, -w + 1e-7};
    const double *prm[1] = {phis};
    double out[4];
    assert_int_equal(pc_eval(p, pc_find_output(s, "M"), 2, prm,
                             (const double[]){a, b}, pts, 2, out, NULL, NULL),
                     PC_OK);
    for (int k = 0; k < 2; k++) {
        double len = hypot(out[2 * k], out[2 * k + 1]);
        assert_true(len > 1e3); /* far out on the branch */
        assert_true(fabs(out[2 * k] / len - a / c) < 1e-5);
        assert_true(fabs(out[2 * k + 1] / len - (k ? -b : b) / c) < 1e-5);
    }
    pc_plan_free(p);
    pc_scheme_free(s);
}

static void test_circles(void **state)
{
    (void)state;
    /* variant 2: centre C, radius R; triangle with a = |BC|, b = |CA| */
    const double a = 2.5, b = 3, g = 1.1, R = 1.7;
    /* variant 1: the locus seeing CA under delta: centre (b/2, b cot(delta)/2),
     * radius b/(2 sin delta), C = 0 and A = (b, 0) */
    const double dl = 0.9, be = 0.8;
    /* engineering discriminant: chord c, sagitta h, O the chord's midpoint
     * at the origin, C on the axis at |OC| = 2c^2h/(c^2 - 4h^2) */
    const double cc = 4, h = 1, r = (cc * cc / 4 + h * h) / (2 * h);
    const double oc = 2 * cc * cc * h / (cc * cc - 4 * h * h);
    /* the article's circles: through a triangle (the circumcentre), and
     * through A, C tangent to AD at A (D on the x axis from A = 0: the
     * centre on the y axis at (|C|^2)/(2 C_y)) */
    const double tA[2] = {0.3, -0.2}, tB[2] = {2.9, 0.4}, tC[2] = {1.1, 2.3};
    double ox, oy;
    {
        double d = 2 * (tA[0] * (tB[1] - tC[1]) + tB[0] * (tC[1] - tA[1]) +
                        tC[0] * (tA[1] - tB[1]));
        double a2 = tA[0] * tA[0] + tA[1] * tA[1];
        double b2 = tB[0] * tB[0] + tB[1] * tB[1];
        double c2 = tC[0] * tC[0] + tC[1] * tC[1];
        ox = (a2 * (tB[1] - tC[1]) + b2 * (tC[1] - tA[1]) +
              c2 * (tA[1] - tB[1])) /
             d;
        oy = (a2 * (tC[0] - tB[0]) + b2 * (tA[0] - tC[0]) +
              c2 * (tB[0] - tA[0])) /
             d;
    }
    const double R3 = hypot(tA[0] - ox, tA[1] - oy);
    const double qC[2] = {1.4, 2.2},
                 ky = (qC[0] * qC[0] + qC[1] * qC[1]) / (2 * qC[1]);
    const Case cases[] = {
        {"examples/circle_three_points.pcs",
         {0},
         {tA[0], tA[1]},
         {tB[0], tB[1]},
         {tC[0], tC[1]},
         CIRCLE,
         {ox, oy},
         {0, 0},
         R3,
         0,
         50},
        {"examples/circle_two_points_tangent.pcs",
         {0},
         {0, 0},
         {0, 0},
         {qC[0], qC[1]},
         CIRCLE,
         {0, ky},
         {0, 0},
         ky,
         0,
         50,
         {1.7, 0}},
        {"examples/circle_angle_2.pcs",
         {a, b, g, R},
         {b, 0},
         {a * cos(g), a * sin(g)},
         {0, 0},
         CIRCLE,
         {0, 0},
         {0, 0},
         R,
         0,
         2 * PI},
        {"examples/circle_angle_1.pcs",
         {a, b, g, dl, be},
         {b, 0},
         {a * cos(g), a * sin(g)},
         {0, 0},
         CIRCLE,
         {b / 2, b / tan(dl) / 2},
         {0, 0},
         b / (2 * sin(dl)),
         0,
         PI},
        {"examples/circle_engineering_discriminant.pcs",
         {cc, h},
         {-cc / 2, 0},
         {cc / 2, 0},
         {0, oc},
         CIRCLE,
         {0, h - r},
         {0, 0},
         r,
         0,
         1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        check_case(&cases[i]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ellipses),
        cmocka_unit_test(test_hyperbolas),
        cmocka_unit_test(test_circles),
        cmocka_unit_test(test_hyperbola_asymptotes),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    pc_cleanup();
    return rc;
}
