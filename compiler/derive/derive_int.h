/*
 * derive_int.h - private to compiler/derive/ and compiler/pipeline.c: the
 * Deriver (the state of one derivation), the Value it computes, and the
 * helpers the files of compiler/derive/ share.
 *
 * Definitions are reduced in source order, each to an exact Value (a RatFun
 * for scalars, a PointEq for combinations of points), memoised per
 * definition; a name refers to the memoised value.  The weight sum of every
 * combination-valued definition is checked here (contract section 3): it must
 * be identically 1 (a point) or 0 (a vector).
 *
 * The files, by idea:
 *   value.c      Values, the exact decimal reader, size guards, time budget,
 *                assumptions, kernel errors and the kernels' normal form
 *   expr.c       eval: the expression nodes, calls, pow, subst, meet
 *   functions.c  the scalar functions (sqrt, sin, ..., pi)
 *   metric.c     the metric atoms dot, dist, angle, and coord
 *   ringplan.c   the ring of a scheme: its variables and kernel slots
 *   deriver.c    the Deriver's setup, the declared bounds, the definitions
 *   solve_stmt.c the `solve` statement
 *   outputs.c    the outputs: checks and DerivedOutput
 *   steps_rec.c  the steps recorder (derive --steps) and the named kernels
 *   check.c      the `check` statements proved (compiler/check.h)
 *   derived.c    the Derived result: free, find, errors, file reading
 * Every shared helper is named derive_* or deriver_* (they are not static:
 * the prefix keeps them out of a user's way in libpointcalc.a).
 */
#ifndef PC_DERIVE_INT_H
#define PC_DERIVE_INT_H

#include <stdio.h>

#include "base/diag.h"
#include "base/source.h"
#include "compiler/algebra/kernel.h"
#include "compiler/algebra/linsolve.h"
#include "compiler/derive.h"
#include "compiler/sema.h"
#include "grammar/ast.h"

/* the value of an expression while deriving */
typedef struct Value {
    int is_point; // 1: p holds a combination of base points; 0: s a scalar
    RatFun s;
    PointEq p;
} Value;

typedef struct Deriver {
    Diag *diag;
    const Ring *r;
    SemaInfo *info;
    Value *defs; // one per definition, initialised
    int *state;  // per definition: 0 not yet, 1 done, -1 failed
    const Source *src;
    double deadline; // CLOCK_MONOTONIC seconds; 0: no time budget
    double max_seconds;
    int keep_abs;       // DeriveOptions.keep_abs
    int expired;        // the time budget ran out (reported once)
    FILE *verbose;      // progress per definition, or NULL
    slong ucol0;        // unknown k is point column ucol0 + k while unknown
    PointEq *usol;      // per unknown point: its solution, once solved
    RatFunStruct *ssol; // per unknown scalar: its solution, once solved
    slong *uvar;        // per unknown scalar: its ring variable (else -1)
    int *usolved;       // per unknown: 1 once its solve succeeded
    Kernels *K;         // functions and pi (kernel.h), or NULL: none used
    unsigned char **dassume;  // per definition and per unknown: the ends of
    unsigned char **uassume;  // declared bounds its value rests on (K->cur
                              // while it was derived, and its names'), or
                              // NULL: none
    DeriveNumericFn *numeric; // DeriveOptions.numeric
    const Derived *d;         // the result being derived (its names, for
                              // the numeric solve's view)
} Deriver;

/* values that kernel operations take: beyond this many terms they are
 * refused (they work with per-weight gcds, sized for chapter 2's conics) */
enum { KERNEL_MAX_TERMS = 20000 };

/* ---- value.c ------------------------------------------------------------ */

