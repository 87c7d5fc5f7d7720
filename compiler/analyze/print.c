/*
 * print.c - the report of `analyze` (analyze.h): text for people, JSON
 * for programs (docs/analyze.md has both forms).  Parameter values are
 * exact text where they are exact ("1/2", "(1 - sqrt(5))/2"), else
 * numbers (%.17g: the isolating interval's midpoint).
 */
#include "compiler/analyze/analyze.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/mem.h"
#include "base/numfmt.h"
#include "base/strbuf.h"

/* ---- constant combinations of base points ------------------------------- */

/* "C - A", "(A + 2*C)/3": the weights w[0..npoints-1] over their least
 * common denominator, a positive term first */
static char *combo_text(const fmpq *w, const Derived *d)
{
    fmpz_t L, k;
    fmpz_init_set_ui(L, 1);
    fmpz_init(k);
    slong n = 0, firstpos = -1;
    for (slong i = 0; i < d->npoints; i++) {
        if (fmpq_is_zero(w + i))
            continue;
        fmpz_lcm(L, L, fmpq_denref(w + i));
        n++;
        if (firstpos < 0 && fmpq_sgn(w + i) > 0)
            firstpos = i;
    }
    StrBuf b = {0};
    int paren = !fmpz_is_one(L) && n > 1;
    if (paren)
        sb_puts(&b, "(");
    int started = 0;
    for (slong j = -1; j < d->npoints; j++) {
        slong i = j < 0 ? firstpos : j;
        if (i < 0 || (j >= 0 && i == firstpos) || fmpq_is_zero(w + i))
            continue;
        fmpz_divexact(k, L, fmpq_denref(w + i));
        fmpz_mul(k, k, fmpq_numref(w + i));
        if (started)
            sb_puts(&b, fmpz_sgn(k) < 0 ? " - " : " + ");
        else if (fmpz_sgn(k) < 0)
            sb_puts(&b, "-");
        fmpz_abs(k, k);
        if (!fmpz_is_one(k)) {
            sb_fmpz(&b, k);
            sb_puts(&b, "*");
        }
        sb_puts(&b, d->points[i]);
        started = 1;
    }
    if (!started)
        sb_puts(&b, "0");
    if (paren)
        sb_puts(&b, ")");
    if (!fmpz_is_one(L)) {
        sb_puts(&b, "/");
        sb_fmpz(&b, L);
    }
    fmpz_clear(k);
    fmpz_clear(L);
    return sb_take(&b);
}

static void combo_json(FILE *out, const fmpq *w, const Derived *d)
{
    fputs("{", out);
    int first = 1;
    for (slong i = 0; i < d->npoints; i++) {
        if (fmpq_is_zero(w + i))
            continue;
        char *s = fmpq_get_str(NULL, 10, w + i);
        fputs(first ? "" : ", ", out);
        json_string(out, d->points[i]);
        fputs(": ", out);
        json_string(out, s);
        flint_free(s);
        first = 0;
    }
    fputs("}", out);
}

/* "0.5*A + 0.5*B": numeric weights w[0..npoints-1] (%.15g), tiny ones
 * (below 1e-14 of the largest) left out */
static char *combo_num_text(const double *w, const Derived *d)
{
    double big = 0;
    for (slong i = 0; i < d->npoints; i++)
        big = fmax(big, fabs(w[i]));
    StrBuf b = {0};
    for (slong i = 0; i < d->npoints; i++) {
        if (fabs(w[i]) <= 1e-14 * big || w[i] == 0)
            continue;
        char num[40];
        pc_snprintf(num, sizeof num, "%.15g", fabs(w[i]));
        sb_puts(&b, b.len ? (w[i] < 0 ? " - " : " + ") : w[i] < 0 ? "-" : "");
        if (strcmp(num, "1") != 0) {
            sb_puts(&b, num);
            sb_puts(&b, "*");
        }
        sb_puts(&b, d->points[i]);
    }
    if (!b.len)
        sb_puts(&b, "0");
    return sb_take(&b);
}

