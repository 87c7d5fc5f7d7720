/*
 * derive.h - the whole front half of the pipeline as one call, and its
 * result: the exact, reduced point equations of a scheme's outputs.
 *
 *   source -> parse -> sema_check -> derive  ==>  Derived
 *
 * A Derived is what every back end reads: `derive` prints it, codegen lowers
 * it to a Plan for emit-c and eval.  It owns its Ring and every value.
 */
#ifndef PC_DERIVE_H
#define PC_DERIVE_H

#include <stdio.h>

#include "compiler/pteq.h"
#include "compiler/ratfun.h"
#include "compiler/ring.h"
#include "compiler/source.h"

typedef enum Kind {
    KIND_SCALAR, // a rational function of params and consts
    KIND_POINT,  // a point equation whose weights sum to 1
    KIND_VECTOR, // a point equation whose weights sum to 0
} Kind;

typedef struct DerivedOutput {
    const char *name; // the defined name (owned by the Derived)
    Kind kind;
    PointEq eq;    // KIND_POINT / KIND_VECTOR: the reduced equation, over
                   // one common denominator (pteq.h)
    RatFunStruct *w; // KIND_POINT / KIND_VECTOR: eq->len weights, w[i] that
                     // of eq->terms[i].point, each reduced on its own (what
                     // derive prints and codegen lowers); NULL for scalars
    RatFun scalar; // KIND_SCALAR: the reduced value
    int line;      // 1-based line of its definition in the scheme
    Span span;     // the defined name in its definition (for diagnostics)
} DerivedOutput;

typedef struct Derived {
    char *scheme;   // scheme name (`scheme NAME` or the file's base name)
    char *filename; // as given
    char *text;     // owned copy of the scheme text (len bytes), so that back
    size_t len;     // ends can report errors with the source line and caret
    slong npoints;  // base points, declaration order
    char **points;
    slong nparams; // params, declaration order: ring variables 0..nparams-1
    char **params;
    slong nconsts; // consts: ring variables nparams..nparams+nconsts-1
    char **consts;
    slong nextra;  // ring variables after the consts (unknown scalars of
    char **extra;  // `solve`, which no output depends on), their names
    Ring ring;
    struct Kernels *kernels; // the ring variables after the extra ones:
                             // functions and pi (kernel.h), or NULL
    RatFunStruct *range;      // 2 * nparams: each param's declared range
    unsigned char *has_range; // (lo, hi), exact; has_range[i] = 0: none
    slong noutputs; // `output` list (default: the last definition)
    DerivedOutput *outputs;
} Derived;

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
} DeriveOptions;

/* The options of a command line's derivation: its budget, -v (progress to
 * err) and -D; *bad_define as above (may be NULL). */
struct BudgetOptions;
DeriveOptions derive_options_cli(const struct BudgetOptions *b, FILE *err,
                                 int *bad_define);

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

/* Same, reading the file; an unreadable file, a directory, or a file of
 * more than DERIVE_MAX_SOURCE bytes is one error ("FILE: error: cannot read
 * the file: WHY"), found in bounded time and memory. */
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

/* Index of the output / point / param / const called name, or -1. */
slong derived_find_output(const Derived *d, const char *name);
slong derived_find_point(const Derived *d, const char *name);
slong derived_find_param(const Derived *d, const char *name);
slong derived_find_const(const Derived *d, const char *name);

#endif
