/*
 * table.c - eval's CSV and JSON writers (see table.h).
 *
 * Both walk the same columns: the grid's params, its swept consts, then
 * the selected outputs' coordinates.
 */
#include "driver/cli/table.h"

#include <math.h>

#include "base/json.h"
#include "base/numfmt.h"

int table_columns(const Plan *p, int o, int dim)
{
    return p->outputs[o].kind == KIND_SCALAR ? 1 : dim;
}

void table_number(FILE *out, double v, TableFormat f)
{
    if (f == TABLE_JSON)
        json_number(out, v);
    else if (isnan(v))
        fputs("nan", out);
    else if (isinf(v))
        fputs(v > 0 ? "inf" : "-inf", out);
    else
        pc_fprintf(out, "%.17g", v == 0 ? 0.0 : v); // never "-0"
}

/* the name of axis i of the grid and where its value is */
static const char *axis_name(const Plan *p, const EvalAxis *x)
{
    return x->param >= 0 ? p->params[x->param] : p->consts[x->cnst];
}

static double axis_value(const EvalAxis *x, const TableRow *r)
{
    return x->param >= 0 ? r->params[x->param] : r->consts[x->cnst];
}

/* ---- CSV -------------------------------------------------------------- */

/* column c of the grid's axes: the params first, then the swept consts
 * (the grid itself varies the consts slowest) */
static const EvalAxis *column_axis(const EvalSetup *s, int c)
{
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < s->naxes; i++)
            if ((s->axes[i].param >= 0) == (pass == 0) && c-- == 0)
                return &s->axes[i];
    return NULL;
}

static void csv_head(FILE *out, const Plan *p, const EvalSetup *s)
{
    const char *sep = "";
    for (int c = 0; c < s->naxes; c++, sep = ",")
        fprintf(out, "%s%s", sep, axis_name(p, column_axis(s, c)));
    for (int j = 0; j < s->nsel; j++) {
        const PlanOutput *o = &p->outputs[s->sel[j]];
        if (o->kind == KIND_SCALAR) {
            fprintf(out, "%s%s", sep, o->name);
            sep = ",";
            continue;
        }
        for (int c = 1; c <= s->dim; c++, sep = ",")
            fprintf(out, "%s%s.%d", sep, o->name, c);
    }
    fputc('\n', out);
}

static void csv_row(FILE *out, const Plan *p, const EvalSetup *s,
                    const TableRow *r)
{
    const char *sep = "";
    for (int c = 0; c < s->naxes; c++, sep = ",") {
        fputs(sep, out);
        table_number(out, axis_value(column_axis(s, c), r), TABLE_CSV);
    }
    for (int j = 0; j < s->nsel; j++) {
        int nc = table_columns(p, s->sel[j], s->dim);
        for (int c = 0; c < nc; c++, sep = ",") {
            fputs(sep, out);
            table_number(out, r->values[j][c], TABLE_CSV);
        }
    }
    fputc('\n', out);
}

/* ---- JSON ------------------------------------------------------------- */

/* "key": [the names of the axes of one sort] */
static void json_axis_names(FILE *out, const char *key, const Plan *p,
                            const EvalSetup *s, int params)
{
    const char *sep = "";
    fprintf(out, "\"%s\": [", key);
    for (int i = 0; i < s->naxes; i++) {
        if ((s->axes[i].param >= 0) != params)
            continue;
        fputs(sep, out);
        json_string(out, axis_name(p, &s->axes[i]));
        sep = ", ";
    }
    fputs("]", out);
}

static void json_head(FILE *out, const Plan *p, const EvalSetup *s)
{
    fputs("{\"scheme\": ", out);
    json_string(out, p->name);
    fputs(", ", out);
    json_axis_names(out, "params", p, s, 1);
    fputs(", ", out);
    json_axis_names(out, "consts", p, s, 0);
    fputs(", \"outputs\": [", out);
    for (int j = 0; j < s->nsel; j++) {
        const PlanOutput *o = &p->outputs[s->sel[j]];
        fputs(j ? ", " : "", out);
        fputs("{\"name\": ", out);
        json_string(out, o->name);
        fprintf(out, ", \"kind\": \"%s\", \"dim\": %d}", kind_name(o->kind),
                table_columns(p, s->sel[j], s->dim));
    }
    fputs("],\n \"samples\": [", out);
}

