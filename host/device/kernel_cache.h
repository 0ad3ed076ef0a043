/* SPDX-License-Identifier: MIT */
/* kernel_cache.h: compiled program binaries on disk, keyed by a hash of everything that decides the
 * binary (source, build options, device, driver), in $XDG_CACHE_HOME/pt (default ~/.cache/pt).
 * Entries are written atomically with a header (size, checksum); the file is untrusted input: an
 * entry whose header does not match its bytes (truncated, edited, older format) is never given to
 * the driver: load warns and returns false, and the caller rebuilds. A cache folder that cannot be
 * written is a warning, never an error: the render goes on without the cache. */
#ifndef PT_KERNEL_CACHE_H
#define PT_KERNEL_CACHE_H

/* The cache's size bound (kernel_cache.c prune; PT_KERNEL_CACHE_MB overrides): a few hundred
 * feature sets' parts. */
#define KERNEL_CACHE_DEFAULT_MB 512

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* FNV-1a 64 over the NUL-terminated strings parts[0..n), each followed by a separator byte. */
uint64_t kernel_cache_key(const char *const *parts, size_t n);
/* The cache folder (created on demand by store); "" when neither XDG_CACHE_HOME nor HOME is set. */
const char *kernel_cache_dir(void);
/* Before the first OpenCL call: checks that the cache folder can be written, warning once when it
 * cannot; then, unless POCL_CACHE_DIR is set, points PoCL's own cache (which lives under the same
 * cache home, and without which PoCL offers no device) at a private folder in $TMPDIR or /tmp. */
void kernel_cache_prepare(void);
/* *data is malloc'ed (the program binary, header removed); false when there is no usable entry
 * (a present but unusable one is also warned about). */
bool kernel_cache_load(uint64_t key, unsigned char **data, size_t *size);
/* Best effort: a cache that cannot be written is a warning (once), not an error. Entries are
 * written to a temporary name and renamed, so processes storing one key at once both succeed and
 * leave one whole entry; then the least recently used entries are removed while the folder is over
 * its size bound. */
void kernel_cache_store(uint64_t key, const unsigned char *data, size_t size);

#endif
