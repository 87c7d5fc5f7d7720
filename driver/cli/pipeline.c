/*
 * pipeline.c - the front of every command: parse -> expand -> sema ->
 * derive (derive_file_ex runs them in order), then lower to a Plan for
 * the numeric back ends, under the budget of the command line.
 */
#include "driver/cli/cli.h"

Derived *cli_derive_file_steps(const char *file, const BudgetOptions *b,
                               int keep, FILE *err, int *rc)
{
    int bad_define = 0, nerr = 0;
    DeriveOptions opt = derive_options_cli(b, err, &bad_define);
    opt.keep_steps = (keep & CLI_KEEP_STEPS) != 0;
    opt.keep_failed_checks = (keep & CLI_KEEP_CHECKS) != 0;
    budget_arm(b->max_seconds, b->max_memory);
    Derived *d = derive_file_ex(file, err, &nerr, &opt);
    budget_disarm(); /* the derivation is budgeted, not the output */
    budget_phase("printing the result");      /* for the memory budget */
    *rc = d ? nerr != 0 : bad_define ? 2 : 1; /* d and 1: failed checks */
    return d;
}

Plan *cli_plan_file(const char *file, const BudgetOptions *b, FILE *err,
                    int *rc, Derived **derived)
{
    int bad_define = 0;
    DeriveOptions opt = derive_options_cli(b, err, &bad_define);
    budget_arm(b->max_seconds, b->max_memory);
    Derived *d = derive_file_ex(file, err, NULL, &opt);
    budget_phase("lowering the equations to numbers");
    Plan *p = d ? lower_derived(d, err) : NULL;
    budget_disarm(); /* evaluation takes what the grid asks for */
    budget_phase("writing the result");
    *rc = p ? 0 : !d && bad_define ? 2 : 1;
    if (p && derived)
        *derived = d;
    else
        derived_free(d);
    return p;
}
