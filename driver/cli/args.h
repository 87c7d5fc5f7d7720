/*
 * args.h - the command line's shared option parsing.
 *
 *   args_parse        the loop every command runs: FILE, the options of
 *                     every command (budget, -v, -D: budget_parse_option),
 *                     the command's own options through a callback, and the
 *                     usage errors (unknown option, second FILE, no FILE)
 *   NameList          --output NAME[,NAME...] (repeatable), and
 *                     args_select_outputs: those names as a Plan's outputs
 *   EvalArgs          eval's --at A=x,y --set k=SPEC --param t=SPEC
 *                     --output NAME[,NAME...], as typed (no scheme needed)
 *   EvalSetup         those checked against a Plan: the selected outputs,
 *                     the points' coordinates, the consts' values and the
 *                     grid of samples (the given params and the swept
 *                     consts)
 *
 * eval and plot share EvalArgs and EvalSetup (driver/cli/cmd_eval.c is the
 * model):
 *
 *   EvalArgs a;  eval_args_init(&a);
 *   args_parse(argc, argv, usage, &budget, &file, my_option, &ctx, err)
 *       with my_option calling eval_args_option(&a, ...) first;
 *   Plan *p = cli_plan_file(file, &budget, err, &rc, NULL);
 *   EvalSetup s;  eval_setup(&s, &a, p, usage, err);
 *   double *consts = a copy of s.consts (p->nconsts values);
 *   for each run of rows sharing their consts (eval_setup_run), in blocks:
 *       eval_setup_row(&s, row, params, consts) per row ... plan_eval(...)
 *   eval_setup_clear(&s);  eval_args_clear(&a);
 *
 * Every usage error is reported to err as "pointcalc: MESSAGE" and the
 * usage synopsis, and returns 2.
 */
#ifndef PC_ARGS_H
#define PC_ARGS_H

#include <stddef.h>
#include <stdio.h>

#include "driver/cli/budget.h"
#include "runtime/plan.h"
#include "runtime/sample.h"

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
/* "pointcalc: MESSAGE\n" then usage, to err; returns 2 */
int args_usage_error(FILE *err, const char *usage, const char *fmt, ...);

/* A command's own options: the number of arguments used at argv[i] (0:
 * not one of its options; -1: a usage error, already reported). */
typedef int ArgsOption(void *ctx, int argc, char **argv, int i, FILE *err);

/* Parses argv[1..]: budget options into *b (defaults first), the
 * command's options through opt (may be NULL), one FILE into *file.
 * Returns 0, or 2 after reporting a usage error. */
/* args_parse's loop alone: the FILE is optional (*file NULL when none),
 * and with file NULL the command takes none (natural). */
int args_scan(int argc, char **argv, const char *usage, BudgetOptions *b,
              const char **file, ArgsOption *opt, void *ctx, FILE *err);
int args_parse(int argc, char **argv, const char *usage, BudgetOptions *b,
               const char **file, ArgsOption *opt, void *ctx, FILE *err);

/* argv[i + 1] when option argv[i] has a value after it, else NULL */
const char *args_value(int argc, char **argv, int i);

/* ---- --output NAME[,NAME...] ------------------------------------------ */

/* names as typed, in order (repeatable options append) */
typedef struct NameList {
    char **v; // owned
    int n;
} NameList;

/* appends the comma-separated names of list; -1 on an empty name */
int args_names_add(NameList *l, const char *list);
void args_names_clear(NameList *l);
/* --output's names as output indices of p, in order, into sel (room for
 * p->noutputs); every output when l is empty.  Returns the count, or -1
 * after a usage error (an unknown output, one given twice). */
int args_select_outputs(int *sel, const NameList *l, const Plan *p,
                        const char *usage, FILE *err);

/* ---- eval's options --------------------------------------------------- */

/* one NAME=TEXT of --at, --set or --param */
typedef struct Assign {
    char *name;       // owned
    const char *text; // borrowed from argv: the text after '='
} Assign;

typedef struct EvalArgs {
    Assign *at, *set, *param; // owned arrays, in the order given
    int nat, nset, nparam;
    NameList outputs; // --output
} EvalArgs;

void eval_args_init(EvalArgs *a);
void eval_args_clear(EvalArgs *a);
/* --at, --set, --param, --output at argv[i]: as ArgsOption */
int eval_args_option(EvalArgs *a, int argc, char **argv, int i,
                     const char *usage, FILE *err);

/* ---- eval's options against a Plan ------------------------------------ */

/* One dimension of the grid of samples. */
typedef struct EvalAxis {
    int param; // the param it sets, or -1
    int cnst;  // the const it sets (a swept const), or -1
    Spec spec; // owned: its values
} EvalAxis;

typedef struct EvalSetup {
    int nsel, *sel; // the selected outputs (indices into the plan), owned
    int dim;        // coordinates per point (0: no --at given)
    int npoints;
    double **pt;    // per base point: dim coordinates (owned), or NULL when
                    // not given (no selected output uses it)
    double *consts; // per const: its value; a swept const's for the row
                    // last given to eval_setup_row; 0 when not given
    int nparams;
    int naxes;      // the grid: the swept consts (slowest), then the
    EvalAxis *axes; // given params, each in declaration order; the last
                    // axis varies fastest
    size_t rows;    // the product of the axes' sizes
} EvalSetup;

/* Checks a against p: every name exists and is given once, every point,
 * const and param that a selected output uses is given, the points have
 * one dimension, numbers and SPECs are well-formed.  Returns 0, or 2
 * after a usage error; eval_setup_clear in both cases. */
int eval_setup(EvalSetup *s, const EvalArgs *a, const Plan *p,
               const char *usage, FILE *err);
void eval_setup_clear(EvalSetup *s);

/* Row `row` of the grid: params[i] for every param of the plan (0 for a
 * param that is not given: no selected output uses it) and consts[k] for
 * every swept const (the others are left alone). */
void eval_setup_row(const EvalSetup *s, size_t row, double *params,
                    double *consts);
/* how many rows from `row` on share the consts' values (at least 1): a
 * block plan_eval can take at once */
size_t eval_setup_run(const EvalSetup *s, size_t row);

/* "A, B, C" of names[0..n-1] (or "none") into buf, truncated to size;
 * returns buf (for messages) */
const char *args_name_list(char *const *names, int n, char *buf, size_t size);

#endif
