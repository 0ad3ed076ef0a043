// SPDX-License-Identifier: MIT
/* libFuzzer target: the Assimp path (host/io/assimp_reader.c, host/scene/import_assimp.c). The
 * input's first byte picks the format (STL, OFF, FBX, 3DS, X3D); the rest is the file. Assimp
 * itself is fuzzed upstream (OSS-Fuzz); this checks what pt does with what it hands back. */
#include "scene/import_assimp.h"

#include "fuzz_input.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const names[] = {"x.stl", "x.off", "x.fbx", "x.3ds", "x.x3d"};
    if (size < 1)
        return 0;
    char path[128];
    snprintf(path, sizeof path, "%s", fuzz_path(names[data[0] % 5]));
    fuzz_write(path, data + 1, size - 1);
    ImportedScene s = {0};
    Error err = {0};
    if (import_assimp(path, &s, &err)) {
        for (int i = 0; i < s.num_meshes; i++) {
            const Mesh *m = &s.meshes[i].mesh;
            fuzz_check_mesh(m);
        }
    } else if (!err.message[0]) {
        abort();
    }
    imported_scene_free(&s);
    return 0;
}
