/*
 * expand.h - families of points, integer constants and comprehensions.
 *
 * One scheme for every order (monograph 4.8): the pass between the parser
 * and sema that unrolls
 *
 *   int n = 12                       an integer scheme constant (-D n=24
 *                                    overrides it on the command line)
 *   point M[1..n+1]                  a family: the points M_1 ... M_13
 *   unknown C[2..n]                  a family of unknowns
 *   M[i], M[n+1]                     one member (an index out of range is an
 *                                    error that names the index's value)
 *   bezier(t, M[1], C[2..n], M[13])  a range among a call's arguments
 *   solve E = F for i in 2..n for C[2..n]
 *                                    one equation per value of i
 *   output C[2..n]                   ranges and members in name lists
 *
 * into the plain statements sema already knows: member i of family M is the
 * name M_i everywhere after this pass (in derive's output, JSON and C), and
 * an int constant or a comprehension variable becomes its number.  Integer
 * expressions take + - * / ^ over whole numbers (a division must be exact).
 * A declared name that is also a member's name (M_3 beside M[1..5]) is an
 * error, so member names never clash.
 */
#ifndef PC_EXPAND_H
#define PC_EXPAND_H

#include "base/arena.h"
#include "base/diag.h"
#include "grammar/ast.h"

/* the most family members and unrolled equations of one scheme, together */
#define EXPAND_MAX_MEMBERS 100000
/* the most expression nodes the unrolling may copy */
#define EXPAND_MAX_NODES (1 << 22)
/* |int| < 2^40: every integer of a scheme */
#define EXPAND_MAX_INT ((slong)1 << 40)

#include <flint/flint.h>

/* Rewrites s in place (new nodes in a).  defines[k] is "NAME=INTEGER" (the
 * command line's -D), overriding `int NAME = ...`; used[k] (ndefines
 * entries) is set to 1 for each define the scheme declares.  Errors go to
 * diag; returns their number. */
int expand_scheme(Scheme *s, Arena *a, Diag *diag, const char *const *defines,
                  int ndefines, char *used);

/* 0 when text is "NAME=INTEGER" with a valid name and |INTEGER| <
 * EXPAND_MAX_INT (for the command line's usage check) */
int expand_check_define(const char *text);

#endif
