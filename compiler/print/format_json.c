/*
 * format_json.c - the JSON form of derive's result (contract section 4).
 *
 * Every weight is format_weight's reduced, re-readable expression; names
 * are the scheme's identifiers, the scheme's name goes through
 * json_string (it may come from any file name).  An output that uses
 * abs() or sign() of its param also carries its "knots" (knots_print.h).
 */
#include "compiler/print/format_int.h"

#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/json.h"
#include "base/mem.h"
#include "compiler/print/book.h"
#include "compiler/print/format.h"
#include "compiler/print/knots_print.h"

/* "key": ["A","B"] */
static void json_names(FILE *out, const char *key, char *const *names, slong n)
{
    fprintf(out, "\"%s\": [", key);
    for (slong i = 0; i < n; i++) {
        fputs(i ? "," : "", out);
        json_string(out, names[i]);
    }
    fputs("]", out);
}

void format_json_weight(FILE *out, const char *key, const RatFun w,
                        const Derived *d, BookMemo *memo)
{
    FormatShare share = {d, memo};
    char *s = memo ? format_weight_share(w, &share)
                   : format_weight_k(w, &d->ring, d->kernels);
    json_string(out, key);
    fputs(": ", out);
    json_string(out, s);
    pc_free(s);
}

/* , "assumes": ["t >= 0", "e < 1"]: the ends of declared ranges the
 * output's derivation rested on (docs/language.md, "Declared ranges");
 * nothing when there are none */
static void json_assumes(FILE *out, const Derived *d, const DerivedOutput *o)
{
    int first = 1;
    for (slong v = 0; o->assumed && v < d->nparams + d->nconsts; v++)
        for (int upper = 0; upper < 2; upper++) {
            if (!(o->assumed[v] & (upper ? 2 : 1)))
                continue;
            int open = d->bound_flags[v] &
                       (upper ? DERIVED_BOUND_HI_OPEN : DERIVED_BOUND_LO_OPEN);
            char *b =
                format_weight_k(d->bound + 2 * v + upper, &d->ring, d->kernels);
            char *txt = pc_xasprintf(
                "%s %s %s",
                v < d->nparams ? d->params[v] : d->consts[v - d->nparams],
                upper ? (open ? "<" : "<=") : (open ? ">" : ">="), b);
            fputs(first ? ", \"assumes\": [" : ", ", out);
            json_string(out, txt);
            first = 0;
            pc_free(txt);
            pc_free(b);
        }
    if (!first)
        fputs("]", out);
}

/* {"name": "M", "kind": "point", "terms": {"A": "..", ..}} */
static void json_output(FILE *out, const Derived *d, const DerivedOutput *o,
                        BookMemo *memo)
{
    fputs("{\"name\": ", out);
    json_string(out, o->name);
    fprintf(out, ", \"kind\": \"%s\", ", kind_name(o->kind));
    if (o->kind == KIND_SCALAR) {
        format_json_weight(out, "value", o->scalar, d, memo);
    } else {
        fputs("\"terms\": {", out);
        for (slong k = 0; k < o->eq->len; k++) {
            fputs(k ? ", " : "", out);
            format_json_weight(out, d->points[o->eq->terms[k].point], &o->w[k],
                               d, memo);
        }
        fputs("}", out);
    }
    json_assumes(out, d, o);
    knots_json(out, d, o - d->outputs); /* the knots: knots_print.h */
    fputs("}", out);
}

/* ,\n "checks": [{"line": 12, "kind": "tangent", "verdict": "pass"}, ..]:
 * every check statement's verdict (compiler/check.h); "order" and "found"
 * for C, G, contact and order, "detail" (what differs) for a failed one;
 * nothing when the scheme has no check */
static void json_checks(FILE *out, const Derived *d)
{
    if (!d->nchecks)
        return;
    fputs(",\n \"checks\": [", out);
    for (slong i = 0; i < d->nchecks; i++) {
        const DerivedCheck *c = &d->checks[i];
        fprintf(out, "%s{\"line\": %d, \"kind\": \"%s\"", i ? ",\n  " : "",
                c->line, c->kind);
        if (strcmp(c->kind, "C") == 0 || strcmp(c->kind, "G") == 0 ||
            strcmp(c->kind, "contact") == 0 || strcmp(c->kind, "order") == 0)
            fprintf(out, ", \"order\": %d, \"found\": %d", c->order, c->found);
        fprintf(out, ", \"verdict\": \"%s\"",
                c->pass > 0    ? "pass"
                : c->pass == 0 ? "fail"
                               : "error");
        if (c->detail) {
            fputs(", \"detail\": ", out);
            json_string(out, c->detail);
        }
        fputs("}", out);
    }
    fputs("]", out);
}

void format_json(FILE *out, const Derived *d)
{
    fputs("{\"scheme\": ", out);
    json_string(out, d->scheme);
    fputs(", ", out);
    json_names(out, "points", d->points, d->npoints);
    fputs(", ", out);
    json_names(out, "params", d->params, d->nparams);
    fputs(", ", out);
    json_names(out, "consts", d->consts, d->nconsts);
    fputs(",\n \"outputs\": [", out);
    BookMemo *memo = book_memo_new(); /* the weights share factors */
    for (slong i = 0; i < d->noutputs; i++) {
        fputs(i ? ",\n  " : "", out);
        derived_mark(d, i); /* blamed if a budget runs out */
        json_output(out, d, &d->outputs[i], memo);
    }
    book_memo_free(memo, d);
    budget_statement(NULL, (Span){0, 0}); /* printed: no output to blame */
    fputs("]", out);
    json_checks(out, d);
    fputs("}\n", out);
}
