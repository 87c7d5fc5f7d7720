/*
 * libpointcalc.h - pointcalc as a C library (docs/api.md).
 *
 *   pc_scheme_parse / pc_scheme_load   text -> exact reduced equations
 *   pc_weight_str                      a weight as text
 *   pc_compile                         equations -> numeric plan
 *   pc_eval                            plan -> coordinates, n samples
 *   pc_emit_c                          equations -> C source (as emit-c)
 *   pc_natural_fit / pc_natural_point  curves in natural parametrization
 *                                      (as `pointcalc natural`)
 *
 * Link with build/libpointcalc.a -lflint -lgmp -lm.  Nothing is ever
 * printed: diagnostics come back as text.  Strings returned by the library
 * are malloc'ed; release them with free().  Objects are independent of each
 * other (a plan outlives its scheme); none is thread-safe to share while
 * being freed, but distinct objects may be used from distinct threads at
 * once (docs/api.md, "Threads": pc_use_memory_budget before the threads,
 * pc_thread_cleanup before a thread exits, pc_cleanup at the end).
 */
#ifndef LIBPOINTCALC_H
#define LIBPOINTCALC_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pc_scheme pc_scheme; // a derived scheme (exact)
typedef struct pc_plan pc_plan;     // its numeric program

typedef enum pc_kind {
    PC_NOKIND = -1, // pc_output_kind of a bad index
    PC_SCALAR,      // a rational function of params and consts
    PC_POINT,       // weights sum to 1
    PC_VECTOR,      // weights sum to 0
} pc_kind;

enum {
    PC_OK = 0,
    PC_EINVAL = -1, // a bad argument (index out of range, missing point...)
};

/* Derives a scheme from text (len bytes; `name` is the file name used in
 * diagnostics and as the default scheme name).  On error returns NULL and,
 * when diagnostics is not NULL, *diagnostics receives the messages in the
 * FILE:LINE:COL: error: format (free() it; set to NULL on success). */
pc_scheme *pc_scheme_parse(const char *name, const char *text, size_t len,
                           char **diagnostics);
/* Same, reading the file at path (at most 16 MiB). */
pc_scheme *pc_scheme_load(const char *path, char **diagnostics);

/* The work budget of a derivation.  max_seconds: wall clock, checked
 * between exact operations (0: none; pc_scheme_parse and pc_scheme_load use
 * 60); when it runs out the derivation fails with the diagnostic "the time
 * budget of S s ran out while deriving this" at the expression it was
 * deriving.  One FLINT operation is not interrupted (the library sets no
 * signal handler), but products whose size estimate is beyond the limits
 * are refused before they start, so none runs for long, and a derivation
 * that ends past the budget fails all the same (at the definition or
 * output it worked on last).  The same budget
 * bounds each later pc_compile and pc_emit_c of the scheme, counted from
 * the call: past it they return NULL with "the time budget of S s ran out
 * while lowering this to numbers" at the output being lowered (pc_emit_c:
 * or "... while writing the C", its one pass over the plan). */
typedef struct pc_options {
    double max_seconds;
    /* ndefines strings "NAME=INTEGER" overriding the scheme's `int NAME =
     * ...` (the command line's -D; e.g. the order of a family scheme), or
     * NULL; a define the scheme does not declare is an error */
    const char *const *defines;
    int ndefines;
} pc_options;
pc_scheme *pc_scheme_parse_opts(const char *name, const char *text, size_t len,
                                const pc_options *opt, char **diagnostics);
pc_scheme *pc_scheme_load_opts(const char *path, const pc_options *opt,
                               char **diagnostics);

/* Process-wide, and to be called before any other pc_ function (and before
 * the program's own first use of GMP or FLINT): routes GMP's and FLINT's
 * allocations through the library's counted allocators and sets a memory
 * budget of `bytes` (0: none) for them and for everything the library
 * allocates itself (names, texts, generated C, plans; the strings it
 * returns leave the count when they are handed over).  When the budget would be
 * exceeded, or the system refuses memory, no error can be returned from inside
 * GMP: the library writes "pointcalc: error: the memory budget ran out" (or
 * "out of memory") to stderr and ends the process with _exit(1).  Without
 * this call GMP's own policy applies (it aborts). */
void pc_use_memory_budget(size_t bytes);
void pc_scheme_free(pc_scheme *s);

/* Names, in declaration order; indices are 0-based. */
const char *pc_scheme_name(const pc_scheme *s);
int pc_npoints(const pc_scheme *s);
const char *pc_point_name(const pc_scheme *s, int i);
int pc_nparams(const pc_scheme *s);
const char *pc_param_name(const pc_scheme *s, int i);
int pc_nconsts(const pc_scheme *s);
const char *pc_const_name(const pc_scheme *s, int i);
int pc_noutputs(const pc_scheme *s);
const char *pc_output_name(const pc_scheme *s, int i);
pc_kind pc_output_kind(const pc_scheme *s, int i); // PC_NOKIND: bad index
int pc_output_line(const pc_scheme *s, int i);     // definition line, -1: bad i
/* index of the output / point called name, or -1 */
int pc_find_output(const pc_scheme *s, const char *name);
int pc_find_point(const pc_scheme *s, const char *name);

