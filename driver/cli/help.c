/*
 * help.c - `pointcalc help [CMD]`, `pointcalc CMD --help` and the texts
 * of usage errors: one synopsis and one help text per command.
 */
#include "driver/cli/cli.h"

#include <string.h>

#include "driver/cli/args.h"
#include "driver/cli/fit.h"
#include "driver/cli/natural.h"

const char cli_usage[] =
    "usage: pointcalc derive FILE [--format text|latex|json] [--origin POINT]\n"
    "                        [--steps] [--knots] [--standalone] [--width "
    "N]\n"
    "       pointcalc emit-c FILE [-o OUT.c] [--header OUT.h] [--prefix NAME]\n"
    "                        [--output NAME[,NAME...]]\n"
    "       pointcalc eval   FILE --at A=x,y[,z...] ... [--set k=SPEC ...]\n"
    "                        --param t=SPEC ... [--output NAME[,NAME...]] "
    "[--format csv|json]\n"
    "       pointcalc plot   FILE --at A=x,y[,z...] ... [--output NAME,...] "
    "[-o OUT.svg]\n"
    "                        [--at-param t=VALUE] ...   (pointcalc help plot)\n"
    "       pointcalc fit    --target 'EXPR' --on LO,HI --nodes N  (pointcalc "
    "help fit)\n"
    "       pointcalc natural --from X,Y,PHI [--through X,Y[,PHI]]... --to "
    "X,Y,PHI\n"
    "                        [--law linear|quadratic|cubic]  (pointcalc help "
    "natural)\n"
    "       pointcalc analyze FILE [--output NAME,...] [--set k=VALUE ...]\n"
    "                        [--format text|json|latex]  (pointcalc help "
    "analyze)\n"
    "       pointcalc help [derive|emit-c|eval|plot|fit|natural|analyze]\n"
    "       pointcalc CMD --help;  pointcalc --version\n"
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
    "  --max-seconds S     wall-clock budget of the derivation (and of\n"      \
    "                      derive's printing; default 60; 0: none)\n"          \
    "  --max-memory SIZE   memory budget of the exact arithmetic, bytes or "   \
    "K, M, G\n"                                                                \
    "                      (default 2G; 0: none)\n"                            \
    "  -v, --verbose       the time and size of every definition and solve, "  \
    "on stderr\n"                                                              \
    "  -D NAME=INTEGER     overrides the scheme's 'int NAME = ...' (e.g. the " \
    "order of\n"                                                               \
    "                      a family scheme)\n"                                 \
    "  --keep-abs          params' declared ranges simplify no abs or sign "   \
    "(abs(t)\n"                                                                \
    "                      stays abs(t) on t in [0, 4])\n"                     \
    "  -h, --help          this text\n"                                        \
    "\nExit status: 0 success, 1 an error in the scheme, 2 a usage error.\n"

#define DERIVE_USAGE                                                           \
    "usage: pointcalc derive FILE [--format text|latex|json] [--origin "       \
    "POINT]\n"                                                                 \
    "                        [--steps] [--knots] [--standalone] [--width "     \
    "N]\n"

#define EMIT_C_USAGE                                                           \
    "usage: pointcalc emit-c FILE [-o OUT.c] [--header OUT.h] [--prefix "      \
    "NAME]\n"                                                                  \
    "                      [--output NAME[,NAME...]] ... [--functions LIST]\n" \
    "                      [--kernel weights|collapsed] [--dump-plan]\n"

#define EVAL_USAGE                                                             \
    "usage: pointcalc eval FILE --at A=x,y[,z...] ... [--set k=SPEC ...]\n"    \
    "                    --param t=SPEC ... [--output NAME[,NAME...]] ... "    \
    "[--format csv|json]\n"

#define PLOT_USAGE                                                             \
    "usage: pointcalc plot FILE --at A=x,y[,z...] ... [--set k=VALUE ...]\n"   \
    "                      [--param t=LO:HI[:N] | u=VALUE ...] "               \
    "[--output NAME[,NAME...]] ...\n"                                          \
    "                      [-o OUT.svg] [--at-param t=VALUE [--aux "           \
    "NAME[,NAME...]]]\n"                                                       \
    "                      [--view xy|xz|yz|iso|AZ,EL] [--tangents SPEC] "     \
    "[--tangent-scale S]\n"                                                    \
    "                      [--comb] [--comb-teeth N] [--comb-scale S] "        \
    "[--size W[xH]]\n"                                                         \
    "                      [--window X0,Y0,X1,Y1] [--max-samples N]\n"