static void combo_num_json(FILE *out, const double *w, const Derived *d)
{
    fputs("{", out);
    int first = 1;
    for (slong i = 0; i < d->npoints; i++) {
        if (w[i] == 0)
            continue;
        fputs(first ? "" : ", ", out);
        json_string(out, d->points[i]);
        fputs(": ", out);
        json_number(out, w[i]);
        first = 0;
    }
    fputs("}", out);
}

/* ---- text ---------------------------------------------------------------- */

static void root_text(FILE *out, const AnRoot *r)
{
    if (r->exact) {
        fputs(r->exact, out);
        if (r->exact[strspn(r->exact, "-0123456789/")])
            pc_fprintf(out, " = %.16g", r->value);
    } else
        pc_fprintf(out, "%.16g", r->value);
    if (r->mult > 1)
        pc_fprintf(out, " (multiplicity %ld)", (long)r->mult);
}

static void roots_text(FILE *out, const char *what, const AnRoots *r,
                       const char *param)
{
    fprintf(out, "  %s: ", what);
    if (!r->n)
        fputs("none", out);
    for (slong i = 0; i < r->n; i++) {
        if (r->v[i].mult == AN_RUN_START && i + 1 < r->n) {
            pc_fprintf(out, "%s%s in [%.16g, %.16g] (all of it)", i ? ", " : "",
                       param, r->v[i].value, r->v[i + 1].value);
            i++;
            continue;
        }
        fprintf(out, "%s%s = ", i ? ", " : "", param);
        root_text(out, r->v + i);
    }
    fputs("\n", out);
}

static void end_text(FILE *out, const AnCurve *c, const AnEnd *e,
                     const Derived *d, const char *param)
{
    char *p = combo_text(e->point, d);
    fprintf(out, "  %s = %s: ", param, e->t);
    if (e->infinite) {
        fprintf(out, "at infinity, in the direction %s\n", p);
        pc_free(p);
        return;
    }
    fprintf(out, "%s = %s", c->name, p);
    pc_free(p);
    if (e->tangent) {
        char *tg = combo_text(e->tangent, d);
        const char *var = e->t[0] == 'o' ? "s" : param;
        if (e->first == 1)
            fprintf(out, ", d%s/d%s = %s", c->name, var, tg);
        else
            fprintf(out,
                    ", d^%ld%s/d%s^%ld = %s (the lower derivatives "
                    "vanish)",
                    (long)e->first, c->name, var, (long)e->first, tg);
        pc_free(tg);
        if (e->parallel < 0)
            fputs(" (a straight line)", out);
        else
            fprintf(out, "; smoothness order %ld", (long)e->parallel);
    }
    fputs("\n", out);
}

/* a curvature, or "-" where M' = 0 */
static void kappa_text(FILE *out, double k)
{
    if (isnan(k))
        fputs("- (dM/dt = 0)", out);
    else
        pc_fprintf(out, "%.15g", k);
}

static void metric_text(FILE *out, const AnCurve *c, const char *t)
{
    if (c->metric_missing)
        fputs("  curvature, arc length: --at misses a point of it\n", out);
    if (!c->has_metric)
        return;
    fputs("  curvature at the ends: ", out);
    kappa_text(out, c->kappa_end[0]);
    fputs(", ", out);
    kappa_text(out, c->kappa_end[1]);
    fputs("\n", out);
    const char *what[2] = {"largest", "smallest"};
    for (int e = 0; e < 2; e++)
        if (c->has_kappa_ext[e])
            pc_fprintf(out, "  %s curvature: %.15g at %s = %.15g\n", what[e],
                       c->kappa_ext[e], t, c->kappa_ext_t[e]);
    if (isnan(c->length))
        fputs("  arc length: not found (|M'| varies too much over the range "
              "for 2^20 evaluations)\n",
              out);
    else
        pc_fprintf(out, "  arc length: %.15g\n", c->length);
}

/* what a curve found numerically is, in words */
static const char *nature_text(const char *nature)
{
    if (strcmp(nature, "transcendental") == 0)
        return "transcendental: no degree or order";
    if (strcmp(nature, "algebraic") == 0)
        return "not rational (roots): degree and order not found";
    if (strcmp(nature, "piecewise") == 0)
        return "piecewise (abs): no single degree or order";
    return "with distances of the base points: degree and order not found";
}

