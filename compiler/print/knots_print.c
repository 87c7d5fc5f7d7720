/*
 * knots_print.c - the knots of derive's outputs as text (derive --knots)
 * and as JSON (part of derive --format json); the analysis itself is
 * compiler/derive/knots.c, the meaning of every field knots.h and
 * docs/composite.md ("Knots and smoothness").
 *
 * Numbers and weights are written as format_weight_k writes weights:
 * exact, re-readable, abs(x) for x*sign(x).
 */
#include "compiler/print/knots_print.h"

#include <stdlib.h>
#include <string.h>

#include <flint/fmpq.h>

#include "base/json.h"
#include "base/mem.h"
#include "base/strbuf.h"
#include "compiler/print/format.h"
#include "compiler/print/format_int.h"

/* The jump of knot k of output o as a combination of base points, "6*B -
 * 6/5*O": each term a number times the point where the weight is a number,
 * else B*(w); a scalar's value.  Caller frees with pc_free(). */
static char *knots_jump_text(const Derived *d, const DerivedOutput *o,
                             const Knot *k)
{
    if (!k->jump)
        return pc_xstrdup("");
    if (o->kind == KIND_SCALAR)
        return format_weight_k(k->jump, &d->ring, d->kernels);
    StrBuf b = {0};
    fmpq_t q;
    fmpq_init(q);
    for (slong i = 0; i < k->njump; i++) {
        const RatFunStruct *w = k->jump + i;
        if (ratfun_is_zero(w, &d->ring))
            continue;
        const char *pt = d->points[o->eq->terms[i].point];
        if (ratfun_get_fmpq(q, w, &d->ring)) {
            int neg = fmpq_sgn(q) < 0;
            sb_puts(&b, b.len ? (neg ? " - " : " + ") : (neg ? "-" : ""));
            fmpq_abs(q, q);
            if (!fmpq_is_one(q)) {
                char *c = fmpq_get_str(NULL, 10, q);
                sb_puts(&b, c);
                sb_puts(&b, "*");
                flint_free(c);
            }
            sb_puts(&b, pt);
        } else {
            char *s = format_weight_k(w, &d->ring, d->kernels);
            sb_puts(&b, b.len ? " + " : "");
            sb_puts(&b, pt);
            sb_puts(&b, "*(");
            sb_puts(&b, s);
            sb_puts(&b, ")");
            pc_free(s);
        }
    }
    fmpq_clear(q);
    if (!b.len)
        sb_puts(&b, "0");
    return sb_take(&b);
}

/* the derivative of order j of output NAME by param T: "R", "dR/dt",
 * "d2R/dt2" */
static char *deriv_name(const char *name, const char *t, int j)
{
    if (j == 0)
        return pc_xstrdup(name);
    if (j == 1)
        return pc_xasprintf("d%s/d%s", name, t);
    return pc_xasprintf("d%d%s/d%s%d", j, name, t, j);
}

/* "R at t = 1: C^1, G^0; jump of d2R/dt2: 6*B - 6*O" */
static void print_knot(FILE *out, const Derived *d, const DerivedOutput *o,
                       const char *t, const Knot *k)
{
    char *at = format_weight_k(k->t, &d->ring, d->kernels);
    fprintf(out, "%s at %s = %s: ", o->name, t, at);
    pc_free(at);
    if (!k->analysed) {
        if (k->continuity >= 0)
            fprintf(out, "C^%d; derivative %d not analysed (%s)\n",
                    k->continuity, k->jump_order, k->why);
        else
            fprintf(out, "not analysed (%s)\n", k->why);
        return;
    }
    if (k->continuity < 0)
        fputs("not continuous", out);
    else
        fprintf(out, "C^%d%s", k->continuity, k->c_more ? " or more" : "");
    if (k->geometric >= 0)
        fprintf(out, ", G^%d%s", k->geometric, k->g_more ? " or more" : "");
    else if (k->geometric == -2)
        fprintf(out, ", G not decided (%s)", k->gwhy);
    if (k->jump) {
        char *dn = deriv_name(o->name, t, k->jump_order);
        char *j = knots_jump_text(d, o, k);
        fprintf(out, "; jump of %s: %s", dn, j);
        pc_free(j);
        pc_free(dn);
    }
    fputs("\n", out);
}

