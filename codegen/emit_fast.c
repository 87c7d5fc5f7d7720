/*
 * emit_fast.c - the fused NAME_M_batch for dim 2 and 3 and the
 * forwarding functions (NAME_M, NAME_M_batch calling the _checked ones).
 *
 * When the pole flag only checks factors of the common denominator L and
 * its inverse 1/L, a pole or an overflow makes 1/L NaN, so the fast loop
 * needs no flags: the rows are written straight to a restrict out, the
 * numerators summed and multiplied by 1/L once, and a block whose rows or
 * L are not finite is handed to NAME_M_batch_checked (docs/codegen.md,
 * "Batch code").  Called by emit_c_kernel after emit_weights.c's code.
 */
#include "base/mem.h"
#include "codegen/emit_c_int.h"

#include <stdlib.h>
#include <string.h>

/* 1 when r is a factor of the product L: a leaf of its MUL/POWI tree */
static int factor_of(const Plan *p, int L, int r, int depth)
{
    if (L == r)
        return 1;
    const PlanIns *x = &p->ins[L];
    if (depth > 256)
        return 0;
    if (x->op == PLAN_MUL)
        return factor_of(p, x->a, r, depth + 1) ||
               factor_of(p, x->b, r, depth + 1);
    if (x->op == PLAN_POWI)
        return factor_of(p, x->a, r, depth + 1);
    return 0;
}

/* In the pole flag bad, the register 1/L whose overflow it checks, when
 * every other flag in it checks a factor of L (lower.c): then 1/L made NaN
 * where L * (1/L) is not about 1 marks every flagged sample, and the fast
 * _batch needs no flags.  -1 when bad has another shape (a function's
 * domain, a flag of something else). */
static int pole_inverse(const Plan *p, int bad)
{
    int stack[512], ns = 0, inv = -1, poles[512], np = 0;
    stack[ns++] = bad;
    while (ns > 0) {
        const PlanIns *x = &p->ins[stack[--ns]];
        if (x->op == PLAN_POLE) {
            const PlanIns *d = &p->ins[x->a];
            if (d->op == PLAN_DIV && p->ins[d->a].op == PLAN_CONST &&
                p->k[p->ins[d->a].a] == 1.0) {
                if (inv >= 0 && inv != x->a)
                    return -1;
                inv = x->a;
            } else if (np < 512) {
                poles[np++] = x->a;
            } else {
                return -1;
            }
        } else if (x->op == PLAN_ADD || x->op == PLAN_MUL) {
            if (ns + 2 > 512)
                return -1;
            stack[ns++] = x->a;
            stack[ns++] = x->b;
        } else if (x->op != PLAN_CONST) {
            return -1; // a DOMAIN flag, or a shape lower.c does not make
        }
    }
    if (inv < 0)
        return -1;
    for (int i = 0; i < np; i++)
        if (!factor_of(p, p->ins[inv].b, poles[i], 0))
            return -1;
    return inv;
}

/* 1 when register r reads register x (through any instruction): one pass
 * from x to r, the Plan being in dependency order (mark: nins bytes) */
static int reads(const Plan *p, int r, int x, unsigned char *mark)
{
    if (r < x)
        return 0;
    memset(mark + x, 0, (size_t)(r - x + 1));
    mark[x] = 1;
    for (int i = x + 1; i <= r; i++) {
        const PlanIns *in = &p->ins[i];
        switch ((PlanOp)in->op) {
        case PLAN_NEG:
        case PLAN_POWI:
        case PLAN_POLE:
        case PLAN_FN:
        case PLAN_DOMAIN:
        case PLAN_NATX:
        case PLAN_NATY:
        case PLAN_ISNAN:
            mark[i] = in->a >= x && mark[in->a];
            break;
        case PLAN_ADD:
        case PLAN_SUB:
        case PLAN_MUL:
        case PLAN_DIV:
        case PLAN_ATAN2:
            mark[i] =
                (in->a >= x && mark[in->a]) || (in->b >= x && mark[in->b]);
            break;
        default:
            mark[i] = 0;
        }
    }
    return mark[r];
}

/* A weight w = f1 * f2 * ... * inv as a product: the factors beside inv
 * on the chain of MULs from w down to inv (lower.c builds it so), into
 * f[] (at most nmax); their number, or -1 when w is not of that shape */
static int inverse_factors(const Plan *p, int w, int inv, int *f, int nmax,
                           unsigned char *seen)
{
    int n = 0;
    while (w != inv) {
        const PlanIns *x = &p->ins[w];
        if (x->op != PLAN_MUL || n == nmax)
            return -1;
        int ina = reads(p, x->a, inv, seen);
        int inb = reads(p, x->b, inv, seen);
        if (ina == inb) // both or neither
            return -1;
        f[n++] = ina ? x->b : x->a;
        w = ina ? x->a : x->b;
    }
    return n;
}

