/*
 * cwrite.h - writing C text: the pieces both emitters (the weights code,
 * emit_c.c, and the collapsed kernel, collapse_emit.c) share.
 *
 * A double literal that reads back exactly, argument lists wrapped at 80
 * columns and aligned after their '(' (the line writer), the parameter
 * list of a generated function, and the block check of the fast batch
 * loops.  The generated batch code works in blocks of CWRITE_BLOCK
 * samples.
 */
#ifndef PC_CWRITE_H
#define PC_CWRITE_H

#include <stdio.h>

enum { CWRITE_BLOCK = 64 }; // samples per block in the generated batch code

/* a C double literal that reads back exactly (shortest of %.15g..%.17g,
 * locale-independent): 2.0, 0.5, (-3.0), 1e+20 */
void cwrite_double(FILE *out, double v);

/* Argument lists wrap at 80 columns, continuation aligned after '('. */
typedef struct CwriteLine {
    FILE *out;
    int col, indent;
} CwriteLine;

/* writes head ("NAME(") and starts a list aligned after it */
void cwrite_line_start(CwriteLine *L, FILE *out, const char *head);
/* one argument, then ',' (or ')' when last), wrapped before 80 columns */
void cwrite_line_arg(CwriteLine *L, const char *text, int last);

/* The parameter list of a generated function, wrapped at 80 columns and
 * aligned after its '(': "HEAD[size_t n, ]params, consts, points, int dim,
 * double *out[, unsigned char *status])".  batch: params as arrays (and n
 * first); status: the _batch_checked status argument; restr: the param
 * arrays and out restrict (a definition; compatible with a prototype
 * without). */
void cwrite_params(FILE *out, const char *head, char *const *in, int nparams,
                   int nin, char *const *pt, int npt, int batch, int status,
                   int restr);

/* the block check of the fast batch loops: the CWRITE_BLOCK doubles chk[]
 * summed in halves into chk[0..7], then "IND HEAD chk[0] + ... + chk[7];"
 * (HEAD e.g. "s =" or "chk[0] ="); uses the loop index j */
void cwrite_chk_sum(FILE *out, const char *ind, const char *head);

#endif
