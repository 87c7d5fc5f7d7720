/*
 * outfile.c - whole-file writes by rename, or through to what is not a
 * regular file (see outfile.h).
 *
 * Each path is first resolved: its symbolic links followed one by one
 * (readlink) to the file a rename must replace.  A path that exists and is
 * not a regular file, or whose links pass through /proc (/dev/stdout is
 * /proc/self/fd/1, a "magic" link that may name a pipe), is written
 * through by open(2).  The temporaries are named in a small table the
 * signal handler reads; it only calls unlink and raise.
 */
#define _XOPEN_SOURCE 700 /* readlink, realpath, sigaction, fchown */
#include "driver/cli/outfile.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/diag.h"
#include "base/mem.h"

enum { MAX_LINKS = 40, MAX_PENDING = 4 };

/* one file on its way: where it goes and how */
typedef struct Pending {
    char *target;   // the path written or renamed onto (owned)
    char *tmp;      // the temporary beside it (owned), NULL: written through
    int through;    // 1: open and write the path itself
    int exists;     // the target existed (regular)
    int sig;        // its slot in sig_tmp
    struct stat st; // its status then
} Pending;

/* the temporaries the signal handler removes */
static char *volatile sig_tmp[MAX_PENDING];
static volatile sig_atomic_t sig_ntmp;

static void on_signal(int sig)
{
    for (int i = 0; i < sig_ntmp; i++)
        if (sig_tmp[i])
            unlink(sig_tmp[i]);
    /* SA_RESETHAND restored the default: end as the signal would */
    raise(sig);
}

static const int sig_caught[] = {SIGINT, SIGTERM, SIGHUP};
enum { NSIG_CAUGHT = sizeof sig_caught / sizeof sig_caught[0] };

/* installs on_signal where the signal is not ignored; old[] to restore */
static void signals_catch(struct sigaction old[NSIG_CAUGHT])
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sa.sa_flags = SA_RESETHAND;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < NSIG_CAUGHT; i++)
        sigaddset(&sa.sa_mask, sig_caught[i]);
    for (int i = 0; i < NSIG_CAUGHT; i++) {
        sigaction(sig_caught[i], NULL, &old[i]);
        if (old[i].sa_handler != SIG_IGN)
            sigaction(sig_caught[i], &sa, NULL);
    }
}

static void signals_restore(const struct sigaction old[NSIG_CAUGHT])
{
    for (int i = 0; i < NSIG_CAUGHT; i++)
        sigaction(sig_caught[i], &old[i], NULL);
}

/* blocks (1) or unblocks (0) the caught signals */
static void signals_block(int on, sigset_t *saved)
{
    sigset_t s;
    sigemptyset(&s);
    for (int i = 0; i < NSIG_CAUGHT; i++)
        sigaddset(&s, sig_caught[i]);
    if (on)
        sigprocmask(SIG_BLOCK, &s, saved);
    else
        sigprocmask(SIG_SETMASK, saved, NULL);
}

/* dir part of path with its slash ("" for none), owned */
static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t n = slash ? (size_t)(slash - path) + 1 : 0;
    char *d = pc_xmalloc(n + 1);
    memcpy(d, path, n);
    d[n] = '\0';
    return d;
}

/* Follows the symbolic links of path to the file they end at (owned).
 * *proc is set when a link leads into /proc; 0, or -1 with errno (ELOOP,
 * or readlink's error). */
static int resolve_links(char **res, const char *path, int *proc)
{
    char *cur = pc_xstrdup(path);
    *proc = strncmp(cur, "/proc/", 6) == 0;
    for (int hops = 0;; hops++) {
        struct stat st;
        if (lstat(cur, &st) != 0 || !S_ISLNK(st.st_mode)) {
            *res = cur;
            return 0;
        }
        if (hops == MAX_LINKS) {
            pc_free(cur);
            errno = ELOOP;
            return -1;
        }
        char buf[PATH_MAX];
        ssize_t k = readlink(cur, buf, sizeof buf - 1);
        if (k < 0) {
            int e = errno;
            pc_free(cur);
            errno = e;
            return -1;
        }
        buf[k] = '\0';
        char *next;
        if (buf[0] == '/')
            next = pc_xstrdup(buf);
        else {
            char *d = dir_of(cur);
            size_t dn = strlen(d);
            next = pc_xmalloc(dn + (size_t)k + 1);
            memcpy(next, d, dn);
            memcpy(next + dn, buf, (size_t)k + 1);
            pc_free(d);
        }
        pc_free(cur);
        cur = next;
        if (strncmp(cur, "/proc/", 6) == 0)
            *proc = 1;
    }
}

