/*
 * emit_weights.c - one output as C from its Plan registers: the
 * straight-line NAME_M_checked and the block-wise NAME_M_batch_checked
 * (emit_c.c holds the overview; docs/codegen.md, "Batch code").
 *
 * Every Plan register that an output needs becomes one `const double rN`
 * with a comment naming the scheme line it comes from; constants and inputs
 * are written inline.  The batch function works in blocks of BLOCK
 * samples: uniform registers once per call, then per block the params
 * copied (the tail padded), the peeled weights into w0[], w1[] ... by a
 * fixed-length loop that gcc -O2 vectorises, and the rows summed from
 * them, specialised for dim 2 and 3.  It sits after lower.c (which made
 * the Plan) and is called by emit_c_kernel once per output.
 */
#include "base/mem.h"
#include "codegen/emit_c_int.h"

#include <stdlib.h>
#include <string.h>

void emit_operand(const Ctx *C, int r)
{
    const PlanIns *x = &C->p->ins[r];
    if (x->op == PLAN_CONST)
        cwrite_double(C->out, C->p->k[x->a]);
    else if (x->op == PLAN_INPUT && C->batch && x->a < C->p->nparams)
        fprintf(C->out, "x%d", x->a);
    else if (x->op == PLAN_INPUT)
        fputs(C->N->in[x->a], C->out);
    else
        fprintf(C->out, "r%d", r);
}

