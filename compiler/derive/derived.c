/*
 * derived.c - the Derived result: reading a scheme file (bounded in size
 * and time), freeing, errors reported after derivation, and finding an
 * output or a point by name.
 *
 * Around the pipeline (pipeline.c): derive_file reads, derive_source_ex
 * derives, the back ends read and free the Derived.
 */
#include "compiler/derive/derive_int.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/budget.h"
#include "base/mem.h"

static Derived *file_error(const char *filename, FILE *err, int *nerrors,
                           const char *fmt, const char *what)
{
    if (err) {
        diag_fput_escaped(err, filename);
        fputs(": error: ", err);
        fprintf(err, fmt, what);
        fputc('\n', err);
    }
    if (nerrors)
        *nerrors = 1;
    return NULL;
}

/* At most DERIVE_MAX_SOURCE bytes are read, whatever the file is (a
 * regular file is refused by its size before reading; a device or a pipe
 * after the limit + 1 bytes), so /dev/zero ends at once and in bounded
 * memory. */
Derived *derive_file(const char *filename, FILE *err, int *nerrors)
{
    DeriveOptions opt = {.max_seconds = BUDGET_DEFAULT_SECONDS};
    return derive_file_ex(filename, err, nerrors, &opt);
}

Derived *derive_file_ex(const char *filename, FILE *err, int *nerrors,
                        const DeriveOptions *opt)
{
    char limit[32];
    struct stat sb;
    snprintf(limit, sizeof limit, "%d MiB", DERIVE_MAX_SOURCE >> 20);
    /* O_NONBLOCK: opening a FIFO no one writes to does not wait; reading
     * anything but a regular file then waits (poll) within the time
     * budget, so a silent FIFO ends with a message, not the budget's
     * signal */
    int fd = open(filename, O_RDONLY | O_NONBLOCK | O_NOCTTY);
    if (fd < 0)
        return file_error(filename, err, nerrors, "cannot open the file: %s",
                          strerror(errno));
    if (fstat(fd, &sb) == 0 && S_ISDIR(sb.st_mode)) {
        close(fd);
        return file_error(filename, err, nerrors, "cannot read the file: %s",
                          "it is a directory");
    }
    int regular = fstat(fd, &sb) == 0 && S_ISREG(sb.st_mode);
    if (regular && sb.st_size > (off_t)DERIVE_MAX_SOURCE) {
        close(fd);
        return file_error(filename, err, nerrors,
                          "cannot read the file: it is larger than %s, the "
                          "limit of a scheme",
                          limit);
    }
    if (regular)
        fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    double budget = opt ? opt->max_seconds : 0;
    double deadline = budget > 0 ? derive_now_seconds() + budget : 0;
    size_t cap = 4096, len = 0;
    char *buf = pc_xmalloc(cap);
    int e = 0, timeout = 0;
    for (;;) {
        if (!regular) {
            int ms = -1;
            if (deadline > 0) {
                double left = deadline - derive_now_seconds();
                ms = left <= 0    ? 0
                     : left > 1e6 ? 1000000000
                                  : (int)(left * 1e3) + 1;
            }
            struct pollfd pfd = {.fd = fd, .events = POLLIN};
            int r = poll(&pfd, 1, ms);
            if (r < 0 && errno == EINTR)
                continue;
            if (r < 0) {
                e = errno;
                break;
            }
            if (r == 0) {
                timeout = 1;
                break;
            }
        }
        ssize_t got = read(fd, buf + len, cap - len);
        if (got < 0 && (errno == EINTR || errno == EAGAIN))
            continue;
        if (got < 0) {
            e = errno;
            break;
        }
        if (got == 0)
            break;
        len += (size_t)got;
        if (len > (size_t)DERIVE_MAX_SOURCE)
            break;
        if (len == cap) {
            cap = cap * 2 > (size_t)DERIVE_MAX_SOURCE + 1
                      ? (size_t)DERIVE_MAX_SOURCE + 1
                      : cap * 2;
            buf = pc_xrealloc(buf, cap);
        }
    }
    close(fd);
    if (len > (size_t)DERIVE_MAX_SOURCE) {
        pc_free(buf);
        return file_error(filename, err, nerrors,
                          "cannot read the file: it is larger than %s, the "
                          "limit of a scheme",
                          limit);
    }
    if (timeout) {
        char secs[32];
        budget_format_seconds(secs, sizeof secs, budget);
        pc_free(buf);
        return file_error(filename, err, nerrors,
                          "cannot read the file: it did not end within the "
                          "time budget of %s (a FIFO that no one writes "
                          "to?); raise it with --max-seconds",
                          secs);
    }
    if (e) {
        pc_free(buf);
        return file_error(filename, err, nerrors, "cannot read the file: %s",
                          strerror(e));
    }
    Derived *d = derive_source_ex(filename, buf, len, err, nerrors, opt);
    pc_free(buf);
    return d;
}

