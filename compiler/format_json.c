/*
 * format_json.c - the JSON form of derive's result (contract section 4).
 *
 * Every weight is format_weight's reduced, re-readable expression; names
 * are the scheme's identifiers, the scheme's name goes through
 * json_string (it may come from any file name).
 */
#include "compiler/format_json.h"

#include <stdlib.h>

#include "compiler/format.h"
#include "compiler/json.h"

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

static const char *kind_name(Kind k)
{
    return k == KIND_POINT ? "point" : k == KIND_VECTOR ? "vector" : "scalar";
}

/* "key": "WEIGHT" with w's reduced form */
static void json_weight(FILE *out, const char *key, const RatFun w,
                        const Derived *d)
{
    char *s = format_weight_k(w, &d->ring, d->kernels);
    json_string(out, key);
    fputs(": ", out);
    json_string(out, s);
    free(s);
}

/* {"name": "M", "kind": "point", "terms": {"A": "..", ..}} */
static void json_output(FILE *out, const Derived *d, const DerivedOutput *o)
{
    fputs("{\"name\": ", out);
    json_string(out, o->name);
    fprintf(out, ", \"kind\": \"%s\", ", kind_name(o->kind));
    if (o->kind == KIND_SCALAR) {
        json_weight(out, "value", o->scalar, d);
        fputs("}", out);
        return;
    }
    fputs("\"terms\": {", out);
    for (slong k = 0; k < o->eq->len; k++) {
        fputs(k ? ", " : "", out);
        json_weight(out, d->points[o->eq->terms[k].point], &o->w[k], d);
    }
    fputs("}}", out);
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
    for (slong i = 0; i < d->noutputs; i++) {
        fputs(i ? ",\n  " : "", out);
        json_output(out, d, &d->outputs[i]);
    }
    fputs("]}\n", out);
}