void knots_print(FILE *out, const Derived *d)
{
    for (slong o = 0; o < d->noutputs; o++) {
        const DerivedOutput *out_o = &d->outputs[o];
        KnotList L;
        knots_analyse(&L, d, o);
        const char *t = L.param >= 0 ? d->params[L.param] : NULL;
        for (slong i = 0; i < L.n; i++)
            print_knot(out, d, out_o, t, &L.k[i]);
        for (slong i = 0; i < L.nskip; i++)
            fprintf(out,
                    "%s: the zeros of %s are not analysed (only rational "
                    "zeros are, and those of an argument linear in %s whose "
                    "sign change is known)\n",
                    out_o->name, L.skip[i], t);
        if (L.note)
            fprintf(out, "%s: %s\n", out_o->name, L.note);
        else if (L.n == 0 && L.nskip == 0)
            fprintf(out, "%s: no knots\n", out_o->name);
        knots_clear(&L, d);
    }
}

static void json_knot(FILE *out, const Derived *d, const DerivedOutput *o,
                      const Knot *k)
{
    fputs("{", out);
    format_json_weight(out, "t", k->t, d, NULL);
    if (k->continuity >= 0 || k->analysed)
        fprintf(out, ", \"continuity\": %d", k->continuity);
    else
        fputs(", \"continuity\": null", out);
    if (k->c_more)
        fputs(", \"continuity_or_more\": true", out);
    if (k->analysed && k->geometric != -2)
        fprintf(out, ", \"geometric\": %d", k->geometric);
    else
        fputs(", \"geometric\": null", out);
    if (k->g_more)
        fputs(", \"geometric_or_more\": true", out);
    if (k->jump_order >= 0)
        fprintf(out, ", \"jump_order\": %d", k->jump_order);
    else
        fputs(", \"jump_order\": null", out);
    if (!k->jump) {
        fputs(", \"jump\": null", out);
    } else if (o->kind == KIND_SCALAR) {
        fputs(", ", out);
        format_json_weight(out, "jump", k->jump, d, NULL);
    } else {
        fputs(", \"jump\": {", out);
        int first = 1;
        for (slong i = 0; i < k->njump; i++) {
            if (ratfun_is_zero(k->jump + i, &d->ring))
                continue;
            fputs(first ? "" : ", ", out);
            format_json_weight(out, d->points[o->eq->terms[i].point],
                               k->jump + i, d, NULL);
            first = 0;
        }
        char *v = knots_jump_text(d, o, k);
        fputs("}, \"jump_vector\": ", out);
        json_string(out, v);
        pc_free(v);
    }
    if (!k->analysed) {
        fputs(", \"analysed\": false, \"note\": ", out);
        json_string(out, k->why);
    } else if (k->gwhy) {
        fputs(", \"geometric_note\": ", out);
        json_string(out, k->gwhy);
    }
    fputs("}", out);
}

void knots_json(FILE *out, const Derived *d, slong o)
{
    if (!knots_present(d, o))
        return;
    const DerivedOutput *out_o = &d->outputs[o];
    KnotList L;
    knots_analyse(&L, d, o);
    fputs(", \"knots\": [", out);
    for (slong i = 0; i < L.n; i++) {
        fputs(i ? ", " : "", out);
        json_knot(out, d, out_o, &L.k[i]);
    }
    fputs("]", out);
    if (L.nskip) {
        fputs(", \"knots_not_analysed\": [", out);
        for (slong i = 0; i < L.nskip; i++) {
            fputs(i ? ", " : "", out);
            json_string(out, L.skip[i]);
        }
        fputs("]", out);
    }
    if (L.note) {
        fputs(", \"knots_note\": ", out);
        json_string(out, L.note);
    }
    knots_clear(&L, d);
}
