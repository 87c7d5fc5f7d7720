/*
 * ast.h - the syntax tree of a scheme (house style 1.3).
 *
 * One fat, commented Node for every expression, one Stmt for every statement
 * form of contract section 2.  Grammar actions only call the ast_new_*
 * constructors below; sema.c fills the annotation fields.  All nodes live in
 * the compilation's Arena.
 */
#ifndef PC_AST_H
#define PC_AST_H

#include <stdio.h>

#include "base/arena.h"
#include "base/source.h"

/* X-macro: node kind, dump name.  One comment of semantics per kind. */
#define PC_NODE_KINDS(X)                                                       \
    X(ND_NUM, "num")   /* exact number; text kept verbatim (0.3 is 3/10) */    \
    X(ND_NAME, "name") /* a declared name: point, param, const, definition */  \
    X(ND_NEG, "neg")   /* -lhs */                                              \
    X(ND_ADD, "+")     /* lhs + rhs: scalars, or combinations of points */     \
    X(ND_SUB, "-")     /* lhs - rhs */                                         \
    X(ND_MUL, "*")     /* lhs * rhs: at most one side a combination */         \
    X(ND_DIV, "/")     /* lhs / rhs: rhs a non-zero scalar */                  \
    X(ND_POW, "^")     /* lhs ^ rhs: rhs an integer constant */                \
    X(ND_CALL, "call") /* name(args): a builtin (along, meet, sin, ...) */     \
    X(ND_INDEX, "index") /* name[lhs], or name[lhs..rhs] as call arguments:    \
                            members of a family (expand.c replaces them) */    \
    X(ND_COMPR, "compr") /* text(lhs for var in args..args->next): sum or      \
                            prod over an index (expand.c unrolls it) */

typedef enum NodeKind {
#define X(k, s) k,
    PC_NODE_KINDS(X)
#undef X
} NodeKind;

typedef struct Sym Sym;             // compiler/sema.h
typedef struct CheckInfo CheckInfo; // compiler/check.h

typedef struct Node Node;
struct Node {
    NodeKind kind;
    Span span;  // the whole expression, blamed in diagnostics
    Node *next; // next argument in a call's list
    int depth;  // height of the tree below (a leaf: 1); bounds recursion

    // ND_NEG, ND_ADD .. ND_POW
    Node *lhs;
    Node *rhs;

    // ND_NUM: the literal text; ND_NAME, ND_CALL: the identifier
    const char *text;
    Span name_span; // ND_CALL: the function name only

    // ND_CALL
    Node *args; // linked by next
    int nargs;

    // ND_COMPR: the index variable (its bounds are args and args->next)
    const char *var;
    Span var_span;

    // set by expand.c on the root of a user function's expansion: the
    // call it replaced (its span and name), for the notes of diagnostics
    const Node *call_site;

    // filled by sema
    Sym *sym;     // ND_NAME: what the name means
    int builtin;  // ND_CALL: a Builtin (compiler/sema.h)
    int is_point; // 1 if the value is a combination of points, 0 a scalar
};

/* A name in a declaration list (`point A, B`, `output M, N`): a plain
 * name, one member NAME[index], or a family or range NAME[lo..hi]. */
typedef struct Name Name;
struct Name {
    const char *text;
    Span span;
    Name *next;
    Node *index;   // NAME[index], or NULL
    Node *lo, *hi; // NAME[lo..hi], or NULL
};

#define PC_STMT_KINDS(X)                                                       \
    X(ST_SCHEME, "scheme")   /* scheme NAME */                                 \
    X(ST_POINT, "point")     /* point A, B, ...: the simplex */                \
    X(ST_PARAM, "param")     /* param t [in [lo, hi]] */                       \
    X(ST_CONST, "const")     /* const k, pD */                                 \
    X(ST_INT, "int")         /* int n = EXPR: an integer scheme constant */    \
    X(ST_UNKNOWN, "unknown") /* unknown C1, C2 (solved by `solve`) */          \
    X(ST_DEF, "def")         /* NAME = EXPR */                                 \
    X(ST_FUNC, "function")   /* def NAME(a, b) = EXPR: a user function */      \
    X(ST_SOLVE, "solve")     /* solve EQ, ... for X, ... */                    \
    X(ST_OUTPUT, "output")   /* output NAME, ... */                            \
    X(ST_FIT, "fit")     /* fit X to f on [lo, hi] [samples m]: names X, f;    \
                            lo, hi; expr m or NULL (docs/fit.md) */            \
    X(ST_CHECK, "check") /* check L = R | check PRED(...) [at t = v, ...]:     \
                            expr L or the claim, rhs R or NULL, eqs the        \
                            bindings of `at` (compiler/check.h) */

