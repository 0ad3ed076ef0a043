/* SPDX-License-Identifier: MIT */
/* fs.h: small file-system helpers shared by commands, caches and tools, and the atomic write:
 * a file is written to "<path>.tmp-<pid>" in the same folder, flushed to disk and renamed over
 * path, so an interrupted or failed write never leaves a half-written file at path. */
#ifndef PT_FS_H
#define PT_FS_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

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

/* A path named inside a file (a glTF URI, an MTL map, a COLLADA image, a Mitsuba or pbrt file
 * name), resolved against that file's folder into out[size]. Such paths are relative and stay
 * inside the folder: an absolute one, or one whose ".." lead outside the folder (checked on the
 * text, before any file is touched), is refused with ERR_PATH_ESCAPES naming `what` (the key or
 * element, e.g. "images[0].uri") and the path, unless fs_set_allow_outside_paths(true) (pt
 * --allow-outside-paths). A JSON scene's own paths are not checked: the user wrote them. */
bool fs_resolve_inside(const char *container, const char *ref, const char *what, char *out,
                       size_t size, Error *err);
void fs_set_allow_outside_paths(bool allow);
bool fs_allow_outside_paths(void);

/* Checks before a long computation that a file can be created at path: not empty, not a folder,
 * its folder exists and is writable, and room for the temporary name. ERR_OUTPUT otherwise. */
bool fs_check_writable(const char *path, Error *err);

/* An atomic write in three steps: fs_check_writable(path), write everything to the file named by
 * fs_temp_path(path), then fs_finish_atomic_write. */
void fs_temp_path(const char *path, char *temp, size_t size);
/* Removes what an atomic write of path killed mid-way (SIGKILL, a crash) left: regular files named
 * exactly fs_temp_path(path) for a process id that is not running here. Another pt writing the
 * same path now keeps its file. Returns how many were removed. */
int fs_remove_stale_temps(const char *path);
/* written: the temporary file is complete. Then it is flushed and renamed over path; otherwise, or
 * when that fails (err set), it is removed. */
bool fs_finish_atomic_write(const char *temp, const char *path, bool written, Error *err);
/* Called once a temporary file is complete, just before it is renamed into place (pt's signal
 * tests raise a signal there: the rename must still happen). NULL = none. */
void fs_set_before_rename_hook(void (*hook)(void));

/* The three steps for data already in memory (caches, CSVs). */
bool fs_write_atomic(const char *path, const void *data, size_t size, Error *err);

#endif
