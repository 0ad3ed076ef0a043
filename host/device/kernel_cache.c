// SPDX-License-Identifier: MIT
#include "device/kernel_cache.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

uint64_t kernel_cache_key(const char *const *parts, size_t n)
{
    uint64_t hash = 1469598103934665603ull;
    for (size_t i = 0; i < n; i++) {
        for (const unsigned char *p = (const unsigned char *)parts[i]; *p; p++)
            hash = (hash ^ *p) * 1099511628211ull;
        hash = (hash ^ 0xffu) * 1099511628211ull; /* keeps ("ab","c") apart from ("a","bc") */
    }
    return hash;
}

const char *kernel_cache_dir(void)
{
    static char dir[1024];
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (xdg && *xdg)
        snprintf(dir, sizeof dir, "%s/pt", xdg);
    else if (home && *home)
        snprintf(dir, sizeof dir, "%s/.cache/pt", home);
    else
        dir[0] = '\0';
    return dir;
}

static void entry_path(uint64_t key, char *out, size_t size)
{
    snprintf(out, size, "%s/kernels-%016llx.bin", kernel_cache_dir(), (unsigned long long)key);
}

bool kernel_cache_load(uint64_t key, unsigned char **data, size_t *size)
{
    if (!kernel_cache_dir()[0])
        return false;
    char path[1100];
    entry_path(key, path, sizeof path);
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    bool ok = false;
    if (fseek(f, 0, SEEK_END) == 0) {
        long n = ftell(f);
        if (n > 0 && fseek(f, 0, SEEK_SET) == 0) {
            *data = malloc((size_t)n);
            if (*data && fread(*data, 1, (size_t)n, f) == (size_t)n) {
                *size = (size_t)n;
                ok = true;
            } else {
                free(*data);
                *data = NULL;
            }
        }
    }
    fclose(f);
    return ok;
}

/* mkdir -p for the cache folder. */
static bool make_dirs(const char *dir)
{
    char path[1024];
    snprintf(path, sizeof path, "%s", dir);
    for (char *p = path + 1; *p; p++) {
        if (*p == '/') {
            *p = '\0';
            if (mkdir(path, 0755) != 0 && errno != EEXIST)
                return false;
            *p = '/';
        }
    }
    return mkdir(path, 0755) == 0 || errno == EEXIST;
}

void kernel_cache_store(uint64_t key, const unsigned char *data, size_t size)
{
    const char *dir = kernel_cache_dir();
    if (!dir[0] || !make_dirs(dir))
        return;
    char path[1100], tmp[1200];
    entry_path(key, path, sizeof path);
    snprintf(tmp, sizeof tmp, "%s.tmp-%d", path, (int)getpid());
    FILE *f = fopen(tmp, "wb");
    if (!f)
        return;
    bool ok = fwrite(data, 1, size, f) == size;
    ok = (fclose(f) == 0) && ok;
    if (!ok || rename(tmp, path) != 0)
        unlink(tmp);
}
