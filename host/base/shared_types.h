/* SPDX-License-Identifier: MIT */
/* shared_types.h: the host's view of cl/shared.h, with the layout checks that keep it equal to the
 * device's (the report_layout test kernel checks the other side). */
#ifndef PT_SHARED_TYPES_H
#define PT_SHARED_TYPES_H

#include <stddef.h>

#include "../../cl/shared.h"

/* Sizes as SHARED_STRUCTS lists them; offsets and the device side: tests/test_device.c. */
#define SHARED_STRUCT_SIZE_CHECK(type, size) _Static_assert(sizeof(type) == (size), #type " layout");
#define SHARED_FIELD_NO_CHECK(type, field)
SHARED_STRUCTS(SHARED_STRUCT_SIZE_CHECK, SHARED_FIELD_NO_CHECK)
#undef SHARED_STRUCT_SIZE_CHECK
#undef SHARED_FIELD_NO_CHECK
_Static_assert(sizeof(RenderParams) % 16 == 0, "RenderParams must stay a multiple of 16 bytes");

#endif
