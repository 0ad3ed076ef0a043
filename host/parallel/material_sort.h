/* SPDX-License-Identifier: MIT */
/* material_sort.h: optional stage between intersect_closest and shade_surface that groups the live
 * paths by the material they hit (kernels in cl/parallel/sort_materials.cl):
 *
 *     material_sorter_run(sorter, hit, material_ids, active, sorted_active, live);
 *
 * active_in[0..n) lists path slots; hit[slot].w is as_float(triangle) or HIT_NONE; material_ids
 * holds a uint per triangle. active_out[0..n) receives the same slots ordered by key (the hit
 * triangle's material id, num_materials for a miss, so misses come last), stable: slots of one
 * key keep their order in active_in. A counting sort: per-tile key counts, their exclusive scan
 * (host/parallel/exclusive_scan.c), a scatter that sorts each tile in local memory. 3 launches when the
 * (num_materials + 1) x tiles counts fit one scan work-group (8192 with work-groups of 256; a tile
 * is 4096 entries), else 5. Up to 8192 keys (num_materials < 8192) count in local memory when it
 * holds them beside a tile of keys (about 8000 in 48 KiB); larger tables count with global
 * atomics (one more command: a fill that zeroes the counts).
 * A MaterialSorter owns its kernels and scratch buffers: n keys and (num_materials + 1) x tiles
 * counts, sized for capacity. It is not safe to use one from two threads at once. */
#ifndef PT_MATERIAL_SORT_H
#define PT_MATERIAL_SORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "device/device.h"

/* Keys are 20 bits in the tile sort: num_materials may be up to 2^20 - 1. */
#define MATERIAL_SORT_MAX_MATERIALS ((1u << 20) - 1u)
/* Entries a tile sorts at the default work-group size (256 work items x 16 keys; a device with
 * little local memory takes smaller tiles): the counts are (num_materials + 1) per tile. */
#define MATERIAL_SORT_TILE 4096u

typedef struct MaterialSorter MaterialSorter;

/* Builds a sorter for lists of up to capacity entries with the default work-group size. NULL with
 * err set (ERR_TOO_LARGE) when num_materials exceeds MATERIAL_SORT_MAX_MATERIALS or the counts
 * would exceed 2^32 entries, or when a buffer cannot be allocated (ERR_ALLOC_TOO_LARGE). */
MaterialSorter *material_sorter_create(Device *dev, uint32_t capacity, uint32_t num_materials,
                                       Error *err);

/* The same with an explicit work-group size, lowered to a power of two the kernels allow and at
 * most 256 (a tile position must fit 12 bits); 0 = the default. For tests and tuning. */
MaterialSorter *material_sorter_create_sized(Device *dev, uint32_t capacity,
                                             uint32_t num_materials, size_t group_size,
                                             Error *err);

/* Enqueues the sort of active_in[0..n) into active_out[0..n) (distinct buffers), n <= capacity,
 * without waiting (unless profiling). Entries of active_out from n on are not written. */
void material_sorter_run(MaterialSorter *s, cl_mem hit, cl_mem material_ids, cl_mem active_in,
                         cl_mem active_out, uint32_t n);

/* When ms_accumulator is not NULL, each later run waits for its commands and adds their device
 * time to *ms_accumulator. NULL turns this off again. */
void material_sorter_set_profile(MaterialSorter *s, double *ms_accumulator);

size_t material_sorter_group_size(const MaterialSorter *s);
/* True when the key counts live in local memory (else global atomics). */
bool material_sorter_local_histogram(const MaterialSorter *s);
/* Device commands a sort of n entries takes. */
int material_sorter_launches(const MaterialSorter *s, uint32_t n);

void material_sorter_destroy(MaterialSorter *s);

#endif
