/*
 * pipeline.c - the front of every command: parse -> expand -> sema ->
 * derive (derive_file_ex runs them in order), then lower to a Plan for
 * the numeric back ends, under the budget of the command line.
 *
 * The phases after the derivation are marked for the budget handlers
 * (base/budget.h): printing and lowering at each output (derived_mark),
 * reading the file and writing the result at the whole file.
 */
#include "driver/cli/cli.h"

/* the scheme's file, for the marks of the whole file: only its name is
 * read (argv's string, valid to the end) */
static Source file_src;

void cli_mark_file(const char *phase)
{
    budget_phase(phase);
    budget_statement(file_src.name ? &file_src : NULL, BUDGET_WHOLE_FILE);
}

static void mark_file_name(const char *file)
{
    file_src = (Source){.name = file, .text = "", .len = 0};
    cli_mark_file("reading the file");
}

Derived *cli_derive_file_steps(const char *file, const BudgetOptions *b,
                               int keep, FILE *err, int *rc)
{
    int bad_define = 0, nerr = 0;
    DeriveOptions opt = derive_options_cli(b, err, &bad_define);
    opt.keep_steps = (keep & CLI_KEEP_STEPS) != 0;
    budget_arm(b->max_seconds, b->max_memory);
    mark_file_name(file);
    Derived *d = derive_file_ex(file, err, &nerr, &opt);
    /* the budget stays armed for the printing (the caller disarms it):
     * the time and memory of the whole command are bounded */
    cli_mark_file("printing the result");     /* format marks each output */
    *rc = d ? nerr != 0 : bad_define ? 2 : 1; /* d and 1: failed checks */
    return d;
}

Plan *cli_plan_file(const char *file, const BudgetOptions *b, FILE *err,
                    int *rc, Derived **derived)
{
    int bad_define = 0;
    DeriveOptions opt = derive_options_cli(b, err, &bad_define);
    budget_arm(b->max_seconds, b->max_memory);
    mark_file_name(file);
    Derived *d = derive_file_ex(file, err, NULL, &opt);
    cli_mark_file("lowering the equations to numbers"); /* at each output */
    Plan *p = d ? lower_derived(d, err) : NULL;
    /* the budget stays armed (the caller disarms it: eval before it
     * evaluates, which takes what the grid asks for; emit-c once the C is
     * made, before the files are written) */
    cli_mark_file("writing the result");
    *rc = p ? 0 : !d && bad_define ? 2 : 1;
    if (p && derived)
        *derived = d;
    else
        derived_free(d);
    return p;
}
