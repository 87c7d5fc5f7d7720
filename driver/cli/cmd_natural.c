/*
 * cmd_natural.c - `pointcalc natural --from X,Y,PHI [--through X,Y[,PHI]]...
 * --to X,Y,PHI [--law ...] [--format text|json]`: the composite curve of
 * natural-parametrization segments through the points (docs/natural.md).
 *
 *   options -> points (a later --from starts another curve) -> angles by
 *   the chord rule where not given -> nat_composite (Newton) or, with
 *   --method hooke-jeeves, the article's search segment by segment ->
 *   text | JSON, and the samples, the picture and the C when asked
 *
 * A fit that fails is an error (exit 1) naming the segment; nothing is
 * written to stdout then.
 */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/mem.h"
#include "base/numfmt.h"
#include "driver/cli/args.h"
#include "driver/cli/natural.h"

typedef struct NatArgs {
    NatCli *curves;
    int ncurves;
    int open; // the last curve has its --to
    NatLaw law;
    int has_k0, has_dk0, hj, json, samples, comb;
    double k0, dk0;
    const char *plot, *emit, *scheme, *name, *usage;
} NatArgs;

/* "X,Y" or "X,Y,PHI" into p; the count of numbers, -1 when malformed */
static int parse_point(const char *s, NatPoint *p)
{
    double v[3];
    int n = 0;
    const char *q = s;
    for (;;) {
        char *end;
        v[n] = pc_strtod(q, &end);
        if (end == q || !isfinite(v[n]))
            return -1;
        n++;
        if (!*end)
            break;
        if (*end != ',' || n == 3)
            return -1;
        q = end + 1;
    }
    if (n < 2)
        return -1;
    p->x = v[0], p->y = v[1], p->th = n == 3 ? v[2] : 0, p->has_th = n == 3;
    return n;
}

static void add_point(NatArgs *a, const NatPoint *p)
{
    NatCli *c = &a->curves[a->ncurves - 1];
    c->pts = pc_xrealloc(c->pts, sizeof *c->pts * (size_t)(c->npts + 1));
    c->pts[c->npts++] = *p;
}

/* --from, --through, --to */
static int point_option(NatArgs *a, const char *opt, const char *v, FILE *err)
{
    NatPoint p;
    int n = parse_point(v, &p);
    int need3 = strcmp(opt, "--through") != 0;
    if (n < 0 || (need3 && n != 3))
        return args_usage_error(err, a->usage,
                                "bad value '%s' for %s (expected %s)", v, opt,
                                need3 ? "X,Y,PHI" : "X,Y or X,Y,PHI"),
               -1;
    if (strcmp(opt, "--from") == 0) {
        if (a->ncurves && !a->open)
            return args_usage_error(err, a->usage,
                                    "--from before the previous curve's --to"),
                   -1;
        a->curves = pc_xrealloc(a->curves,
                                sizeof *a->curves * (size_t)(a->ncurves + 1));
        memset(&a->curves[a->ncurves++], 0, sizeof *a->curves);
        a->open = 0;
    } else if (!a->ncurves || a->open)
        return args_usage_error(err, a->usage, "%s before --from", opt), -1;
    if (a->curves[a->ncurves - 1].npts >= NAT_MAX_POINTS)
        return args_usage_error(err, a->usage, "more than %d points",
                                NAT_MAX_POINTS),
               -1;
    add_point(a, &p);
    if (strcmp(opt, "--to") == 0)
        a->open = 1;
    return 2;
}

static int choice(const char *v, const char *const *names, int n)
{
    for (int i = 0; i < n; i++)
        if (strcmp(v, names[i]) == 0)
            return i;
    return -1;
}