/* the place path names once its links, its directory's '.', '..' and
 * slashes are resolved (owned); the path itself when that fails */
static char *canonical(const char *path)
{
    char *r;
    int proc;
    if (resolve_links(&r, path, &proc) != 0)
        return pc_xstrdup(path);
    char *d = dir_of(r);
    const char *base = r + strlen(d);
    char *rd = realpath(d[0] ? d : ".", NULL);
    char *c;
    if (rd) {
        size_t n = strlen(rd) + strlen(base) + 2;
        c = pc_xmalloc(n);
        snprintf(c, n, "%s/%s", strcmp(rd, "/") == 0 ? "" : rd, base);
        free(rd); /* realpath: libc's block, uncounted */
        pc_free(r);
    } else
        c = r;
    pc_free(d);
    return c;
}

int outfile_same(const char *a, const char *b)
{
    struct stat sa, sb;
    int ea = stat(a, &sa) == 0, eb = stat(b, &sb) == 0;
    if (ea && !S_ISREG(sa.st_mode))
        return 0; /* a device or a FIFO may take both */
    if (strcmp(a, b) == 0)
        return 1;
    if (ea && eb)
        return S_ISREG(sa.st_mode) && sa.st_dev == sb.st_dev &&
               sa.st_ino == sb.st_ino;
    if (ea || eb)
        return 0;
    char *ca = canonical(a), *cb = canonical(b);
    int same = strcmp(ca, cb) == 0;
    pc_free(ca);
    pc_free(cb);
    return same;
}

/* the target a rename replaces: dir/.name.XXXXXX beside it (owned) */
static char *temp_name(const char *path)
{
    char *d = dir_of(path);
    size_t dn = strlen(d), cap = strlen(path) + 16;
    char *tmp = pc_xmalloc(cap);
    memcpy(tmp, d, dn);
    snprintf(tmp + dn, cap - dn, ".%s.XXXXXX", path + dn);
    pc_free(d);
    return tmp;
}

/* writes all of text to fd; 0, or -1 with errno */
static int write_all(int fd, const char *text, size_t len)
{
    while (len > 0) {
        ssize_t k = write(fd, text, len);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0) {
            if (k == 0)
                errno = EIO;
            return -1;
        }
        text += k;
        len -= (size_t)k;
    }
    return 0;
}

/* Decides how f goes: through, or by a temporary (created, filled and
 * registered with the signal handler).  0, or -1 with errno. */
