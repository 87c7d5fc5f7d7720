/*
 * expand_int.h - the expander's state, shared by expand.c (families, ints,
 * comprehensions of solve, name lists) and expand_fn.c (user functions,
 * sum/prod, piecewise and join).  Internal to compiler/.
 */
#ifndef PC_EXPAND_INT_H
#define PC_EXPAND_INT_H

#include <flint/flint.h>

#include "base/arena.h"
#include "base/diag.h"
#include "grammar/ast.h"

typedef struct IntSym {
    const char *name;
    slong value;
    Span span;
    int bad; // its definition had an error: uses are not re-reported
} IntSym;

typedef struct Family {
    const char *name;
    slong lo, hi; // members lo..hi (empty when lo > hi)
    Span span;
    const char *what; // "points", "unknowns"
} Family;

/* a name bound while an expression is unrolled: an index variable (of a
 * sum, a product or a solve comprehension) to its value, or a user
 * function's parameter to its argument (already expanded) */
typedef struct Binding {
    const char *name;
    const Node *arg; // a parameter's argument; NULL for an index
    slong value;     // an index's value
} Binding;

/* a user function, `def NAME(params) = body` */
typedef struct Func {
    const char *name;
    Span span; // its name in the def
    Name *params;
    int nparams;
    Node *body;
    int bad; // its definition had an error: calls are not re-reported
} Func;

/* the deepest nesting of function calls inside function bodies */
#define EXPAND_MAX_CALL_DEPTH 200

typedef struct Expander {
    Arena *a;
    Diag *d;
    IntSym *ints;
    int nints, capints;
    Family *fams;
    int nfams, capfams;
    const char **names; // plain names declared so far
    Span *spans;
    int nnames, capnames;
    Func *funcs;
    int nfuncs, capfuncs;
    Binding *binds; // innermost last
    int nbinds, capbinds;
    int frame;      // binds[frame..] are visible: the current function's
    int call_depth; // function bodies being expanded
    Stmt *stmt;     // the statement being expanded
    long members;   // family members and unrolled equations so far
    long nodes;     // nodes copied so far
    int over;       // a size limit was reported
} Expander;

IntSym *ex_find_int(Expander *E, const char *name);
Family *ex_find_family(Expander *E, const char *name);
int ex_find_name(Expander *E, const char *name);
/* the visible binding of name, innermost first, or NULL */
const Binding *ex_find_binding(const Expander *E, const char *name);
void ex_bind(Expander *E, const char *name, const Node *arg, slong value);
/* the innermost visible index binding (for "at i = 3" in messages) */
const Binding *ex_index_binding(const Expander *E);
int ex_check_free(Expander *E, const char *name, Span span, int plain_too);
int ex_eval_int(Expander *E, const Node *n, slong *out);
/* *out = v, or an error at span when |v| >= EXPAND_MAX_INT */
int ex_int_range(Expander *E, Span span, __int128 v, slong *out);
int ex_budget_nodes(Expander *E, const Node *n, long k);
Node *ex_clone(Expander *E, const Node *n);
long ex_count_nodes(const Node *n);
int ex_too_deep(const Node *n);
int ex_rewrite(Expander *E, Node **slot);
/* rewrite_args: a call's arguments, ranges NAME[a..b] replaced by members */
int ex_rewrite_args(Expander *E, Node *call);

/* expand_fn.c */
void ex_define_func(Expander *E, Stmt *st);
/* *slot is a call of a user function, sum/prod, piecewise or join: replaced
 * by its expansion.  Returns 1 when the call was one of these (and *st
 * tells the status: 0 or -1), 0 when it is another call. */
int ex_expand_call(Expander *E, Node **slot, int *st);
int ex_expand_compr(Expander *E, Node **slot);
/* the whole number a sum(...) or prod(...) of whole numbers is */
int ex_eval_int_compr(Expander *E, const Node *n, slong *out);

#endif
