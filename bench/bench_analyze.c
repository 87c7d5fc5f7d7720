/*
 * bench_analyze.c - `pointcalc analyze` in-process (issue 22, docs/analyze.md)
 * beside SymPy doing the same analysis.
 *
 * For each case: the derivation with its steps (derive_source_ex,
 * keep_steps), then analyze_derived on the one output (poles of every
 * definition included), each the median and range of ROUNDS runs; then
 * bench/sympy/bench_analyze.py on the same weights (read from `pointcalc
 * derive --format json`, not timed): poles, index, stop points, the series
 * at the ends and, over three base points, inflections and the implicit
 * equation by resultant - and the ratio of the medians.  PYTHON names the
 * interpreter (make bench finds one with SymPy); "skipped" without one.
 *
 * Goals (issue 22): the Desargues arc in <= 5 ms, the order-12
 * interpolation curve in <= 0.2 s, the book's plane curves of degree <= 6
 * (implicit equation included) in <= 50 ms each.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>

#include "bench/bench_util.h"

#include "base/mem.h"
#include "base/numfmt.h"
#include "compiler/analyze/analyze.h"

enum { ROUNDS = 21, NCASES = 10 };

typedef struct Case {
    const char *file, *define, *output, *lo, *hi;
    double goal_ms; // derive + analyze
} Case;

static const Case CASES[NCASES] = {
    {"examples/desargues_arc.pcs", "", "M", "0", "1", 5},
    {"examples/interpolation_bezier.pcs", "n=12", "X", "0", "1", 200},
    {"examples/desargues_arc.pcs", "", "M_CB", "0", "1", 50},
    {"examples/desargues_arc.pcs", "", "M_AD", "0", "1", 50},
    {"examples/interpolation_conic.pcs", "", "M_parabola", "0", "1", 50},
    {"examples/contour_arcs.pcs", "k=2", "M", "0", "1", 50},
    {"examples/contour_arcs.pcs", "k=3", "M", "0", "1", 50},
    {"examples/contour_arcs.pcs", "k=4", "M", "0", "1", 50},
    {"examples/contour_arcs.pcs", "k=5", "M", "0", "1", 50},
    {"examples/parabola_improper_point.pcs", "", "M63", "0", "1", 50},
};

static char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = pc_xmalloc(1 << 20);
    *len = fread(buf, 1, (1 << 20) - 1, f);
    fclose(f);
    return buf;
}

static Derived *derive(const Case *c, const char *text, size_t len)
{
    const char *defs[1] = {c->define};
    DeriveOptions opt = {.max_seconds = 600,
                         .defines = defs,
                         .ndefines = c->define[0] ? 1 : 0,
                         .keep_steps = 1};
    return derive_source_ex(c->file, text, len, stderr, NULL, &opt);
}

/* median derive and analyze times of one case (ms); -1 on failure */
static double bench_case(const Case *c, double *an_ms)
{
    size_t len;
    char *text = read_file(c->file, &len);
    double td[ROUNDS], ta[ROUNDS];
    if (!text)
        return -1;
    for (int r = 0; r < ROUNDS; r++) {
        double t0 = bench_now_ms();
        Derived *d = derive(c, text, len);
        double t1 = bench_now_ms();
        if (!d) {
            free(text);
            return -1;
        }
        int sel = (int)derived_find_output(d, c->output);
        if (sel < 0) {
            derived_free(d);
            free(text);
            return -1;
        }
        Analysis *a = analyze_derived(d, &sel, 1, NULL);
        ta[r] = bench_now_ms() - t1;
        td[r] = t1 - t0;
        if (r == 0 && a->curves[0].skip)
            printf("  (%s: %s)\n", c->output, a->curves[0].skip);
        analysis_free(a);
        derived_free(d);
    }
    free(text);
    double md, mlo, mhi, ma, alo, ahi;
    bench_stats(td, ROUNDS, &md, &mlo, &mhi);
    bench_stats(ta, ROUNDS, &ma, &alo, &ahi);
    char label[96];
    snprintf(label, sizeof label, "%s %s%s%s%s", c->file + 9, c->output,
             c->define[0] ? " (" : "", c->define, c->define[0] ? ")" : "");
    printf("  %-38s derive %6.3f ms, analyze %6.3f ms [%.3f, %.3f]; total "
           "%6.3f ms (goal %g: %s)\n",
           label, md, ma, alo, ahi, md + ma, c->goal_ms,
           md + ma <= c->goal_ms ? "met" : "MISSED");
    *an_ms = ma;
    return md;
}

/* SymPy on every case; prints each line with the ratio to analyze's
 * median */
static void bench_sympy(const double *an_ms)
{
    char cmd[4096];
    int n = snprintf(cmd, sizeof cmd,
                     "py=${PYTHON:-python3}; $py -c 'import sympy' 2>/dev/null "
                     "|| exit 3; exec $py bench/sympy/bench_analyze.py "
                     "build/pointcalc");
    for (int i = 0; i < NCASES; i++)
        n += snprintf(cmd + n, sizeof cmd - (size_t)n, " '%s|%s|%s|%s|%s'",
                      CASES[i].file, CASES[i].define, CASES[i].output,
                      CASES[i].lo, CASES[i].hi);
    printf("bench_analyze: SymPy, the same analysis of the same weights "
           "(bench/sympy/bench_analyze.py):\n");
    fflush(stdout);
    FILE *p = popen(cmd, "r");
    char line[256];
    int i = 0;
    while (p && i < NCASES && fgets(line, sizeof line, p)) {
        char name[128], val[32];
        double ms;
        if (sscanf(line, "%127s %31s", name, val) != 2)
            continue;
        if (strcmp(val, "timeout") == 0) {
            printf("  %-24s SymPy timeout (over 120 s)\n", name);
            i++;
            continue;
        }
        ms = pc_strtod(val, NULL);
        printf("  %-24s SymPy %9.1f ms = %7.0fx pointcalc's analyze\n", name,
               ms, an_ms[i] > 0 ? ms / an_ms[i] : 0);
        i++;
    }
    if (!p || pclose(p) != 0 || i == 0)
        printf("  skipped (no python3 with sympy, or the script failed)\n");
}

int main(void)
{
    mem_use_for_gmp_flint();
    printf("bench_analyze: derive (with steps) and analyze one output, "
           "in-process, median and range of %d rounds\n",
           ROUNDS);
    double an_ms[NCASES];
    for (int i = 0; i < NCASES; i++)
        if (bench_case(CASES + i, an_ms + i) < 0) {
            printf("  %s: failed\n", CASES[i].file);
            an_ms[i] = -1;
        }
    flint_cleanup_master();
    fflush(stdout);
    if (!getenv("PC_BENCH_PEERS") || strcmp(getenv("PC_BENCH_PEERS"), "0"))
        bench_sympy(an_ms);
    return 0;
}
