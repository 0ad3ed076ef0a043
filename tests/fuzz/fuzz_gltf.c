// SPDX-License-Identifier: MIT
/* libFuzzer target: the glTF import (host/io/gltf_loader.cc, gltf_primitives.cc,
 * gltf_scene_graph.cc; host/scene/gltf_scene.c and the materials through scene_desc_load). The
 * input is a .glb file (a .gltf is its JSON chunk's text, which a mutated GLB reaches too). */
#include "fuzz_input.h"

#include "io/gltf_loader.h"
#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[128];
    snprintf(path, sizeof path, "%s", fuzz_path("x.glb"));
    fuzz_write(path, data, size);
    gltf_loader_set_quiet(true);
    warnings_set_quiet(true);
    GltfFile file;
    Error err = {0};
    if (gltf_load(path, &file, &err)) {
        /* Every index handed on must be inside its array. */
        for (int p = 0; p < file.num_primitives; p++) {
            const Mesh *m = &file.primitives[p].mesh;
            for (size_t t = 0; t < 9 * m->num_triangles; t++) {
                int32_t index = m->corners[t];
                size_t count = t % 3 == 0 ? m->num_positions : t % 3 == 1 ? m->num_texcoords : m->num_normals;
                if (index < -1 || (t % 3 == 0 && index < 0) || (index >= 0 && (size_t)index >= count))
                    abort();
            }
        }
        for (int i = 0; i < file.num_placements; i++)
            if (file.placements[i].mesh < 0 || file.placements[i].mesh >= file.num_meshes)
                abort();
        gltf_free(&file);
        SceneDesc d;
        Error err2 = {0};
        if (scene_desc_load(path, &d, &err2))
            scene_desc_free(&d);
        else if (!err2.message[0])
            abort();
    } else if (!err.message[0]) {
        abort();
    }
    return 0;
}
