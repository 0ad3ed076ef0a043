/* SPDX-License-Identifier: MIT */
/* fuzz_input.h: what the libFuzzer targets share: the loaders read files by path, so each input is
 * written to a file in a folder of this process's own, and warnings are silenced. */
#ifndef PT_FUZZ_INPUT_H
#define PT_FUZZ_INPUT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/error.h"

/* The folder (created once) and a path in it. */
static const char *fuzz_path(const char *name)
{
    static char folder[64];
    static char path[128];
    if (!folder[0]) {
        snprintf(folder, sizeof folder, "/tmp/pt-fuzz-%d", (int)getpid());
        mkdir(folder, 0700);
        warnings_set_quiet(true);
    }
    snprintf(path, sizeof path, "%s/%s", folder, name);
    return path;
}

/* Aborts unless every corner index of a mesh a reader handed on is inside its array (positions
 * always, texcoords and normals or -1). For the readers' targets that include io/mesh.h. */
#ifdef PT_MESH_H
static void fuzz_check_mesh(const Mesh *m)
{
    for (size_t t = 0; t < 9 * m->num_triangles; t++) {
        int32_t index = m->corners[t];
        size_t count = t % 3 == 0 ? m->num_positions : t % 3 == 1 ? m->num_texcoords : m->num_normals;
        if (index < -1 || (t % 3 == 0 && index < 0) || (index >= 0 && (size_t)index >= count))
            abort();
    }
}
#endif

static void fuzz_write(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        abort(); /* the harness itself is broken */
    if (size && fwrite(data, 1, size, f) != size)
        abort();
    fclose(f);
}

#endif
