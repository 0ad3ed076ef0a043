/* SPDX-License-Identifier: MIT */
/* shared_types.h: the host's view of cl/shared.h, with the layout checks that keep it equal to the
 * device's (the report_sizes test kernel checks the other side). */
#ifndef PT_SHARED_TYPES_H
#define PT_SHARED_TYPES_H

#include <stddef.h>

#include "../../cl/shared.h"

_Static_assert(sizeof(Triangle) == 16, "Triangle layout");
_Static_assert(sizeof(BvhNode) == 64, "BvhNode layout");
_Static_assert(sizeof(BvhNodeQuantized) == 32, "BvhNodeQuantized layout");
_Static_assert(sizeof(BvhTriangle) == 48, "BvhTriangle layout");
_Static_assert(sizeof(BvhNode4) == 112 && sizeof(TrianglePack4) == 160, "4-wide BVH layout");
_Static_assert(sizeof(BvhNode8) == 224 && sizeof(TrianglePack8) == 320, "8-wide BVH layout");
_Static_assert(offsetof(BvhNode8, child) == 192 && offsetof(TrianglePack8, prim) == 288, "8-wide BVH layout");
_Static_assert(sizeof(Material) == 80, "Material layout");
_Static_assert(sizeof(TextureInfo) == 16, "TextureInfo layout");
_Static_assert(sizeof(Camera) == 64, "Camera layout");
_Static_assert(sizeof(RenderParams) == 128, "RenderParams layout");
_Static_assert(sizeof(LightEntry) == 16, "LightEntry layout");
_Static_assert(sizeof(RenderParams) % 16 == 0, "RenderParams must stay a multiple of 16 bytes");

#endif