/* The weight of base point `point` in output `output` as reduced text
 * ("-(t-1)^3/(2*t^2-2*t+1)" or an expanded equivalent; "0" when the point
 * does not occur); for a scalar output pass point = -1 for its value.
 * NULL on a bad index, and when writing the text took longer than the
 * scheme's max_seconds (pc_options), counted from the call: the text is
 * written in one pass (its time is linear in its length but for
 * coefficients of millions of digits: 10^7 digits take seconds), read
 * against the clock when it ends.  free() the result. */
char *pc_weight_str(const pc_scheme *s, int output, int point);

/* Lowers every output to one numeric plan.  NULL when an output cannot be
 * evaluated in double precision (a coefficient beyond the double range, a
 * degree above 2^24, an unsolved unknown scalar); then, when diagnostics is not
 * NULL, *diagnostics receives the error (FILE:LINE:COL: error: ...; free() it;
 * set to NULL on success). */
pc_plan *pc_compile(const pc_scheme *s, char **diagnostics);
void pc_plan_free(pc_plan *p);
/* The plan's text dump (as `emit-c --dump-plan`).  free() it. */
char *pc_plan_dump(const pc_plan *p);

/* Evaluates output `output` at n samples:
 *   params[i]  n values of param i (pc_nparams arrays)
 *   consts[i]  the value of const i (may be NULL when there are none)
 *   points[i]  dim coordinates of base point i (NULL allowed for points the
 *              output does not use)
 *   out        n*dim doubles, row-major (n for a scalar output); it must
 *              not overlap the params or the points
 *   status     NULL, or n codes: 0 ok, 1 a pole (a denominator of the
 *              reduced equation is 0), 2 an overflow (a denominator is
 *              not finite in double precision), 4 a function's argument
 *              outside its domain (sqrt of a negative number, ...)
 * At a pole, an overflow or outside a domain the sample's coordinates are
 * NaN; a scalar output that measures points (dist, dot, angle) reads the
 * points and dim too.  Returns PC_OK
 * or PC_EINVAL; *npoles (if not NULL) receives the number of such samples.
 * n = 0 is nothing to do: PC_OK for any valid output, whatever the other
 * arguments (out, params, points may be NULL), as the generated batch. */
int pc_eval(const pc_plan *p, int output, size_t n, const double *const *params,
            const double *consts, const double *const *points, int dim,
            double *out, unsigned char *status, size_t *npoles);

/* C99 source as `pointcalc emit-c` writes it (prefix NULL: scheme name).
 * NULL on failure (a bad prefix, two outputs that make the same C function
 * name, or as pc_compile), with *diagnostics as for pc_compile.  free() it. */
char *pc_emit_c(const pc_scheme *s, const char *prefix, char **diagnostics);

/* ---- curves in natural parametrization (docs/natural.md) ------------- */

/* a segment: k(s) = k[0] + k[1] s + ... + k[degree] s^degree over arc
 * length s in [0, length], from (x0, y0) at tangent angle phi0 */
typedef struct pc_natural_segment {
    double x0, y0, phi0;
    double k[4];
    int degree;
    double length;
} pc_natural_segment;

enum {
    PC_NATURAL_LINEAR = 1,    // clothoids, G1 joints
    PC_NATURAL_QUADRATIC = 2, // the later segments quadratic: G2 joints
    PC_NATURAL_CUBIC = 3,     // the later segments cubic: G3 joints
    PC_ENOFIT = -2,           // a segment could not be fitted
};

/* The composite curve through n >= 2 points, pts[3 i], pts[3 i + 1] and
 * pts[3 i + 2] = x, y and tangent angle (radians) of point i, as
 * `pointcalc natural` fits it: the first segment the clothoid, every later
 * one of `law`.  has_angle: NULL when every angle is given, else n flags (0:
 * the chord rule gives point i's angle).  out receives the n - 1 segments.
 * Angles are directions: reduced to (-pi, pi] (the fit chooses the
 * winding).  Returns PC_OK; PC_EINVAL for n < 2 or above 10000, a bad
 * law, a value that is not finite, a coordinate beyond 1e100 or two
 * consecutive points closer than 1e-100 (where the law's coefficients
 * leave double precision); PC_ENOFIT when a
 * segment cannot be fitted (*bad, if not NULL, receives its index).  Pure:
 * no allocation that outlives the call, safe from any thread. */
int pc_natural_fit(const double *pts, const unsigned char *has_angle, int n,
                   int law, pc_natural_segment *out, int *bad);

/* The point of segment g at arc length s (xy[0], xy[1]; Gauss-Legendre
 * quadrature to about 1e-15 of the length). */
void pc_natural_point(const pc_natural_segment *g, double s, double xy[2]);

/* Releases FLINT's global caches; call once before exit for a clean
 * valgrind report. */
void pc_cleanup(void);
/* Releases the calling thread's FLINT caches (FLINT keeps a cache of
 * integers per thread, which a thread's exit does not free): a thread
 * other than the main one calls it when it is done with the library,
 * before it exits.  The main thread's are released by pc_cleanup. */
void pc_thread_cleanup(void);

#ifdef __cplusplus
}
#endif

#endif