/* const double rN = EXPR;  line comment */
static void instruction(const Ctx *C, int r, const char *indent)
{
    const PlanIns *x = &C->p->ins[r];
    FILE *out = C->out;
    fprintf(out, "%sconst double r%d = ", indent, r);
    switch ((PlanOp)x->op) {
    case PLAN_NEG:
        fputc('-', out);
        emit_operand(C, x->a);
        break;
    case PLAN_ADD:
    case PLAN_SUB:
    case PLAN_MUL:
    case PLAN_DIV:
        emit_operand(C, x->a);
        fprintf(out, " %s ",
                x->op == PLAN_ADD   ? "+"
                : x->op == PLAN_SUB ? "-"
                : x->op == PLAN_MUL ? "*"
                                    : "/");
        emit_operand(C, x->b);
        break;
    case PLAN_POWI:
        fputs("pow(", out);
        emit_operand(C, x->a);
        fprintf(out, ", %d.0)", x->b);
        break;
    case PLAN_FN: {
        int f = x->b & 255, q = x->b >> 8;
        static const char *const cfn[PLAN_NFNS] = {
#define PC_FUNCTION(ID, name, ar, lang, k, p, c, latex, dom)                   \
    PC_WHEN(p)([PLAN_FN_##ID] = c, )
#include "base/functions.def"
#undef PC_FUNCTION
        };
        if (f == PLAN_FN_SIGN) {
            /* quiet comparisons only: gcc does not if-convert x > 0.0
             * under the default -ftrapping-math, and the sample loop of a
             * composite curve (a sign per knot) would stay scalar at -O2;
             * copysign is a bit operation.  sign(+-0) = +-0 */
            fputs("copysign((double)(", out);
            emit_operand(C, x->a);
            fputs(" != 0.0), ", out);
            emit_operand(C, x->a);
            fputs(")", out);
        } else if (f == PLAN_FN_ROOT && q == 3) {
            fputs("cbrt(", out);
            emit_operand(C, x->a);
            fputs(")", out);
        } else if (f == PLAN_FN_ROOT && q % 2) { /* odd: real root */
            fputs("(", out);
            emit_operand(C, x->a);
            fputs(" < 0.0 ? -pow(-", out);
            emit_operand(C, x->a);
            fprintf(out, ", 1.0 / %d.0) : pow(", q);
            emit_operand(C, x->a);
            fprintf(out, ", 1.0 / %d.0))", q);
        } else if (f == PLAN_FN_ROOT) {
            fputs("pow(", out);
            emit_operand(C, x->a);
            fprintf(out, ", 1.0 / %d.0)", q);
        } else {
            fprintf(out, "%s(", cfn[f]);
            emit_operand(C, x->a);
            fputs(")", out);
        }
        break;
    }
    case PLAN_DIST:
        fprintf(out, "pcdist_%s(%s, %s, dim)", C->N->prefix, C->N->pt[x->a],
                C->N->pt[x->b]);
        break;
    case PLAN_COORD: /* coord(P, k): NaN when dim < k (docs/codegen.md) */
        fprintf(out, "(dim > %d ? %s[%d] : (double)NAN)", x->b, C->N->pt[x->a],
                x->b);
        break;
    case PLAN_NATX:
    case PLAN_NATY:
        emit_natural_call(C, x);
        break;
    case PLAN_ISNAN:
        fputs("(double)(isnan(", out);
        emit_operand(C, x->a);
        fputs(") != 0)", out);
        break;
    case PLAN_ATAN2:
        fputs("atan2(", out);
        emit_operand(C, x->a);
        fputs(", ", out);
        emit_operand(C, x->b);
        fputs(")", out);
        break;
    case PLAN_DOMAIN: { /* the argument outside the function's domain */
        PcDomain dom = plan_fn_domain_of(x->b);
        fputs("(double)(", out);
        if (dom == PC_DOM_UNIT) {
            fputs("fabs(", out);
            emit_operand(C, x->a);
            fputs(") > 1.0)", out);
        } else {
            emit_operand(C, x->a);
            fputs(dom == PC_DOM_POS ? " <= 0.0)" : " < 0.0)", out);
        }
        break;
    }
    case PLAN_POLE: /* not ?: - gcc does not if-convert that under the
                       default -ftrapping-math, and the loop would stay
                       scalar */
        fputs("(double)(", out);
        emit_operand(C, x->a);
        fputs(" == 0.0)", out);
        break;
    default:
        break;
    }
    fprintf(out, "; /* line %d", x->line);
    if (C->role[r])
        fprintf(out, ": %s", C->role[r]);
    fputs(" */\n", out);
}

/* every needed computing instruction whose uniformity is `uniform` (or
 * all of them when uniform < 0) */
void emit_instructions(const Ctx *C, int uniform, const char *indent)
{
    for (int r = 0; r < C->p->nins; r++) {
        const PlanIns *x = &C->p->ins[r];
        if (!C->live[r] || x->op == PLAN_CONST || x->op == PLAN_INPUT)
            continue;
        if (uniform >= 0 && x->uniform != uniform)
            continue;
        instruction(C, r, indent);
    }
}

static int uses_point(const PlanOutput *o, int point)
{
    for (int k = 0; k < o->nterms; k++)
        if (o->point[k] == point)
            return 1;
    return 0;
}

/* (void)X; for every argument this output does not read */
static void unused_args(const Ctx *C)
{
    const Plan *p = C->p;
    for (int i = 0; i < C->N->nin; i++) {
        int used = 0;
        for (int r = 0; r < p->nins && !used; r++)
            used = C->live[r] && p->ins[r].op == PLAN_INPUT && p->ins[r].a == i;
        if (!used)
            fprintf(C->out, "    (void)%s;\n", C->N->in[i]);
    }
    int dist = 0; /* distances and coordinates read points and dim */
    for (int r = 0; r < p->nins; r++)
        dist |= C->live[r] &&
                (p->ins[r].op == PLAN_DIST || p->ins[r].op == PLAN_COORD);
    for (int i = 0; i < C->N->npt; i++) {
        int used = C->o->kind != KIND_SCALAR && uses_point(C->o, i);
        for (int r = 0; r < p->nins && !used; r++)
            used = C->live[r] &&
                   ((p->ins[r].op == PLAN_DIST &&
                     (p->ins[r].a == i || p->ins[r].b == i)) ||
                    (p->ins[r].op == PLAN_COORD && p->ins[r].a == i));
        if (!used)
            fprintf(C->out, "    (void)%s;\n", C->N->pt[i]);
    }
    if (C->o->kind == KIND_SCALAR && !dist)
        fputs("    (void)dim;\n", C->out);
}

/* the weight expression of slot k: its register or an inline operand */
static void weight(const Ctx *C, int k)
{
    emit_operand(C, C->o->reg[k]);
}

/* int NAME_M_checked(...): straight-line weights, then the coordinates */
void emit_one(const Ctx *C)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    emit_signature(out, C->p, C->N, C->oi, ONE_CHECKED);
    fputs("\n{\n", out);
    unused_args(C);
    if (o->kind != KIND_SCALAR)
        fputs("    int c;\n", out);
    emit_instructions(C, -1, "    ");
    if (o->bad >= 0) {
        fputs("    if (", out);
        emit_operand(C, o->bad);
        fputs(" != 0.0) { /* a denominator vanishes or overflows */\n", out);
        if (o->kind == KIND_SCALAR)
            fputs("        out[0] = (double)NAN;\n", out);
        else
            fputs("        for (c = 0; c < dim; c++)\n"
                  "            out[c] = (double)NAN;\n",
                  out);
        fputs("        return ", out);
        if (uses_domain(C)) {
            emit_operand(C, o->bad);
            fputs(" >= 1048576.0 ? 4 : ", out);
        }
        emit_operand(C, o->bad);
        fputs(" >= 1.0 ? 1 : 2; /* 1 pole, 2 overflow", out);
        fputs(uses_domain(C) ? ", 4 domain */\n    }\n" : " */\n    }\n", out);
    }
    if (o->kind == KIND_SCALAR) {
        fputs("    out[0] = ", out);
        weight(C, 0);
        fputs(";\n", out);
        /* x - x is 0 unless x is NaN or infinite */
        fputs("    if (!(out[0] - out[0] == 0.0)) { /* not finite: a NaN "
              "input, or beyond double */\n"
              "        out[0] = (double)NAN;\n"
              "        return 3;\n"
              "    }\n",
              out);
    } else {
        fputs("    for (c = 0; c < dim; c++)\n        out[c] = ", out);
        if (o->nterms == 0)
            fputs("0.0", out);
        for (int k = 0; k < o->nterms; k++) {
            if (k)
                fputs("\n                 + ", out);
            weight(C, k);
            fprintf(out, " * %s[c]", C->N->pt[o->point[k]]);
        }
        fputs(";\n", out);
        fputs("    for (c = 0; c < dim; c++)\n"
              "        if (!(out[c] - out[c] == 0.0)) { /* not finite: a NaN "
              "input, or beyond double */\n"
              "            for (c = 0; c < dim; c++)\n"
              "                out[c] = (double)NAN;\n"
              "            return 3;\n"
              "        }\n",
              out);
    }
    fputs("    return 0;\n}\n\n", out);
}

/* the coordinate loop for a known dim (2, 3) or any dim (0) */
static void emit_apply(const Ctx *C, const Slot *slot, int dim, const char *ind)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    if (dim > 0) {
        for (int k = 0; k < o->nterms; k++) {
            const char *P = C->N->pt[o->point[k]];
            fprintf(out, "%sconst double ", ind);
            for (int c = 0; c < dim; c++) {
                fprintf(out, "%sk%d_%d = ", c ? ", " : "", k, c);
                fprintf(out, "%s%s[%d]", scaled(&slot[k]) ? "-" : "", P, c);
            }
            fputs(";\n", out);
        }
        /* a full block gets a fixed trip count: gcc -O2 then vectorises
         * the interleaved stores, which it does not for a variable one */
        for (int full = 1; full >= 0; full--) {
            fprintf(out, full ? "%sif (m == %d) {\n" : "%s} else {\n", ind,
                    BLOCK);
            if (full)
                fprintf(out, "%s    for (j = 0; j < %d; j++) {\n", ind, BLOCK);
            else
                fprintf(out, "%s    for (j = 0; j < m; j++) {\n", ind);
            fprintf(out, "%s        double *o = out + (i0 + j) * %d;\n", ind,
                    dim);
            for (int c = 0; c < dim; c++) {
                fprintf(out, "%s        o[%d] = ", ind, c);
                if (o->nterms == 0)
                    fputs("0.0", out);
                for (int k = 0; k < o->nterms; k++)
                    fprintf(out, "%sw%d[j] * k%d_%d", k ? " + " : "", k, k, c);
                fputs(";\n", out);
            }
            fprintf(out, "%s    }\n", ind);
        }
        fprintf(out, "%s}\n", ind);
        return;
    }
    /* any dim: coordinate by coordinate, the scaled coordinates hoisted */
    fprintf(out, "%sfor (c = 0; c < dim; c++) {\n", ind);
    for (int k = 0; k < o->nterms; k++) {
        fprintf(out, "%s    const double q%d = %s%s[c];\n", ind, k,
                scaled(&slot[k]) ? "-" : "", C->N->pt[o->point[k]]);
    }
    fprintf(out, "%s    double *o = out + i0 * (size_t)dim + (size_t)c;\n",
            ind);
    fprintf(out, "%s    for (j = 0; j < m; j++)\n", ind);
    fprintf(out, "%s        o[j * (size_t)dim] = ", ind);
    if (o->nterms == 0)
        fputs("0.0", out);
    for (int k = 0; k < o->nterms; k++)
        fprintf(out, "%sw%d[j] * q%d", k ? " + " : "", k, k);
    fputs(";\n", out);
    fprintf(out, "%s}\n", ind);
}

