/*
 * cli.h - the commands of the pointcalc command line (contract section 4),
 * one file each in driver/cli/, dispatched by driver/cli/main.c.
 *
 * A command takes argv[0] = its own name and argv[1..] = the arguments as
 * typed; results go to out, messages to err.  Checks happen in this order:
 * option syntax (exit 2), the scheme (exit 1), names against the scheme
 * (exit 2); only then is anything written to out, so nothing reaches out
 * when the scheme has an error or the command line is wrong.
 *
 * Exit status: 0 success, 1 an error in the scheme (or an output file that
 * cannot be written; for eval also a sample at a pole, docs/eval.md), 2 a
 * usage error.
 */
#ifndef PC_CLI_H
#define PC_CLI_H

#include <stdio.h>

#include "codegen/lower.h"
#include "compiler/derive.h"
#include "driver/cli/budget.h"

typedef int CliCommand(int argc, char **argv, FILE *out, FILE *err);

CliCommand cli_derive;  // cmd_derive.c: the exact equations, text|latex|json
CliCommand cli_emit_c;  // cmd_emit_c.c: C99 for the outputs
CliCommand cli_eval;    // cmd_eval.c: numbers, CSV|JSON
CliCommand cli_help;    // help.c: pointcalc help [CMD]
CliCommand cli_plot;    // cmd_plot.c: the curves and the construction as SVG
CliCommand cli_analyze; // cmd_analyze.c: what the curves are, exactly

/* The pipeline every command starts with (pipeline.c).
 *
 * cli_derive_file_steps: parse -> expand -> sema -> derive, under the budget b
 * (armed for the derivation and left armed, in the phase "printing the
 * result": the caller prints under it, then calls budget_disarm).  NULL when
 * the scheme has an error (reported to err; *rc = 1) or a -D names no int of it
 * (*rc = 2). cli_plan_file: the same, then lower to a numeric Plan (also under
 * the budget); NULL with *rc = 1 when an output cannot be lowered.  With
 * derived not NULL, the derivation is handed over there (the caller
 * frees it) when a Plan is returned. */
/* keep: CLI_KEEP_STEPS also records the steps (derive --steps) */
enum { CLI_KEEP_STEPS = 1 };
Derived *cli_derive_file_steps(const char *file, const BudgetOptions *b,
                               int keep, FILE *err, int *rc);
/* the phase of the command from here on (base/budget.h), at the scheme's
 * file (the file of the last cli_derive_file_steps or cli_plan_file) */
void cli_mark_file(const char *phase);
Plan *cli_plan_file(const char *file, const BudgetOptions *b, FILE *err,
                    int *rc, Derived **derived);

/* help.c: the texts.  cli_usage is the general synopsis; help_text and
 * help_usage give a command's full help and its synopsis (for usage
 * errors), NULL for a name that is no command. */
extern const char cli_usage[];
/* analyze_num.c: the curves of a whose weights have functions
 * (AnCurve.numeric), found numerically; set's coordinates (--at) for
 * dist and coord when it gives every point */
struct Analysis;
struct AnSet;
void analyze_numeric(struct Analysis *a, const struct AnSet *set);
/* analyze_num_metric.c: the curvature at the ends, its extremes and the
 * arc length of such a curve c (plan output o) over the samples ts[0..ns-1]
 * (its range, the knots among them), env with every point's coordinates */
struct AnCurve;
struct PlotEnv;
void analyze_num_metric(struct AnCurve *c, const struct PlotEnv *env, int o,
                        const double *ts, int ns);

const char *help_text(const char *cmd);
const char *help_usage(const char *cmd);

#endif