slong derive_scalar_var(const Deriver *D, const Sym *s);
slong derive_point_col(const Deriver *D, const Sym *s);
double derive_now_seconds(void);
int derive_out_of_time_at(Deriver *D, Span span);
int derive_out_of_time(Deriver *D, const Node *n);
void derive_value_init(Value *v, const Ring *r);
void derive_value_clear(Value *v, const Ring *r);
void derive_value_set(Value *res, const Value *x, const Ring *r);
double derive_scalar_bits(const PointEq p, const RatFun s, const Ring *r);
double derive_pair_bits(const PointEq p, const PointEq q, const Ring *r);
int derive_too_big(Deriver *D, double log2_bits, const Node *n);
int derive_eval_point(Deriver *D, PointEq res, const Node *n);
int derive_eval_scalar(Deriver *D, RatFun res, const Node *n);
const Node *derive_nth(const Node *call, int i);
void derive_assume_from(Deriver *D, const unsigned char *a);
void derive_assume_into(Deriver *D, unsigned char **dst);
void derive_assume_clear(Deriver *D);
int derive_value_has_var(const Value *v, slong var, const Ring *r);
char *derive_show(const RatFun x, const Ring *r);
slong derive_value_terms(const Value *v);
int derive_kernel_error(Deriver *D, int rc, const Node *n, const Node *arg);
/* natx(u, k0 ..), naty(u, k0 ..): the law's coefficients numbers */
int derive_eval_natural(Deriver *D, Value *res, const Node *n);
int derive_kernel_error_at(Deriver *D, int rc, Span at, Span arg);
int derive_reduce_value(Deriver *D, Value *v, const Node *n);
LinNormal *derive_solve_normal_form(Deriver *D, LinNormal *nf);
void derive_value_size(const Value *v, slong *terms, slong *deg, slong *bits,
                       const Ring *r);

/* ---- expr.c, functions.c, metric.c -------------------------------------- */

/* res receives the exact value of n; 0 or -1 (reported) */
int derive_eval(Deriver *D, Value *res, const Node *n);
int derive_is_function(int b);
int derive_eval_function(Deriver *D, Value *res, const Node *n);
int derive_eval_metric(Deriver *D, Value *res, const Node *n);
int derive_eval_coord(Deriver *D, Value *res, const Node *n);

/* ---- ringplan.c, deriver.c, solve_stmt.c -------------------------------- */

/* A fresh Derived for info (names, text) and its ring, with nslots_try
 * kernel slots (0: as many as the scheme's calls need at least; updated
 * to the number reserved) */
Derived *derive_plan_ring(const SemaInfo *info, const char *filename,
                          const char *text, size_t len, slong *nslots_try);
void deriver_init(Deriver *D, Derived *d, SemaInfo *info, Diag *diag,
                  const Source *src, double start, const DeriveOptions *opt);
void deriver_clear(Deriver *D);
void derive_all(Deriver *D, Derived *d);
void derive_solve(Deriver *D, Stmt *st);
/* solve_num.c: a `solve ... near ...` of unknown scalars; eqs/seqs as
 * derive_solve evaluated them (seqs[e] when scalar_eq[e], else eqs[e]) */
void derive_solve_numeric(Deriver *D, Stmt *st, PointEq *eqs,
                          RatFunStruct *seqs, const char *scalar_eq,
                          Equation **eqn, slong neq, Sym **syms, slong nunk);
/* solve_stmt.c: the unknown scalar var solved by v, substituted into
 * every value derived so far */
void derive_substitute_scalar(Deriver *D, slong var, const RatFun v,
                              const Stmt *st);

/* ---- check.c ------------------------------------------------------------ */

/* every check statement (compiler/check.h) proved or reported, its
 * verdict into d->checks */
void derive_checks(Deriver *D, Derived *d);

/* ---- outputs.c, steps_rec.c --------------------------------------------- */

const Sym *derive_unsolved_in(const Deriver *D, const Value *v);
void derive_output_fill(DerivedOutput *o, const char *name, Span span,
                        const Value *v, const Source *src, const Ring *r);
void derive_output_clear(DerivedOutput *o, const Ring *r);
void derive_collect_outputs(Deriver *D, Derived *d);
void derive_final_deadline(Deriver *D);
void derive_step_clear(DerivedStep *st, const Ring *r);
void derive_record_steps(Deriver *D, Derived *d, const Source *src);
void derive_record_named(Deriver *D, Derived *d, const Source *src);

#endif
