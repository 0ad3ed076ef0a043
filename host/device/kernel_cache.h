/* SPDX-License-Identifier: MIT */
/* kernel_cache.h: compiled program binaries on disk, keyed by a hash of everything that decides the
 * binary (source, build options, device, driver), in $XDG_CACHE_HOME/pt (default ~/.cache/pt).
 * Entries are written atomically; a corrupt or stale entry is simply rebuilt by the caller. */
#ifndef PT_KERNEL_CACHE_H
#define PT_KERNEL_CACHE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* FNV-1a 64 over the NUL-terminated strings parts[0..n), each followed by a separator byte. */
uint64_t kernel_cache_key(const char *const *parts, size_t n);
/* The cache folder (created on demand by store); "" when neither XDG_CACHE_HOME nor HOME is set. */
const char *kernel_cache_dir(void);
/* *data is malloc'ed; false when there is no entry. */
bool kernel_cache_load(uint64_t key, unsigned char **data, size_t *size);
/* Best effort: a cache that cannot be written is not an error. */
void kernel_cache_store(uint64_t key, const unsigned char *data, size_t size);

#endif
