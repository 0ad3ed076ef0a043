// SPDX-License-Identifier: MIT
/* bench_gltf_import FILE.gltf|.glb [runs]: the import time of a glTF on this thread (no device):
 * gltf_load (parse, buffers, decode of every placed primitive) and scene_load's whole CPU side
 * up to the flattened SceneData (materials, vertex unification, meshes and instances; no BVH).
 * Prints the best of `runs` (default 3). A 1M-triangle file: python3 tools/make_gltf_tests.py
 * --big 1000000 big.glb. */
#include <stdio.h>
#include <stdlib.h>

#include "base/clock.h"
#include "io/gltf_loader.h"
#include "scene/scene.h"

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: %s FILE.gltf|FILE.glb [runs]\n", argv[0]);
        return 2;
    }
    int runs = argc == 3 ? atoi(argv[2]) : 3;
    double best_load = 1e30, best_scene = 1e30;
    size_t triangles = 0;
    for (int r = 0; r < (runs > 0 ? runs : 1); r++) {
        Error err = {0};
        GltfFile f;
        double t0 = seconds_now();
        if (!gltf_load(argv[1], &f, &err)) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        double t1 = seconds_now();
        triangles = 0;
        for (int p = 0; p < f.num_primitives; p++)
            triangles += f.primitives[p].mesh.num_triangles;
        gltf_free(&f);
        Scene s;
        double t2 = seconds_now();
        if (!scene_load(argv[1], &s, &err)) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        double t3 = seconds_now();
        scene_free(&s);
        best_load = t1 - t0 < best_load ? t1 - t0 : best_load;
        best_scene = t3 - t2 < best_scene ? t3 - t2 : best_scene;
    }
    printf("%s: %zu triangles: gltf_load %.3f s, scene_load (to SceneData, no BVH) %.3f s "
           "(best of %d, one thread)\n", argv[1], triangles, best_load, best_scene, runs);
    return 0;
}