/* (void)NAME_M_batch_checked(N, param + OFF..., consts, points, dim, DST,
 * NULL); or, N NULL, (void)NAME_M_checked(params, consts, points, dim,
 * DST); */
static void checked_call(const Ctx *C, const char *ind, const char *n,
                         const char *off, const char *dst)
{
    CwriteLine L;
    char *head = pc_xasprintf(
        "%s(void)%s(", ind,
        C->N->fn[NVARIANTS * C->oi + (n ? BATCH_CHECKED : ONE_CHECKED)]);
    cwrite_line_start(&L, C->out, head);
    pc_free(head);
    if (n)
        cwrite_line_arg(&L, n, 0);
    for (int i = 0; i < C->N->nin; i++) {
        char *a =
            pc_xasprintf("%s%s", C->N->in[i], i < C->p->nparams ? off : "");
        cwrite_line_arg(&L, a, 0);
        pc_free(a);
    }
    for (int i = 0; i < C->N->npt; i++)
        cwrite_line_arg(&L, C->N->pt[i], 0);
    cwrite_line_arg(&L, "dim", 0);
    cwrite_line_arg(&L, dst, !n);
    if (n)
        cwrite_line_arg(&L, "NULL", 1);
    fputs(";\n", C->out);
}

enum { NF = 32 }; // factors of a weight beside 1/L, at most

/* the branch of dim (3 or 2) of the fused loop: the points' coordinates,
 * the full blocks (weights, rows, the block check) and the hand-over of a
 * block that is not finite.  hoist: the weights are f[k * NF ...] times
 * 1/L (register inv), summed before the one multiplication. */
static void fast_dim(Ctx *C, const Slot *slot, const int *nf, const int *f,
                     int inv, int hoist, int dim)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    const Plan *p = C->p;
    fprintf(out, dim == 3 ? "    if (dim == 3) {\n" : "    } else {\n");
    for (int k = 0; k < o->nterms; k++) {
        const char *P = C->N->pt[o->point[k]];
        fputs("        const double ", out);
        for (int c = 0; c < dim; c++)
            fprintf(out, "%sk%d_%d = %s%s[%d]", c ? ", " : "", k, c,
                    scaled(&slot[k]) ? "-" : "", P, c);
        fputs(";\n", out);
    }
    fprintf(out, "        for (i0 = 0; i0 < nfull; i0 += %d) {\n", BLOCK);
    for (int i = 0; i < p->nparams; i++)
        if (param_used(C, i))
            fprintf(out, "            const double *p%d = %s + i0;\n", i,
                    C->N->in[i]);
    fprintf(out,
            "            double *o = out + i0 * %d;\n"
            "            for (j = 0; j < %d; j++) {\n",
            dim, BLOCK);
    for (int i = 0; i < p->nparams; i++)
        if (param_used(C, i))
            fprintf(out, "                const double x%d = p%d[j];\n", i, i);
    C->batch = 1;
    emit_instructions(C, 0, "                ");
    for (int k = 0; hoist && k < o->nterms; k++) {
        fprintf(out, "                const double w%d = ", k);
        for (int i = 0; i < nf[k]; i++) {
            fputs(i ? " * " : "", out);
            emit_operand(C, f[k * NF + i]);
        }
        fputs(nf[k] == 0 ? "1.0;" : ";", out);
        const char *r =
            C->role[o->reg[k]] ? C->role[o->reg[k]] : C->role[slot[k].root];
        fprintf(out, " /* %s%s, times the denominator */\n", r ? r : "weight",
                scaled(&slot[k]) ? ", negated" : "");
    }
    for (int c = 0; c < dim; c++) {
        fprintf(out, "                const double q%d = %s", c,
                hoist ? "(" : "");
        for (int k = 0; k < o->nterms; k++) {
            fputs(k ? " + " : "", out);
            if (hoist)
                fprintf(out, "w%d", k);
            else
                emit_operand(C, slot[k].root);
            fprintf(out, " * k%d_%d", k, c);
        }
        if (hoist) {
            fputs(") * ", out);
            emit_operand(C, inv);
        }
        fputs(";\n", out);
    }
    for (int c = 0; c < dim; c++)
        fprintf(out, "                o[%d * j%s] = q%d;\n", dim,
                c == 0   ? ""
                : c == 1 ? " + 1"
                         : " + 2",
                c);
    /* the coordinates and the denominator L summed: not finite when
     * one of them is (a pole makes 1/L infinite; L beyond double makes
     * 1/L 0 and the coordinates wrong), or rarely when the sum
     * overflows */
    fputs("                chk[j] = q0 + q1", out);
    fputs(dim == 3 ? " + q2" : "", out);
    if (inv >= 0) {
        fputs(" + ", out);
        emit_operand(C, p->ins[inv].b);
    }
    fputs(";\n", out);
    C->batch = 0;
    fputs("            }\n", out);
    cwrite_chk_sum(out, "            ", "chk[0] =");
    fputs("            if (!(chk[0] - chk[0] == 0.0)) /* not finite */\n", out);
    char *nn = pc_xasprintf("%d", BLOCK);
    checked_call(C, "                ", nn, " + i0", "o");
    pc_free(nn);
    fputs("        }\n", out);
}

