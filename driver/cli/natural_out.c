/*
 * natural_out.c - what `pointcalc natural` writes besides the fit: the
 * samples (JSON), the picture (SVG) and the curve as C (natural.h).
 *
 * Points along a segment come from its evaluation table (nat_table_build:
 * Chebyshev pieces checked to 1e-15 of the length), the angle and the
 * curvature from the exact polynomials.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/mem.h"
#include "base/numfmt.h"
#include "driver/cli/natural.h"
#include "driver/cli/outfile.h"
#include "driver/cli/svgfig.h"

void natural_samples_json(FILE *out, const NatCurve *c, int n)
{
    fputc('[', out);
    for (int i = 0; i < c->nseg; i++) {
        const NatSegment *g = &c->seg[i];
        NatTable t;
        nat_table_build(&t, g);
        fputs(i ? ",\n  [" : "\n  [", out);
        for (int j = 0; j <= n; j++) {
            double s = g->length * j / n, v[6];
            v[0] = s;
            nat_table_eval(&t, s, &v[1], &v[2]);
            v[3] = nat_phi(g, s), v[4] = nat_kappa(g, s),
            v[5] = nat_dkappa(g, s);
            fputs(j ? ", [" : "[", out);
            for (int q = 0; q < 6; q++) {
                fputs(q ? ", " : "", out);
                json_number(out, v[q]);
            }
            fputc(']', out);
        }
        fputc(']', out);
        nat_table_free(&t);
    }
    fputc(']', out);
}

/* ---- the picture --------------------------------------------------------- */

enum { SVG_SEG_SAMPLES = 200, SVG_TEETH = 60 };

static const char natural_style[] =
    ".curve { fill: none; stroke: #1f4e9c; stroke-width: 2 }\n"
    ".comb, .tooth { fill: none; stroke: #c0504d; stroke-width: 0.7 }\n"
    ".tangent { fill: none; stroke: #555; stroke-width: 1 }\n"
    ".point { fill: white; stroke: #000; stroke-width: 1.2 }\n";

static void draw_curve(SvgFig *f, const NatCurve *c)
{
    svgfig_line_begin(f, "curve");
    for (int i = 0; i < c->nseg; i++) {
        NatTable t;
        nat_table_build(&t, &c->seg[i]);
        for (int j = i ? 1 : 0; j <= SVG_SEG_SAMPLES; j++) {
            double x, y;
            nat_table_eval(&t, c->seg[i].length * j / SVG_SEG_SAMPLES, &x, &y);
            svgfig_line_to(f, x, y);
        }
        nat_table_free(&t);
    }
    svgfig_line_end(f);
}

/* the comb: the normal scaled by -k (drawn on the convex side), its
 * outline and its teeth */
static void draw_comb(SvgFig *f, const NatCurve *c, double scale)
{
    for (int i = 0; i < c->nseg; i++) {
        const NatSegment *g = &c->seg[i];
        NatTable t;
        nat_table_build(&t, g);
        double tip[SVG_TEETH + 1][4];
        for (int j = 0; j <= SVG_TEETH; j++) {
            double s = g->length * j / SVG_TEETH, ph = nat_phi(g, s);
            double k = -nat_kappa(g, s) * scale;
            nat_table_eval(&t, s, &tip[j][0], &tip[j][1]);
            tip[j][2] = tip[j][0] - k * sin(ph);
            tip[j][3] = tip[j][1] + k * cos(ph);
        }
        svgfig_line_begin(f, "comb");
        for (int j = 0; j <= SVG_TEETH; j++)
            svgfig_line_to(f, tip[j][2], tip[j][3]);
        svgfig_line_end(f);
        for (int j = 0; j <= SVG_TEETH; j++)
            svgfig_segment(f, "tooth", tip[j][0], tip[j][1], tip[j][2],
                           tip[j][3]);
        nat_table_free(&t);
    }
}

static void draw_points(SvgFig *f, const NatCli *k, double len)
{
    for (int i = 0; i < k->npts; i++) {
        const NatPoint *p = &k->pts[i];
        double dx = len * cos(p->th), dy = len * sin(p->th);
        svgfig_segment(f, "tangent", p->x - dx, p->y - dy, p->x + dx,
                       p->y + dy);
        svgfig_circle(f, "point", p->x, p->y, 4);
    }
}

static double max_kappa(const NatCurve *c)
{
    double m = 0;
    for (int i = 0; i < c->nseg; i++)
        for (int j = 0; j <= SVG_TEETH; j++)
            m = fmax(m, fabs(nat_kappa(&c->seg[i],
                                       c->seg[i].length * j / SVG_TEETH)));
    return m;
}

