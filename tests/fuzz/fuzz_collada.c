// SPDX-License-Identifier: MIT
/* libFuzzer target: the COLLADA reader and its mapping to a pt scene (host/io/collada_reader.c,
 * host/scene/import_collada.c). The input is the .dae file. */
#include "scene/import_collada.h"

#include "fuzz_input.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[128];
    snprintf(path, sizeof path, "%s", fuzz_path("x.dae"));
    fuzz_write(path, data, size);
    ImportedScene s = {0};
    Error err = {0};
    if (import_collada(path, &s, &err)) {
        /* Every index handed on must be inside its array; every object names a mesh. */
        for (int i = 0; i < s.num_meshes; i++) {
            const Mesh *m = &s.meshes[i].mesh;
            fuzz_check_mesh(m);
            for (size_t t = 0; t < m->num_triangles; t++)
                if (m->material_ids[t] < -1 || (m->material_ids[t] >= 0 && (size_t)m->material_ids[t] >= m->num_materials))
                    abort();
        }
        const cJSON *o;
        cJSON_ArrayForEach(o, cJSON_GetObjectItemCaseSensitive(s.root, "objects"))
            if (imported_scene_find_mesh(&s, cJSON_GetObjectItemCaseSensitive(o, "mesh")->valuestring) < 0)
                abort();
    } else if (!err.message[0]) {
        abort();
    }
    imported_scene_free(&s);
    return 0;
}
