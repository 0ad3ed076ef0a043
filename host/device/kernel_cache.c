// SPDX-License-Identifier: MIT
#include "device/kernel_cache.h"

#include <errno.h>
#include <stdatomic.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

#include "base/env.h"
#include "base/error.h"
#include "base/fs.h"

/* An entry is a header then the driver's binary. The file is untrusted (truncated by a full disk,
 * written by another version, edited): drivers read their binaries without bounds checks (PoCL
 * reads past a truncated one), so nothing reaches the driver unless the header's size and
 * checksum match the bytes on disk. The "-v2" in the name keeps older, headerless entries apart. */
#define ENTRY_MAGIC "ptkcache"
#define ENTRY_VERSION 2u
/* No real program binary comes near this; a larger size field is corruption. */
#define ENTRY_MAX_PAYLOAD ((uint64_t)1 << 30)

typedef struct {
    char magic[8];
    uint32_t version, reserved;
    uint64_t payload_size;
    uint64_t payload_hash; /* FNV-1a 64 of the payload */
} EntryHeader;

static uint64_t fnv1a(const unsigned char *data, size_t size, uint64_t hash)
{
    for (size_t i = 0; i < size; i++)
        hash = (hash ^ data[i]) * 1099511628211ull;
    return hash;
}

uint64_t kernel_cache_key(const char *const *parts, size_t n)
{
    uint64_t hash = 1469598103934665603ull;
    for (size_t i = 0; i < n; i++) {
        hash = fnv1a((const unsigned char *)parts[i], strlen(parts[i]), hash);
        hash = (hash ^ 0xffu) * 1099511628211ull; /* keeps ("ab","c") apart from ("a","bc") */
    }
    return hash;
}

const char *kernel_cache_dir(void)
{
    /* One buffer per thread: a part can build on a thread of its own (device_build_in_background)
     * while the render's thread builds or loads another. */
    static _Thread_local char dir[1024];
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
    snprintf(out, size, "%s/kernels-%016llx-v2.bin", kernel_cache_dir(), (unsigned long long)key);
}

/* Why the entry's bytes cannot be a binary we wrote; NULL when they can. */
static const char *entry_problem(const unsigned char *bytes, size_t size)
{
    EntryHeader header;
    if (size < sizeof header)
        return "shorter than its header";
    memcpy(&header, bytes, sizeof header);
    if (memcmp(header.magic, ENTRY_MAGIC, sizeof header.magic) != 0)
        return "not a pt kernel cache entry";
    if (header.version != ENTRY_VERSION)
        return "written by another version of pt";
    if (header.payload_size == 0 || header.payload_size > ENTRY_MAX_PAYLOAD ||
        header.payload_size != size - sizeof header)
        return "truncated, or its size field is wrong";
    if (fnv1a(bytes + sizeof header, size - sizeof header, 1469598103934665603ull) !=
        header.payload_hash)
        return "checksum mismatch";
    return NULL;
}

bool kernel_cache_load(uint64_t key, unsigned char **data, size_t *size)
{
    *data = NULL;
    *size = 0;
    if (!kernel_cache_dir()[0])
        return false;
    char path[1100];
    entry_path(key, path, sizeof path);
    /* O_NONBLOCK: a FIFO in place of the entry must not block the open; fstat refuses it. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    FILE *f = fd >= 0 ? fdopen(fd, "rb") : NULL;
    if (!f) {
        if (fd >= 0)
            close(fd);
        return false; /* no entry: the usual first run */
    }
    struct stat st;
    unsigned char *bytes = NULL;
    size_t got = 0;
    const char *problem = NULL;
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode))
        problem = "not a regular file";
    else if ((uint64_t)st.st_size > ENTRY_MAX_PAYLOAD + sizeof(EntryHeader))
        problem = "too large";
    else if (!(bytes = malloc((size_t)st.st_size + 1)))
        problem = "out of memory";
    else if ((got = fread(bytes, 1, (size_t)st.st_size, f)) != (size_t)st.st_size)
        problem = "unreadable";
    else
        problem = entry_problem(bytes, got);
    fclose(f);
    if (problem) {
        free(bytes);
        warn("kernel cache entry %s is unusable (%s): the kernels are rebuilt", path, problem);
        return false;
    }
    *size = got - sizeof(EntryHeader);
    memmove(bytes, bytes + sizeof(EntryHeader), *size);
    *data = bytes;
    utimes(path, NULL); /* used now: the last to go when the cache is pruned */
    return true;
}

/* ---- The size bound ------------------------------------------------------------------------ */

typedef struct {
    char name[64];
    off_t size;
    time_t used;
} CachedEntry;

static int oldest_first(const void *a, const void *b)
{
    time_t x = ((const CachedEntry *)a)->used, y = ((const CachedEntry *)b)->used;
    return (x > y) - (x < y);
}

/* Entries are the binaries of every scene's feature set, part and device a user ever rendered
 * with, and each new driver or pt version makes new ones: without a bound the folder only grows.
 * Over the limit (PT_KERNEL_CACHE_MB, default KERNEL_CACHE_DEFAULT_MB), the least recently used
 * entries go (a load touches its entry) until the rest fill three quarters of it. Another process
 * may be pruning at once: a file already gone is fine. */
