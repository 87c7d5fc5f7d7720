/*
 * cwrite.c - writing C text for both emitters (cwrite.h): number
 * literals that read back exactly, the line writer that wraps argument
 * lists, the generated functions' parameter lists and the fast loops'
 * block check.  Plain text out; it knows nothing of Plans or schemes.
 */
#include "codegen/cwrite.h"
#include "base/mem.h"
#include "base/numfmt.h"

#include <stdlib.h>
#include <string.h>

enum { BLOCK = CWRITE_BLOCK };

/* a double literal that reads back exactly: 2.0, 0.5, (-3.0), 1e+20 */
void cwrite_double(FILE *out, double v)
{
    char buf[40];
    pc_snprintf(buf, sizeof buf, "%.17g", v);
    /* the shortest of %.15g/%.16g/%.17g that round-trips */
    for (int prec = 15; prec < 17; prec++) {
        char t[40];
        pc_snprintf(t, sizeof t, "%.*g", prec, v);
        if (pc_strtod(t, NULL) == v) {
            memcpy(buf, t, sizeof t);
            break;
        }
    }
    int plain = strspn(buf, "-0123456789") == strlen(buf);
    fprintf(out, v < 0 ? "(%s%s)" : "%s%s", buf, plain ? ".0" : "");
}

void cwrite_line_start(CwriteLine *L, FILE *out, const char *head)
{
    L->out = out;
    fputs(head, out);
    L->col = (int)strlen(head);
    L->indent = L->col;
}

void cwrite_line_arg(CwriteLine *L, const char *text, int last)
{
    int len = (int)strlen(text) + (last ? 1 : 2);
    if (L->col > L->indent && L->col + 1 + len > 79) {
        fprintf(L->out, "\n%*s", L->indent, "");
        L->col = L->indent;
    } else if (L->col > L->indent) {
        fputc(' ', L->out);
        L->col++;
    }
    fprintf(L->out, "%s%s", text, last ? ")" : ",");
    L->col += len;
}

void cwrite_params(FILE *out, const char *head, char *const *in, int nparams,
                   int nin, char *const *pt, int npt, int batch, int status,
                   int restr)
{
    CwriteLine L;
    cwrite_line_start(&L, out, head);
    if (batch)
        cwrite_line_arg(&L, "size_t n", 0);
    for (int i = 0; i < nin; i++) {
        char *arg = pc_xasprintf(
            "%s%s",
            batch && i < nparams
                ? (restr ? "const double *restrict " : "const double *")
                : "double ",
            in[i]);
        cwrite_line_arg(&L, arg, 0);
        pc_free(arg);
    }
    for (int i = 0; i < npt; i++) {
        char *arg = pc_xasprintf("const double *%s", pt[i]);
        cwrite_line_arg(&L, arg, 0);
        pc_free(arg);
    }
    cwrite_line_arg(&L, "int dim", 0);
    cwrite_line_arg(&L, restr ? "double *restrict out" : "double *out",
                    !status);
    if (status)
        cwrite_line_arg(&L, "unsigned char *status", 1);
}

void cwrite_chk_sum(FILE *out, const char *ind, const char *head)
{
    /* in halves, in loops of fixed length that vectorise (a plain sum of
     * doubles does not at -O2: gcc keeps its order; nor does an int count
     * of a double compare with SSE2) */
    for (int h = BLOCK / 2; h >= 8; h /= 2)
        fprintf(out,
                "%sfor (j = 0; j < %d; j++)\n"
                "%s    chk[j] += chk[j + %d];\n",
                ind, h, ind, h);
    fprintf(out,
            "%s%s chk[0] + chk[1] + chk[2] + chk[3] + chk[4] + chk[5] + "
            "chk[6] + chk[7];\n",
            ind, head);
}