/* the slots of the batch code and the registers it needs (C->live) */
static void batch_slots(Ctx *C, Slot *slot, char **owned, int nslots,
                        int scalar)
{
    const PlanOutput *o = C->o;
    const Plan *p = C->p;
    /* what the batch code computes: the roots of the peeled weights, their
     * uniform factors, the pole flag (a scalar is written as it is) */
    memset(C->live, 0, (size_t)p->nins);
    for (int k = 0; k < nslots; k++) {
        Slot *s = &slot[k];
        if (scalar) {
            s->root = o->reg[k];
            s->sign = 1;
        } else {
            s->root = plan_peel(p, o->reg[k], &s->sign);
        }
        C->live[s->root] = 1;
        if (scaled(s) && !C->role[s->root]) {
            owned[k] = pc_xasprintf("%s, negated", C->role[o->reg[k]]
                                                       ? C->role[o->reg[k]]
                                                       : "weight");
            C->role[s->root] = owned[k];
        }
    }
    if (o->bad >= 0)
        C->live[o->bad] = 1;
    plan_live_close(p, C->live);
}

/* the signature, the locals, the uniform registers and bad_in */
static void batch_head(Ctx *C, const Slot *slot, int nslots, int scalar)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    const Plan *p = C->p;
    emit_signature(out, p, C->N, C->oi, BATCH_CHECKED);
    fputs("\n{\n", out);
    unused_args(C);
    for (int i = 0; i < p->nparams; i++)
        if (param_used(C, i))
            fprintf(out, "    double pad%d[%d]; /* %s, tail block padded */\n",
                    i, BLOCK, C->N->in[i]);
    for (int k = 0; k < nslots; k++) {
        const char *r = C->role[slot[k].root];
        fprintf(out, "    double w%d[%d]; /* %s */\n", k, BLOCK,
                scalar ? "value"
                : r    ? r
                       : "weight");
    }
    if (o->bad >= 0)
        fprintf(out, "    double fb[%d]; /* pole flags, +0.5: overflow */\n",
                BLOCK);
    fputs("    size_t i0, j, nbad = 0;\n", out);
    if (!scalar)
        fputs("    int c;\n", out);
    C->batch = 0;
    emit_instructions(C, 1, "    ");
    /* non-finite consts or point coordinates: every sample is status 3 */
    fputs("    int bad_in = 0;\n", out);
    for (int i = p->nparams; i < C->N->nin; i++)
        fprintf(out, "    bad_in |= !(%s - %s == 0.0);\n", C->N->in[i],
                C->N->in[i]);
    if (!scalar) {
        int any_pt = 0;
        for (int k = 0; k < o->nterms; k++)
            any_pt |= o->point[k] >= 0;
        if (any_pt) {
            fputs("    for (c = 0; c < dim; c++) {\n", out);
            for (int k = 0; k < o->nterms; k++) {
                if (o->point[k] < 0)
                    continue;
                const char *nm = C->N->pt[o->point[k]];
                fprintf(out, "        bad_in |= !(%s[c] - %s[c] == 0.0);\n", nm,
                        nm);
            }
            fputs("    }\n", out);
        }
    }
}

