/*
 * svgfig.h - a small SVG figure in user coordinates, for the pictures of
 * `natural --plot` and `fit --plot` (plot's own figures are runtime/svg.c,
 * which draws Plans).  The figure is built in memory and written whole
 * through outfile_write (driver/cli/outfile.h): a failure leaves no file.
 *
 *   SvgFig g;  svgfig_begin(&g, box, style);
 *   svgfig_line_begin(&g, "curve"); svgfig_line_to(&g, x, y) ...;
 *   svgfig_line_end(&g);  svgfig_circle(&g, "point", x, y, r);
 *   svgfig_end(&g, path, err)
 *
 * Coordinates: box = {xmin, ymin, xmax, ymax} maps to SVGFIG_WIDTH pixels
 * across (the aspect kept, y up) inside a 20-pixel margin; every number
 * is written with two decimals in the C locale.
 */
#ifndef PC_SVGFIG_H
#define PC_SVGFIG_H

#include <stddef.h>
#include <stdio.h>

enum { SVGFIG_WIDTH = 720, SVGFIG_MARGIN = 20 };

typedef struct SvgFig {
    double x0, y1, k; // the box's left and top, pixels per unit
    FILE *out;        // the memory stream
    char *text;
    size_t len;
} SvgFig;

/* box: the user coordinates to show (a degenerate box is widened);
 * style: the <style> sheet's rules */
void svgfig_begin(SvgFig *g, const double *box, const char *style);
void svgfig_line_begin(SvgFig *g, const char *cls);
void svgfig_line_to(SvgFig *g, double x, double y);
void svgfig_line_end(SvgFig *g);
/* a segment of its own (a tooth, a tangent) */
void svgfig_segment(SvgFig *g, const char *cls, double x0, double y0, double x1,
                    double y1);
void svgfig_circle(SvgFig *g, const char *cls, double x, double y, double r);
/* closes the document and writes it to path; 0, or 1 after a message */
int svgfig_end(SvgFig *g, const char *path, FILE *err);

/* grows box {xmin, ymin, xmax, ymax} to hold (x, y); a box starts as
 * {INFINITY, INFINITY, -INFINITY, -INFINITY} */
void svgfig_grow(double *box, double x, double y);

#endif
