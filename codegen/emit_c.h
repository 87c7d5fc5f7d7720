/*
 * emit_c.h - Plan -> C99 (contract section 5).
 *
 * For every output M of scheme NAME (NAME = --prefix when given):
 *
 *   void   NAME_M(params, consts, points, int dim, double *out);
 *   void   NAME_M_batch(size_t n, param arrays, consts, points, int dim,
 *                       double *out);
 *   int    NAME_M_checked(... as NAME_M ...);   0 ok, 1 pole, 2 overflow,
 *                                                3 not finite, 4 domain
 *   size_t NAME_M_batch_checked(... as NAME_M_batch ...,
 *                               unsigned char *status);  number of samples
 *                                                         not 0
 *
 * At a pole (a denominator of the reduced equation is 0) every coordinate
 * is NaN; the _checked variants also report it (docs/codegen.md).  The code
 * needs only <math.h> and <stddef.h>.
 */
#ifndef PC_EMIT_C_H
#define PC_EMIT_C_H

#include <stdio.h>

#include "compiler/derive.h"
#include "runtime/plan.h"

/* prefix: names' prefix (NULL: the scheme name, made a C identifier);
 * source: the scheme file named in the banner (may be NULL). */
void emit_c(FILE *out, const Plan *p, const char *prefix, const char *source);
/* The matching header: include guard and the prototypes. */
void emit_c_header(FILE *out, const Plan *p, const char *prefix,
                   const char *source);

/* Which of the four functions per output are emitted (emit-c
 * --functions): a set of these bits (0 or EMIT_C_ALL: all four).  A
 * _checked function that is not asked for but whose plain variant is
 * (which calls it) is emitted static. */
enum {
    EMIT_C_ONE = 1,           // NAME_M
    EMIT_C_ONE_CHECKED = 2,   // NAME_M_checked
    EMIT_C_BATCH = 4,         // NAME_M_batch
    EMIT_C_BATCH_CHECKED = 8, // NAME_M_batch_checked
    EMIT_C_ALL = 15,
};
void emit_c_ex(FILE *out, const Plan *p, const char *prefix, const char *source,
               unsigned functions);
void emit_c_header_ex(FILE *out, const Plan *p, const char *prefix,
                      const char *source, unsigned functions);
/* emit_c_ex with the collapsed kernel (emit-c --kernel collapsed,
 * codegen/collapse.h) for the outputs p->collapse says (lower_collapse;
 * NULL: emit_c_ex) */
void emit_c_kernel(FILE *out, const Plan *p, const char *prefix,
                   const char *source, unsigned functions);
/* the bits of a --functions list ("plain,batch", "checked", "all" ...);
 * 0 when an item is not one of plain, checked, batch, batch_checked, all
 * (*bad then points at it) */
unsigned emit_c_parse_functions(const char *list, const char **bad);

/* 1 when two outputs would generate the same C function name (*o1 < *o2,
 * e.g. outputs M and M_batch: NAME_M_batch), or a name that is a C keyword
 * or macro (*o1 == *o2); *name receives it (pc_free() it).  0 when every name
 * is usable.  emit_c's output compiles only when this is 0. */
int emit_c_clash(const Plan *p, const char *prefix, int *o1, int *o2,
                 char **name);
/* emit_c_clash for p lowered from d, reported at the output's definition
 * (FILE:LINE:COL: error: ...) on err; 1 when it reported, else 0.  The one
 * check emit-c and pc_emit_c make. */
int emit_c_check(const Plan *p, const Derived *d, const char *prefix,
                 FILE *err);

/* 1 if s is usable as a --prefix: a C identifier that is not a keyword
 * and does not begin with _ (reserved at file scope, C11 7.1.3). */
int emit_c_valid_prefix(const char *s);

#endif
