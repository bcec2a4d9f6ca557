/* Output files for the batch programs, with every error checked.
 *
 * gfortran (12) ignores ENOSPC from write(2) (seen with /dev/full), so the
 * batch programs format their lines in Fortran and hand them here.  A regular
 * file (or a new one) is written under a temporary name beside it and renamed
 * into place only when everything reached the disk (fsync); a device, FIFO or
 * standard output (path "-") is written directly.  Each call returns 0 on
 * success and an errno-like code otherwise.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* 1 when path names a regular file or nothing yet; 0 for a device, FIFO, folder, ... */
int pendula_regular_or_absent(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return 1;
    return S_ISREG(st.st_mode) ? 1 : 0;
}

/* Open path for writing: fd > 0 on success (1 for "-"), -errno on failure.
   tmp receives the temporary name used ("" when written directly). */
int pendula_out_open(const char *path, char *tmp, int tmplen)
{
    int fd;
    tmp[0] = '\0';
    if (strcmp(path, "-") == 0)
        return 1;
    if (pendula_regular_or_absent(path)) {
        if (snprintf(tmp, (size_t)tmplen, "%s.part", path) >= tmplen)
            return -ENAMETOOLONG;
        fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    } else {
        fd = open(path, O_WRONLY);
    }
    return fd < 0 ? -errno : fd;
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
        if (!abandon && tmp[0] != '\0' && fsync(fd) != 0)
            err = errno;
        if (close(fd) != 0 && !err)
            err = errno;
    }
    if (tmp[0] != '\0') {
        if (!err && !abandon) {
            if (rename(tmp, path) != 0)
                err = errno;
        }
        if (err || abandon)
            unlink(tmp);
    }
    return err;
}
