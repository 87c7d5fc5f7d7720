/*
 * collapse_emit.c - the C of the collapsed kernel (collapse.h;
 * docs/codegen.md "The collapsed kernel"): NAME_M_batch_checked for an
 * output collapse.c found collapsible, each coordinate one polynomial in
 * tau evaluated by Horner, its coefficients combined once per call.
 *
 * Full blocks of dims 3 and 2 try a fast loop first (rows straight to a
 * restrict out, one block check); a block with anything to flag, the tail,
 * other dims and non-finite inputs take the general code, and samples
 * outside [lo, hi] (or NaN) the weights code (emit_weights.c's, static).
 * Called by emit_c_kernel; the C-writing helpers are cwrite.c's.
 */
#include "base/mem.h"
#include "codegen/collapse.h"
#include "codegen/cwrite.h"

#include <stdlib.h>
#include <string.h>

enum { BLOCK = CWRITE_BLOCK }; // samples per block, as the weights code's

/* the definition's first line(s); restr: the param arrays and out are
 * restrict (compatible with the header's prototype, which has no
 * restrict: gcc honours restrict on parameters, not on local pointers) */
static void signature(FILE *out, const CollapseNames *N, const char *fn,
                      int is_static, int restr)
{
    char *head = pc_xasprintf("%ssize_t %s(", is_static ? "static " : "", fn);
    cwrite_params(out, head, N->in, N->nparams, N->nin, N->pt, N->npt, 1, 1,
                  restr);
    pc_free(head);
}

/* is coefficient j of the numerators non-zero for some point? */
static int nz(const CollapseOutput *o, int j)
{
    for (int k = 0; k < o->nterms; k++)
        if (o->a[j * o->nterms + k] != 0)
            return 1;
    return 0;
}

/* sum_k a_jk P_k[idx] */
static void coef_expr(FILE *out, const CollapseOutput *o,
                      const CollapseNames *N, int j, const char *idx)
{
    int any = 0;
    for (int k = 0; k < o->nterms; k++) {
        double a = o->a[j * o->nterms + k];
        if (a == 0)
            continue;
        if (any)
            fputs(" + ", out);
        if (a == 1) {
            fprintf(out, "%s[%s]", N->pt[o->point[k]], idx);
        } else {
            cwrite_double(out, a);
            fprintf(out, " * %s[%s]", N->pt[o->point[k]], idx);
        }
        any = 1;
    }
    if (!any)
        fputs("0.0", out);
}

/* Horner in x0 of the numerator coefficients called HEADj (HEAD "k0_":
 * k0_0, k0_1 ...) or, HEAD NULL, of the denominator's literals */
static void horner(FILE *out, const CollapseOutput *o, const char *head)
{
    int top = -1;
    for (int j = 0; j <= o->deg; j++)
        if (head ? nz(o, j) : o->b[j] != 0)
            top = j;
    if (top < 0) {
        fputs("0.0", out);
        return;
    }
    for (int j = 0; j < top; j++)
        fputc('(', out);
    for (int j = top; j >= 0; j--) {
        int has = head ? nz(o, j) : o->b[j] != 0;
        if (j < top) {
            fputs(" * x0", out);
            if (has)
                fputs(" + ", out);
        }
        if (has) {
            if (head)
                fprintf(out, "%s%d", head, j);
            else
                cwrite_double(out, o->b[j]);
        }
        if (j < top)
            fputc(')', out);
    }
}

static int den_const(const CollapseOutput *o)
{
    for (int j = 1; j <= o->deg; j++)
        if (o->b[j] != 0)
            return 0;
    return 1;
}

/* tau, the denominator and the flags of sample j (t = p<pi>[j]): x0, r1
 * (1/denominator, or 1.0 for a constant one) and fb[j] = pole + 0.5
 * overflow + 4 per failed range test.  The range tests use == only (with
 * fabs): quiet comparisons, which gcc -O2 vectorises under the default
 * -ftrapping-math, where it does not vectorise t >= lo. */
/* x0 = tau, r2 = t - lo, r3 = hi - t and (dc 0) r0 = the denominator,
 * r1 = 1/r0 of sample j */