#define ANALYZE_USAGE                                                          \
    "usage: pointcalc analyze FILE [--output NAME[,NAME...]] ... "             \
    "[--set k=VALUE ...]\n"                                                    \
    "                         [--format text|json|latex]\n"

#define HELP_USAGE                                                             \
    "usage: pointcalc help [derive|emit-c|eval|plot|fit|analyze]\n"

static const char derive_help[] = DERIVE_USAGE
    "\n"
    "Reduces the scheme exactly and prints the final point equation of every\n"
    "output (default: the last definition).  Its check statements are\n"
    "proved; one that fails is an error (exit 1; JSON still lists every\n"
    "verdict, as \"checks\"; docs/language.md, Checks).\n"
    "\n"
    "  --format text       one line per output, as the book writes it "
    "(default)\n"
    "  --format latex      the same as display math\n"
    "  --format json       the contract's JSON: every weight as a reduced "
    "expression\n"
    "  --origin POINT      text and LaTeX relative to a base point: (A - C)*f "
    "+ ... + C\n"
    "  --steps             first every step in source order: each "
    "definition's point\n"
    "                      equation, each meet's S/V-theorem determinant and "
    "line\n"
    "                      parameters (JSON: a \"steps\" array)\n"
    "  --knots             then, for every knot of abs() and sign() of the "
    "param, the\n"
    "                      continuity C^k, the geometric order G^k and the "
    "exact jump\n"
    "                      of the first discontinuous derivative "
    "(docs/composite.md;\n"
    "                      JSON always has them, as \"knots\")\n"
    "  --standalone        LaTeX: a whole document (article, amsmath) for "
    "pdflatex\n"
    "  --width N           LaTeX: equations wider than N columns of source "
    "are\n"
    "                      broken between terms (multline*; default "
    "80)\n" COMMON_HELP;

static const char emit_c_help[] = EMIT_C_USAGE
    "\n"
    "Emits C99 for the outputs: NAME_M (one point), NAME_M_batch (arrays of\n"
    "parameters) and their _checked forms, which report poles.\n"
    "\n"
    "  -o OUT.c            write the C there (default: stdout)\n"
    "  --header OUT.h      also write the prototypes\n"
    "  --prefix NAME       the prefix of the function names (default: the "
    "scheme's name)\n"
    "  --output NAMES      which outputs, repeatable or comma-separated "
    "(default: all)\n"
    "  --functions LIST    which forms: plain, checked, batch, batch_checked, "
    "all\n"
    "  --kernel collapsed  batch functions: each coordinate one polynomial in "
    "the\n"
    "                      param, where a bound over its declared range "
    "keeps\n"
    "                      1e-13 (docs/codegen.md); default: weights\n"
    "  --dump-plan         print the numeric plan instead "
    "(debugging)\n" COMMON_HELP;

static const char eval_help[] = EVAL_USAGE
    "\n"
    "Evaluates the outputs at coordinates of the base points, over parameter\n"
    "values; several params form a grid, the last varying fastest.\n"
    "\n"
    "  --at A=x,y,...      the coordinates of base point A (every point the "
    "same\n"
    "                      dimension)\n"
    "  --set k=SPEC        the value of const k; a list or lo:hi:count sweeps "
    "it\n"
    "                      (each value a whole grid of the params)\n"
    "  --param t=SPEC      the values of param t: 0.5, a list 0,0.25,1, or "
    "lo:hi:count\n"
    "  --output NAMES      which outputs, repeatable or comma-separated "
    "(default: all)\n"
    "  --format csv|json   CSV with a header (default), or JSON\n"
    "\nOnly the points, consts and params that the selected outputs use need\n"
    "to be given.  A sample at a pole or not finite is NaN in the output and\n"
    "makes the exit status 1 (docs/eval.md).\n" COMMON_HELP;