static void prune(const char *dir)
{
    long limit_mb = KERNEL_CACHE_DEFAULT_MB;
    Error err = {0};
    if (!env_int("PT_KERNEL_CACHE_MB", 1, 1 << 20, KERNEL_CACHE_DEFAULT_MB, &limit_mb, &err)) {
        warn("%s", err.message);
        return;
    }
    DIR *d = opendir(dir);
    if (!d)
        return;
    CachedEntry *entries = NULL;
    size_t count = 0, room = 0;
    off_t total = 0;
    for (struct dirent *e; (e = readdir(d));) {
        size_t n = strlen(e->d_name);
        if (strncmp(e->d_name, "kernels-", 8) != 0 || n >= sizeof entries->name || n < 4 ||
            strcmp(e->d_name + n - 4, ".bin") != 0)
            continue;
        char path[1400];
        struct stat st;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (stat(path, &st) != 0 || !S_ISREG(st.st_mode))
            continue;
        if (count == room) {
            room = room ? 2 * room : 64;
            CachedEntry *grown = realloc(entries, room * sizeof *grown);
            if (!grown)
                break;
            entries = grown;
        }
        snprintf(entries[count].name, sizeof entries[count].name, "%s", e->d_name);
        entries[count].size = st.st_size;
        entries[count].used = st.st_mtime;
        total += st.st_size;
        count++;
    }
    closedir(d);
    off_t limit = (off_t)limit_mb << 20;
    if (total > limit) {
        qsort(entries, count, sizeof *entries, oldest_first);
        for (size_t i = 0; i < count && total > limit / 4 * 3; i++) {
            char path[1400];
            snprintf(path, sizeof path, "%s/%s", dir, entries[i].name);
            if (unlink(path) == 0 || errno == ENOENT)
                total -= entries[i].size;
        }
    }
    free(entries);
}

/* mkdir -p for the cache folder (base/fs.h), and a folder this process may write into. */
static bool make_dirs(const char *dir)
{
    if (!fs_make_dirs(dir)) {
        if (errno == 0 || errno == EEXIST)
            errno = ENOTDIR;
        return false;
    }
    return access(dir, W_OK | X_OK) == 0;
}

static atomic_bool warned_unwritable;

static void warn_unwritable(const char *dir, int error)
{
    if (!atomic_exchange(&warned_unwritable, true))
        warn("kernel cache folder %s is not writable (%s): kernels are compiled on every run", dir,
             strerror(error));
}

void kernel_cache_prepare(void)
{
    const char *dir = kernel_cache_dir();
    if (!dir[0] || make_dirs(dir))
        return;
    warn_unwritable(dir, errno);
    /* PoCL keeps its own cache in the same cache home ($XDG_CACHE_HOME/pocl) and reports no
     * device at all when it cannot create it; give it a private folder of its own instead. */
    if (getenv("POCL_CACHE_DIR"))
        return;
    const char *tmp = getenv("TMPDIR");
    static char pocl[1024];
    snprintf(pocl, sizeof pocl, "%s/pt-pocl-cache-%ld", tmp && *tmp ? tmp : "/tmp", (long)getuid());
    struct stat st;
    if (mkdir(pocl, 0700) != 0 && errno != EEXIST)
        return;
    /* Only a folder of our own: another user could have made one under that name first. */
    if (lstat(pocl, &st) == 0 && S_ISDIR(st.st_mode) && st.st_uid == getuid())
        setenv("POCL_CACHE_DIR", pocl, 1);
}

void kernel_cache_store(uint64_t key, const unsigned char *data, size_t size)
{
    const char *dir = kernel_cache_dir();
    if (!dir[0] || size == 0 || size > ENTRY_MAX_PAYLOAD)
        return;
    if (!make_dirs(dir)) {
        warn_unwritable(dir, errno);
        return;
    }
    char path[1100], tmp[1200];
    entry_path(key, path, sizeof path);
    /* Unique to the store, not only the process: two threads of one process can store the same
     * key (identical devices each building a part). */
    static atomic_uint stores;
    snprintf(tmp, sizeof tmp, "%s.tmp-%d-%u", path, (int)getpid(), atomic_fetch_add(&stores, 1u));
    FILE *f = fopen(tmp, "wb");
    if (!f) {
        warn_unwritable(dir, errno);
        return;
    }
    EntryHeader header = {.version = ENTRY_VERSION,
                          .payload_size = size,
                          .payload_hash = fnv1a(data, size, 1469598103934665603ull)};
    memcpy(header.magic, ENTRY_MAGIC, sizeof header.magic);
    bool ok = fwrite(&header, sizeof header, 1, f) == 1 && fwrite(data, 1, size, f) == size;
    ok = (fclose(f) == 0) && ok;
    if (!ok || rename(tmp, path) != 0)
        unlink(tmp);
    else
        prune(dir);
}