/* "key": {NAME: VALUE, ...} for the axes of one sort */
static void json_axis_values(FILE *out, const char *key, const Plan *p,
                             const EvalSetup *s, const TableRow *r, int params)
{
    const char *sep = "";
    fprintf(out, "\"%s\": {", key);
    for (int i = 0; i < s->naxes; i++) {
        const EvalAxis *x = &s->axes[i];
        if ((x->param >= 0) != params)
            continue;
        fputs(sep, out);
        json_string(out, axis_name(p, x));
        fputs(": ", out);
        json_number(out, axis_value(x, r));
        sep = ", ";
    }
    fputs("}", out);
}

/* "values": {"M": [x, y], "s": v} */
static void json_values(FILE *out, const Plan *p, const EvalSetup *s,
                        const TableRow *r)
{
    fputs("\"values\": {", out);
    for (int j = 0; j < s->nsel; j++) {
        const PlanOutput *o = &p->outputs[s->sel[j]];
        int nc = table_columns(p, s->sel[j], s->dim);
        fputs(j ? ", " : "", out);
        json_string(out, o->name);
        fputs(o->kind == KIND_SCALAR ? ": " : ": [", out);
        for (int c = 0; c < nc; c++) {
            fputs(c ? ", " : "", out);
            json_number(out, r->values[j][c]);
        }
        fputs(o->kind == KIND_SCALAR ? "" : "]", out);
    }
    fputs("}", out);
}

/* the sort of a status in JSON: 0 "poles", 1 "nonfinite", 2 "domain" */
static int status_sort(unsigned char st)
{
    return st == PLAN_STATUS_POLE ? 0 : st == PLAN_STATUS_DOMAIN ? 2 : 1;
}

/* , "poles": [..], "nonfinite": [..], "domain": [..], the empty ones left
 * out */
static void json_statuses(FILE *out, const Plan *p, const EvalSetup *s,
                          const TableRow *r)
{
    static const char *const keys[] = {"poles", "nonfinite", "domain"};
    for (int k = 0; k < 3; k++) {
        const char *sep = NULL;
        for (int j = 0; j < s->nsel; j++) {
            unsigned char st = r->status[j];
            if (st == PLAN_STATUS_OK || status_sort(st) != k)
                continue;
            if (!sep)
                fprintf(out, ", \"%s\": [", keys[k]);
            fputs(sep ? sep : "", out);
            json_string(out, p->outputs[s->sel[j]].name);
            sep = ", ";
        }
        if (sep)
            fputc(']', out);
    }
}

static void json_row(FILE *out, const Plan *p, const EvalSetup *s,
                     const TableRow *r, size_t index)
{
    fputs(index ? ",\n  {" : "\n  {", out);
    json_axis_values(out, "params", p, s, r, 1);
    fputs(", ", out);
    json_axis_values(out, "consts", p, s, r, 0);
    fputs(", ", out);
    json_values(out, p, s, r);
    json_statuses(out, p, s, r);
    fputc('}', out);
}

/* ---- either ----------------------------------------------------------- */

void table_head(FILE *out, TableFormat f, const Plan *p, const EvalSetup *s)
{
    if (f == TABLE_JSON)
        json_head(out, p, s);
    else
        csv_head(out, p, s);
}

void table_row(FILE *out, TableFormat f, const Plan *p, const EvalSetup *s,
               const TableRow *r, size_t index)
{
    if (f == TABLE_JSON)
        json_row(out, p, s, r, index);
    else
        csv_row(out, p, s, r);
}

void table_tail(FILE *out, TableFormat f, size_t rows)
{
    if (f == TABLE_JSON)
        fputs(rows ? "\n]}\n" : "]}\n", out);
}
