/*
 * sema.h - semantic analysis: names, kinds, arity (contract sections 2, 3).
 *
 * sema_check resolves every name to a Sym, every call to a Builtin, and
 * infers statically whether each expression is a scalar or a combination of
 * points (Node.is_point).  Weight sums need the algebra and are checked in
 * compiler/derive/.  All errors are reported (not just the first).
 */
#ifndef PC_SEMA_H
#define PC_SEMA_H

/* the deepest expression tree sema accepts (every pass recurses over it) */
#define SEMA_MAX_DEPTH 2000
/* the largest k of coord(P, k) */
#define SEMA_MAX_COORD 1000000
/* step(t, a, w, m): the largest smoothness m (a polynomial of degree 21) */
#define SEMA_MAX_STEP_ORDER 10

#include "base/arena.h"
#include "base/diag.h"
#include "base/functions.h"
#include "grammar/ast.h"

/* X-macro: the constructions and metric calls: builtin, name, min args,
 * max args (-1: any), what it returns (1 combination, 0 scalar, -1 as its
 * first argument).  The scalar functions follow them, one row each of
 * base/functions.def (those with lang = 1). */
#define PC_BUILTINS(X)                                                         \
    X(BI_ALONG, "along", 3, 3, 1)    /* P + (Q - P)*s */                       \
    X(BI_DIVIDE, "divide", 3, 3, 1)  /* (P + k*Q)/(1 + k) */                   \
    X(BI_MEET, "meet", 2, 2, 1)      /* meet(line, line|plane) */              \
    X(BI_LINE, "line", 2, 2, 1)      /* only inside meet */                    \
    X(BI_PLANE, "plane", 3, 3, 1)    /* only inside meet */                    \
    X(BI_SUBST, "subst", 3, 3, -1)   /* subst(E, t|A, s|P): kind of E */       \
    X(BI_DIFF, "diff", 2, 3, -1)     /* diff(E, t[, n]) */                     \
    X(BI_BEZIER, "bezier", 3, -1, 1) /* bezier(t, P0, ..., Pn) */              \
    X(BI_DOT, "dot", 2, 2, 0)        /* metric: U . V */                       \
    X(BI_DIST, "dist", 2, 2, 0)      /* metric: |PQ| */                        \
    X(BI_ANGLE, "angle", 3, 3, 0)    /* metric: angle PQR at Q */              \
    X(BI_COORD, "coord", 2, 2, 0)    /* coordinate k of a point or vector */   \
    X(BI_NATX, "natx", 2, 5, 0)      /* natx(u, k0, k1, k2, k3): natural */    \
    X(BI_NATY, "naty", 2, 5, 0)      /* naty(...) curves (kernel.h)      */

typedef enum Builtin {
#define X(id, name, lo, hi, res) id,
    PC_BUILTINS(X)
#undef X
        BI_FIRST_FUNCTION, // the scalar functions (pi the first, as a call)
    BI_BEFORE_FUNCTIONS = BI_FIRST_FUNCTION - 1,
#define PC_FUNCTION(ID, name, ar, lang, k, p, c, latex, dom)                   \
    PC_WHEN(lang)(BI_##ID, )
#include "base/functions.def"
#undef PC_FUNCTION
    BI_COUNT
} Builtin;

typedef enum SymKind {
    SYM_POINT,   // base point of the simplex; index = point number
    SYM_PARAM,   // current parameter; index = ring variable
    SYM_CONST,   // symbolic constant; index = its place among the consts (its
                 // ring variable is nparams + index)
    SYM_UNKNOWN, // unknown point of a `solve`; index = unknown number
    SYM_DEF,     // NAME = EXPR; index = definition number
} SymKind;

struct Sym {
    const char *name; // arena
    SymKind kind;
    Span span;       // where it was declared or defined
    int index;       // see SymKind
    int is_point;    // SYM_POINT, SYM_DEF of a combination: 1; scalars: 0
    int bad;         // its definition had an error: uses are not re-reported
    Stmt *decl;      // SYM_PARAM, SYM_CONST: the declaring statement (its
                     // range, or the `> 0` of a positive constant)
    Stmt *def;       // SYM_DEF: the statement
    Stmt *solved_by; // SYM_UNKNOWN: the `solve` that determines it, or NULL
    Sym *next;       // in the table's bucket chain
};

typedef struct SemaInfo {
    const char *scheme_name; // from `scheme NAME`, or NULL
    Sym **points;            // declaration order
    int npoints;
    Sym **params; // ring variables 0..nparams-1
    int nparams;
    Sym **consts; // ring variables nparams..
    int nconsts;
    Sym **defs; // definition order
    int ndefs;
    Sym **unknowns; // declaration order: unknown k is the point column
    int nunknowns;  // npoints + k while it is unknown (compiler/derive/)
    Stmt **steps;   // the definitions and solves in source order
    int nsteps;
    Sym **outputs; // `output` list (definitions and solved unknowns),
    int noutputs;  // default the last definition
    Stmt **checks; // the check statements without errors, source order
    int nchecks;   // (compiler/check.h)
} SemaInfo;

/* Checks s and returns what it found, also when it reported errors
 * (diag->nerrors grew): definitions with an error (or using one) are
 * marked bad, so that the others can still be derived and checked. */
SemaInfo *sema_check(Scheme *s, Arena *a, Diag *diag);

/* 1 when name is a built-in function of the language (along, sin, ...) */
int sema_is_builtin(const char *name);

#endif