static int number_option(NatArgs *a, const char *opt, const char *v, FILE *err)
{
    char *end;
    double d = pc_strtod(v, &end);
    if (strcmp(opt, "--samples") == 0) {
        long l = strtol(v, &end, 10);
        if (end == v || *end || l < 1 || l > 1000000)
            return args_usage_error(err, a->usage,
                                    "bad value '%s' for --samples (expected an "
                                    "integer 1..1000000)",
                                    v),
                   -1;
        a->samples = (int)l;
        return 2;
    }
    if (end == v || *end || !isfinite(d))
        return args_usage_error(err, a->usage,
                                "bad value '%s' for %s (expected a number)", v,
                                opt),
               -1;
    if (strcmp(opt, "--k0") == 0)
        a->k0 = d, a->has_k0 = 1;
    else
        a->dk0 = d, a->has_dk0 = 1;
    return 2;
}

static int natural_option(void *ctx, int argc, char **argv, int i, FILE *err)
{
    NatArgs *a = ctx;
    static const char *const laws[] = {"linear", "quadratic", "cubic"};
    static const char *const methods[] = {"newton", "hooke-jeeves"};
    static const char *const formats[] = {"text", "json"};
    const char *opt = argv[i], *v = args_value(argc, argv, i);
    if (strcmp(opt, "--comb") == 0)
        return a->comb = 1, 1;
    static const char *const known[] = {
        "--from",   "--through", "--to",     "--law",     "--k0",
        "--dk0",    "--method",  "--format", "--samples", "--plot",
        "--emit-c", "--name",    "--scheme"};
    int k = choice(opt, known, 13);
    if (k < 0)
        return 0;
    if (!v)
        return args_usage_error(err, a->usage, "%s needs a value", opt), -1;
    if (k <= 2)
        return point_option(a, opt, v, err);
    if (k == 4 || k == 5 || k == 8)
        return number_option(a, opt, v, err);
    if (k >= 9) {
        *(k == 9    ? &a->plot
          : k == 10 ? &a->emit
          : k == 11 ? &a->name
                    : &a->scheme) = v;
        return 2;
    }
    const char *const *names = k == 3 ? laws : k == 6 ? methods : formats;
    int c = choice(v, names, k == 3 ? 3 : 2);
    if (c < 0)
        return args_usage_error(err, a->usage,
                                "unknown %s '%s'; expected %s, %s%s%s", opt + 2,
                                v, names[0], names[1], k == 3 ? " or " : "",
                                k == 3 ? names[2] : ""),
               -1;
    if (k == 3)
        a->law = (NatLaw)(c + 1);
    else if (k == 6)
        a->hj = c;
    else
        a->json = c;
    return 2;
}

/* a C identifier (the scheme's and the C's name) */
static int name_ok(const char *s)
{
    if (!(isalpha((unsigned char)*s) || *s == '_'))
        return 0;
    for (; *s; s++)
        if (!(isalnum((unsigned char)*s) || *s == '_'))
            return 0;
    return 1;
}