static const char *dim_text(slong dim)
{
    return dim <= 1   ? "a straight line"
           : dim == 2 ? "a plane curve"
                      : "a space curve";
}

static void num_end_text(FILE *out, const AnCurve *c, const AnEnd *e,
                         const Derived *d, const char *param)
{
    if (!e->num) {
        fprintf(out,
                "  %s = %s: no finite point (a pole, or outside a "
                "function's domain)\n",
                param, e->t);
        return;
    }
    char *p = combo_num_text(e->num, d);
    pc_fprintf(out, "  %s = %s: %s = %s", param, e->t, c->name, p);
    pc_free(p);
    if (e->num_tan) {
        char *tg = combo_num_text(e->num_tan, d);
        if (e->first == 1)
            fprintf(out, ", d%s/d%s = %s", c->name, param, tg);
        else
            fprintf(out, ", d^2%s/d%s^2 = %s (d%s/d%s = 0)", c->name, param, tg,
                    c->name, param);
        pc_free(tg);
    }
    fputs("\n", out);
}

static void passes_text(FILE *out, const AnCurve *c, const Derived *d,
                        const char *t)
{
    fputs("  passes through: ", out);
    if (!c->npass)
        fputs("no base point", out);
    for (slong i = 0; i < c->npass; i++) {
        fprintf(out, "%s%s at %s = ", i ? "; " : "",
                d->points[c->pass[i].point], t);
        const AnRoots *r = &c->pass[i].t;
        for (slong k = 0; k < r->n; k++) {
            fputs(k ? ", " : "", out);
            if (r->v[k].mult == AN_RUN_START && k + 1 < r->n) {
                pc_fprintf(out, "[%.16g, %.16g] (all of it)", r->v[k].value,
                           r->v[k + 1].value);
                k++;
            } else
                root_text(out, r->v + k);
        }
    }
    fputs("\n", out);
}

/* a curve with functions, found numerically (AnCurve.numeric) */
static void num_curve_text(FILE *out, const AnCurve *c, const Derived *d)
{
    const char *t = d->ring.names[c->param];
    fprintf(out, "%s: a %s curve in %s", c->name,
            c->kind == KIND_POINT ? "point" : "vector", t);
    if (c->bounded && c->num_done)
        pc_fprintf(out, " in [%.15g, %.15g]", c->num_lo, c->num_hi);
    fprintf(out, ", %s", nature_text(c->nature));
    if (c->num_done && c->kind == KIND_POINT)
        fprintf(out, ", %s", dim_text(c->dim));
    fprintf(out, "; it has %s\n", c->functions);
    if (!c->num_done) {
        fprintf(out, "  not evaluated: %s\n",
                c->num_why ? c->num_why : "no numeric analysis was run");
        return;
    }
    pc_fprintf(
        out, "  found numerically (to 1e-15) over %s in [%.15g, %.15g]%s\n", t,
        c->num_lo, c->num_hi, c->bounded ? "" : " (no declared range)");
    if (!isnan(c->undefined[0]))
        pc_fprintf(out,
                   "  undefined (a function's domain) between %s = "
                   "%.15g and %.15g\n",
                   t, c->undefined[0], c->undefined[1]);
    for (slong i = 0; i < c->nends; i++)
        num_end_text(out, c, c->ends + i, d, t);
    if (c->kind == KIND_POINT)
        passes_text(out, c, d, t);
    roots_text(out, "poles", &c->poles, t);
    if (c->kind == KIND_POINT)
        roots_text(out, "stop points", &c->stops, t);
    if (c->has_infl)
        roots_text(out, "inflections", &c->infl, t);
    metric_text(out, c, t);
}