/* the block loop's head: the params (the tail padded), the varying
 * registers, the pole flags fb[] and the weights w0[], w1[] ... */
static void batch_weights(Ctx *C, const Slot *slot, int nslots)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    const Plan *p = C->p;
    fprintf(out, "    for (i0 = 0; i0 < n; i0 += %d) {\n", BLOCK);
    fprintf(out, "        const size_t m = n - i0 < %d ? n - i0 : %d;\n", BLOCK,
            BLOCK);
    if (o->bad >= 0)
        fputs("        int nb = 0; /* poles in the block */\n", out);
    for (int i = 0; i < p->nparams; i++) {
        if (!param_used(C, i))
            continue;
        fprintf(out, "        const double *p%d = %s + i0;\n", i, C->N->in[i]);
    }
    int any = 0;
    for (int i = 0; i < p->nparams; i++)
        any |= param_used(C, i);
    if (any) {
        fprintf(out, "        if (m < %d) {\n", BLOCK);
        for (int i = 0; i < p->nparams; i++) {
            if (!param_used(C, i))
                continue;
            fprintf(out,
                    "            for (j = 0; j < %d; j++)\n"
                    "                pad%d[j] = j < m ? p%d[j] : 0.0;\n"
                    "            p%d = pad%d;\n",
                    BLOCK, i, i, i, i);
        }
        fputs("        }\n", out);
    }
    fprintf(out, "        for (j = 0; j < %d; j++) {\n", BLOCK);
    for (int i = 0; i < p->nparams; i++)
        if (param_used(C, i))
            fprintf(out, "            const double x%d = p%d[j];\n", i, i);
    C->batch = 1;
    emit_instructions(C, 0, "            ");
    if (o->bad >= 0) {
        fputs("            fb[j] = ", out);
        emit_operand(C, o->bad);
        fputs(";\n", out);
    }
    for (int k = 0; k < nslots; k++) {
        fprintf(out, "            w%d[j] = ", k);
        emit_operand(C, slot[k].root);
        fputs(";\n", out);
    }
    C->batch = 0;
    fputs("        }\n", out);
}

