/*
 * budget.h - what every layer needs of the work budget: its defaults, the
 * statement being derived (so that a handler of the command line can say
 * where a budget ran out), and the budgets as messages write them.
 *
 * The library only marks the statement it works on (budget_statement); the
 * hard limits (timer and memory handler) belong to the command line
 * (driver/cli/budget.h), which reads the mark with budget_where.
 */
#ifndef PC_BASE_BUDGET_H
#define PC_BASE_BUDGET_H

#include <stddef.h>

#include "base/source.h"

#define BUDGET_DEFAULT_SECONDS 60.0
#define BUDGET_DEFAULT_MEMORY ((size_t)2 << 30) /* 2 GiB */

/* The statement being derived by this thread (src NULL: none).  src must
 * stay valid until the next call. */
void budget_statement(const Source *src, Span span);

/* The statement last marked on this thread (*src NULL: none); safe in a
 * signal handler: the mark is published by flipping an index. */
void budget_where(const Source **src, Span *span);

/* A mark for the whole file (budget_statement(src, BUDGET_WHOLE_FILE)):
 * the handlers then write "FILE: error: ..." */
#define BUDGET_WHOLE_FILE ((Span){-1, -2}) /* diag.h's DIAG_WHOLE_FILE */

/* What this thread does, for the budget handlers' messages ("ran out
 * while PHASE"): a static string, or NULL while deriving ("deriving
 * this").  The phases of the pipeline, each with its mark:
 *   "lexing and parsing the scheme"  the whole file (compiler/pipeline.c)
 *   "expanding this"                 each statement (expand.c)
 *   "checking the scheme"            the whole file (sema)
 *   NULL: "deriving this"            each definition (derive/)
 *   "printing this"                  each output (derived_mark)
 *   "lowering this to numbers"       each output (derived_mark)
 *   "writing the result"             the whole file (the command line)
 * budget_phase_now reads it (safe in a signal handler). */
void budget_phase(const char *phase);
const char *budget_phase_now(void);

/* The time budget of this thread's work after the derivation, for a
 * library caller that has no timer of its own (the C API, the fuzz
 * targets): budget_deadline_set(s) gives the work from now on s seconds
 * (0: none); budget_late() is 1 once they have passed.  The passes that
 * recurse or loop over terms (printing, lowering, writing C) check it at
 * each step and stop: lowering and writing with a located error ("the time
 * budget of S ran out while lowering this"), printing by abandoning its
 * search for shorter forms and cutting its text short (a sum stops after
 * its first term: "+ ..."), so that what it writes is bounded too (a
 * caller that set the deadline then discards it), the analysis
 * (analyze.h) by leaving the curve it was in.  budget_deadline_seconds
 * is the s given, for the message.  Per thread; the command line, which
 * has its timer, sets none. */
void budget_deadline_set(double seconds);
int budget_late(void);
double budget_deadline_seconds(void);
/* The derivation's own deadline, for the loops below it that have no
 * Deriver to ask (meet_ff.c): derive_source_ex sets it (CLOCK_MONOTONIC
 * seconds, 0: none) for its duration and clears it; budget_late() is 1
 * past it too. */
void budget_derive_until(double at);

/* "60 s", "2 GiB", "512 MiB": the budgets as the messages write them */
void budget_format_seconds(char *buf, size_t cap, double s);
void budget_format_bytes(char *buf, size_t cap, size_t b);

#endif