int natural_svg(const char *path, const NatCli *curves, int n, int comb,
                FILE *err)
{
    double b[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY}, km = 0;
    for (int c = 0; c < n; c++) {
        for (int i = 0; i < curves[c].npts; i++)
            svgfig_grow(b, curves[c].pts[i].x, curves[c].pts[i].y);
        for (int i = 0; i < curves[c].curve.nseg; i++)
            for (int j = 0; j <= 16; j++) {
                const NatSegment *g = &curves[c].curve.seg[i];
                double x, y;
                nat_point(g, g->length * j / 16, &x, &y);
                svgfig_grow(b, x, y);
            }
        km = fmax(km, max_kappa(&curves[c].curve));
    }
    double diag = hypot(b[2] - b[0], b[3] - b[1]), pad = 0.12 * diag;
    double scale = km > 0 ? 0.15 * diag / km : 0;
    double box[4] = {b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad};
    SvgFig f;
    svgfig_begin(&f, box, natural_style);
    for (int c = 0; c < n; c++) {
        if (comb && scale > 0)
            draw_comb(&f, &curves[c].curve, scale);
        draw_curve(&f, &curves[c].curve);
        draw_points(&f, &curves[c], 0.06 * diag);
    }
    return svgfig_end(&f, path, err);
}

/* ---- the C --------------------------------------------------------------- */

static void c_array(FILE *out, const char *name, const char *what,
                    const double *v, size_t n)
{
    pc_fprintf(out, "static const double %s_%s[%zu] = {", name, what, n);
    for (size_t i = 0; i < n; i++)
        pc_fprintf(out, "%s%.17g",
                   i % 3 ? ", "
                   : i   ? ",\n    "
                         : "\n    ",
                   v[i]);
    fputs("};\n", out);
}

static void c_tables(FILE *out, const NatCurve *c, const char *name)
{
    int ns = c->nseg;
    double *start = pc_xcalloc((size_t)ns * 5 + 1, sizeof *start);
    double *scale = start + ns + 1, *off = scale + ns, *np = off + ns;
    double *nc = np + ns;
    double *cx = NULL, *cy = NULL;
    size_t total = 0;
    int ncoef = NAT_CHEB_DEGREE + 1;
    for (int i = 0; i < ns; i++) {
        NatTable t;
        nat_table_build(&t, &c->seg[i]);
        start[i + 1] = start[i] + c->seg[i].length;
        scale[i] = t.scale, off[i] = (double)total, np[i] = t.npanels;
        nc[i] = t.ncoef;
        size_t m = (size_t)t.npanels * (size_t)ncoef;
        cx = pc_xrealloc(cx, sizeof *cx * (total + m));
        cy = pc_xrealloc(cy, sizeof *cy * (total + m));
        memcpy(cx + total, t.cx, sizeof *cx * m);
        memcpy(cy + total, t.cy, sizeof *cy * m);
        total += m;
        nat_table_free(&t);
    }
    double *law = pc_xcalloc((size_t)ns * 5, sizeof *law);
    for (int i = 0; i < ns; i++) { // phi0, then k0 .. k3
        law[5 * i] = c->seg[i].phi0;
        for (int j = 0; j <= c->seg[i].degree; j++)
            law[5 * i + 1 + j] = c->seg[i].k[j];
    }
    c_array(out, name, "law", law, (size_t)ns * 5);
    pc_free(law);
    c_array(out, name, "start", start, (size_t)ns + 1);
    c_array(out, name, "scale", scale, (size_t)ns);
    c_array(out, name, "offset", off, (size_t)ns);
    c_array(out, name, "panels", np, (size_t)ns);
    c_array(out, name, "ncoef", nc, (size_t)ns);
    c_array(out, name, "cx", cx, total);
    c_array(out, name, "cy", cy, total);
    pc_free(start);
    pc_free(cx);
    pc_free(cy);
}

/* the evaluator: $ is the name, # the segments' count */
static const char c_body[] =
    "\n/* the segment of arc length s */\n"
    "static int $_segment(double s)\n{\n"
    "    int g = 0;\n"
    "    while (g + 1 < # && s >= $_start[g + 1])\n        g++;\n"
    "    return g;\n}\n\n"
    "/* the point at arc length s (clamped to the curve) */\n"
    "void $(double s, double p[2])\n{\n"
    "    int g = $_segment(s);\n"
    "    double u = (s - $_start[g]) * $_scale[g];\n"
    "    int n = (int)$_panels[g], q = u > 0 ? (int)u : 0;\n"
    "    if (!(u > 0))\n        u = 0;\n"
    "    if (q >= n)\n        q = n - 1, u = n;\n"
    "    const double *cx = $_cx + (long)$_offset[g] + q * $_NCOEF;\n"
    "    const double *cy = $_cy + (long)$_offset[g] + q * $_NCOEF;\n"
    "    double z = 2 * (u - q) - 1, z2 = 2 * z;\n"
    "    double bx1 = 0, bx2 = 0, by1 = 0, by2 = 0;\n"
    "    for (int j = (int)$_ncoef[g] - 1; j >= 1; j--) {\n"
    "        double bx = z2 * bx1 - bx2 + cx[j], by = z2 * by1 - by2 + cy[j];\n"
    "        bx2 = bx1, bx1 = bx, by2 = by1, by1 = by;\n    }\n"
    "    p[0] = z * bx1 - bx2 + cx[0];\n"
    "    p[1] = z * by1 - by2 + cy[0];\n}\n\n"
    "/* the tangent angle a[0] and the curvature a[1] at arc length s (the\n"
    " * exact polynomials; s clamped to the curve) */\n"
    "void $_angle_curvature(double s, double a[2])\n{\n"
    "    int g = $_segment(s);\n"
    "    const double *k = $_law + 5 * g;\n"
    "    double v = s - $_start[g], len = $_start[g + 1] - $_start[g];\n"
    "    v = v < 0 ? 0 : v > len ? len : v;\n"
    "    a[0] = k[0] + v * (k[1] + v * (k[2] / 2 + v * (k[3] / 3 + v * k[4] / "
    "4)));\n"
    "    a[1] = k[1] + v * (k[2] + v * (k[3] + v * k[4]));\n}\n\n"
    "/* n points: p[2 i], p[2 i + 1] at s[i] */\n"
    "void $_batch(const double *s, double *p, long n)\n{\n"
    "    for (long i = 0; i < n; i++)\n        $(s[i], p + 2 * i);\n}\n";