void derived_free(Derived *d)
{
    if (!d)
        return;
    for (slong i = 0; i < d->noutputs; i++)
        derive_output_clear(&d->outputs[i], &d->ring);
    pc_free(d->outputs);
    for (slong i = 0; i < d->nsteps; i++)
        derive_step_clear(&d->steps[i], &d->ring);
    pc_free(d->steps);
    for (slong i = 0; i < d->nnamed; i++)
        pc_free(d->named[i].name);
    pc_free(d->named);
    for (slong i = 0; i < d->nchecks; i++)
        pc_free(d->checks[i].detail);
    pc_free(d->checks);
    if (d->kernels) {
        kernels_clear(d->kernels);
        pc_free(d->kernels);
    }
    if (d->range)
        ratfun_vec_clear(d->range, 2 * d->nparams, &d->ring);
    pc_free(d->has_range);
    if (d->bound)
        ratfun_vec_clear(d->bound, 2 * (d->nparams + d->nconsts), &d->ring);
    pc_free(d->bound_flags);
    ring_clear(&d->ring);
    for (slong i = 0; i < d->npoints; i++)
        pc_free(d->points[i]);
    for (slong i = 0; i < d->nparams; i++)
        pc_free(d->params[i]);
    for (slong i = 0; i < d->nconsts; i++)
        pc_free(d->consts[i]);
    for (slong i = 0; i < d->nextra; i++)
        pc_free(d->extra[i]);
    pc_free(d->extra);
    pc_free(d->points);
    pc_free(d->params);
    pc_free(d->consts);
    pc_free(d->scheme);
    const Source *marked;
    Span span;
    budget_where(&marked, &span);
    if (marked == &d->src) /* no mark left pointing into freed memory */
        budget_statement(NULL, span);
    source_clear(&d->src);
    pc_free(d->filename);
    pc_free(d->text);
    pc_free(d);
}

void derived_mark(const Derived *d, slong i)
{
    budget_statement(&d->src, d->outputs[i].span);
}

void derived_error(const Derived *d, FILE *err, Span span, const char *fmt, ...)
{
    Source src;
    Diag diag;
    va_list ap;
    source_init(&src, d->filename, d->text, d->len);
    diag_init(&diag, &src, err);
    va_start(ap, fmt);
    diag_verror(&diag, span, fmt, ap);
    va_end(ap);
    source_clear(&src);
}

static slong find(char *const *names, slong n, const char *name)
{
    for (slong i = 0; i < n; i++)
        if (strcmp(names[i], name) == 0)
            return i;
    return -1;
}

slong derived_find_output(const Derived *d, const char *name)
{
    for (slong i = 0; i < d->noutputs; i++)
        if (strcmp(d->outputs[i].name, name) == 0)
            return i;
    return -1;
}

slong derived_find_point(const Derived *d, const char *name)
{
    return find(d->points, d->npoints, name);
}