static void sample_values(FILE *out, const CollapseOutput *o, int pi, int dc,
                          const char *ind, int line)
{
    fprintf(out, "%sconst double x0 = (p%d[j] - ", ind, pi);
    cwrite_double(out, o->mid);
    fputs(") * ", out);
    cwrite_double(out, o->scale);
    fputs(";\n", out);
    fprintf(out, "%sconst double r2 = p%d[j] - ", ind, pi);
    cwrite_double(out, o->lo);
    fprintf(out, ", r3 = ");
    cwrite_double(out, o->hi);
    fprintf(out, " - p%d[j];\n", pi);
    if (!dc) {
        fprintf(out, "%sconst double r0 = ", ind);
        horner(out, o, NULL);
        fprintf(out, "; /* line %d: denominator */\n", line);
        fprintf(out, "%sconst double r1 = 1.0 / r0;\n", ind);
    }
}

static void sample(FILE *out, const CollapseOutput *o, int pi, int dc,
                   const char *ind, int line)
{
    sample_values(out, o, pi, dc, ind, line);
    fprintf(out,
            "%sfb[j] = %s4.0 * ((double)(r2 != fabs(r2)) + (double)(r3 != "
            "fabs(r3)));\n",
            ind,
            dc ? "" : "(double)(r0 == 0.0) + 0.5 * (double)(r1 == 0.0) + ");
}

/* the coordinates of row j for dim 3 or 2 from x0 and r1 */
static void row(FILE *out, const CollapseOutput *o, int dim, int dc,
                const char *ind)
{
    fprintf(out, "%sdouble *o = out + (i0 + j) * %d;\n", ind, dim);
    for (int c = 0; c < dim; c++) {
        char head[16];
        snprintf(head, sizeof head, "k%d_", c);
        fprintf(out, "%so[%d] = ", ind, c);
        if (!dc)
            fputc('(', out);
        horner(out, o, head);
        fputs(dc ? ";\n" : ") * r1;\n", out);
    }
}

/* The fast path of a full block for dim 3 or 2 (no bad input): one
 * loop of fixed length that computes each sample and writes its row
 * straight to out (t and out are restrict parameters, so gcc vectorises it
 * at -O2 and without an alias check at -O3), and chk[j] = 0 when sample j
 * is in [lo, hi] and its coordinates and denominator are finite; else
 * negative or NaN: (v - v) is NaN for v not finite, (r - fabs(r)) is
 * negative for r < 0 (quiet operations only, which vectorise under
 * -ftrapping-math).  Every value that the general code would flag (a pole:
 * 1/0 in every coordinate; an overflow: an infinite denominator; a
 * coordinate not finite; outside the range, NaN) makes chk[j] non-zero. */
static void fast_loop(FILE *out, const CollapseOutput *o, int pi, int dc,
                      int dim, int line)
{
    const char *ind = "                ";
    fprintf(out, "            %sif (dim == %d) {\n", dim == 3 ? "" : "} else ",
            dim);
    fprintf(out, "            %sdouble *o = out + i0 * %d;\n", "    ", dim);
    fprintf(out, "                for (j = 0; j < %d; j++) {\n", BLOCK);
    ind = "                    ";
    sample_values(out, o, pi, dc, ind, line);
    for (int c = 0; c < dim; c++) {
        char head[16];
        snprintf(head, sizeof head, "k%d_", c);
        fprintf(out, "%sconst double q%d = ", ind, c);
        if (!dc)
            fputc('(', out);
        horner(out, o, head);
        fputs(dc ? ";\n" : ") * r1;\n", out);
    }
    for (int c = 0; c < dim; c++)
        fprintf(out, "%so[%d * j + %d] = q%d;\n", ind, dim, c, c);
    fprintf(out, "%s{\n%s    const double v = q0 + q1%s%s;\n", ind, ind,
            dim == 3 ? " + q2" : "", dc ? "" : " + r0");
    fprintf(out,
            "%s    chk[j] = (v - v) + ((r2 - fabs(r2)) + (r3 - fabs(r3)));\n"
            "%s}\n",
            ind, ind);
    fputs("                }\n", out);
}

