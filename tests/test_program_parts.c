// SPDX-License-Identifier: MIT
/* PROGRAM_PARTS (host/device/device.h) against the kernel source: every kernel lives in the part
 * whose list names it, that is, its definition sits inside `#if PT_PART(<that part>)`; a kernel no
 * list names is in CORE or outside every part's #if (then every part has it). device_kernel looks
 * a kernel up by the lists alone, so a kernel moved between parts on one side only builds here
 * and fails the first render that asks for it (on a GPU, say, the split shading of a scene over
 * 2^15 triangles). Reads the embedded source as text: no device, no build. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "device/device_internal.h"

extern const unsigned char pt_kernel_source[];
extern const size_t pt_kernel_source_length;

#define MAX_DEPTH 32

/* The part a PT_PART(NAME) directive names, or -1 for a part that does not exist. */
static int part_named(const char *name, size_t n)
{
    for (int i = 0; i < PROGRAM_PART_COUNT; i++)
        if (strlen(program_parts[i].name) == n && strncmp(program_parts[i].name, name, n) == 0)
            return i;
    return -1;
}

Test(program_parts, every_kernel_is_where_its_part_list_says)
{
    const char *src = (const char *)pt_kernel_source, *end = src + pt_kernel_source_length;
    /* The open conditionals: the part a `#if PT_PART(X)` names, else PROGRAM_PART_COUNT. */
    int open[MAX_DEPTH], depth = 0, kernels = 0, in_parts = 0;
    for (const char *line = src; line < end;) {
        const char *eol = memchr(line, '\n', (size_t)(end - line));
        if (!eol)
            eol = end;
        const char *t = line;
        while (t < eol && (*t == ' ' || *t == '\t'))
            t++;
        size_t len = (size_t)(eol - t);
        if (len >= 3 && strncmp(t, "#if", 3) == 0) {
            cr_assert_lt(depth, MAX_DEPTH);
            const char *p = strstr(t, "PT_PART(");
            int part = PROGRAM_PART_COUNT;
            if (p && p < eol) {
                const char *name = p + strlen("PT_PART(");
                part = part_named(name, strcspn(name, ")"));
                cr_expect_geq(part, 0, "#if PT_PART names no part: %.*s", (int)len, t);
            }
            open[depth++] = part;
        } else if (len >= 6 && strncmp(t, "#endif", 6) == 0) {
            cr_assert_gt(depth, 0, "an #endif without its #if");
            depth--;
        } else if (len > 12 && strncmp(t, "kernel void ", 12) == 0) {
            const char *name = t + 12;
            char kernel[128];
            snprintf(kernel, sizeof kernel, "%.*s", (int)strcspn(name, "("), name);
            int part = PROGRAM_PART_CORE; /* outside every part's #if: every part has it */
            for (int d = depth - 1; d >= 0; d--)
                if (open[d] != PROGRAM_PART_COUNT) {
                    part = open[d];
                    in_parts++;
                    break;
                }
            cr_expect_eq(program_part_of_kernel(kernel), part,
                         "%s: defined in part %s, listed in part %s", kernel,
                         part >= 0 ? program_parts[part].name : "?",
                         program_parts[program_part_of_kernel(kernel)].name);
            kernels++;
        }
        line = eol + 1;
    }
    cr_expect_eq(depth, 0, "unclosed #if");
    cr_expect_gt(kernels, 20, "only %d kernels found", kernels);
    cr_expect_gt(in_parts, 8, "only %d kernels inside a part's #if", in_parts);
}
