/* SPDX-License-Identifier: MIT */
/* fs.h: small file-system helpers shared by commands, caches and tools. */
#ifndef PT_FS_H
#define PT_FS_H

#include <stdbool.h>
#include <stddef.h>

/* True when something (file, folder, ...) exists at path. */
bool fs_exists(const char *path);
/* mkdir -p: creates path and its missing parents (0755); true when the folder exists after. */
bool fs_make_dirs(const char *path);
/* mkdir -p for the folder that will hold the file at path (nothing when path has no folder). */
bool fs_make_parent_dirs(const char *path);
/* True when name ends in suffix, ignoring ASCII case (".EXR" matches ".exr"). */
bool fs_has_suffix(const char *name, const char *suffix);
/* The name of a scene or file without folders and without its last extension
 * ("scenes/cornell-box/" -> "cornell-box", "a/b.json" -> "b"), into out[size]. */
void fs_stem(const char *path, char *out, size_t size);

#endif