/* the comment, the signature and the locals */
static void batch_head(FILE *out, const CollapseOutput *o,
                       const CollapseNames *N, int dc)
{
    int pi = o->param, K = o->nterms;
    fprintf(out,
            "/* %s, collapsed kernel (emit-c --kernel collapsed): for %s in\n"
            " * [%.17g, %.17g], each coordinate one polynomial, coefficients\n"
            " * combined once per call: %s.\n"
            " * The bound is relative to max_k |P_k[c]| * sum_k |w_k|.  Other\n"
            " * values of %s (or NaN): the weights code, %s. */\n",
            N->fn, N->in[pi], o->lo, o->hi, o->why, N->in[pi], N->fallback);
    signature(out, N, N->fn, N->is_static, 1);
    fputs("\n{\n", out);
    for (int i = 0; i < N->nparams; i++)
        if (i != pi)
            fprintf(out, "    (void)%s;\n", N->in[i]);
    for (int i = 0; i < N->npt; i++) {
        int used = 0;
        for (int k = 0; k < K; k++)
            used |= o->point[k] == i;
        if (!used)
            fprintf(out, "    (void)%s;\n", N->pt[i]);
    }
    fprintf(out,
            "    double pad%d[%d]; /* %s, tail block padded */\n"
            "    double w0[%d]; /* tau = (%s - m) * scale */\n",
            pi, BLOCK, N->in[pi], BLOCK, N->in[pi]);
    if (!dc)
        fprintf(out, "    double w1[%d]; /* 1/denominator */\n", BLOCK);
    fprintf(out,
            "    double fb[%d]; /* pole flags, +0.5: overflow, +4: outside "
            "the range */\n",
            BLOCK);
    fprintf(out,
            "    double chk[%d]; /* fast path: 0 when sample j is plain */\n",
            BLOCK);
    fputs("    size_t i0, j, nbad = 0, nfull;\n    int c, bad = 0;\n", out);
}

/* the coefficients k<c>_<j> of dims 3 and 2 and the flag of non-finite
 * inputs (bad), once per call */
static void coefficients(FILE *out, const CollapseOutput *o,
                         const CollapseNames *N, int line)
{
    int K = o->nterms;
    /* the coefficients of dims 3 and 2, once per call */
    for (int c = 0; c < 3; c++) {
        int first = 1;
        for (int j = 0; j <= o->deg; j++)
            if (nz(o, j)) {
                fprintf(out, "%sk%d_%d = 0.0", first ? "    double " : ", ", c,
                        j);
                first = 0;
            }
        if (!first)
            fputs(";\n", out);
    }
    fputs("    if (dim == 2 || dim == 3) { /* line ", out);
    fprintf(out, "%d: the coefficients per coordinate */\n", line);
    for (int c = 0; c < 3; c++) {
        char idx[4];
        snprintf(idx, sizeof idx, "%d", c);
        if (c == 2)
            fputs("        if (dim == 3) {\n", out);
        for (int j = 0; j <= o->deg; j++) {
            if (!nz(o, j))
                continue;
            fprintf(out, "%s        k%d_%d = ", c == 2 ? "    " : "", c, j);
            coef_expr(out, o, N, j, idx);
            fputs(";\n", out);
        }
        if (c == 2)
            fputs("        }\n", out);
    }
    fputs("    }\n", out);
    /* non-finite consts or point coordinates: every sample is status 3 */
    for (int i = N->nparams; i < N->nin; i++)
        fprintf(out, "    bad |= !(%s - %s == 0.0);\n", N->in[i], N->in[i]);
    fputs("    for (c = 0; c < dim; c++) {\n", out);
    for (int k = 0; k < K; k++)
        fprintf(out, "        bad |= !(%s[c] - %s[c] == 0.0);\n",
                N->pt[o->point[k]], N->pt[o->point[k]]);
    fputs("    }\n", out);
}

