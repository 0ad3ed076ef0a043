// SPDX-License-Identifier: MIT
#include "base/fs.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

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
