/*
 * outfile.h - files the commands write (emit-c's -o and --header, plot's
 * -o): whole or not at all, and written the way a shell's `>` writes them.
 *
 * A regular file (new, or reached through symbolic links) is written to a
 * temporary file beside it and renamed into place: a reader sees the old
 * file or the new one, never a mixture.  The link stays a link (the
 * temporary goes beside the link's target), an existing file keeps its
 * mode.  Anything else that exists (a device, a FIFO, /dev/stdout) is
 * opened and written through, as `>` does.  An existing file the user may
 * not write is refused ("Permission denied"); root, whom permissions do
 * not stop, is refused a regular file that nobody may write (no w bit).
 * SIGINT and SIGTERM during the write remove the temporaries.
 */
#ifndef PC_OUTFILE_H
#define PC_OUTFILE_H

#include <stddef.h>
#include <stdio.h>

/* one file to write: path NULL means the stream `out` */
typedef struct OutFile {
    const char *path;
    const char *text;
    size_t len;
} OutFile;

/* 1 when a and b name the same file: the same text, the same regular file
 * (inode), or -- when they do not exist yet -- the same place once
 * symbolic links, '.', '..' and repeated slashes are resolved */
int outfile_same(const char *a, const char *b);

/* Writes files[0..n-1]: every temporary first, then the files written
 * through, then the renames, then the ones that go to out.  0, or 1 after
 * a message on err; on a failure before the renames no file is changed
 * and no temporary is left. */
int outfile_write_all(const OutFile *files, int n, FILE *out, FILE *err);

/* one file: outfile_write_all of {path, text, len} */
int outfile_write(const char *path, const char *text, size_t len, FILE *out,
                  FILE *err);

#endif
