/*
 * svgfig.c - a small SVG figure in user coordinates (svgfig.h).
 */
#include "driver/cli/svgfig.h"

#include <math.h>
#include <stdlib.h>

#include "base/mem.h"
#include "base/numfmt.h"
#include "driver/cli/outfile.h"

void svgfig_grow(double *b, double x, double y)
{
    if (!isfinite(x) || !isfinite(y))
        return;
    b[0] = fmin(b[0], x), b[1] = fmin(b[1], y);
    b[2] = fmax(b[2], x), b[3] = fmax(b[3], y);
}

void svgfig_begin(SvgFig *g, const double *box, const char *style)
{
    double b[4] = {box[0], box[1], box[2], box[3]};
    if (!(b[0] <= b[2]) || !(b[1] <= b[3]))
        b[0] = b[1] = -1, b[2] = b[3] = 1;
    double w = b[2] - b[0], h = b[3] - b[1], m = fmax(fmax(w, h), 1e-300);
    if (w < 1e-3 * m) // a vertical or horizontal figure keeps some width
        b[0] -= 0.05 * m, b[2] += 0.05 * m, w = b[2] - b[0];
    if (h < 1e-3 * m)
        b[1] -= 0.05 * m, b[3] += 0.05 * m, h = b[3] - b[1];
    g->x0 = b[0], g->y1 = b[3];
    g->k = (SVGFIG_WIDTH - 2 * SVGFIG_MARGIN) / w;
    int height = (int)ceil(h * g->k) + 2 * SVGFIG_MARGIN;
    g->text = NULL;
    g->len = 0;
    g->out = pc_xopen_memstream(&g->text, &g->len);
    pc_fprintf(g->out,
               "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" "
               "height=\"%d\" viewBox=\"0 0 %d %d\">\n<style>\n%s</style>\n"
               "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
               SVGFIG_WIDTH, height, SVGFIG_WIDTH, height, style);
}

static void put_xy(SvgFig *g, double x, double y)
{
    pc_fprintf(g->out, "%.2f,%.2f", SVGFIG_MARGIN + (x - g->x0) * g->k,
               SVGFIG_MARGIN + (g->y1 - y) * g->k);
}

void svgfig_line_begin(SvgFig *g, const char *cls)
{
    fprintf(g->out, "<polyline class=\"%s\" points=\"", cls);
}

void svgfig_line_to(SvgFig *g, double x, double y)
{
    if (!isfinite(x) || !isfinite(y))
        return;
    put_xy(g, x, y);
    fputc(' ', g->out);
}

void svgfig_line_end(SvgFig *g)
{
    fputs("\"/>\n", g->out);
}

void svgfig_segment(SvgFig *g, const char *cls, double x0, double y0, double x1,
                    double y1)
{
    svgfig_line_begin(g, cls);
    svgfig_line_to(g, x0, y0);
    svgfig_line_to(g, x1, y1);
    svgfig_line_end(g);
}

void svgfig_circle(SvgFig *g, const char *cls, double x, double y, double r)
{
    if (!isfinite(x) || !isfinite(y))
        return;
    pc_fprintf(g->out,
               "<circle class=\"%s\" r=\"%.2f\" cx=\"%.2f\" cy=\"%.2f\"/>\n",
               cls, r, SVGFIG_MARGIN + (x - g->x0) * g->k,
               SVGFIG_MARGIN + (g->y1 - y) * g->k);
}

int svgfig_end(SvgFig *g, const char *path, FILE *err)
{
    fputs("</svg>\n", g->out);
    pc_xclose_memstream(g->out);
    g->out = NULL;
    int rc = outfile_write(path, g->text, g->len, NULL, err);
    pc_free(g->text);
    g->text = NULL;
    return rc;
}
