/*
 * main.c - the pointcalc command line (contract section 4).
 *
 *   pointcalc derive FILE [--format text|latex|json] [--origin POINT]
 *   pointcalc emit-c FILE [-o OUT.c] [--header OUT.h] [--prefix NAME]
 *   pointcalc eval   FILE --at A=x,y[,z...] ... [--set k=V ...] --param t=SPEC ...
 *
 * Exit status: 0 success, 1 an error in the scheme, 2 a usage error.
 * Nothing reaches stdout when the scheme has an error.
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include <flint/flint.h>

#include "codegen/cli.h"
#include "compiler/budget.h"
#include "compiler/derive.h"
#include "compiler/format.h"
#include "compiler/mem.h"

#define PC_VERSION "0.1.0"

static const char usage[] =
    "usage: pointcalc derive FILE [--format text|latex|json] [--origin POINT]\n"
    "       pointcalc emit-c FILE [-o OUT.c] [--header OUT.h] [--prefix NAME]\n"
    "       pointcalc eval   FILE --at A=x,y[,z...] ... [--set k=VALUE ...]\n"
    "                        --param t=SPEC ... [--output NAME] "
    "[--format csv|json]\n"
    "       pointcalc --help | --version\n"
    "\n"
    "\n"
    "Every command also takes --max-seconds S and --max-memory SIZE (the\n"
    "budget of the derivation; defaults 60 and 2G, 0 for none) and -v,\n"
    "--verbose (the time and size of every definition, on stderr), and\n"
    "-D NAME=INTEGER, which overrides the scheme's 'int NAME = ...'.\n"
    "\n"
    "Reduces a point-calculus scheme (.pcs) exactly to its final point\n"
    "equations, emits C for them, or evaluates them.  SPEC is a value (0.5),\n"
    "a list (0,0.25,1) or lo:hi:count.  See docs/language.md.\n";

static int derive_main(int argc, char **argv)
{
    const char *file = NULL, *origin = NULL;
    FormatStyle style = FMT_TEXT;
    BudgetOptions bo;
    budget_options_default(&bo);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int used = budget_parse_option(&bo, argc, argv, i, stderr);
        if (used < 0)
            return 2;
        if (used > 0) {
            i += used - 1;
            continue;
        }
        if (strcmp(a, "--format") == 0 && i + 1 < argc) {
            const char *f = argv[++i];
            if (strcmp(f, "text") == 0)
                style = FMT_TEXT;
            else if (strcmp(f, "latex") == 0)
                style = FMT_LATEX;
            else if (strcmp(f, "json") == 0)
                style = FMT_JSON;
            else {
                fprintf(stderr,
                        "pointcalc: unknown format '%s'; expected text, "
                        "latex or json\n",
                        f);
                return 2;
            }
        } else if (strcmp(a, "--origin") == 0 && i + 1 < argc) {
            origin = argv[++i];
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "pointcalc: unknown or incomplete option '%s'\n%s",
                    a, usage);
            return 2;
        } else if (!file) {
            file = a;
        } else {
            fprintf(stderr, "pointcalc: derive takes one FILE, found '%s'\n",
                    a);
            return 2;
        }
    }
    if (!file) {
        fprintf(stderr, "pointcalc: derive needs a scheme FILE\n%s", usage);
        return 2;
    }
    int nerrors = 0;
    DeriveOptions opt = {.max_seconds = bo.max_seconds,
                         .verbose = bo.verbose ? stderr : NULL,
                         .defines = bo.defines,
                         .ndefines = bo.ndefines};
    budget_arm(bo.max_seconds, bo.max_memory);
    Derived *d = derive_file_ex(file, stderr, &nerrors, &opt);
    budget_disarm(); /* the derivation is budgeted, not the printing */
    if (!d)
        return 1;
    slong o = -1;
    if (origin) {
        o = derived_find_point(d, origin);
        if (o < 0) {
            fprintf(stderr,
                    "pointcalc: --origin '%s' is not a base point of the "
                    "scheme\n",
                    origin);
            derived_free(d);
            return 2;
        }
    }
    format_derived(stdout, d, style, o);
    derived_free(d);
    return 0;
}

int main(int argc, char **argv)
{
    int rc;
    /* before anything allocates: GMP and FLINT under the one policy */
    mem_use_for_gmp_flint();
    if (argc < 2) {
        fputs(usage, stderr);
        return 2;
    }
    const char *cmd = argv[1];
    int help = strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0;
    if ((help || strcmp(cmd, "--version") == 0) && argc > 2) {
        fprintf(stderr, "pointcalc: %s takes no arguments, found '%s'\n", cmd,
                argv[2]);
        return 2;
    }
    if (help)
        rc = fputs(usage, stdout) < 0;
    else if (strcmp(cmd, "--version") == 0)
        rc = printf("pointcalc %s\n", PC_VERSION) < 0;
    else if (strcmp(cmd, "derive") == 0)
        rc = derive_main(argc - 1, argv + 1);
    else if (strcmp(cmd, "emit-c") == 0)
        rc = emit_c_main(argc - 1, argv + 1, stdout, stderr);
    else if (strcmp(cmd, "eval") == 0)
        rc = eval_main(argc - 1, argv + 1, stdout, stderr);
    else {
        fprintf(stderr, "pointcalc: unknown command '%s'\n%s", cmd, usage);
        rc = 2;
    }
    flint_cleanup_master();
    /* output that did not reach its file (a full disk, a closed pipe) is
     * an error too, never a silent exit 0 */
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "pointcalc: cannot write the output: %s\n",
                strerror(errno));
        if (rc == 0)
            rc = 1;
    }
    return rc;
}
