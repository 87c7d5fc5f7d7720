/*
 * outfile.c - whole-file writes by rename (see outfile.h).
 */
#include "compiler/cli/outfile.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "compiler/mem.h"

int outfile_same(const char *a, const char *b)
{
    struct stat sa, sb;
    if (strcmp(a, b) == 0)
        return 1;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

/* dir/.name.XXXXXX next to path (owned) */
static char *temp_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t dir = slash ? (size_t)(slash - path) + 1 : 0;
    size_t cap = strlen(path) + 16;
    char *tmp = pc_xmalloc(cap);
    memcpy(tmp, path, dir);
    snprintf(tmp + dir, cap - dir, ".%s.XXXXXX", path + dir);
    return tmp;
}

int outfile_write(const char *path, const char *text, size_t len, FILE *out,
                  FILE *err)
{
    if (!path) {
        fwrite(text, 1, len, out);
        return 0;
    }
    char *tmp = temp_name(path);
    int fd = mkstemp(tmp);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    int ok = f != NULL && fwrite(text, 1, len, f) == len;
    int e = errno;
    if (f != NULL && fclose(f) != 0 && ok) {
        ok = 0;
        e = errno;
    } else if (f == NULL && fd >= 0) {
        close(fd);
    }
    if (ok) {
        /* mkstemp makes the file 0600; give it what a new file gets */
        mode_t mask = umask(0);
        umask(mask);
        chmod(tmp, 0666 & ~mask);
        if (rename(tmp, path) != 0) {
            ok = 0;
            e = errno;
        }
    }
    if (!ok) {
        fprintf(err, "pointcalc: cannot write '%s': %s\n", path, strerror(e));
        if (fd >= 0)
            unlink(tmp);
    }
    free(tmp);
    return !ok;
}