static void curve_text(FILE *out, const AnCurve *c, const Derived *d)
{
    if (c->skip) {
        fprintf(out, "%s: not analysed: %s\n", c->name, c->skip);
        return;
    }
    if (c->numeric) {
        num_curve_text(out, c, d);
        return;
    }
    const char *t = d->ring.names[c->param];
    fprintf(out, "%s: %s curve in %s", c->name,
            c->kind == KIND_POINT ? "a point" : "a vector", t);
    if (c->bounded)
        fprintf(out, " in [%s, %s]", c->ends[0].t, c->ends[1].t);
    fprintf(out, ", degree %ld", (long)c->degree);
    if (c->kind == KIND_POINT) {
        fprintf(out, ", order %ld, ", (long)c->order);
        if (c->index == 1)
            fputs("proper", out);
        else
            fprintf(out, "traced %ld times", (long)c->index);
        fprintf(out, ", %s", dim_text(c->dim));
    }
    fputs("\n", out);
    if (!c->bounded)
        fprintf(out,
                "  (no declared range: the ends are %s -> oo, s = "
                "1/%s)\n",
                t, t);
    for (slong i = 0; i < c->nends; i++)
        end_text(out, c, c->ends + i, d, t);
    if (c->kind == KIND_POINT)
        passes_text(out, c, d, t);
    roots_text(out, "poles", &c->poles, t);
    if (c->kind == KIND_POINT)
        roots_text(out, "stop points", &c->stops, t);
    if (c->has_infl)
        roots_text(out, "inflections", &c->infl, t);
    if (c->implicit)
        fprintf(out, "  implicit, in barycentric coordinates: %s = 0\n",
                c->implicit);
    if (c->implicit_xy)
        fprintf(out, "  implicit, in Cartesian coordinates (x, y): %s = 0\n",
                c->implicit_xy);
    metric_text(out, c, t);
}

/* the consts analysed at their generic value (no --set), "" if none */
static char *generic_consts(const Analysis *a)
{
    StrBuf b = {0};
    for (slong k = 0; k < a->d->nconsts; k++) {
        if (a->cgiven[k] || !a->cused[k])
            continue;
        sb_puts(&b, b.len ? ", " : "");
        sb_puts(&b, a->d->consts[k]);
        sb_puts(&b, " = ");
        char *s = fmpq_get_str(NULL, 10, a->cvalue + k);
        sb_puts(&b, s);
        flint_free(s);
    }
    if (!b.len)
        sb_puts(&b, "");
    return sb_take(&b);
}

void analyze_print_text(FILE *out, const Analysis *a)
{
    const Derived *d = a->d;
    char *g = generic_consts(a);
    if (*g)
        fprintf(out,
                "consts without --set, at generic values: %s (what holds "
                "for all values but a few: degree, order, dim; the rest is "
                "for these values)\n",
                g);
    pc_free(g);
    for (slong i = 0; i < a->ncurves; i++)
        curve_text(out, a->curves + i, d);
    int any = 0;
    for (slong i = 0; i < a->ndefs; i++) {
        const AnDef *f = a->defs + i;
        if (!f->poles.n)
            continue;
        if (!any)
            fputs("poles of the definitions in their param's range:\n", out);
        any = 1;
        fprintf(out, "  %s (line %d): ", f->name, f->line);
        for (slong k = 0; k < f->poles.n; k++) {
            fprintf(out, "%s%s = ", k ? ", " : "", d->ring.names[f->param]);
            root_text(out, f->poles.v + k);
        }
        fputs("\n", out);
    }
    if (a->ndefs && !any)
        fputs("no definition has a pole in its param's range\n", out);
}

/* ---- JSON ---------------------------------------------------------------- */

static void roots_json(FILE *out, const AnRoots *r)
{
    fputs("[", out);
    for (slong i = 0; i < r->n; i++) {
        fputs(i ? ", " : "", out);
        if (r->v[i].mult == AN_RUN_START && i + 1 < r->n) {
            fputs("[", out);
            json_number(out, r->v[i].value);
            fputs(", ", out);
            json_number(out, r->v[++i].value);
            fputs("]", out);
        } else if (r->v[i].exact)
            json_string(out, r->v[i].exact);
        else
            json_number(out, r->v[i].value);
    }
    fputs("]", out);
}