static int check_args(NatArgs *a, FILE *err)
{
    if (!a->ncurves)
        return args_usage_error(
            err, a->usage, "no curve: give --from X,Y,PHI and --to X,Y,PHI");
    if (!a->open)
        return args_usage_error(err, a->usage, "the last curve has no --to");
    if ((a->has_k0 || a->has_dk0) && a->law == NAT_LINEAR)
        return args_usage_error(
            err, a->usage,
            "--k0 and --dk0 fix the start of a quadratic or cubic law; the "
            "linear law has no room for them");
    if (a->has_dk0 && a->law != NAT_CUBIC)
        return args_usage_error(err, a->usage, "--dk0 needs --law cubic");
    for (int c = 0; a->hj && c < a->ncurves; c++)
        if (a->curves[c].npts > NAT_MAX_HJ_POINTS)
            return args_usage_error(
                err, a->usage,
                "--method hooke-jeeves takes at most %d points a curve",
                NAT_MAX_HJ_POINTS);
    if ((double)a->samples * (a->curves[0].npts - 1) > 1e7)
        return args_usage_error(
            err, a->usage,
            "--samples %d over %d segments is more than 10^7 samples",
            a->samples, a->curves[0].npts - 1);
    if (a->hj && a->law != NAT_LINEAR)
        return args_usage_error(err, a->usage,
                                "--method hooke-jeeves is the article's search "
                                "for the linear law only");
    if ((a->emit || a->scheme) && a->ncurves > 1)
        return args_usage_error(err, a->usage,
                                "%s writes one curve; this command line has %d",
                                a->emit ? "--emit-c" : "--scheme", a->ncurves);
    if (a->scheme && !name_ok(a->name))
        return args_usage_error(err, a->usage,
                                "--name '%s' is not a scheme name (a letter or "
                                "'_', then letters, digits and '_')",
                                a->name);
    for (int c = 0; c < a->ncurves; c++)
        for (int i = 0; i < a->curves[c].npts; i++) {
            const NatPoint *p = &a->curves[c].pts[i];
            if (fabs(p->x) > NAT_MAX_COORD || fabs(p->y) > NAT_MAX_COORD ||
                (i + 1 < a->curves[c].npts &&
                 hypot(p->x - p[1].x, p->y - p[1].y) < NAT_MIN_CHORD &&
                 (p->x != p[1].x || p->y != p[1].y)))
                return args_usage_error(
                    err, a->usage,
                    "point %d of curve %d: coordinates up to 1e100 and "
                    "points at least 1e-100 apart (beyond, the curvature "
                    "law's coefficients leave double precision)",
                    i + 1, c + 1);
            if (i + 1 == a->curves[c].npts)
                continue;
            if (p->x == p[1].x && p->y == p[1].y)
                return args_usage_error(
                    err, a->usage,
                    "points %d and %d of curve %d coincide: a segment needs "
                    "two distinct points",
                    i + 1, i + 2, c + 1);
        }
    return 0;
}

static const char *law_name(NatLaw l)
{
    return l == NAT_CUBIC       ? "cubic"
           : l == NAT_QUADRATIC ? "quadratic"
                                : "linear";
}

/* c[0] + c[1] s + ... with %.10g coefficients; a term below 1e-13 of
 * the polynomial's size on [0, S] is rounding (a circle's k1 of 1e-17)
 * and not written (the JSON has every coefficient as computed) */
static void print_poly(FILE *out, const double *c, int deg, const char *var,
                       double S)
{
    double size = 0, sj = 1;
    for (int j = 0; j <= deg; j++, sj *= S)
        size += fabs(c[j]) * sj;
    int any = 0;
    sj = 1;
    for (int j = 0; j <= deg; j++, sj *= S) {
        double v = c[j];
        if (fabs(v) * sj <= 1e-13 * size || v == 0)
            continue;
        if (any)
            pc_fprintf(out, v < 0 ? " - %.10g" : " + %.10g", fabs(v));
        else
            pc_fprintf(out, "%.10g", v);
        if (j)
            fprintf(out, j == 1 ? "*%s" : "*%s^%d", var, j);
        any = 1;
    }
    if (!any)
        fputc('0', out);
}

/* never "-0" */
static double nz(double v)
{
    return v == 0 ? 0.0 : v;
}

