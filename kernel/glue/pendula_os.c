/* Output files for the batch programs, with every error checked.
 *
 * gfortran (12) ignores ENOSPC from write(2) (seen with /dev/full), so the
 * batch programs format their lines in Fortran and hand them here.  One rule
 * for every file written (the same as python/pendula/_files.py):
 *
 *   - only a regular file (or a name not yet taken) is ever written; a device,
 *     FIFO, socket or folder under the name is refused (PENDULA_ENOTREG) and
 *     left as it was.  Standard output is the path "-";
 *   - the content goes to a fresh temporary name beside the target
 *     (".NAME.XXXXXX.part", mode 0666 less the umask), is fsynced, and is
 *     renamed onto the target only when complete;
 *   - a missing parent folder is an error (ENOENT), never created;
 *   - every temporary name is kept in a small table until it is renamed or
 *     removed, so that the program's failure path (pendula_out_abandon_all) and
 *     SIGINT / SIGTERM / SIGHUP (pendula_out_guard_signals installs a handler
 *     that unlinks them, then re-raises the signal) leave nothing behind.
 *
 * The table is the one piece of process state here: a signal handler can only
 * reach what is global.  It is touched by the batch programs' single thread.
 * Each call returns 0 on success and an errno-like code otherwise.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* a target that is not a regular file (device, FIFO, socket): refused */
#define PENDULA_ENOTREG 10001
#define MAX_TMP 8
#define TMP_LEN 4200

static char tmp_table[MAX_TMP][TMP_LEN];
static volatile sig_atomic_t tmp_used[MAX_TMP];

static void remember(const char *tmp)
{
    for (int i = 0; i < MAX_TMP; i++) {
        if (!tmp_used[i]) {
            strncpy(tmp_table[i], tmp, TMP_LEN - 1);
            tmp_table[i][TMP_LEN - 1] = '\0';
            tmp_used[i] = 1;
            return;
        }
    }
}

static void forget(const char *tmp)
{
    for (int i = 0; i < MAX_TMP; i++) {
        if (tmp_used[i] && strcmp(tmp_table[i], tmp) == 0) {
            tmp_used[i] = 0;
            return;
        }
    }
}

/* Remove every temporary file still open (the failure path of a program). */
void pendula_out_abandon_all(void)
{
    for (int i = 0; i < MAX_TMP; i++) {
        if (tmp_used[i]) {
            unlink(tmp_table[i]);
            tmp_used[i] = 0;
        }
    }
}

static void on_signal(int sig)
{
    /* unlink is async-signal-safe; then die of the signal as if unhandled */
    for (int i = 0; i < MAX_TMP; i++)
        if (tmp_used[i])
            unlink(tmp_table[i]);
    signal(sig, SIG_DFL);
    raise(sig);
}

/* Install the handler that removes the temporary files on SIGINT, SIGTERM and
   SIGHUP, and ignore SIGXFSZ (batch programs only: never in the Python process). */
void pendula_out_guard_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    /* a file-size limit (ulimit -f) is a write error (EFBIG, exit 5), not a core dump */
    signal(SIGXFSZ, SIG_IGN);
}

/* 1 when path names a regular file or nothing yet; 0 for a device, FIFO, folder, ... */
int pendula_regular_or_absent(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return 1;
    return S_ISREG(st.st_mode) ? 1 : 0;
}

/* What a file to be read is, before anything reads it (the scene readers of both
   programs, so that they give one verdict): 0 a regular file (its size in *size),
   -ENOENT no such file, -EISDIR a folder, -PENDULA_ENOTREG a device, FIFO or
   socket (never read: /dev/zero would never end, a FIFO would wait), or -errno
   when it cannot be opened (EACCES ...).  Opened without blocking (O_NONBLOCK:
   a FIFO's open never waits for a writer) and examined by fstat on that descriptor. */
