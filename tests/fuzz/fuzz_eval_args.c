/*
 * fuzz_eval_args.c - libFuzzer target for eval's command line: the input
 * is split at NUL bytes into arguments, which follow `eval` and a fixed
 * scheme (examples/desargues_arc.pcs, read from the working directory):
 * --at points, --set consts, --param specs (values, lists, lo:hi:count),
 * --output, --format, in any order and any spelling.  Every spec is also
 * parsed on its own (runtime/sample.h).  Any crash, sanitizer report, or
 * an exit status other than 0, 1 or 2, is a bug.  Inputs whose grid has
 * more than 10^4 rows are skipped: a long evaluation is what they ask for,
 * not a fault.  The same arguments then go to `plot` (its own options
 * among them: --at-param, --view, --tangents, --comb ...; the SVG to
 * /dev/null), unless one is -o, which would write a file.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "driver/cli/cli.h"
#include "runtime/sample.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define MAX_ARGS 64

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *buf = malloc(size + 1);
    char *argv[MAX_ARGS + 3];
    int argc = 0;
    double rows = 1;
    if (buf == NULL)
        return 0;
    memcpy(buf, data, size);
    buf[size] = '\0';
    argv[argc++] = (char *)"eval";
    argv[argc++] = (char *)"examples/desargues_arc.pcs";
    for (size_t i = 0; i <= size && argc < MAX_ARGS + 2;) {
        argv[argc++] = buf + i;
        i += strlen(buf + i) + 1;
    }
    argv[argc] = NULL;
    for (int i = 2; i < argc; i++) {
        const char *eq = strchr(argv[i], '=');
        Spec s;
        char msg[256];
        if (eq != NULL && sample_parse(&s, eq + 1, msg, sizeof msg) == 0) {
            if (strcmp(argv[i - 1], "--param") == 0 ||
                strcmp(argv[i - 1], "--set") == 0)
                rows *= (double)s.n;
            sample_clear(&s);
        }
    }
    if (rows <= 1e4) {
        FILE *out = fopen("/dev/null", "w"), *err = fopen("/dev/null", "w");
        if (out != NULL && err != NULL) {
            int rc = cli_eval(argc, argv, out, err);
            if (rc < 0 || rc > 2)
                abort();
            int writes = 0;
            for (int i = 2; i < argc; i++)
                writes |= strcmp(argv[i], "-o") == 0;
            argv[0] = (char *)"plot";
            rc = writes ? 0 : cli_plot(argc, argv, out, err);
            if (rc < 0 || rc > 2)
                abort();
        }
        if (out)
            fclose(out);
        if (err)
            fclose(err);
    }
    free(buf);
    return 0;
}
