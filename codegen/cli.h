/*
 * cli.h - the emit-c and eval subcommands (contract section 4), called by
 * compiler/main.c.  argv[0] is the subcommand word, argv[1..] the
 * arguments as typed.  Results go to out, messages to err; nothing reaches
 * out when the scheme has an error or the command line is wrong.
 *
 * Exit status: 0 ok, 1 scheme error (or an output file that cannot be
 * written; for eval also: some sample hit a pole, see docs/eval.md),
 * 2 usage error.
 */
#ifndef PC_CLI_H
#define PC_CLI_H

#include <stdio.h>

int emit_c_main(int argc, char **argv, FILE *out, FILE *err);
int eval_main(int argc, char **argv, FILE *out, FILE *err);

#endif