static void end_json(FILE *out, const AnEnd *e, const Derived *d)
{
    fputs("{\"t\": ", out);
    json_string(out, e->t);
    fprintf(out, ", \"infinite\": %s, \"%s\": ", e->infinite ? "true" : "false",
            e->infinite ? "direction" : "point");
    combo_json(out, e->point, d);
    if (e->tangent) {
        fprintf(out, ", \"derivative_order\": %ld, \"derivative\": ",
                (long)e->first);
        combo_json(out, e->tangent, d);
        fputs(", \"smoothness\": ", out);
        if (e->parallel < 0)
            fputs("null", out);
        else
            fprintf(out, "%ld", (long)e->parallel);
    }
    fputs("}", out);
}

/* a number, null for NAN */
static void number_or_null(FILE *out, double v)
{
    if (isnan(v))
        fputs("null", out);
    else
        json_number(out, v);
}

static void metric_json(FILE *out, const AnCurve *c)
{
    fputs(", \"curvature_ends\": [", out);
    number_or_null(out, c->kappa_end[0]);
    fputs(", ", out);
    number_or_null(out, c->kappa_end[1]);
    fputs("], \"curvature_max\": ", out);
    number_or_null(out, c->has_kappa_ext[0] ? c->kappa_ext[0] : NAN);
    fputs(", \"curvature_max_at\": ", out);
    number_or_null(out, c->has_kappa_ext[0] ? c->kappa_ext_t[0] : NAN);
    fputs(", \"curvature_min\": ", out);
    number_or_null(out, c->has_kappa_ext[1] ? c->kappa_ext[1] : NAN);
    fputs(", \"curvature_min_at\": ", out);
    number_or_null(out, c->has_kappa_ext[1] ? c->kappa_ext_t[1] : NAN);
    fputs(", \"arc_length\": ", out);
    json_number(out, c->length);
}

static void passes_json(FILE *out, const AnCurve *c, const Derived *d)
{
    fputs(", \"passes\": [", out);
    for (slong i = 0; i < c->npass; i++) {
        fputs(i ? ", " : "", out);
        fputs("{\"point\": ", out);
        json_string(out, d->points[c->pass[i].point]);
        fputs(", \"t\": ", out);
        roots_json(out, &c->pass[i].t);
        fputs("}", out);
    }
    fputs("]", out);
}

/* the rest of a curve found numerically, after its name and kind */
static void num_curve_json(FILE *out, const AnCurve *c, const Derived *d)
{
    fputs(", \"param\": ", out);
    json_string(out, d->ring.names[c->param]);
    fputs(", \"numeric\": true, \"functions\": ", out);
    json_string(out, c->functions);
    fputs(", \"degree\": ", out);
    json_string(out, c->nature);
    fputs(", \"order\": ", out);
    json_string(out, c->nature);
    if (!c->num_done) {
        fputs(", \"skipped\": ", out);
        json_string(out, c->num_why ? c->num_why : "not evaluated");
        fputs(", \"poles\": null, \"stop_points\": null, "
              "\"inflections\": null}",
              out);
        return;
    }
    fputs(", \"range\": [", out);
    json_number(out, c->num_lo);
    fputs(", ", out);
    json_number(out, c->num_hi);
    fputs("], \"undefined\": ", out);
    if (isnan(c->undefined[0]))
        fputs("null", out);
    else {
        fputs("[", out);
        json_number(out, c->undefined[0]);
        fputs(", ", out);
        json_number(out, c->undefined[1]);
        fputs("]", out);
    }
    if (c->kind == KIND_POINT)
        fprintf(out, ", \"dim\": %ld", (long)c->dim);
    fputs(", \"poles\": ", out);
    roots_json(out, &c->poles);
    fputs(", \"stop_points\": ", out);
    if (c->kind == KIND_POINT)
        roots_json(out, &c->stops);
    else
        fputs("null", out);
    fputs(", \"inflections\": ", out);
    if (c->has_infl)
        roots_json(out, &c->infl);
    else
        fputs("null", out);
    if (c->kind == KIND_POINT)
        passes_json(out, c, d);
    fputs(", \"ends\": [", out);
    for (slong i = 0; i < c->nends; i++) {
        const AnEnd *e = c->ends + i;
        fputs(i ? ", {\"t\": " : "{\"t\": ", out);
        json_string(out, e->t);
        if (!e->num) { /* no finite point there */
            fputs(", \"infinite\": true, \"point\": null}", out);
            continue;
        }
        fputs(", \"infinite\": false, \"point\": ", out);
        combo_num_json(out, e->num, d);
        if (e->num_tan) {
            fprintf(out, ", \"derivative_order\": %ld, \"derivative\": ",
                    (long)e->first);
            combo_num_json(out, e->num_tan, d);
        }
        fputs("}", out);
    }
    fputs("], \"implicit\": null", out);
    if (c->has_metric)
        metric_json(out, c);
    fputs("}", out);
}