/* void NAME_M_batch(...) for dim 2 and 3: the weights and the coordinates
 * in one fixed-length loop per block, written straight to out (restrict:
 * out does not overlap the inputs), the tail block through a local
 * buffer; a pole or an overflow makes 1/L NaN, so no flags.  Other dims,
 * scalars and outputs with domain checks call _batch_checked.  0 when it
 * did not apply (nothing written). */
int emit_batch_fast(Ctx *C)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    const Plan *p = C->p;
    if (o->kind == KIND_SCALAR || o->nterms == 0 || uses_domain(C))
        return 0;
    int inv = -1;
    if (o->bad >= 0 && (inv = pole_inverse(p, o->bad)) < 0)
        return 0;
    Slot *slot = pc_xcalloc((size_t)o->nterms, sizeof *slot);
    int *nf = pc_xcalloc((size_t)o->nterms, sizeof *nf);
    int *f = pc_xcalloc((size_t)o->nterms * NF, sizeof *f);
    unsigned char *seen = pc_xmalloc((size_t)p->nins + 1);
    /* with 1/L a factor of every weight, the coordinates are summed from
     * the numerators and multiplied by 1/L once each: fewer products, and
     * the sums do not wait for the division */
    int hoist = inv >= 0;
    for (int k = 0; k < o->nterms; k++) {
        slot[k].root = plan_peel(p, o->reg[k], &slot[k].sign);
        if (hoist)
            nf[k] = inverse_factors(p, slot[k].root, inv, f + k * NF, NF, seen);
        hoist &= nf[k] >= 0;
    }
    pc_free(seen);
    memset(C->live, 0, (size_t)p->nins);
    for (int k = 0; k < o->nterms; k++) {
        if (!hoist)
            C->live[slot[k].root] = 1;
        for (int i = 0; hoist && i < nf[k]; i++)
            C->live[f[k * NF + i]] = 1;
    }
    if (hoist)
        C->live[inv] = 1;
    plan_live_close(p, C->live);
    if (inv >= 0 && !C->live[inv]) { // the weights do not use 1/L
        pc_free(slot);
        pc_free(nf);
        pc_free(f);
        return 0;
    }

    emit_signature_ex(out, p, C->N, C->oi, BATCH, 1);
    fputs("\n{\n", out);
    fprintf(out,
            "    const size_t nfull = n - n %% %d; /* in full blocks */\n"
            "    double chk[%d]; /* per sample: finite or not */\n"
            "    size_t i0, j;\n",
            BLOCK, BLOCK);
    /* other dims, the tail block and a block with a value that is not
     * finite: the general code (which also writes NaN at poles and
     * overflows, and is what this computes where it can) */
    fputs("    if (dim != 2 && dim != 3) {\n", out);
    checked_call(C, "        ", "n", "", "out");
    fputs("        return;\n    }\n", out);
    C->batch = 0;
    emit_instructions(C, 1, "    ");
    for (int dim = 3; dim >= 2; dim--)
        fast_dim(C, slot, nf, f, inv, hoist, dim);
    fputs("    }\n    if (nfull < n)\n", out);
    checked_call(C, "        ", "n - nfull", " + nfull",
                 "out + nfull * (size_t)dim");
    fputs("}\n\n", out);
    pc_free(slot);
    pc_free(nf);
    pc_free(f);
    return 1;
}

/* the call of the _checked variant with the arguments of the variant v
 * (ONE or BATCH) being defined */
void emit_forward(const Ctx *C, Variant v)
{
    emit_signature(C->out, C->p, C->N, C->oi, v);
    fputs("\n{\n", C->out);
    checked_call(C, "    ", v == BATCH ? "n" : NULL, "", "out");
    fputs("}\n\n", C->out);
}