static void print_text(FILE *out, const NatArgs *a, const NatCli *k)
{
    const NatCurve *c = &k->curve;
    fprintf(out, "natural curve through %d points, %s law (%s), %s\n", k->npts,
            law_name(a->law),
            a->law == NAT_CUBIC       ? "G3"
            : a->law == NAT_QUADRATIC ? "G2"
                                      : "G1",
            a->hj ? "Hooke-Jeeves" : "Newton");
    for (int i = 0; i < c->nseg; i++) {
        const NatSegment *g = &c->seg[i];
        const NatPoint *p = &k->pts[i];
        double ph[NAT_MAX_DEGREE + 2] = {g->phi0};
        for (int j = 0; j <= g->degree; j++)
            ph[j + 1] = g->k[j] / (j + 1);
        pc_fprintf(
            out,
            "segment %d: (%.10g, %.10g) at %.10g -> (%.10g, %.10g) at %.10g\n",
            i + 1, nz(p->x), nz(p->y), nz(p->th), nz(p[1].x), nz(p[1].y),
            nz(p[1].th));
        fputs("  k(s)   = ", out);
        print_poly(out, g->k, g->degree, "s", g->length);
        fputs("\n  phi(s) = ", out);
        print_poly(out, ph, g->degree + 1, "s", g->length);
        pc_fprintf(out, "\n  S = %.15g\n", g->length);
    }
    for (int i = 0; i + 1 < c->nseg; i++)
        pc_fprintf(out, "joint %d: |dphi| = %.3g, |dk| = %.3g, |dk'| = %.3g\n",
                   i + 2, fabs(c->joint[i].dphi), fabs(c->joint[i].dk),
                   fabs(c->joint[i].ddk));
    pc_fprintf(out, "%s: %d, integrals: %d, end-point error: %.3g\n",
               a->hj ? "pattern moves" : "Newton steps", c->stats.iterations,
               c->stats.integrals, c->stats.error);
}

static void json_array(FILE *out, const double *v, int n)
{
    fputc('[', out);
    for (int i = 0; i < n; i++) {
        if (i)
            fputs(", ", out);
        json_number(out, v[i]);
    }
    fputc(']', out);
}

static void print_json(FILE *out, const NatArgs *a, const NatCli *k)
{
    const NatCurve *c = &k->curve;
    fprintf(out, "{\"law\": \"%s\", \"method\": \"%s\", \"points\": [",
            law_name(a->law), a->hj ? "hooke-jeeves" : "newton");
    for (int i = 0; i < k->npts; i++) {
        double v[3] = {k->pts[i].x, k->pts[i].y, k->pts[i].th};
        fputs(i ? ", " : "", out);
        json_array(out, v, 3);
    }
    fputs("],\n \"segments\": [", out);
    for (int i = 0; i < c->nseg; i++) {
        const NatSegment *g = &c->seg[i];
        fputs(i ? ",\n  {\"k\": " : "\n  {\"k\": ", out);
        json_array(out, g->k, g->degree + 1);
        fputs(", \"length\": ", out);
        json_number(out, g->length);
        fputs(", \"phi0\": ", out);
        json_number(out, g->phi0);
        fputc('}', out);
    }
    fputs("],\n \"joints\": [", out);
    for (int i = 0; i + 1 < c->nseg; i++) {
        double v[3] = {c->joint[i].dphi, c->joint[i].dk, c->joint[i].ddk};
        fputs(i ? ", " : "", out);
        json_array(out, v, 3);
    }
    pc_fprintf(out, "],\n \"iterations\": %d, \"integrals\": %d, \"error\": ",
               c->stats.iterations, c->stats.integrals);
    json_number(out, c->stats.error);
    if (a->samples) {
        fputs(",\n \"samples\": ", out);
        natural_samples_json(out, c, a->samples);
    }
    fputs("}", out);
}

static void args_free(NatArgs *a)
{
    for (int c = 0; c < a->ncurves; c++) {
        pc_free(a->curves[c].pts);
        nat_curve_free(&a->curves[c].curve);
    }
    pc_free(a->curves);
}

static int fit_all(NatArgs *a, FILE *err)
{
    for (int c = 0; c < a->ncurves; c++) {
        NatCli *k = &a->curves[c];
        int bad;
        NatChain ch = {a->law, a->has_k0, a->k0, a->dk0, a->hj};
        int rc = nat_composite(k->pts, k->npts, &ch, &k->curve, &bad);
        if (rc && a->hj) {
            pc_fprintf(err,
                       "pointcalc: natural: curve %d, segment %d: Hooke-Jeeves "
                       "did not reach the end point within 1e-12 of the chord "
                       "in %d integrals\n",
                       c + 1, bad + 1, NAT_HJ_MAX_EVALS);
            return 1;
        }
        if (rc) {
            pc_fprintf(err,
                       "pointcalc: natural: curve %d, segment %d: no %s "
                       "segment reaches point %d from the start values the "
                       "joint gives (Newton by continuation from the "
                       "clothoid and from 42 starts, %d steps); try --law "
                       "linear, or other points\n",
                       c + 1, bad + 1, law_name(a->law), bad + 2,
                       k->curve.stats.iterations);
            return 1;
        }
    }
    return 0;
}

