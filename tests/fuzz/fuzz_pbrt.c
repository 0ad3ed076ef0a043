// SPDX-License-Identifier: MIT
/* libFuzzer target: the pbrt-v4 importer (host/io/pbrt_parser.c, host/scene/import_pbrt*.c) through
 * scene_desc_load. The input is the .pbrt file; an accepted scene must name only in-memory meshes
 * that exist, and every triangle corner must index inside its mesh's arrays. */
#include "fuzz_input.h"

#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_mesh(const Mesh *m)
{
    for (size_t t = 0; t < 9 * m->num_triangles; t++) {
        int32_t index = m->corners[t];
        size_t count = t % 3 == 0 ? m->num_positions : t % 3 == 1 ? m->num_texcoords : m->num_normals;
        if (index < -1 || (t % 3 == 0 && index < 0) || (index >= 0 && (size_t)index >= count))
            abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[128];
    snprintf(path, sizeof path, "%s", fuzz_path("scene.pbrt"));
    fuzz_write(path, data, size);
    SceneDesc desc;
    Error err = {0};
    if (scene_desc_load(path, &desc, &err)) {
        for (int i = 0; i < desc.imported.num_meshes; i++)
            check_mesh(&desc.imported.meshes[i].mesh);
        scene_desc_free(&desc);
    } else if (!err.message[0]) {
        abort(); /* a failure must say why */
    }
    return 0;
}
