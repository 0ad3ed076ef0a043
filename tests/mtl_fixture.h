/* SPDX-License-Identifier: MIT */
/* mtl_fixture.h: what the MTL tests (test_io_mtl.c, test_io_mtl_paths.c) share: one triangle's
 * OBJ vertices and a quiet OBJ load that must succeed (header only). */
#ifndef PT_TEST_MTL_FIXTURE_H
#define PT_TEST_MTL_FIXTURE_H

#include <criterion/criterion.h>
#include <stdbool.h>

#include "app/cli.h"
#include "io/obj_loader.h"

#define TRIANGLE_V "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

/* Loads quietly; fails the test with the error message if it does not load. */
static inline void load_ok(const char *path, Mesh *mesh)
{
    Error err = {0};
    warnings_set_quiet(true);
    cr_assert(obj_load(path, mesh, &err), "%s: %s", path, err.message);
}

#endif