int cli_natural(int argc, char **argv, FILE *out, FILE *err)
{
    NatArgs a = {.law = NAT_LINEAR,
                 .usage = help_usage("natural"),
                 .name = "natural_curve"};
    BudgetOptions b;
    int rc = args_scan(argc, argv, a.usage, &b, NULL, natural_option, &a, err);
    if (!rc)
        rc = check_args(&a, err);
    if (!rc) {
        budget_phase("fitting");
        budget_arm(b.max_seconds, b.max_memory);
        rc = fit_all(&a, err);
        budget_disarm();
    }
    if (!rc && a.plot)
        rc = natural_svg(a.plot, a.curves, a.ncurves, a.comb, err);
    if (!rc && a.emit)
        rc = natural_emit_c(a.emit, &a.curves[0].curve, a.name, err);
    if (!rc && a.scheme)
        rc = natural_scheme(a.scheme, &a.curves[0].curve, a.name, err);
    for (int c = 0; !rc && c < a.ncurves; c++) {
        if (!a.json)
            print_text(out, &a, &a.curves[c]);
        else {
            fputs(a.ncurves == 1 ? "" : c ? ",\n " : "{\"curves\": [\n ", out);
            print_json(out, &a, &a.curves[c]);
            fputs(a.ncurves == 1       ? "\n"
                  : c + 1 == a.ncurves ? "]}\n"
                                       : "",
                  out);
        }
    }
    args_free(&a);
    return rc;
}

const char natural_help[] = NATURAL_USAGE
    "\n"
    "Plane curves in natural parametrization (the natural-parametrization\n"
    "article, docs/natural.md): the curvature k(s) a polynomial in the arc\n"
    "length s, phi(s) its integral, x + iy = int exp(i phi) ds.  Fitted\n"
    "through the points in order, each with its tangent angle PHI (radians);\n"
    "an angle not given comes from the chord rule (inner points: the\n"
    "direction from the previous to the next point; ends: the mirror of the\n"
    "next angle in the end chord).  The first segment has the linear law (the\n"
    "clothoid, Newton on Bertolazzi and Frego's one equation); every later\n"
    "one has --law's: linear (G1 joints), quadratic (G2: the curvature\n"
    "continues), cubic (G3: its derivative too).  A later --from starts\n"
    "another curve.\n"
    "\n"
    "  --k0 K, --dk0 D     the first segment's start curvature (and its\n"
    "                      derivative, cubic) under the quadratic/cubic law\n"
    "  --method M          newton (default) or hooke-jeeves (the article's\n"
    "                      search, linear law)\n"
    "  --format text|json  json: \"segments\" [{\"k\": [k0, k1, ...], "
    "\"length\"}]\n"
    "  --samples N         N + 1 samples a segment (s, x, y, phi, k, k') in\n"
    "                      the JSON\n"
    "  --plot FILE.svg     the curves, their points and end tangents; --comb\n"
    "                      adds the curvature comb\n"
    "  --emit-c FILE.c     C for the curve: void F(double s, double p[2]) "
    "over\n"
    "                      the whole arc length (--name F, default\n"
    "                      natural_curve)\n"
    "  --scheme FILE.pcs   the curve as a scheme: natx and naty of each\n"
    "                      segment's law, joined by piecewise in s (--name:\n"
    "                      the scheme's name)\n"
    "\nExit status: 0 success, 1 a fit that fails, 2 a usage error.\n";
