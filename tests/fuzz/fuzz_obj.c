// SPDX-License-Identifier: MIT
/* libFuzzer target: the OBJ loader (obj_lines + tinyobjloader + triangulation) and its MTL files.
 * The input is an OBJ, optionally followed by a line "#MTL" and the text of m.mtl, which the OBJ
 * can name with "mtllib m.mtl". */
#include "fuzz_input.h"

#include "io/obj_loader.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char separator[] = "\n#MTL\n";
    size_t obj_size = size;
    for (size_t i = 0; i + sizeof separator - 1 <= size; i++)
        if (memcmp(data + i, separator, sizeof separator - 1) == 0) {
            obj_size = i;
            break;
        }
    char obj[128], mtl[128];
    snprintf(obj, sizeof obj, "%s", fuzz_path("x.obj"));
    snprintf(mtl, sizeof mtl, "%s", fuzz_path("m.mtl"));
    fuzz_write(obj, data, obj_size);
    size_t mtl_start = obj_size < size ? obj_size + sizeof separator - 1 : size;
    fuzz_write(mtl, data + mtl_start, size - mtl_start);
    Mesh mesh;
    Error err = {0};
    if (obj_load(obj, &mesh, &err)) {
        /* Every index handed on must be inside its array. */
        for (size_t t = 0; t < 9 * mesh.num_triangles; t += 3)
            if (mesh.corners[t] < 0 || (size_t)mesh.corners[t] >= mesh.num_positions)
                abort();
        mesh_free(&mesh);
    } else if (!err.message[0]) {
        abort();
    }
    return 0;
}