/* the block loop's head and the fast path of a full block */
static void block_fast(FILE *out, const CollapseOutput *o,
                       const CollapseNames *N, int dc, int line)
{
    int pi = o->param;
    /* the full blocks of dims 3 and 2 (finite inputs) try the fast path
     * first; a block where it finds anything to flag, the tail, other dims
     * and non-finite inputs: the general code below */
    fprintf(out,
            "    nfull = (dim == 3 || dim == 2) && !bad ? n - n %% %d : 0;\n",
            BLOCK);
    fprintf(out, "    for (i0 = 0; i0 < n; i0 += %d) {\n", BLOCK);
    fprintf(out,
            "        const size_t m = n - i0 < %d ? n - i0 : %d;\n"
            "        const double *p%d = %s + i0;\n"
            "        int nb = 0;\n",
            BLOCK, BLOCK, pi, N->in[pi]);
    fputs("        if (i0 < nfull) { /* the fast path */\n"
          "            double s;\n",
          out);
    fast_loop(out, o, pi, dc, 3, line);
    fast_loop(out, o, pi, dc, 2, line);
    fputs("            }\n", out);
    /* the sum of chk (0 only when every chk[j] is) */
    cwrite_chk_sum(out, "            ", "s =");
    fputs("            if (s == 0.0) {\n"
          "                if (status != NULL)\n",
          out);
    fprintf(out,
            "                    for (j = 0; j < %d; j++)\n"
            "                        status[i0 + j] = 0;\n"
            "                continue;\n"
            "            }\n"
            "            /* something to flag: the block again, by the general "
            "code */\n"
            "        }\n",
            BLOCK);
}

/* the general code: the tail padded, tau, 1/denominator and the flags
 * of the block, and a block with samples outside [lo, hi] handed to the
 * weights code */
static void block_samples(FILE *out, const CollapseOutput *o,
                          const CollapseNames *N, int dc, int line)
{
    int pi = o->param;
    fprintf(out,
            "        if (m < %d) {\n"
            "            for (j = 0; j < %d; j++)\n"
            "                pad%d[j] = j < m ? p%d[j] : ",
            BLOCK, BLOCK, pi, pi);
    cwrite_double(out, o->lo);
    fprintf(out, ";\n            p%d = pad%d;\n        }\n", pi, pi);
    /* tau, 1/denominator and the flags into block arrays: a loop of
     * fixed length that reads p and writes only locals (gcc -O2 vectorises
     * it without an alias check, which its cost model at -O2 refuses) */
    fprintf(out, "        for (j = 0; j < %d; j++) {\n", BLOCK);
    sample(out, o, pi, dc, "            ", line);
    fputs("            w0[j] = x0;\n", out);
    if (!dc)
        fputs("            w1[j] = r1;\n", out);
    fputs("        }\n", out);
    fprintf(out,
            "        for (j = 0; j < %d; j++)\n"
            "            nb += fb[j] != 0.0;\n"
            "        if (nb != 0) {\n"
            "            for (j = 0; j < m && fb[j] < 4.0; j++)\n"
            "                ;\n"
            "            if (j < m) { /* outside [lo, hi], or NaN: the weights "
            "code */\n"
            "                nbad += %s(m, ",
            BLOCK, N->fallback);
    for (int i = 0; i < N->nin; i++)
        fprintf(out, i == pi ? "%s + i0, " : "%s, ", N->in[i]);
    for (int i = 0; i < N->npt; i++)
        fprintf(out, "%s, ", N->pt[i]);
    fputs("dim,\n"
          "                    out + i0 * (size_t)dim, status != NULL ? status "
          "+ i0 : NULL);\n"
          "                continue;\n"
          "            }\n"
          "        }\n",
          out);
}

