/*
 * fit_data.c - a target given as data (`pointcalc fit --data FILE.csv`,
 * docs/fit.md): the natural cubic spline through x,y rows, and its exact
 * derivative, so that the fit is the same problem as for a function.
 *
 *   FILE.csv -> rows (an optional header, x increasing) -> the second
 *   derivatives m_k (tridiagonal, m_0 = m_n = 0) -> s(x), s'(x)
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/numfmt.h"
#include "driver/cli/fit.h"

enum { FIT_DATA_MAX_ROWS = 1000000, FIT_DATA_LINE = 4096 };

/* "x,y" (spaces around either allowed) into *x, *y; -1 when not that */
static int parse_row(const char *line, double *x, double *y)
{
    char *end, *end2;
    *x = pc_strtod(line, &end);
    if (end == line)
        return -1;
    end += strspn(end, " \t");
    if (*end != ',')
        return -1;
    *y = pc_strtod(end + 1, &end2);
    if (end2 == end + 1)
        return -1;
    end2 += strspn(end2, " \t\r\n");
    return *end2 || !isfinite(*x) || !isfinite(*y) ? -1 : 0;
}

/* the natural spline's second derivatives (Thomas algorithm) */
static void spline_solve(FitSpline *s)
{
    int n = s->n;
    double *c = pc_xcalloc((size_t)n, sizeof *c);
    s->m[0] = s->m[n - 1] = 0;
    for (int i = 1; i < n - 1; i++) {
        double h0 = s->x[i] - s->x[i - 1], h1 = s->x[i + 1] - s->x[i];
        double d =
            6 * ((s->y[i + 1] - s->y[i]) / h1 - (s->y[i] - s->y[i - 1]) / h0);
        double b = 2 * (h0 + h1) - h0 * c[i - 1];
        c[i] = h1 / b;
        s->m[i] = (d - h0 * s->m[i - 1]) / b;
    }
    for (int i = n - 2; i >= 1; i--)
        s->m[i] -= c[i] * s->m[i + 1];
    pc_free(c);
}

static int data_error(FILE *err, const char *path, long line, const char *why)
{
    if (line > 0)
        fprintf(err, "%s:%ld: error: %s\n", path, line, why);
    else
        fprintf(err, "%s: error: %s\n", path, why);
    return -1;
}

/* the rows of f into s; -1 after reporting */
static int read_rows(FitSpline *s, FILE *f, const char *path, FILE *err)
{
    char line[FIT_DATA_LINE];
    int cap = 0;
    long no = 0;
    while (fgets(line, sizeof line, f)) {
        double x, y;
        no++;
        if (!strchr(line, '\n') && !feof(f))
            return data_error(err, path, no, "line too long");
        if (!line[strspn(line, " \t\r\n")])
            continue;
        if (parse_row(line, &x, &y) != 0) {
            if (no == 1)
                continue; /* a header */
            return data_error(err, path, no,
                              "expected a row 'x,y' of two numbers");
        }
        if (s->n > 0 && !(x > s->x[s->n - 1]))
            return data_error(err, path, no, "x must increase from row to row");
        if (s->n == FIT_DATA_MAX_ROWS)
            return data_error(err, path, no, "too many rows");
        if (s->n == cap) {
            cap = cap ? 2 * cap : 64;
            s->x = pc_xrealloc(s->x, sizeof *s->x * (size_t)cap);
            s->y = pc_xrealloc(s->y, sizeof *s->y * (size_t)cap);
        }
        s->x[s->n] = x;
        s->y[s->n++] = y;
    }
    if (s->n < 3)
        return data_error(err, path, 0,
                          "expected at least 3 rows 'x,y' for a spline");
    return 0;
}

/* FILE.csv into its spline; NULL after reporting to err */
static FitSpline *fit_spline_read(const char *path, FILE *err)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(err, "%s: error: cannot open the file: %s\n", path,
                strerror(errno));
        return NULL;
    }
    FitSpline *s = pc_xcalloc(1, sizeof *s);
    int rc = read_rows(s, f, path, err);
    fclose(f);
    if (rc != 0) {
        fit_spline_free(s);
        return NULL;
    }
    s->m = pc_xmalloc(sizeof *s->m * (size_t)s->n);
    spline_solve(s);
    return s;
}

void fit_spline_free(FitSpline *s)
{
    if (!s)
        return;
    pc_free(s->x);
    pc_free(s->y);
    pc_free(s->m);
    pc_free(s);
}

size_t fit_spline_eval(const FitSpline *s, int o, size_t n, const double *x,
                       double *v, unsigned char *st)
{
    size_t bad = 0;
    for (size_t i = 0; i < n; i++) {
        double t = x[i];
        st[i] = 0;
        if (!(t >= s->x[0] && t <= s->x[s->n - 1])) {
            st[i] = 3;
            v[i] = NAN;
            bad++;
            continue;
        }
        int lo = 0, hi = s->n - 1; /* x[lo] <= t <= x[hi], hi = lo + 1 */
        while (hi - lo > 1) {
            int mid = (lo + hi) / 2;
            if (s->x[mid] <= t)
                lo = mid;
            else
                hi = mid;
        }
        double h = s->x[hi] - s->x[lo], a = (s->x[hi] - t) / h,
               b = (t - s->x[lo]) / h;
        if (o == 0)
            v[i] = a * s->y[lo] + b * s->y[hi] +
                   ((a * a * a - a) * s->m[lo] + (b * b * b - b) * s->m[hi]) *
                       h * h / 6;
        else
            v[i] = (s->y[hi] - s->y[lo]) / h -
                   (3 * a * a - 1) * h * s->m[lo] / 6 +
                   (3 * b * b - 1) * h * s->m[hi] / 6;
    }
    return bad;
}

int fit_target_data(FitTarget *t, const char *csv, FitOptions *o, FILE *err)
{
    memset(t, 0, sizeof *t);
    t->spline = fit_spline_read(csv, err);
    if (!t->spline)
        return -1;
    t->label = csv;
    const FitSpline *s = t->spline;
    if (isnan(o->lo))
        o->lo = s->x[0];
    if (isnan(o->hi))
        o->hi = s->x[s->n - 1];
    if (o->lo < s->x[0] || o->hi > s->x[s->n - 1]) {
        pc_fprintf(err,
                   "pointcalc: fit: the interval [%.9g, %.9g] must lie "
                   "within the data's [%.9g, %.9g] (%s)\n",
                   o->lo, o->hi, s->x[0], s->x[s->n - 1], csv);
        fit_spline_free(t->spline);
        t->spline = NULL;
        return -1;
    }
    return 0;
}
