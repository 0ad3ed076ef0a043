// SPDX-License-Identifier: MIT
/* mesh.c: see mesh.h. */
#include "io/mesh.h"

#include <stdlib.h>
#include <string.h>

void mesh_free(Mesh *mesh)
{
    free(mesh->positions);
    free(mesh->normals);
    free(mesh->texcoords);
    free(mesh->corners);
    free(mesh->material_ids);
    free(mesh->materials);
    memset(mesh, 0, sizeof *mesh);
}