static const char plot_help[] = PLOT_USAGE
    "\n"
    "Draws the curves of the point outputs over the swept param's range as "
    "SVG,\n"
    "the base points labelled, and at --at-param the construction "
    "(docs/plot.md).\n"
    "\n"
    "  --at A=x,y,...      the coordinates of base point A (every point the "
    "same\n"
    "                      dimension; 3 and more are projected, see --view)\n"
    "  --set k=VALUE       the value of const k\n"
    "  --param t=LO:HI[:N] the swept param and its range (default: the range "
    "the\n"
    "                      scheme declares; N initial segments, default 64)\n"
    "  --param u=VALUE     the value of a param that is not swept\n"
    "  --output NAMES      which point outputs, repeatable or comma-separated\n"
    "                      (default: all)\n"
    "  -o OUT.svg          write the SVG there (default: stdout)\n"
    "  --at-param t=VALUE  draw the construction there: its points and "
    "lines\n"
    "  --aux NAMES         which of its points (default: every point "
    "definition)\n"
    "  --view V            xy, xz, yz, iso (default in 3D) or "
    "AZIMUTH,ELEVATION\n"
    "  --tangents SPEC     tangent vectors dM/dt at these param values\n"
    "  --tangent-scale S   drawn as S*dM/dt (default 1)\n"
    "  --comb              the curvature comb; --comb-teeth N (default 100),\n"
    "                      --comb-scale S (default: automatic)\n"
    "  --size W[xH]        pixels (default 720 wide)\n"
    "  --window X0,Y0,X1,Y1  the window in projected coordinates (default: "
    "fitted)\n"
    "  --max-samples N     the sample budget per curve (default 4000)\n"
    "\nPoles are cut, never joined.\n" COMMON_HELP;

static const char analyze_help[] = ANALYZE_USAGE
    "\n"
    "Finds exactly what each output curve in one param is (docs/analyze.md):\n"
    "its degree, order and whether it is traced once; the point and the "
    "first\n"
    "non-zero derivative at each end of the declared range, and its "
    "order of\n"
    "smoothness there; the base points it passes through; its poles, stop\n"
    "points and (plane curves) inflections in the range, exact where they "
    "are\n"
    "rational or quadratic, else isolated to 1e-15; the implicit equation "
    "of a\n"
    "plane curve over three base points; the poles of every definition.\n"
    "A const without --set is taken at a generic value (said in the "
    "report);\n"
    "a curve with functions (sin, sqrt, abs, ...) is analysed numerically.\n"
    "\n"
    "  --output NAMES      which outputs, repeatable or comma-separated "
    "(default: all)\n"
    "  --set k=VALUE       analyse with const k at this exact value (1/3, "
    "0.25)\n"
    "  --at A=x,y,...      coordinates of base points: then also the "
    "curvature at the\n"
    "                      ends, its largest and smallest value and the arc "
    "length,\n"
    "                      and the implicit equation in x, y (exact "
    "coordinates)\n"
    "  --format FORMAT     text (for people, the default), json (for "
    "programs) or\n"
    "                      latex (the formulas as derive --format "
    "latex)\n" COMMON_HELP;

static const char help_help[] =
    HELP_USAGE "\nPrints the general usage, or the help of one command.\n";

typedef struct HelpEntry {
    const char *cmd, *usage, *help;
} HelpEntry;

static const HelpEntry entries[] = {
    {"derive", DERIVE_USAGE, derive_help},
    {"emit-c", EMIT_C_USAGE, emit_c_help},
    {"eval", EVAL_USAGE, eval_help},
    {"plot", PLOT_USAGE, plot_help},
    {"fit", FIT_USAGE, fit_help},
    {"natural", NATURAL_USAGE, natural_help},
    {"analyze", ANALYZE_USAGE, analyze_help},
    {"help", HELP_USAGE, help_help},
};

static const HelpEntry *find(const char *cmd)
{
    for (size_t i = 0; i < sizeof entries / sizeof entries[0]; i++)
        if (strcmp(entries[i].cmd, cmd) == 0)
            return &entries[i];
    return NULL;
}

const char *help_text(const char *cmd)
{
    const HelpEntry *e = find(cmd);
    return e ? e->help : NULL;
}

const char *help_usage(const char *cmd)
{
    const HelpEntry *e = find(cmd);
    return e ? e->usage : NULL;
}

/* pointcalc help [CMD] */
int cli_help(int argc, char **argv, FILE *out, FILE *err)
{
    if (argc > 2)
        return args_usage_error(err, HELP_USAGE,
                                "help takes one command, found '%s'", argv[2]);
    const char *h = argc == 2 ? help_text(argv[1]) : cli_usage;
    if (!h)
        return args_usage_error(err, HELP_USAGE,
                                "no help on '%s'; expected derive, emit-c, "
                                "eval, plot, fit or analyze",
                                argv[1]);
    return fputs(h, out) < 0;
}
