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

enum { SVG_W = 720, SVG_SEG_SAMPLES = 200, SVG_TEETH = 60 };

typedef struct Frame {
    double x0, y0, x1, y1, k; // the box and pixels per unit
    FILE *out;
} Frame;

static void px(const Frame *f, double x, double y)
{
    pc_fprintf(f->out, "%.2f,%.2f", 20 + (x - f->x0) * f->k,
               20 + (f->y1 - y) * f->k);
}

static void grow(double *b, double x, double y)
{
    b[0] = fmin(b[0], x), b[1] = fmin(b[1], y);
    b[2] = fmax(b[2], x), b[3] = fmax(b[3], y);
}

static void draw_curve(const Frame *f, const NatCurve *c)
{
    fputs("<polyline class=\"curve\" points=\"", f->out);
    for (int i = 0; i < c->nseg; i++) {
        NatTable t;
        nat_table_build(&t, &c->seg[i]);
        for (int j = i ? 1 : 0; j <= SVG_SEG_SAMPLES; j++) {
            double x, y;
            nat_table_eval(&t, c->seg[i].length * j / SVG_SEG_SAMPLES, &x, &y);
            px(f, x, y);
            fputc(' ', f->out);
        }
        nat_table_free(&t);
    }
    fputs("\"/>\n", f->out);
}

static void draw_comb(const Frame *f, const NatCurve *c, double scale)
{
    for (int i = 0; i < c->nseg; i++) {
        const NatSegment *g = &c->seg[i];
        NatTable t;
        nat_table_build(&t, g);
        fputs("<polyline class=\"comb\" points=\"", f->out);
        for (int j = 0; j <= SVG_TEETH; j++) {
            double s = g->length * j / SVG_TEETH, x, y, ph = nat_phi(g, s);
            double k = -nat_kappa(g, s) * scale;
            nat_table_eval(&t, s, &x, &y);
            px(f, x - k * sin(ph), y + k * cos(ph));
            fputc(' ', f->out);
        }
        fputs("\"/>\n", f->out);
        for (int j = 0; j <= SVG_TEETH; j++) {
            double s = g->length * j / SVG_TEETH, x, y, ph = nat_phi(g, s);
            double k = -nat_kappa(g, s) * scale;
            nat_table_eval(&t, s, &x, &y);
            fputs("<polyline class=\"tooth\" points=\"", f->out);
            px(f, x, y);
            fputc(' ', f->out);
            px(f, x - k * sin(ph), y + k * cos(ph));
            fputs("\"/>\n", f->out);
        }
        nat_table_free(&t);
    }
}

static void draw_points(const Frame *f, const NatCli *k, double len)
{
    for (int i = 0; i < k->npts; i++) {
        const NatPoint *p = &k->pts[i];
        fputs("<polyline class=\"tangent\" points=\"", f->out);
        px(f, p->x - len * cos(p->th), p->y - len * sin(p->th));
        fputc(' ', f->out);
        px(f, p->x + len * cos(p->th), p->y + len * sin(p->th));
        fputs("\"/>\n<circle class=\"point\" r=\"4\" cx=\"", f->out);
        pc_fprintf(f->out, "%.2f\" cy=\"%.2f\"/>\n", 20 + (p->x - f->x0) * f->k,
                   20 + (f->y1 - p->y) * f->k);
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
            grow(b, curves[c].pts[i].x, curves[c].pts[i].y);
        for (int i = 0; i < curves[c].curve.nseg; i++)
            for (int j = 0; j <= 16; j++) {
                double x, y;
                nat_point(&curves[c].curve.seg[i],
                          curves[c].curve.seg[i].length * j / 16, &x, &y);
                grow(b, x, y);
            }
        km = fmax(km, max_kappa(&curves[c].curve));
    }
    double diag = hypot(b[2] - b[0], b[3] - b[1]), pad = 0.12 * diag;
    double scale = km > 0 ? 0.15 * diag / km : 0;
    b[0] -= pad, b[1] -= pad, b[2] += pad, b[3] += pad;
    char *text = NULL;
    size_t len = 0;
    Frame f = {b[0], b[1], b[2], b[3], (SVG_W - 40) / fmax(b[2] - b[0], 1e-300),
               NULL};
    f.out = pc_xopen_memstream(&text, &len);
    int h = (int)ceil((b[3] - b[1]) * f.k) + 40;
    pc_fprintf(
        f.out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
        "viewBox=\"0 0 %d %d\">\n<style>\n"
        ".curve { fill: none; stroke: #1f4e9c; stroke-width: 2 }\n"
        ".comb, .tooth { fill: none; stroke: #c0504d; stroke-width: 0.7 }\n"
        ".tangent { fill: none; stroke: #555; stroke-width: 1 }\n"
        ".point { fill: white; stroke: #000; stroke-width: 1.2 }\n"
        "</style>\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
        SVG_W, h, SVG_W, h);
    for (int c = 0; c < n; c++) {
        if (comb && scale > 0)
            draw_comb(&f, &curves[c].curve, scale);
        draw_curve(&f, &curves[c].curve);
        draw_points(&f, &curves[c], 0.06 * diag);
    }
    fputs("</svg>\n", f.out);
    pc_xclose_memstream(f.out);
    int rc = outfile_write(path, text, len, NULL, err);
    free(text);
    return rc;
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
    c_array(out, name, "start", start, (size_t)ns + 1);
    c_array(out, name, "scale", scale, (size_t)ns);
    c_array(out, name, "offset", off, (size_t)ns);
    c_array(out, name, "panels", np, (size_t)ns);
    c_array(out, name, "ncoef", nc, (size_t)ns);
    c_array(out, name, "cx", cx, total);
    c_array(out, name, "cy", cy, total);
    free(start);
    free(cx);
    free(cy);
}

/* the evaluator: $ is the name, # the segments' count */
static const char c_body[] =
    "\n/* the point at arc length s (clamped to the curve) */\n"
    "void $(double s, double p[2])\n{\n"
    "    int g = 0;\n"
    "    while (g + 1 < # && s >= $_start[g + 1])\n        g++;\n"
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
    free(text);
    return rc;
}
