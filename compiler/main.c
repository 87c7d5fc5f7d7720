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
#include "codegen/plot_cli.h"
#include "compiler/budget.h"
#include "compiler/derive.h"
#include "compiler/format.h"
#include "compiler/mem.h"
#include "compiler/steps.h"

#define PC_VERSION "0.1.0"

static const char usage[] =
    "usage: pointcalc derive FILE [--format text|latex|json] [--origin POINT]\n"
    "                        [--steps]\n"
    "       pointcalc emit-c FILE [-o OUT.c] [--header OUT.h] [--prefix NAME]\n"
    "       pointcalc eval   FILE --at A=x,y[,z...] ... [--set k=VALUE ...]\n"
    "                        --param t=SPEC ... [--output NAME[,NAME...]] "
    "[--format csv|json]\n"
    "       pointcalc plot   FILE --at A=x,y[,z...] ... [--output NAME,...] "
    "[-o OUT.svg]\n"
    "                        [--at-param t=VALUE] ...   (pointcalc help plot)\n"
    "       pointcalc help [derive|emit-c|eval|plot] | CMD --help | --version\n"
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

#define COMMON_HELP                                                            \
    "\nOptions of every command:\n"                                            \
    "  --max-seconds S     wall-clock budget of the derivation (default 60; "  \
    "0: none)\n"                                                               \
    "  --max-memory SIZE   memory budget of the exact arithmetic, bytes or "   \
    "K, M, G\n"                                                                \
    "                      (default 2G; 0: none)\n"                            \
    "  -v, --verbose       the time and size of every definition and solve, "  \
    "on stderr\n"                                                              \
    "  -D NAME=INTEGER     overrides the scheme's 'int NAME = ...' (e.g. the " \
    "order of\n"                                                               \
    "                      a family scheme)\n"                                 \
    "  -h, --help          this text\n"                                        \
    "\nExit status: 0 success, 1 an error in the scheme, 2 a usage error.\n"

static const char derive_help[] =
    "usage: pointcalc derive FILE [--format text|latex|json] [--origin POINT]\n"
    "                        [--steps]\n"
    "\n"
    "Reduces the scheme exactly and prints the final point equation of every\n"
    "output (default: the last definition).\n"
    "\n"
    "  --format text       one line per output, as the book writes it "
    "(default)\n"
    "  --format latex      the same as display math\n"
    "  --format json       the contract's JSON: every weight as a reduced "
    "expression\n"
    "  --origin POINT      text and LaTeX relative to a base point: (A - C)*f "
    "+ ... + C\n"
    "  --steps             first every step in source order: each definition's "
    "point\n"
    "                      equation, each meet's S/V-theorem determinant and "
    "line\n"
    "                      parameters (JSON: a \"steps\" array)\n" COMMON_HELP;

static const char emit_help[] =
    "usage: pointcalc emit-c FILE [-o OUT.c] [--header OUT.h] [--prefix NAME]\n"
    "                      [--functions LIST] [--dump-plan]\n"
    "\n"
    "Emits C99 for the outputs: NAME_M (one point), NAME_M_batch (arrays of\n"
    "parameters) and their _checked forms, which report poles.\n"
    "\n"
    "  -o OUT.c            write the C there (default: stdout)\n"
    "  --header OUT.h      also write the prototypes\n"
    "  --prefix NAME       the prefix of the function names (default: the "
    "scheme's name)\n"
    "  --functions LIST    which forms: plain, checked, batch, batch_checked, "
    "all\n"
    "  --dump-plan         print the numeric plan instead (debugging)\n"
    COMMON_HELP;

static const char eval_help[] =
    "usage: pointcalc eval FILE --at A=x,y[,z...] ... [--set k=VALUE ...]\n"
    "                    --param t=SPEC ... [--output NAME[,NAME...]] ... "
    "[--format csv|json]\n"
    "\n"
    "Evaluates the outputs at coordinates of the base points, over parameter\n"
    "values; several params form a grid, the last varying fastest.\n"
    "\n"
    "  --at A=x,y,...      the coordinates of base point A (every point the "
    "same\n"
    "                      dimension)\n"
    "  --set k=VALUE       the value of const k\n"
    "  --param t=SPEC      the values of param t: 0.5, a list 0,0.25,1, or "
    "lo:hi:count\n"
    "  --output NAMES      which outputs, repeatable or comma-separated "
    "(default: all)\n"
    "  --format csv|json   CSV with a header (default), or JSON\n"
    "\nA sample at a pole or not finite is NaN in the output and makes the\n"
    "exit status 1 (docs/eval.md).\n" COMMON_HELP;

/* plot's: its usage and options (codegen/plot_cli.c), the common ones */
static const char *plot_help(void)
{
    static char buf[8192];
    if (!buf[0])
        snprintf(buf, sizeof buf, "%s%s%s", plot_usage, plot_help_text,
                 COMMON_HELP);
    return buf;
}

/* the help of command cmd, or NULL */
static const char *command_help(const char *cmd)
{
    return strcmp(cmd, "derive") == 0   ? derive_help
           : strcmp(cmd, "emit-c") == 0 ? emit_help
           : strcmp(cmd, "eval") == 0   ? eval_help
           : strcmp(cmd, "plot") == 0   ? plot_help()
                                        : NULL;
}

static int derive_main(int argc, char **argv)
{
    const char *file = NULL, *origin = NULL;
    FormatStyle style = FMT_TEXT;
    int steps = 0;
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
        } else if (strcmp(a, "--steps") == 0) {
            steps = 1;
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
    int nerrors = 0, bad_define = 0;
    DeriveOptions opt = derive_options_cli(&bo, stderr, &bad_define);
    opt.keep_steps = steps;
    budget_arm(bo.max_seconds, bo.max_memory);
    Derived *d = derive_file_ex(file, stderr, &nerrors, &opt);
    budget_disarm(); /* the derivation is budgeted, not the printing */
    if (!d)
        return bad_define ? 2 : 1;
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
    if (steps && style != FMT_JSON) { /* the steps, then the outputs */
        steps_print(stdout, d, style, o);
        fputs("\n", stdout);
    }
    if (steps && style == FMT_JSON)
        steps_print(stdout, d, style, o);
    else
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
    /* pointcalc help [CMD], pointcalc CMD --help */
    if (strcmp(cmd, "help") == 0) {
        if (argc > 3) {
            fprintf(stderr, "pointcalc: help takes one command, found '%s'\n",
                    argv[3]);
            return 2;
        }
        const char *h = argc == 3 ? command_help(argv[2]) : usage;
        if (!h) {
            fprintf(stderr,
                    "pointcalc: no help on '%s'; expected derive, emit-c, "
                    "eval or plot\n",
                    argv[2]);
            return 2;
        }
        return fputs(h, stdout) < 0;
    }
    if (command_help(cmd))
        for (int i = 2; i < argc; i++)
            if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0)
                return fputs(command_help(cmd), stdout) < 0;
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
    else if (strcmp(cmd, "plot") == 0)
        rc = plot_main(argc - 1, argv + 1, stdout, stderr);
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