/* the general code's rows, and NaN rows at poles and overflows */
static void block_rows(FILE *out, const CollapseOutput *o,
                       const CollapseNames *N, int dc)
{
    /* the rows from w0 and w1: dims 3 and 2 with a fixed trip count in a
     * full block (the interleaved stores vectorise), any other dim
     * coordinate by coordinate */
    for (int dim = 3; dim >= 2; dim--) {
        fprintf(out, "        %sif (dim == %d) {\n", dim == 3 ? "" : "} else ",
                dim);
        for (int full = 1; full >= 0; full--) {
            fprintf(out,
                    full ? "            if (m == %d) {\n"
                         : "            } else {\n",
                    BLOCK);
            fprintf(out,
                    full ? "                for (j = 0; j < %d; j++) {\n"
                         : "                for (j = 0; j < m; j++) {\n",
                    BLOCK);
            fputs("                    const double x0 = w0[j];\n", out);
            if (!dc)
                fputs("                    const double r1 = w1[j];\n", out);
            row(out, o, dim, dc, "                    ");
            fputs("                }\n", out);
        }
        fputs("            }\n", out);
    }
    fputs("        } else {\n"
          "            for (c = 0; c < dim; c++) {\n",
          out);
    for (int j = 0; j <= o->deg; j++) {
        if (!nz(o, j))
            continue;
        fprintf(out, "                const double q%d = ", j);
        coef_expr(out, o, N, j, "c");
        fputs(";\n", out);
    }
    fputs("                double *o = out + i0 * (size_t)dim + (size_t)c;\n"
          "                for (j = 0; j < m; j++) {\n"
          "                    const double x0 = w0[j];\n"
          "                    o[j * (size_t)dim] = ",
          out);
    if (!dc)
        fputc('(', out);
    horner(out, o, "q");
    fputs(dc ? ";\n" : ") * w1[j];\n", out);
    fputs("                }\n"
          "            }\n"
          "        }\n",
          out);
    if (!dc) {
        fputs("        if (nb != 0) /* poles or overflows in this block: NaN "
              "rows */\n"
              "            for (j = 0; j < m; j++) {\n"
              "                if (fb[j] == 0.0)\n"
              "                    continue;\n"
              "                nbad++;\n"
              "                for (c = 0; c < dim; c++)\n"
              "                    out[(i0 + j) * (size_t)dim + (size_t)c] = "
              "(double)NAN;\n"
              "            }\n",
              out);
    }
}

/* the statuses of the block, the end of the loop and of the function */
static void statuses(FILE *out, int dc)
{
    /* statuses: 1 and 2 from the flags; 3 where a coordinate is not
     * finite (the coordinates are looked at, in one loop over the block's
     * rows) or an input is not */
    fputs("        if (status != NULL) {\n"
          "            const double *o = out + i0 * (size_t)dim;\n",
          out);
    if (!dc)
        fputs("            for (j = 0; j < m; j++)\n"
              "                status[i0 + j] = (unsigned char)(fb[j] >= 1.0 ? "
              "1 : fb[j] != 0.0 ? 2 : 0);\n",
              out);
    else
        fputs("            for (j = 0; j < m; j++)\n"
              "                status[i0 + j] = 0;\n",
              out);
    fputs("            nb = bad;\n"
          "            for (j = 0; j < m * (size_t)dim; j++)\n"
          "                nb += !(o[j] - o[j] == 0.0);\n"
          "            if (nb != 0)\n"
          "                for (j = 0; j < m; j++) {\n"
          "                    if (status[i0 + j] != 0)\n"
          "                        continue;\n"
          "                    if (!bad) {\n"
          "                        for (c = 0; c < dim; c++)\n"
          "                            if (!(o[j * (size_t)dim + (size_t)c] - "
          "o[j * (size_t)dim + (size_t)c] == 0.0))\n"
          "                                break;\n"
          "                        if (c == dim)\n"
          "                            continue;\n"
          "                    }\n"
          "                    for (c = 0; c < dim; c++)\n"
          "                        out[(i0 + j) * (size_t)dim + (size_t)c] = "
          "(double)NAN;\n"
          "                    nbad++;\n"
          "                    status[i0 + j] = 3;\n"
          "                }\n"
          "        }\n"
          "    }\n"
          "    return nbad;\n"
          "}\n\n",
          out);
}

void collapse_emit_batch(FILE *out, const CollapseOutput *o,
                         const CollapseNames *N, int line)
{
    int dc = den_const(o);
    batch_head(out, o, N, dc);
    coefficients(out, o, N, line);
    block_fast(out, o, N, dc, line);
    block_samples(out, o, N, dc, line);
    block_rows(out, o, N, dc);
    statuses(out, dc);
}

void collapse_banner(FILE *out, const Collapse *c)
{
    fputs("/*\n * Kernel (emit-c --kernel collapsed), per output:\n", out);
    for (int i = 0; i < c->n; i++) {
        const CollapseOutput *o = &c->o[i];
        fprintf(out, " * %s: %s%s\n", o->name,
                o->ok ? "collapsed, " : "the weights kernel: ", o->why);
    }
    fputs(" */\n\n", out);
}

int collapse_name_free(const char *name, char *const *list, int n)
{
    for (int i = 0; i < n; i++)
        if (list[i] && strcmp(list[i], name) == 0)
            return 0;
    return 1;
}
