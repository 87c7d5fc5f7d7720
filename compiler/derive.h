/*
 * derive.h - the whole front half of the pipeline as one call, and its
 * result: the exact, reduced point equations of a scheme's outputs.
 *
 *   source -> parse -> expand -> sema_check -> plan the ring -> derive
 *          -> outputs [-> steps]  ==>  Derived
 *
 * (compiler/pipeline.c runs the passes; derive's are in compiler/derive/)
 *
 * A Derived is what every back end reads: `derive` prints it, codegen lowers
 * it to a Plan for emit-c and eval.  It owns its Ring and every value.
 */
#ifndef PC_DERIVE_H
#define PC_DERIVE_H

#include <stdio.h>

#include "base/kind.h"
#include "base/source.h"
#include "compiler/algebra/pteq.h"
#include "compiler/algebra/ratfun.h"
#include "compiler/algebra/ring.h"

typedef struct DerivedOutput {
    const char *name; // the defined name (owned by the Derived)
    Kind kind;
    PointEq eq;      // KIND_POINT / KIND_VECTOR: the reduced equation, over
                     // one common denominator (pteq.h)
    RatFunStruct *w; // KIND_POINT / KIND_VECTOR: eq->len weights, w[i] that
                     // of eq->terms[i].point, each reduced on its own (what
                     // derive prints and codegen lowers); NULL for scalars
    RatFun scalar;   // KIND_SCALAR: the reduced value
    int line;        // 1-based line of its definition in the scheme
    Span span;       // the defined name in its definition (for diagnostics)
    char *diff_of;   // defined as diff(NAME, t[, n]) of a name: NAME (owned),
    char *diff_var;  // t (owned) and n; else both NULL and diff_order 0
    int diff_order;  // (the printers write dM/dt for it)
    unsigned char *assumed; // per param and const (nparams + nconsts): the
                            // ends of its declared bounds this value rests
                            // on (1 lower, 2 upper: the derivation simplified
                            // on them), or NULL: none
} DerivedOutput;

/* What produced a step's value (derive --steps, docs/language.md). */
typedef enum StepOp {
    STEP_EXPR,   // any other expression: arithmetic, a name, functions
    STEP_ALONG,  // along(P, Q, s): args P, Q; scalar s
    STEP_DIVIDE, // divide(P, Q, k): args P, Q; scalar k
    STEP_MEET,   // meet(line(P, Q), line(R, S) | plane(R, S, U)): args
                 // P, Q, R, S[, U]; the meet fields below
    STEP_SUBST,  // subst(E, x, s|X): var x; scalar s (a param or const
                 // replaced) or args[0] = X (a base point or unknown)
    STEP_DIFF,   // diff(E, t[, n]): var t, order n
    STEP_BEZIER, // bezier(s, P0, ..., Pn): args P0..Pn; scalar s
    STEP_SOLVE,  // `solve ... for X, ...`: one step per unknown, in the
                 // `for` list; value = its solution
} StepOp;

/*
 * One step of the derivation: a definition (or an unknown a solve
 * determines), in source order, with its reduced value and, for the
 * constructions, what they were built from.  Values are final: a
 * definition that holds an unknown shows it replaced by the solution of
 * a later `solve` (a value that still holds an unsolved unknown is
 * `pending` and left zero).
 *
 * meet, as the monograph solves it (1.3.5, the S- and V-theorems): the
 * first line P, Q and the points of the second flat but one, V1[, V2],
 * form a simplex; the remaining point W of the second flat is written
 * in it, W = P*a + Q*b + V1*c1 [+ V2*c2] (sv_coord = a, b, c1[, c2]);
 * the moving point M = P*(1 - lambda) + Q*lambda makes the triangle
 * M V1 W (the tetrahedron M V1 V2 W) vanish when
 *     | a          b       c1 .. |
 *     | 1-lambda   lambda  0  .. |  = 0,  i.e.  (1 - lambda)*b - lambda*a = 0,
 *     | 0          0       1  .. |
 * so lambda = b/(a + b), and det = a + b vanishes exactly when the flats
 * are parallel.  (The article on the Desargues arc writes J in simplex
 * S, N, T: a = p_j, b = q_j.)
 */
