// SPDX-License-Identifier: MIT
#include "base/fs.h"

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

bool fs_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

bool fs_make_dirs(const char *path)
{
    char copy[4096];
    if (!path[0] || (size_t)snprintf(copy, sizeof copy, "%s", path) >= sizeof copy)
        return false;
    for (char *p = copy + 1; *p; p++) {
        if (*p != '/')
            continue;
        *p = '\0';
        if (mkdir(copy, 0755) != 0 && errno != EEXIST)
            return false;
        *p = '/';
    }
    struct stat st;
    return (mkdir(copy, 0755) == 0 || errno == EEXIST) && stat(copy, &st) == 0 && S_ISDIR(st.st_mode);
}

bool fs_make_parent_dirs(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash || slash == path)
        return true;
    char folder[4096];
    if ((size_t)(slash - path) >= sizeof folder)
        return false;
    snprintf(folder, sizeof folder, "%.*s", (int)(slash - path), path);
    return fs_make_dirs(folder);
}

bool fs_has_suffix(const char *name, const char *suffix)
{
    size_t n = strlen(name), m = strlen(suffix);
    return n >= m && strcasecmp(name + n - m, suffix) == 0;
}

void fs_stem(const char *path, char *out, size_t size)
{
    if (size == 0)
        return;
    size_t end = strlen(path);
    while (end > 1 && path[end - 1] == '/') /* "scenes/box/" names the folder "box" */
        end--;
    size_t start = end;
    while (start > 0 && path[start - 1] != '/')
        start--;
    size_t len = end - start;
    const char *dot = NULL;
    for (const char *p = path + start; p < path + end; p++)
        if (*p == '.' && p != path + start)
            dot = p;
    if (dot)
        len = (size_t)(dot - (path + start));
    snprintf(out, size, "%.*s", (int)len, path + start);
}

/* ---- Paths inside files ------------------------------------------------------------------- */

static bool allow_outside_paths;

void fs_set_allow_outside_paths(bool allow) { allow_outside_paths = allow; }
bool fs_allow_outside_paths(void) { return allow_outside_paths; }

/* True when the relative path ref climbs above its starting folder ("a/../../b" does, "a/../b"
 * does not); "." and empty components do not count. */
static bool climbs_out(const char *ref)
{
    int depth = 0;
    for (const char *p = ref; *p;) {
        const char *end = strchr(p, '/');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        if (n == 2 && p[0] == '.' && p[1] == '.') {
            if (--depth < 0)
                return true;
        } else if (n > 0 && !(n == 1 && p[0] == '.')) {
            depth++;
        }
        p += n;
        while (*p == '/')
            p++;
    }
    return false;
}

bool fs_resolve_inside(const char *container, const char *ref, const char *what, char *out,
                       size_t size, Error *err)
{
    if (!allow_outside_paths && (ref[0] == '/' || climbs_out(ref))) {
        error_set(err, ERR_PATH_ESCAPES, container, 0,
                  "%s: %s \"%s\" leaves the file's folder (paths in a scene file are relative to "
                  "it; pt --allow-outside-paths reads them anyway)", container, what, ref);
        return false;
    }
    int n;
    const char *slash = strrchr(container, '/');
    if (ref[0] == '/' || !slash)
        n = snprintf(out, size, "%s", ref);
    else
        n = snprintf(out, size, "%.*s/%s", (int)(slash - container), container, ref);
    if (n < 0 || (size_t)n >= size) {
        error_set(err, ERR_TOO_LARGE, container, 0, "%s: %s: path too long", container, what);
        return false;
    }
    return true;
}

/* ---- Atomic writes -------------------------------------------------------------------------- */

/* Splits off the folder of `path` ("." when it has none). */
static bool folder_of(const char *path, char *folder, size_t size)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return snprintf(folder, size, ".") < (int)size;
    size_t length = slash == path ? 1 : (size_t)(slash - path);
    if (length >= size)
        return false;
    memcpy(folder, path, length);
    folder[length] = '\0';
    return true;
}

