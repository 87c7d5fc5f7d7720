/*
 * pipeline.c - the front of every command: parse -> expand -> sema ->
 * derive (derive_file_ex runs them in order), then lower to a Plan for
 * the numeric back ends, under the budget of the command line.
 */
#include "driver/cli/cli.h"

Derived *cli_derive_file_steps(const char *file, const BudgetOptions *b,
                               int keep_steps, FILE *err, int *rc)
{
    int bad_define = 0;
    DeriveOptions opt = derive_options_cli(b, err, &bad_define);
    opt.keep_steps = keep_steps;
    budget_arm(b->max_seconds, b->max_memory);
    Derived *d = derive_file_ex(file, err, NULL, &opt);
    /* the budget stays armed for the printing (the caller disarms it):
     * the time and memory of the whole command are bounded */
    budget_phase("printing the result");
    *rc = d ? 0 : bad_define ? 2 : 1;
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