/* the rows from the weights, NaN rows at poles, statuses 1, 2 and 4 */
static void batch_rows(const Ctx *C, const Slot *slot, int scalar)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    /* counted in a loop of its own, in an int: inside the weight loop the
     * count (with two flags per sample) keeps gcc -O2 from vectorising it,
     * and clang vectorises an int sum but not a double one */
    if (o->bad >= 0)
        fprintf(out,
                "        for (j = 0; j < %d; j++)\n"
                "            nb += fb[j] != 0.0;\n",
                BLOCK);
    if (scalar) {
        fputs("        for (j = 0; j < m; j++)\n"
              "            out[i0 + j] = w0[j];\n",
              out);
    } else {
        fputs("        if (dim == 3) {\n", out);
        emit_apply(C, slot, 3, "            ");
        fputs("        } else if (dim == 2) {\n", out);
        emit_apply(C, slot, 2, "            ");
        fputs("        } else {\n", out);
        emit_apply(C, slot, 0, "            ");
        fputs("        }\n", out);
    }
    if (o->bad >= 0) {
        fputs("        if (nb != 0) /* poles or overflows in this block: NaN "
              "rows */\n"
              "            for (j = 0; j < m; j++) {\n"
              "                if (fb[j] == 0.0)\n"
              "                    continue;\n"
              "                nbad++;\n",
              out);
        if (scalar)
            fputs("                out[i0 + j] = (double)NAN;\n", out);
        else
            fputs("                for (c = 0; c < dim; c++)\n"
                  "                    out[(i0 + j) * (size_t)dim + (size_t)c]"
                  " = (double)NAN;\n",
                  out);
        fputs("            }\n"
              "        if (status != NULL)\n"
              "            for (j = 0; j < m; j++)\n"
              "                status[i0 + j] = (unsigned char)(",
              out);
        if (uses_domain(C))
            fputs("fb[j] >= 1048576.0 ? 4 : ", out);
        fputs("fb[j] >= 1.0 ? 1 : fb[j] != 0.0 ? 2 : 0);\n", out);
    } else
        fputs("        if (status != NULL)\n"
              "            for (j = 0; j < m; j++)\n"
              "                status[i0 + j] = 0;\n",
              out);
}

