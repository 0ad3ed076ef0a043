/* SPDX-License-Identifier: MIT */
/* turned_instances.h: the instanced scene that tests/test_instances_render.c and
 * tests/test_instances_flat.c render (the Cornell box and three turned, scaled, one mirrored,
 * tetrahedra), and the check that a fixture's BVH finds the brute force's hits. Header-only;
 * the includer defines _DEFAULT_SOURCE (realpath) before its first include. */
#ifndef PT_TESTS_TURNED_INSTANCES_H
#define PT_TESTS_TURNED_INSTANCES_H

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

/* An asymmetric tetrahedron, faces counter-clockwise seen from outside. */
static const char *const tetra_text = "v 0 0 0\nv 1 0 0\nv 0 2 0\nv 0 0 3\n"
                                      "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/* A scene of the Cornell box and the tetrahedron objects given (JSON object entries after the
 * box's, naming "tetra.obj"), seen from the box's camera. */
static inline const char *box_and_tetra_scene(const char *tetra_objects)
{
    const char *dir = test_temp_dir();
    char box[1024];
    cr_assert(realpath("scenes/cornell-box/CornellBox-Original.obj", box));
    test_write_file(dir, "tetra.obj", tetra_text);
    char json[4096];
    snprintf(json, sizeof json,
             "{\"camera\": {\"eye\": [0, 1, 3.9], \"target\": [0, 1, 0], \"fov_y\": 39.3},\n"
             " \"objects\": [{\"obj\": \"%s\"},\n%s]}\n",
             box, tetra_objects);
    return test_write_file(dir, "scene.json", json);
}

/* The Cornell box with three turned, scaled (one mirrored) tetrahedra as instances. */
static inline const char *turned_instances_scene(void)
{
    return box_and_tetra_scene(
        "  {\"obj\": \"tetra.obj\", \"transform\": [{\"scale\": 0.3}, {\"rotate\": {\"axis\": "
        "[0, 1, 0], \"angle\": 30}}, {\"translate\": [-0.5, 0.1, 0.2]}]},\n"
        "  {\"obj\": \"tetra.obj\", \"transform\": [{\"scale\": [-0.25, 0.3, 0.3]}, {\"rotate\": "
        "{\"axis\": [1, 0, 1], \"angle\": -40}}, {\"translate\": [0.45, 0.6, -0.3]}]},\n"
        "  {\"obj\": \"tetra.obj\", \"transform\": [{\"matrix\": [0.2, 0.1, 0, 0.1, 0, 0.25, 0, "
        "1.2, 0.05, 0, 0.3, 0.1, 0, 0, 0, 1]}]}");
}

/* The fixture's BVH finds the hits that testing every triangle finds: the same bits of a
 * 48 x 48 render (the fixture is closed after). */
static inline void expect_brute_force_bits(RenderFixture *f, const char *what)
{
    RenderSettings s = {.spp = 4, .max_depth = 4, .seed = 5};
    float *bvh = render_fixture_render(f, s, NULL);
    s.brute_force = true;
    float *brute = render_fixture_render(f, s, NULL);
    cr_expect(memcmp(bvh, brute, 48 * 48 * 3 * sizeof(float)) == 0, "%s missed hits", what);
    free(bvh), free(brute);
    render_fixture_close(f);
}

#endif