int pendula_read_kind(const char *path, long long *size)
{
    struct stat st;
    int fd, e;
    *size = 0;
    if (path[0] == '\0')
        return -ENOENT;
    if (stat(path, &st) != 0)
        return -errno;
    if (S_ISDIR(st.st_mode))
        return -EISDIR;
    if (!S_ISREG(st.st_mode))
        return -PENDULA_ENOTREG;
    fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return -errno;
    e = fstat(fd, &st) != 0 ? errno : 0;
    close(fd);
    if (e)
        return -e;
    if (!S_ISREG(st.st_mode))
        return -PENDULA_ENOTREG;
    *size = (long long)st.st_size;
    return 0;
}

/* Open path for writing: fd > 0 on success (1 for "-"), -errno on failure
   (-PENDULA_ENOTREG for a target that is not a regular file, -EISDIR for a
   folder).  tmp receives the temporary name used ("" for standard output). */
int pendula_out_open(const char *path, char *tmp, int tmplen)
{
    struct stat st;
    const char *slash;
    int fd, n;
    mode_t mask;
    tmp[0] = '\0';
    if (strcmp(path, "-") == 0)
        return 1;
    if (path[0] == '\0')
        return -ENOENT;
    if (stat(path, &st) == 0) {
        if (S_ISDIR(st.st_mode))
            return -EISDIR;
        if (!S_ISREG(st.st_mode))
            return -PENDULA_ENOTREG;
    }
    slash = strrchr(path, '/');
    if (slash == NULL)
        n = snprintf(tmp, (size_t)tmplen, ".%s.XXXXXX.part", path);
    else
        n = snprintf(tmp, (size_t)tmplen, "%.*s/.%s.XXXXXX.part", (int)(slash - path), path, slash + 1);
    if (n < 0 || n >= tmplen || n >= TMP_LEN) {
        tmp[0] = '\0';
        return -ENAMETOOLONG;
    }
    fd = mkstemps(tmp, 5);
    if (fd < 0) {
        int e = errno;
        tmp[0] = '\0';
        return -e;
    }
    remember(tmp);
    mask = umask(0);
    umask(mask);
    (void)fchmod(fd, 0666 & ~mask);
    return fd;
}

/* Write n bytes; 0 or errno. */
int pendula_out_write(int fd, const char *buf, long n)
{
    while (n > 0) {
        ssize_t w = write(fd, buf, (size_t)n);
        if (w < 0) {
            if (errno == EINTR)
                continue;
            return errno;
        }
        buf += w;
        n -= w;
    }
    return 0;
}

/* Finish: fsync and close (not standard output), rename tmp onto path when
   tmp is not empty; on failure (or when abandon is set) remove tmp.  0 or errno. */
int pendula_out_close(int fd, const char *tmp, const char *path, int abandon)
{
    int err = 0;
    if (fd != 1) {
        if (!abandon && fsync(fd) != 0)
            err = errno;
        if (close(fd) != 0 && !err)
            err = errno;
    } else if (!abandon && fflush(stdout) != 0) {
        err = errno;
    }
    if (tmp[0] != '\0') {
        if (!err && !abandon) {
            /* the target may have become something else meanwhile: still only a regular file is replaced */
            if (!pendula_regular_or_absent(path))
                err = PENDULA_ENOTREG;
            else if (rename(tmp, path) != 0)
                err = errno;
        }
        if (err || abandon)
            unlink(tmp);
        forget(tmp);
    }
    return err;
}

/* The words for an error code of the calls above (strerror, or the refusal
   of a target that is not a regular file). */
void pendula_out_errtext(int err, char *buf, int len)
{
    if (err == PENDULA_ENOTREG)
        snprintf(buf, (size_t)len, "not a regular file (a device, FIFO or socket is never written or replaced)");
    else
        snprintf(buf, (size_t)len, "%s", strerror(err));
}

/* A real as text, the one number format of every CSV pendula writes (the
   Python layer writes '%.17g' % x): 17 significant digits, enough to read
   back the same double, trailing zeros dropped; nan, inf, -inf. */
int pendula_fmt_real(double x, char *buf, int len)
{
    if (isnan(x))
        return snprintf(buf, (size_t)len, "nan");
    return snprintf(buf, (size_t)len, "%.17g", x);
}