/* status 3: the samples not finite for another reason */
static void batch_not_finite(const Ctx *C, int nslots, int scalar)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    /* samples not finite for another reason: a NaN parameter, or a
     * weight beyond double (x - x is 0 unless x is NaN or infinite),
     * counted over the block's weights in a loop of fixed length (it
     * vectorises, like the pole count); the rows are looked at only when
     * one is not finite.  Non-finite points or consts were found before
     * the loop (bad_in). */
    /* w - w is 0, or NaN when w is NaN or infinite; the sum of them
     * compared with != (like the pole count) vectorises */
    fprintf(out,
            "        if (status != NULL) { /* only when asked: it costs "
            "~1 ns a sample */\n"
            "            int nf = bad_in;\n"
            "            for (j = 0; j < %d; j++)\n"
            "                nf += ",
            BLOCK);
    for (int k = 0; k < nslots; k++)
        fprintf(out, "%s(w%d[j] - w%d[j])",
                k ? "\n                      + " : "", k, k);
    if (nslots == 0) /* an output that is identically zero */
        fputs("(double)0", out);
    fputs(" != 0.0;\n", out);
    fputs("            if (nf != 0)\n"
          "                for (j = 0; j < m; j++) {\n",
          out);
    if (o->bad >= 0)
        fputs("                    if (fb[j] != 0.0)\n"
              "                        continue;\n",
              out);
    fputs("                    if (!bad_in", out);
    for (int k = 0; k < nslots; k++)
        fprintf(out, "\n                        && w%d[j] - w%d[j] == 0.0", k,
                k);
    fputs(")\n                        continue;\n", out);
    if (scalar)
        fputs("                    out[i0 + j] = (double)NAN;\n", out);
    else
        fputs("                    for (c = 0; c < dim; c++)\n"
              "                        out[(i0 + j) * (size_t)dim + "
              "(size_t)c] = (double)NAN;\n",
              out);
    fputs("                    nbad++;\n"
          "                    status[i0 + j] = 3;\n"
          "                }\n"
          "        }\n",
          out);
}

/* size_t NAME_M_batch_checked(...): blocks of BLOCK samples */
void emit_batch(Ctx *C)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    int scalar = o->kind == KIND_SCALAR;
    int nslots = scalar ? 1 : o->nterms;
    Slot *slot = pc_xcalloc((size_t)nslots + 1, sizeof *slot);
    char **owned = pc_xcalloc((size_t)nslots + 1, sizeof *owned);
    batch_slots(C, slot, owned, nslots, scalar);
    batch_head(C, slot, nslots, scalar);
    batch_weights(C, slot, nslots);
    batch_rows(C, slot, scalar);
    batch_not_finite(C, nslots, scalar);
    fputs("    }\n    return nbad;\n}\n\n", out);
    for (int k = 0; k < nslots; k++) {
        if (owned[k])
            C->role[slot[k].root] = NULL;
        pc_free(owned[k]);
    }
    pc_free(owned);
    pc_free(slot);
}