static void curve_json(FILE *out, const AnCurve *c, const Derived *d)
{
    fputs("{\"name\": ", out);
    json_string(out, c->name);
    fprintf(out, ", \"kind\": \"%s\"", kind_name(c->kind));
    if (c->skip) { /* the keys every output has, null */
        fputs(", \"skipped\": ", out);
        json_string(out, c->skip);
        fputs(", \"degree\": null, \"poles\": null, \"stop_points\": null, "
              "\"inflections\": null}",
              out);
        return;
    }
    if (c->numeric) {
        num_curve_json(out, c, d);
        return;
    }
    fputs(", \"param\": ", out);
    json_string(out, d->ring.names[c->param]);
    fprintf(out, ", \"degree\": %ld", (long)c->degree);
    if (c->kind == KIND_POINT)
        fprintf(out,
                ", \"order\": %ld, \"index\": %ld, \"proper\": %s, "
                "\"dim\": %ld",
                (long)c->order, (long)c->index,
                c->index == 1 ? "true" : "false", (long)c->dim);
    fputs(", \"poles\": ", out);
    roots_json(out, &c->poles);
    fputs(", \"stop_points\": ", out);
    if (c->kind == KIND_POINT)
        roots_json(out, &c->stops);
    else
        fputs("null", out);
    fputs(", \"inflections\": ", out);
    if (c->has_infl)
        roots_json(out, &c->infl);
    else
        fputs("null", out);
    if (c->kind == KIND_POINT)
        passes_json(out, c, d);
    fputs(", \"ends\": [", out);
    for (slong i = 0; i < c->nends; i++) {
        fputs(i ? ", " : "", out);
        end_json(out, c->ends + i, d);
    }
    fputs("], \"implicit\": ", out);
    if (c->implicit_j)
        json_string(out, c->implicit_j);
    else
        fputs("null", out);
    if (c->implicit_xy_j) {
        fputs(", \"implicit_xy\": ", out);
        json_string(out, c->implicit_xy_j);
    }
    if (c->has_metric)
        metric_json(out, c);
    fputs("}", out);
}

void analyze_print_json(FILE *out, const Analysis *a)
{
    const Derived *d = a->d;
    fputs("{\"scheme\": ", out);
    json_string(out, d->scheme);
    fputs(", \"generic_consts\": {", out);
    for (slong k = 0, n = 0; k < d->nconsts; k++) {
        if (a->cgiven[k] || !a->cused[k])
            continue;
        fputs(n++ ? ", " : "", out);
        json_string(out, d->consts[k]);
        char *s = fmpq_get_str(NULL, 10, a->cvalue + k);
        fputs(": ", out);
        json_string(out, s);
        flint_free(s);
    }
    fputs("}", out);
    fputs(", \"outputs\": [", out);
    for (slong i = 0; i < a->ncurves; i++) {
        fputs(i ? ",\n  " : "\n  ", out);
        curve_json(out, a->curves + i, d);
    }
    fputs("],\n \"definitions\": [", out);
    for (slong i = 0; i < a->ndefs; i++) {
        const AnDef *f = a->defs + i;
        fputs(i ? ",\n  " : "\n  ", out);
        fputs("{\"name\": ", out);
        json_string(out, f->name);
        fprintf(out, ", \"line\": %d, \"param\": ", f->line);
        json_string(out, d->ring.names[f->param]);
        fputs(", \"poles\": ", out);
        roots_json(out, &f->poles);
        fputs("}", out);
    }
    fputs("]}\n", out);
}
