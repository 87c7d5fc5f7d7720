/*
 * plot_cli.h - the plot subcommand (docs/plot.md), called by the driver.
 * argv[0] is the subcommand word.  The SVG goes to -o's file (or out),
 * messages to err.  Exit status: 0 ok, 1 scheme error or unwritable
 * output, 2 usage error.
 */
#ifndef PC_PLOT_CLI_H
#define PC_PLOT_CLI_H

#include <stdio.h>

extern const char plot_usage[];
extern const char plot_help_text[]; // the options, after the usage
int plot_main(int argc, char **argv, FILE *out, FILE *err);

#endif