typedef enum StmtKind {
#define X(k, s) k,
    PC_STMT_KINDS(X)
#undef X
} StmtKind;

/* `lhs = rhs` inside solve, or `lhs = rhs for var in lo..hi` (one
 * equation per value of var; expand.c unrolls it) */
typedef struct Equation Equation;
struct Equation {
    Node *lhs, *rhs;
    Span span;
    Equation *next;
    const char *var; // the comprehension's variable, or NULL
    Span var_span;
    Node *lo, *hi;
    const char *what; // a joint of join(): "g1 g2", the two segments that
                      // must meet (lhs = g1's end, rhs = g2's start)
};

typedef struct Stmt Stmt;
struct Stmt {
    StmtKind kind;
    Span span; // the whole statement
    Stmt *next;
    Name *names;          // ST_POINT/PARAM/CONST/UNKNOWN/OUTPUT/SOLVE(for ...),
                          // ST_FUNC: the parameters
    Name *name;           // ST_SCHEME, ST_DEF, ST_FUNC: the defined name;
                          // ST_CHECK: `i = 3` of an instance of `check
                          // ... for i in a..b` (expand.c), else NULL
    Node *expr;           // ST_DEF, ST_FUNC (the body); ST_FIT: samples
                          // (NULL: the default)
    Node *lo, *hi;        // ST_PARAM range (both NULL when absent); ST_FIT:
                          // the interval; ST_CONST:
                          // its bounds (`const e in (0, 1)`, `const a > 0`: lo
                          // only, `const k < 1`: hi only)
    int lo_open, hi_open; // ST_PARAM, ST_CONST: an end that is excluded
                          // ('(' or ')', '>' or '<')
    Equation *eqs;        // ST_SOLVE; ST_CHECK: the bindings `at t = v`
                          // (lhs the name, rhs the value)
    const char *data;     // ST_FIT: the file of `to data "FILE.csv"` (arena),
                          // or NULL: the target is the name f
    Equation *start;      // ST_SOLVE: a numeric solve's starts, `near a = 1,
                          // b = 0` (lhs the name, rhs the value); NULL: an
                          // exact solve
    Node *rhs;            // ST_CHECK: R of `check L = R`, or NULL
    Equation *joints;     // ST_DEF: where the segments of a join() must meet
                          // (expand.c; derive checks them)

    // filled by sema
    Sym *sym;         // ST_DEF: the defined name
    int scalar;       // ST_UNKNOWN: `unknown scalar k, ...`
    int bad;          // ST_SOLVE, ST_PARAM (its range), ST_CHECK: an error was
                      // reported; derive skips it
    CheckInfo *check; // ST_CHECK: the claim resolved (compiler/check.h)
};

typedef struct Scheme {
    Stmt *stmts; // in source order
} Scheme;

Node *ast_new_num(Arena *a, const char *text, Span span);
Node *ast_new_name(Arena *a, const char *text, Span span);
Node *ast_new_unary(Arena *a, NodeKind kind, Node *lhs, Span span);
Node *ast_new_binary(Arena *a, NodeKind kind, Node *lhs, Node *rhs, Span span);
/* args: a list built with ast_append */
Node *ast_new_call(Arena *a, const char *name, Span name_span, Node *args,
                   Span span);
/* name(body for var in lo..hi): a sum or product over an index */
Node *ast_new_compr(Arena *a, const char *name, Span name_span, Node *body,
                    const char *var, Span var_span, Node *lo, Node *hi,
                    Span span);
/* name[lo] (hi NULL) or the range name[lo..hi] */
Node *ast_new_index(Arena *a, const char *name, Span name_span, Node *lo,
                    Node *hi, Span span);
Node *ast_append(Node *list, Node *item);
Name *ast_new_namelist(Arena *a, const char *text, Span span);
Name *ast_append_name(Name *list, Name *item);
Equation *ast_new_equation(Arena *a, Node *lhs, Node *rhs, Span span);
Equation *ast_append_equation(Equation *list, Equation *item);
Stmt *ast_new_stmt(Arena *a, StmtKind kind, Span span);

/* deterministic S-expression dump, for golden tests (tests/unit/test_front.c;
 * no command-line flag prints it) */
void ast_dump(FILE *out, const Scheme *s);

#endif
