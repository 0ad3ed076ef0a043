// SPDX-License-Identifier: MIT
#include "io/input_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *file_type_name(mode_t mode)
{
    if (S_ISDIR(mode))
        return "a directory";
    if (S_ISFIFO(mode))
        return "a FIFO";
    if (S_ISCHR(mode))
        return "a character device";
    if (S_ISBLK(mode))
        return "a block device";
    if (S_ISSOCK(mode))
        return "a socket";
    return "not a regular file";
}

int input_file_open(const char *path, const char *kind, long long *size, Error *err)
{
    /* O_NONBLOCK: opening a FIFO must not wait for a writer before fstat can refuse it. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ENOENT)
            error_set(err, ERR_FILE_MISSING, path, 0, "%s: no such file", path);
        else
            error_set(err, ERR_FILE_READ, path, 0, "%s: cannot open %s: %s", path, kind,
                      strerror(errno));
        return -1;
    }
    struct stat st;
    if (fstat(fd, &st) != 0) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: %s", path, strerror(errno));
    } else if (!S_ISREG(st.st_mode)) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: is %s, not %s", path,
                  file_type_name(st.st_mode), kind);
    } else {
        *size = (long long)st.st_size;
        return fd;
    }
    close(fd);
    return -1;
}

bool input_file_read(const char *path, const char *kind, size_t limit, char **data, size_t *size,
                     Error *err)
{
    *data = NULL;
    *size = 0;
    long long file_size = 0;
    int fd = input_file_open(path, kind, &file_size, err);
    if (fd < 0)
        return false;
    bool ok = false;
    if ((unsigned long long)file_size > limit) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: %lld bytes is over the limit of %zu MiB for %s",
                  path, file_size, limit >> 20, kind);
    } else if (!(*data = malloc((size_t)file_size + 1))) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory for %lld bytes", path, file_size);
    } else {
        /* The file may shrink while it is read: what was read is what counts. */
        size_t want = (size_t)file_size, got = 0;
        ok = true;
        while (got < want) {
            ssize_t n = read(fd, *data + got, want - got);
            if (n < 0 && errno == EINTR)
                continue;
            if (n < 0) {
                error_set(err, ERR_FILE_READ, path, 0, "%s: %s", path, strerror(errno));
                ok = false;
                break;
            }
            if (n == 0)
                break;
            got += (size_t)n;
        }
        if (ok) {
            (*data)[got] = '\0';
            *size = got;
        } else {
            free(*data);
            *data = NULL;
        }
    }
    close(fd);
    return ok;
}