typedef struct DerivedStep {
    StepOp op;
    DerivedOutput value; // name, kind, the reduced value (format_output_rhs
                         // prints it), line and span of the definition
    int pending;         // 1: the value holds an unknown no solve
                         // determines; value, args and the meet data are
                         // zero
    char *expr;          // the right-hand side as written (the solve
                         // statement for STEP_SOLVE), owned
    slong nargs;         // along, divide: 2; bezier: n + 1; meet: 2 + nb;
    DerivedOutput *args; // subst of a point: 1.  Each defining point's
                         // reduced value, named by its text ("P",
                         // "A + B"); for the plots of auxiliary lines
    RatFun scalar;       // along: s; divide: k; bezier: s; subst of a
                         // param or const: the replacement; else 0
    const char *var;     // subst, diff: the name replaced or
                         // differentiated by (owned), else NULL
    long order;          // diff: n (1 by default)
    /* meet only (else nparams = 0, has_sv = 0) */
    slong nfirst;           // args[0..nfirst-1] define the first line (2)
    slong nparams;          // 1 + (nb - 1)
    RatFunStruct *params;   // [0]: lambda, M = P + (Q - P)*lambda; [1..]:
                            // mu_j, M = R + (S - R)*mu_1 [+ (U - R)*mu_2]
    int has_sv;             // 1: the S/V-theorem data below was found (a
                            // point of the second flat outside line PQ)
    slong sv_w;             // args[sv_w] is W; the simplex is args 0, 1
                            // and the second flat's others, in order
    RatFunStruct *sv_coord; // nb + 1 coordinates a, b, c1[, c2] of W
    RatFun det;             // a + b (has_sv), else 0
} DerivedStep;

/* Derived.bound_flags: which bounds a param or const has, which ends are
 * open, and whether a result rests on them (a sign proved from them,
 * kernel.h: abs(t) = t for t in [0, 1]): the numeric side then checks
 * that a value lies within them (status 4, docs/eval.md). */
enum {
    DERIVED_BOUND_LO = 1,
    DERIVED_BOUND_HI = 2,
    DERIVED_BOUND_LO_OPEN = 4,
    DERIVED_BOUND_HI_OPEN = 8,
    DERIVED_BOUND_LO_ASSUMED = 16,
    DERIVED_BOUND_HI_ASSUMED = 32,
    DERIVED_BOUND_ASSUMED = 48,
};

/* A scalar definition whose value is a power of one function or distance
 * (a kernel, kernel.h): `a = dist(A, C)^2`, `c = sqrt(a^2 - b^2)`, `g =
 * angle(A, C, B)`.  The printers write results through its name, as the
 * book writes them through a, c, gamma (docs/language.md). */
typedef struct DerivedName {
    char *name; // the defined name (owned)
    slong var;  // the value is var^exp
    ulong exp;
    int line; // 1-based line of the definition: names print only in
              // what is defined after them
} DerivedName;

/* The verdict of one `check` statement (compiler/check.h; docs/language.md
 * "Checks"), in source order. */
typedef struct DerivedCheck {
    int line;         // 1-based line of the statement
    const char *kind; // static: "equal", "on_line", "on_plane", "parallel",
                      // "tangent", "contact", "C", "G"
    int order;        // contact, C, G: the k claimed; else 0
    int found;        // contact, C, G: the order found (-1: not even
                      // continuous; up to k, or k + 1 for contact); else -1
    int pass;         // 1 proved, 0 failed (detail says why), -1 an error
                      // stopped it (reported as such)
    char *detail;     // failed: what differs, in the book's form (owned)
} DerivedCheck;

typedef struct Derived {
    char *scheme;   // scheme name (`scheme NAME` or the file's base name)
    char *filename; // as given
    char *text;     // owned copy of the scheme text (len bytes), so that back
    size_t len;     // ends can report errors with the source line and caret
    Source src;     // filename and text as a Source (derived_mark)
    slong npoints;  // base points, declaration order
    char **points;
    slong nparams; // params, declaration order: ring variables 0..nparams-1
    char **params;
    slong nconsts; // consts: ring variables nparams..nparams+nconsts-1
    char **consts;
    slong nextra; // ring variables after the consts (unknown scalars of
    char **extra; // `solve`, which no output depends on), their names
    Ring ring;
    struct Kernels *kernels;  // the ring variables after the extra ones:
                              // functions and pi (kernel.h), or NULL
    RatFunStruct *range;      // 2 * nparams: each param's declared range
    unsigned char *has_range; // (lo, hi), exact; has_range[i] = 0: none
    /* the declared bounds of every param and const (ring variables 0 ..
     * nparams + nconsts - 1): lower and upper, exact numbers or constant
     * expressions (2*pi), and what the derivation assumed of them */
    RatFunStruct *bound;        // 2 per variable: lower, upper
    unsigned char *bound_flags; // per variable: DERIVED_BOUND_* bits
    slong noutputs;             // `output` list (default: the last definition)
    DerivedOutput *outputs;
    slong nsteps;       // DeriveOptions.keep_steps: the steps in source
    DerivedStep *steps; // order (above); else 0 and NULL
    slong nnamed;       // the named kernel powers (above), source order
    DerivedName *named;
    slong nchecks;        // the check statements, source order (above)
    DerivedCheck *checks; // (owned; NULL when there are none)
} Derived;

/* A numeric solve (`solve ... for a, b near a = 1, b = 0`, docs/language.md
 * "Numeric solve"): the compiler derives the residuals of its equations and
 * their Jacobian exactly, and a back end that can evaluate them
 * (DeriveOptions.numeric: codegen/numsolve.h lowers them to a Plan and runs
 * runtime/lsq.h) finds the values, which the derivation then takes as exact
 * decimals. */
