/*
 * outfile.h - files the commands write (emit-c's -o and --header): whole
 * or not at all.
 */
#ifndef PC_OUTFILE_H
#define PC_OUTFILE_H

#include <stddef.h>
#include <stdio.h>

/* 1 when a and b name the same file: the same text, or the same inode */
int outfile_same(const char *a, const char *b);

/* Writes text[0..len-1] to path, or to out when path is NULL; 0, or 1
 * after a message on err.  The file is written whole to a temporary file
 * in the same directory and renamed into place, so a reader (or a
 * concurrent pointcalc) sees the old file or the new one, never a
 * mixture, and a failed write leaves the old one alone. */
int outfile_write(const char *path, const char *text, size_t len, FILE *out,
                  FILE *err);

#endif