static int prepare(Pending *pd, const OutFile *f)
{
    struct stat st;
    int proc = 0;
    memset(pd, 0, sizeof *pd);
    if (stat(f->path, &st) == 0 && !S_ISREG(st.st_mode)) {
        if (S_ISDIR(st.st_mode)) {
            errno = EISDIR;
            return -1;
        }
        pd->through = 1;
    } else if (resolve_links(&pd->target, f->path, &proc) != 0)
        return -1;
    if (!pd->through && proc) {
        pc_free(pd->target);
        pd->target = NULL;
        pd->through = 1;
    }
    if (pd->through)
        pd->target = pc_xstrdup(f->path);
    if (stat(pd->target, &pd->st) == 0 && S_ISREG(pd->st.st_mode)) {
        pd->exists = 1;
        /* as `>` would: the user must be allowed to write the file; root
         * may write anything, so for root a file nobody may write is the
         * sign of one meant to stay as it is */
        if (access(pd->target, W_OK) != 0 ||
            (geteuid() == 0 && (pd->st.st_mode & 0222) == 0)) {
            errno = EACCES;
            return -1;
        }
    }
    if (pd->through)
        return 0;
    pd->tmp = temp_name(pd->target);
    sigset_t saved;
    signals_block(1, &saved);
    int fd = mkstemp(pd->tmp);
    int e = errno;
    if (fd >= 0) {
        pd->sig = sig_ntmp;
        sig_tmp[sig_ntmp++] = pd->tmp;
    }
    signals_block(0, &saved);
    if (fd < 0) {
        pc_free(pd->tmp);
        pd->tmp = NULL;
        if (pd->exists && (e == EACCES || e == EPERM)) {
            /* a file we may write in a directory we may not: written in
             * place, as `>` writes it (not whole, but not refused) */
            pd->through = 1;
            return 0;
        }
        errno = e;
        return -1;
    }
    mode_t mode;
    if (pd->exists) {
        /* keep the owner where we may (root), then the mode */
        if (fchown(fd, pd->st.st_uid, pd->st.st_gid) != 0) {
            /* not ours to give away: the file becomes the user's */
        }
        mode = pd->st.st_mode & 07777;
    } else {
        /* mkstemp makes the file 0600; give it what a new file gets */
        mode_t mask = umask(0);
        umask(mask);
        mode = 0666 & ~mask;
    }
    int ok = fchmod(fd, mode) == 0 && write_all(fd, f->text, f->len) == 0;
    e = errno;
    if (close(fd) != 0 && ok) {
        ok = 0;
        e = errno;
    }
    errno = e;
    return ok ? 0 : -1;
}

/* writes f through to its path; 0, or -1 with errno */
static int write_through(const Pending *pd, const OutFile *f)
{
    int fd = open(pd->target, O_WRONLY | O_TRUNC | O_NOCTTY);
    if (fd < 0)
        return -1;
    int ok = write_all(fd, f->text, f->len) == 0;
    int e = errno;
    if (close(fd) != 0 && ok) {
        ok = 0;
        e = errno;
    }
    errno = e;
    return ok ? 0 : -1;
}

static int report(FILE *err, const char *path, int e)
{
    fputs("pointcalc: cannot write '", err);
    diag_fput_escaped(err, path);
    fprintf(err, "': %s\n", strerror(e));
    return 1;
}

int outfile_write_all(const OutFile *files, int n, FILE *out, FILE *err)
{
    Pending pd[MAX_PENDING];
    struct sigaction old[NSIG_CAUGHT];
    int rc = 0, np = 0;
    if (n > MAX_PENDING)
        n = MAX_PENDING;
    signals_catch(old);
    /* the temporaries, then the files written through, then the renames */
    for (; np < n && rc == 0; np++)
        if (files[np].path && prepare(&pd[np], &files[np]) != 0)
            rc = report(err, files[np].path, errno);
        else if (!files[np].path)
            memset(&pd[np], 0, sizeof pd[np]);
    for (int i = 0; i < np && rc == 0; i++)
        if (pd[i].through && write_through(&pd[i], &files[i]) != 0)
            rc = report(err, files[i].path, errno);
    for (int i = 0; i < np && rc == 0; i++)
        if (pd[i].tmp && rename(pd[i].tmp, pd[i].target) != 0)
            rc = report(err, files[i].path, errno);
        else if (pd[i].tmp) {
            /* renamed: nothing to remove */
            sigset_t saved;
            signals_block(1, &saved);
            sig_tmp[pd[i].sig] = NULL;
            signals_block(0, &saved);
            pc_free(pd[i].tmp);
            pd[i].tmp = NULL;
        }
    sigset_t saved;
    signals_block(1, &saved);
    for (int i = 0; i < np; i++)
        if (pd[i].tmp)
            unlink(pd[i].tmp);
    sig_ntmp = 0;
    signals_block(0, &saved);
    signals_restore(old);
    for (int i = 0; i < np; i++) {
        pc_free(pd[i].tmp);
        pc_free(pd[i].target);
    }
    for (int i = 0; i < n && rc == 0; i++)
        if (!files[i].path)
            fwrite(files[i].text, 1, files[i].len, out);
    return rc;
}

int outfile_write(const char *path, const char *text, size_t len, FILE *out,
                  FILE *err)
{
    OutFile f = {path, text, len};
    return outfile_write_all(&f, 1, out, err);
}