typedef enum NumericStatus {
    NUMERIC_OK,        // converged: u holds the values
    NUMERIC_NOCONV,    // no convergence (iteration limit, or no step lowers
                       // the residual): u holds what was reached
    NUMERIC_SINGULAR,  // the Jacobian is singular at u (its rank: rank)
    NUMERIC_EVAL,      // the residuals cannot be evaluated at the start (a
                       // pole, or a function outside its domain)
    NUMERIC_NONUMBERS, // the residuals cannot be evaluated in double
                       // precision (a coefficient beyond a double)
} NumericStatus;

typedef struct NumericSystem {
    const Derived *view; // scalar outputs: the m residuals r_i, then the m*n
                         // Jacobian entries dr_i/du_j (output m + i*n + j);
                         // its params are the ring's variables before the
                         // kernels (borrowed from the derivation)
    int n, m;            // unknowns, residuals (m >= n; m > n: least squares)
    const int *input;    // unknown j is the view's param input[j]
    double *u;           // in: the start; out: the values (or what was
                         // reached)
    int max_iter;        // iterations at most
    /* filled by the solver */
    NumericStatus status;
    int iterations;
    int rank;           // NUMERIC_SINGULAR: the rank of the Jacobian found
    double max_resid;   // max |r_i| at u
    double rms_resid;   // sqrt(sum r_i^2 / m) at u
    const char *method; // "damped Newton" or "Levenberg-Marquardt" (static)
} NumericSystem;

/* Finds s->u; returns 0 (and s->status NUMERIC_OK) when converged. */
typedef int DeriveNumericFn(NumericSystem *s);

/* How a derivation runs (budget.h): a wall-clock budget checked between
 * operations (0: none; derive_source uses BUDGET_DEFAULT_SECONDS), and a
 * stream for progress: per definition, its line, the time it took and the
 * size of its value (terms, total degree, coefficient bits), or NULL. */
typedef struct DeriveOptions {
    double max_seconds;
    FILE *verbose;
    const char *const *defines; // ndefines "NAME=INTEGER" overriding the
    int ndefines;               // scheme's `int NAME = ...` (-D), or NULL
    int *bad_define; // if not NULL: set to 1 when a define names no int of
                     // the scheme (a usage error: the command line is
                     // wrong, not the scheme), else 0
    int keep_steps;  // 1: also record Derived.steps (derive --steps); 0
                     // costs nothing
    int keep_abs;    // 1: the declared ranges of params decide no sign, so
                     // abs(t - a) stays abs on param t in [lo, hi]
                     // (--keep-abs); the bounds of consts still do
    int keep_failed_checks;   // 1: a scheme whose only errors are failed
                              // checks still returns its Derived (with
                              // *nerrors > 0), so that derive --format json
                              // can list every verdict
    DeriveNumericFn *numeric; // solves the numeric solves (`near`):
                              // numsolve_run (codegen/numsolve.h), or NULL:
                              // a scheme with one is an error
} DeriveOptions;

/* Derive a scheme from source text.  Diagnostics (contract section 4 format)
 * go to err, which may be NULL to discard them; *nerrors (if not NULL)
 * receives their count.  Returns NULL when the scheme has an error. */
Derived *derive_source(const char *filename, const char *text, size_t len,
                       FILE *err, int *nerrors);
/* the same with options (opt not NULL) */
Derived *derive_source_ex(const char *filename, const char *text, size_t len,
                          FILE *err, int *nerrors, const DeriveOptions *opt);
/* The largest scheme text accepted, in bytes (offsets in spans are int). */
#define DERIVE_MAX_SOURCE (16 << 20)

/* Same, reading the file; a file that cannot be opened ("FILE: error:
 * cannot open the file: WHY"), a directory, or one that cannot be read or
 * holds more than DERIVE_MAX_SOURCE bytes ("FILE: error: cannot read the
 * file: WHY") is one error, found in bounded time and memory. */
Derived *derive_file(const char *filename, FILE *err, int *nerrors);
Derived *derive_file_ex(const char *filename, FILE *err, int *nerrors,
                        const DeriveOptions *opt);
void derived_free(Derived *d);

/* Reports an error found after derivation (a back end's: e.g. a coefficient
 * that no double can hold) at `span` of d's text, in the contract's format
 * (FILE:LINE:COL: error: ..., source line, caret), to err (NULL: nowhere). */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
void derived_error(const Derived *d, FILE *err, Span span, const char *fmt,
                   ...);

/* Marks output i's definition as the statement being worked on
 * (budget_statement), so that a budget that runs out while it is printed
 * or lowered is reported there. */
void derived_mark(const Derived *d, slong i);

/* Index of the output / point called name, or -1. */
slong derived_find_output(const Derived *d, const char *name);
slong derived_find_point(const Derived *d, const char *name);

#endif
