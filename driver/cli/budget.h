/*
 * budget.h - the work budget of a derivation: wall-clock time and memory.
 *
 * FLINT's operations cannot be interrupted, so the budget has two layers:
 *
 *  - derive itself checks the clock between operations (at every node of
 *    an expression) and refuses, before forming them, products whose size
 *    estimate is beyond the limits (ratfun.h, construct.c); a budget that
 *    runs out there is a located error like any other, and this is all
 *    the library does (DeriveOptions.max_seconds);
 *  - the command line adds hard limits (budget_arm): an interval timer
 *    whose signal handler reports at the statement being derived and exits
 *    1 when one FLINT call alone runs past the deadline, and the memory
 *    budget of mem.c's counted allocators, whose handler reports the same
 *    way.  Both handlers print with write(2) only (diag_put_*).
 *
 * derive marks the statement it works on (budget_statement), so that both
 * handlers can say where the budget ran out.
 */
#ifndef PC_CLI_BUDGET_H
#define PC_CLI_BUDGET_H

#include <stddef.h>
#include <stdio.h>

#include "base/budget.h"
#include "compiler/derive.h"

/* Command line only (process-wide): a timer of max_seconds (0: none) and a
 * memory budget of max_memory bytes (0: none) on the counted allocators
 * (mem_use_for_gmp_flint must have been called), each reporting at the
 * current statement and exiting 1 when it runs out. */
void budget_arm(double max_seconds, size_t max_memory);
/* stops the timer (evaluation after a derivation is not budgeted) */
void budget_disarm(void);

/* The options every command takes: --max-seconds S (0: none),
 * --max-memory SIZE (bytes, or with a suffix K, M, G: KiB, MiB, GiB; 0:
 * none), --verbose / -v, and -D NAME=INTEGER / -DNAME=INTEGER (overrides
 * `int NAME = ...` of the scheme).  Returns the number of arguments consumed at
 * argv[*i] (0: not a budget option; -1: a bad value, reported to err). */
#define BUDGET_MAX_DEFINES 64
typedef struct BudgetOptions {
    double max_seconds;
    size_t max_memory;
    int verbose;
    int keep_abs; // --keep-abs: params' ranges simplify no abs (derive.h)
    const char *defines[BUDGET_MAX_DEFINES]; // -D NAME=INTEGER (argv's
    int ndefines;                            // strings), expand.h
} BudgetOptions;
void budget_options_default(BudgetOptions *b);
int budget_parse_option(BudgetOptions *b, int argc, char **argv, int i,
                        FILE *err);

/* The options of a command line's derivation: its budget, -v (progress to
 * err) and -D; *bad_define as DeriveOptions.bad_define (may be NULL). */
DeriveOptions derive_options_cli(const BudgetOptions *b, FILE *err,
                                 int *bad_define);

#endif