static void put_template(FILE *out, const char *t, const char *name, int nseg)
{
    for (; *t; t++) {
        if (*t == '$')
            fputs(name, out);
        else if (*t == '#')
            fprintf(out, "%d", nseg);
        else
            fputc(*t, out);
    }
}

int natural_emit_c(const char *path, const NatCurve *c, const char *name,
                   FILE *err)
{
    char *text = NULL;
    size_t len = 0;
    FILE *out = pc_xopen_memstream(&text, &len);
    pc_fprintf(out,
               "/* generated by pointcalc natural: a curve in natural "
               "parametrization,\n * %d segment(s), s in [0, total length]; "
               "Chebyshev pieces of degree %d. */\n",
               c->nseg, NAT_CHEB_DEGREE);
    pc_fprintf(out, "enum { %s_NCOEF = %d };\n", name, NAT_CHEB_DEGREE + 1);
    c_tables(out, c, name);
    put_template(out, c_body, name, c->nseg);
    pc_xclose_memstream(out);
    int rc = outfile_write(path, text, len, NULL, err);
    pc_free(text);
    return rc;
}

/* ---- the scheme --------------------------------------------------------- */

/* "(x0 + cos(phi0)*Xi(s - a) - sin(phi0)*Yi(s - a))": coordinate c of
 * segment i at s, which starts at arc length a */
static void scheme_coord(FILE *out, const NatSegment *g, int i, double a, int c)
{
    char arg[48];
    if (a == 0)
        snprintf(arg, sizeof arg, "s");
    else
        pc_snprintf(arg, sizeof arg, "s - %.17g", a);
    pc_fprintf(out, "(%.17g + cos(%.17g)*%c%d(%s) %c sin(%.17g)*%c%d(%s))",
               c ? g->y0 : g->x0, g->phi0, c ? 'Y' : 'X', i, arg, c ? '+' : '-',
               g->phi0, c ? 'X' : 'Y', i, arg);
}

int natural_scheme(const char *path, const NatCurve *c, const char *name,
                   FILE *err)
{
    char *text = NULL;
    size_t len = 0;
    FILE *out = pc_xopen_memstream(&text, &len);
    double total = 0;
    for (int i = 0; i < c->nseg; i++)
        total += c->seg[i].length;
    pc_fprintf(out,
               "# generated by pointcalc natural: %d segment(s) in natural\n"
               "# parametrization, s the arc length (docs/natural.md, \"In "
               "the scheme\n# language\"); Xi, Yi: natx and naty of segment "
               "i's curvature law\nscheme %s\n"
               "point O, E1, E2   # a Cartesian frame: the origin, the axes' "
               "unit points\nparam s in [0, %.17g]\n",
               c->nseg, name, total);
    double a = 0;
    for (int i = 0; i < c->nseg; i++) {
        const NatSegment *g = &c->seg[i];
        for (int xy = 0; xy < 2; xy++) {
            pc_fprintf(out, "def %c%d(u) = %s(u", xy ? 'Y' : 'X', i + 1,
                       xy ? "naty" : "natx");
            for (int j = 0; j <= g->degree; j++)
                pc_fprintf(out, ", %.17g", g->k[j]);
            fputs(")\n", out);
        }
        pc_fprintf(out, "M%d = O + ", i + 1);
        scheme_coord(out, g, i + 1, a, 0);
        fputs("*(E1 - O) + ", out);
        scheme_coord(out, g, i + 1, a, 1);
        fputs("*(E2 - O)\n", out);
        a += g->length;
    }
    fputs(c->nseg == 1 ? "M = M1" : "M = piecewise(s", out);
    a = 0;
    for (int i = 0; c->nseg > 1 && i < c->nseg; i++) {
        if (i)
            pc_fprintf(out, ", %.17g", a);
        pc_fprintf(out, ", M%d", i + 1);
        a += c->seg[i].length;
    }
    fputs(c->nseg == 1 ? "\noutput M\n" : ")\noutput M\n", out);
    pc_xclose_memstream(out);
    int rc = outfile_write(path, text, len, NULL, err);
    pc_free(text);
    return rc;
}
