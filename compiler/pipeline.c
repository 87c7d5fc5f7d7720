/*
 * pipeline.c - the passes of a compilation, in order, in one function:
 *
 *   parse -> expand -> sema -> plan the ring -> derive -> outputs -> steps
 *
 * derive_source_ex runs them over a Compilation (pipeline.h); the passes
 * live in grammar/parse.c, expand.c, sema.c and compiler/derive/
 * (ringplan.c, deriver.c, outputs.c, steps_rec.c).  Reading a file is
 * derive_file (derive/derived.c), which ends here.
 */
#include "compiler/pipeline.h"

#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/mem.h"
#include "compiler/derive/derive_int.h"
#include "compiler/expand.h"
#include "grammar/parse.h"

Derived *derive_source(const char *filename, const char *text, size_t len,
                       FILE *err, int *nerrors)
{
    DeriveOptions opt = {.max_seconds = BUDGET_DEFAULT_SECONDS};
    return derive_source_ex(filename, text, len, err, nerrors, &opt);
}

static void compilation_init(Compilation *c, const char *filename,
                             const char *text, size_t len, FILE *err,
                             const DeriveOptions *opt)
{
    *c = (Compilation){
        .filename = filename, .text = text, .len = len, .err = err, .opt = opt};
    c->start = derive_now_seconds();
    if (opt->bad_define)
        *opt->bad_define = 0;
    arena_init(&c->arena);
    source_init(&c->src, filename, text, len);
    diag_init(&c->diag, &c->src, err);
    diag_hold(&c->diag);
}

/* expand the scheme's families and ints, with the command line's -D
 * NAME=INTEGER; a define that names no int of the scheme is a usage error
 * (DeriveOptions.bad_define) */
static void expand_with_defines(Compilation *c)
{
    const DeriveOptions *opt = c->opt;
    int nd = opt->defines ? opt->ndefines : 0;
    char *used = pc_xcalloc((size_t)(nd ? nd : 1), 1);
    expand_scheme(c->scheme, &c->arena, &c->diag, opt->defines, nd, used);
    for (int k = 0; k < nd; k++)
        if (!used[k]) { /* a usage error, like --origin of no point */
            const char *eq = strchr(opt->defines[k], '=');
            int nlen = eq ? (int)(eq - opt->defines[k]) : 0;
            if (c->err)
                fprintf(c->err, "pointcalc: -D %s: %s declares no 'int %.*s'\n",
                        opt->defines[k], c->filename, nlen, opt->defines[k]);
            if (opt->bad_define)
                *opt->bad_define = 1;
            c->diag.nerrors++;
        }
    pc_free(used);
}

/* every error of the compilation is a failed check (a verdict, not an
 * error of the scheme), and the options keep such a result */
static int only_checks_failed(const Compilation *c)
{
    slong failed = 0;
    for (slong i = 0; c->d && i < c->d->nchecks; i++)
        failed += c->d->checks[i].pass == 0;
    return c->opt->keep_failed_checks && failed && c->diag_errors0 == 0 &&
           c->diag.nerrors == failed;
}

/* After a try: a failed derivation is dropped; 1 when it failed because
 * its kernel slots ran out and more may be reserved (its messages are then
 * rolled back and the slots doubled), else 0 */
static int retry_with_more_slots(Compilation *c)
{
    if (c->diag.nerrors == 0 || only_checks_failed(c))
        return 0;
    int again = c->d->kernels && c->d->kernels->full &&
                c->nslots_try < KERNELS_MAX_SLOTS;
    derived_free(c->d);
    c->d = NULL;
    if (again) {
        diag_rollback(&c->diag, c->diag_msgs0, c->diag_errors0);
        c->nslots_try = FLINT_MIN(2 * c->nslots_try, KERNELS_MAX_SLOTS);
    }
    return again;
}

/* the diagnostics out, the count to *nerrors, the memory back */
static Derived *compilation_finish(Compilation *c, int *nerrors)
{
    budget_statement(NULL, (Span){0, 0});
    diag_flush(&c->diag);
    if (nerrors)
        *nerrors = c->diag.nerrors;
    source_clear(&c->src);
    arena_reset(&c->arena);
    return c->d;
}

Derived *derive_source_ex(const char *filename, const char *text, size_t len,
                          FILE *err, int *nerrors, const DeriveOptions *opt)
{
    Compilation c;
    compilation_init(&c, filename, text, len, err, opt);
    budget_derive_until(opt->max_seconds > 0 ? c.start + opt->max_seconds : 0);
    budget_phase("lexing and parsing the scheme");
    budget_statement(&c.src, BUDGET_WHOLE_FILE);
    c.scheme = parse_scheme(&c.src, &c.arena, &c.diag);
    budget_phase("expanding this"); /* expand marks each statement */
    if (c.diag.nerrors == 0)
        expand_with_defines(&c);
    budget_phase("checking the scheme");
    budget_statement(&c.src, BUDGET_WHOLE_FILE);
    if (c.diag.nerrors == 0)
        c.info = sema_check(c.scheme, &c.arena, &c.diag);
    budget_phase(NULL); /* deriving: derive marks each definition */
    /* Kernel slots (functions, pi, distances) are reserved when the ring is
     * built; every unused slot costs in every monomial, so the first try
     * reserves what the scheme's calls need at least, and a derivation
     * that runs out is done again with twice as many (its messages
     * dropped). */
    c.diag_msgs0 = c.diag.nmsgs;
    c.diag_errors0 = c.diag.nerrors;
    for (int again = c.info != NULL; again; again = retry_with_more_slots(&c)) {
        Deriver D;
        c.d =
            derive_plan_ring(c.info, c.filename, c.text, c.len, &c.nslots_try);
        deriver_init(&D, c.d, c.info, &c.diag, &c.src, c.start, opt);
        derive_all(&D, c.d);
        derive_collect_outputs(&D, c.d);
        derive_checks(&D, c.d);
        if (c.diag.nerrors == 0 || only_checks_failed(&c)) {
            if (opt->keep_steps)
                derive_record_steps(&D, c.d, &c.src);
            derive_record_named(&D, c.d, &c.src);
        }
        derive_final_deadline(&D);
        deriver_clear(&D);
    }
    budget_derive_until(0);
    return compilation_finish(&c, nerrors);
}
