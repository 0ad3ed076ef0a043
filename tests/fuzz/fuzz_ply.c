// SPDX-License-Identifier: MIT
/* libFuzzer target: the PLY reader (host/io/ply_header.c, ply_reader.c). The input is the PLY file. */
#include "fuzz_input.h"

#include "io/ply_reader.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[128];
    snprintf(path, sizeof path, "%s", fuzz_path("x.ply"));
    fuzz_write(path, data, size);
    Mesh mesh;
    Error err = {0};
    if (ply_load(path, &mesh, &err)) {
        /* Every index handed on must be inside its array. */
        for (size_t t = 0; t < 9 * mesh.num_triangles; t++) {
            int32_t index = mesh.corners[t];
            size_t count = t % 3 == 0 ? mesh.num_positions : t % 3 == 1 ? mesh.num_texcoords : mesh.num_normals;
            if (index < -1 || (t % 3 == 0 && index < 0) || (index >= 0 && (size_t)index >= count))
                abort();
        }
        mesh_free(&mesh);
    } else if (!err.message[0]) {
        abort();
    }
    return 0;
}
