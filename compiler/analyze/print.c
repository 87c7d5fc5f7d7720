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
    pc_fprintf(out, "  arc length: %.15g\n", c->length);
}

static void curve_text(FILE *out, const AnCurve *c, const Derived *d)
{
    if (c->skip) {
        fprintf(out, "%s: not analysed: %s\n", c->name, c->skip);
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
        fprintf(out, ", %s",
                c->dim <= 1   ? "a straight line"
                : c->dim == 2 ? "a plane curve"
                              : "a space curve");
    }
    fputs("\n", out);
    if (!c->bounded)
        fprintf(out,
                "  (no declared range: the ends are %s -> oo, s = "
                "1/%s)\n",
                t, t);
    for (slong i = 0; i < c->nends; i++)
        end_text(out, c, c->ends + i, d, t);
    if (c->kind == KIND_POINT) {
        fputs("  passes through: ", out);
        if (!c->npass)
            fputs("no base point", out);
        for (slong i = 0; i < c->npass; i++) {
            fprintf(out, "%s%s at %s = ", i ? "; " : "",
                    d->points[c->pass[i].point], t);
            for (slong k = 0; k < c->pass[i].t.n; k++) {
                fputs(k ? ", " : "", out);
                root_text(out, c->pass[i].t.v + k);
            }
        }
        fputs("\n", out);
    }
    roots_text(out, "poles", &c->poles, t);
    if (c->kind == KIND_POINT)
        roots_text(out, "stop points", &c->stops, t);
    if (c->has_infl)
        roots_text(out, "inflections", &c->infl, t);
    if (c->implicit)
        fprintf(out, "  implicit, in barycentric coordinates: %s = 0\n",
                c->implicit);
    metric_text(out, c, t);
}

void analyze_print_text(FILE *out, const Analysis *a)
{
    const Derived *d = a->d;
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
        if (r->v[i].exact)
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
    if (c->kind == KIND_POINT) {
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
    if (c->has_metric)
        metric_json(out, c);
    fputs("}", out);
}

void analyze_print_json(FILE *out, const Analysis *a)
{
    const Derived *d = a->d;
    fputs("{\"scheme\": ", out);
    json_string(out, d->scheme);
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