bool fs_check_writable(const char *path, Error *err)
{
    if (!path || !path[0]) {
        error_set(err, ERR_OUTPUT, "", 0, "output path is empty");
        return false;
    }
    char folder[PATH_MAX];
    /* Room for the ".tmp-<pid>" suffix of the temporary file. */
    if (strlen(path) + 32 >= sizeof folder || !folder_of(path, folder, sizeof folder)) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: output path is too long", path);
        return false;
    }
    struct stat info;
    size_t length = strlen(path);
    if (path[length - 1] == '/' || (stat(path, &info) == 0 && S_ISDIR(info.st_mode))) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: output path is a directory", path);
        return false;
    }
    /* The temporary file is renamed over the target: over a device (/dev/full, /dev/null), a FIFO
     * or a socket that would replace the node itself (as root, in /dev), so only a regular file
     * (or nothing yet) may be there. */
    if (stat(path, &info) == 0 && !S_ISREG(info.st_mode)) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: output path exists and is not a regular file", path);
        return false;
    }
    if (stat(folder, &info) != 0) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: folder %s does not exist (%s)", path, folder,
                  strerror(errno));
        return false;
    }
    if (!S_ISDIR(info.st_mode)) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: %s is not a folder", path, folder);
        return false;
    }
    if (access(folder, W_OK | X_OK) != 0) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: folder %s is not writable (%s)", path, folder,
                  strerror(errno));
        return false;
    }
    return true;
}

void fs_temp_path(const char *path, char *temp, size_t size)
{
    snprintf(temp, size, "%s.tmp-%ld", path, (long)getpid());
}

/* The process id in a name that is prefix followed by digits only (fs_temp_path's form), else 0. */
static long temp_owner(const char *name, const char *prefix)
{
    size_t length = strlen(prefix);
    if (strncmp(name, prefix, length) != 0 || !name[length] || strlen(name + length) > 9)
        return 0;
    for (const char *c = name + length; *c; c++)
        if (*c < '0' || *c > '9')
            return 0;
    return strtol(name + length, NULL, 10);
}

int fs_remove_stale_temps(const char *path)
{
    char folder[PATH_MAX], prefix[NAME_MAX + 1];
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    if (!folder_of(path, folder, sizeof folder) ||
        (size_t)snprintf(prefix, sizeof prefix, "%s.tmp-", base) >= sizeof prefix)
        return 0;
    DIR *dir = opendir(folder);
    if (!dir)
        return 0;
    int removed = 0;
    struct dirent *entry;
    while ((entry = readdir(dir))) {
        long pid = temp_owner(entry->d_name, prefix);
        char temp[PATH_MAX + NAME_MAX + 2];
        struct stat info;
        /* kill(pid, 0) fails with ESRCH only when no such process exists. */
        if (pid <= 0 || pid == (long)getpid() || kill((pid_t)pid, 0) == 0 || errno != ESRCH ||
            (size_t)snprintf(temp, sizeof temp, "%s/%s", folder, entry->d_name) >= sizeof temp ||
            lstat(temp, &info) != 0 || !S_ISREG(info.st_mode))
            continue;
        removed += unlink(temp) == 0;
    }
    closedir(dir);
    return removed;
}

/* Flushes the finished temporary file to disk, then renames it over the target: rename() is
 * atomic, and the flush keeps a crash from leaving a renamed but empty file. */
static bool commit_temp_file(const char *temp, const char *path, Error *err)
{
    int fd = open(temp, O_RDONLY);
    if (fd < 0 || fsync(fd) != 0) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot flush %s (%s)", path, temp,
                  strerror(errno));
        if (fd >= 0)
            close(fd);
        return false;
    }
    close(fd);
    if (rename(temp, path) != 0) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot rename %s over it (%s)", path, temp,
                  strerror(errno));
        return false;
    }
    return true;
}

static void (*g_before_rename)(void);
void fs_set_before_rename_hook(void (*hook)(void)) { g_before_rename = hook; }

bool fs_finish_atomic_write(const char *temp, const char *path, bool written, Error *err)
{
    if (written && g_before_rename)
        g_before_rename();
    if (written && commit_temp_file(temp, path, err))
        return true;
    unlink(temp);
    return false;
}

bool fs_write_atomic(const char *path, const void *data, size_t size, Error *err)
{
    if (!fs_check_writable(path, err))
        return false;
    char temp[PATH_MAX];
    fs_temp_path(path, temp, sizeof temp);
    FILE *f = fopen(temp, "wb");
    if (!f) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot create %s (%s)", path, temp,
                  strerror(errno));
        return false;
    }
    bool written = fwrite(data, 1, size, f) == size;
    int saved_errno = errno;
    if (fclose(f) != 0 && written)
        written = false, saved_errno = errno;
    if (!written)
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot write %s (%s)", path, temp,
                  strerror(saved_errno));
    return fs_finish_atomic_write(temp, path, written, err);
}
