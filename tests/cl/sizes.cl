/* SPDX-License-Identifier: MIT */
/* report_layout: the device's layout of every SHARED_STRUCTS entry (cl/shared.h), in list order:
 * per struct its size, per field its offset and size; tests/test_device.c compares the host's. */
#define REPORT_STRUCT(type, size)                                                                  \
    {                                                                                               \
        out[i++] = sizeof(type);                                                                    \
    }
/* Offsets from a private instance: OpenCL C 1.2 has no offsetof. */
#define REPORT_FIELD(type, field)                                                                  \
    {                                                                                               \
        type x;                                                                                     \
        out[i++] = (uint)((private char *)&x.field - (private char *)&x);                           \
        out[i++] = sizeof(x.field);                                                                 \
    }

kernel void report_layout(global uint *out)
{
    uint i = 0;
    SHARED_STRUCTS(REPORT_STRUCT, REPORT_FIELD)
}
