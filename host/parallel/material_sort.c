// SPDX-License-Identifier: MIT
/* material_sort.c: drives cl/parallel/sort_materials.cl (see the stage list there): count keys per tile ->
 * exclusive scan of the key-major counts (host/parallel/exclusive_scan.c) -> scatter. The tile sort in the
 * scatter takes one split pass per bit of num_materials, so its cost grows with log2 of the number
 * of materials, not with the number itself; only the counts grow with it. */
#include "parallel/material_sort.h"

#include <stdlib.h>

#include "parallel/exclusive_scan.h"

#define KEYS_PER_ITEM 16   /* SORT_KEYS_PER_ITEM in cl/parallel/sort_materials.cl */
#define MAX_GROUP_SIZE 256 /* a tile position must fit SORT_INDEX_BITS = 12 bits */
_Static_assert(MAX_GROUP_SIZE * KEYS_PER_ITEM == MATERIAL_SORT_TILE, "material_sort.h's tile");
#define LOCAL_HISTOGRAM_MAX_KEYS 8192 /* 32 KiB of local memory; larger tables count globally */

struct MaterialSorter {
    Device *dev;
    uint32_t capacity;
    uint32_t num_materials;
    cl_uint key_bits; /* bits of the largest key, num_materials: the tile sort's passes */
    size_t group_size;
    bool local_histogram;
    cl_kernel count_local, count_global, scatter;
    cl_mem keys;   /* per list entry, from the count stage to the scatter */
    cl_mem counts; /* (num_materials + 1) x tiles, key-major; scanned in place into offsets */
    ExclusiveScan *scan;
    double *profile_ms;
};

static size_t div_up(size_t a, size_t b) { return (a + b - 1) / b; }

/* Local memory of count uints padded with one word per 32, as the kernels index them. */
static size_t padded_bytes(size_t count) { return (count + count / 32) * sizeof(cl_uint); }

static size_t tile_local_bytes(size_t group_size) { return padded_bytes(group_size * KEYS_PER_ITEM); }

/* The scatter's local memory: the tile and the scan scratch (2 uints per work item). */
static size_t scatter_local_bytes(size_t group_size)
{
    return tile_local_bytes(group_size) + 2 * group_size * sizeof(cl_uint);
}

static size_t histogram_local_bytes(uint32_t num_materials)
{
    return ((size_t)num_materials + 1) * sizeof(cl_uint);
}

static size_t pick_group_size(MaterialSorter *s, size_t request)
{
    if (request == 0 || request > MAX_GROUP_SIZE)
        request = MAX_GROUP_SIZE;
    cl_kernel kernels[] = {s->count_local, s->count_global, s->scatter};
    size_t size = pow2_group_size(s->dev, kernels, 3, request);
    while (size > 1 && scatter_local_bytes(size) > device_local_mem_bytes(s->dev))
        size /= 2;
    return size;
}

/* Allocates the keys, counts and scan; false with err set when one fails or is too large. */
static bool allocate_buffers(MaterialSorter *s, Error *err)
{
    size_t tiles = div_up(s->capacity, s->group_size * KEYS_PER_ITEM);
    size_t num_counts = ((size_t)s->num_materials + 1) * tiles;
    if (num_counts > UINT32_MAX) {
        error_set(err, ERR_TOO_LARGE, NULL, 0,
                  "material sort: %u materials x %zu tiles of paths is more than 2^32 counts",
                  s->num_materials + 1, tiles);
        return false;
    }
    s->keys = device_buffer(s->dev, "sort_keys", CL_MEM_READ_WRITE,
                            (size_t)s->capacity * sizeof(cl_uint), NULL, err);
    if (s->keys)
        s->counts = device_buffer(s->dev, "sort_counts", CL_MEM_READ_WRITE,
                                  num_counts * sizeof(cl_uint), NULL, err);
    if (s->counts)
        s->scan = exclusive_scan_create(s->dev, num_counts, err);
    return s->scan != NULL;
}

MaterialSorter *material_sorter_create_sized(Device *dev, uint32_t capacity,
                                             uint32_t num_materials, size_t group_size,
                                             Error *err)
{
    if (num_materials > MATERIAL_SORT_MAX_MATERIALS) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "material sort: %u materials, at most %u",
                  num_materials, MATERIAL_SORT_MAX_MATERIALS);
        return NULL;
    }
    MaterialSorter *s = calloc(1, sizeof *s);
    if (!s)
        die("out of memory");
    s->dev = dev;
    s->capacity = capacity;
    s->num_materials = num_materials;
    for (uint32_t largest_key = num_materials; largest_key != 0; largest_key >>= 1)
        s->key_bits++;
    s->count_local = device_kernel(dev, "sort_materials_count_local");
    s->count_global = device_kernel(dev, "sort_materials_count_global");
    s->scatter = device_kernel(dev, "sort_materials_scatter");
    s->group_size = pick_group_size(s, group_size);
    s->local_histogram = num_materials < LOCAL_HISTOGRAM_MAX_KEYS &&
                         histogram_local_bytes(num_materials) + tile_local_bytes(s->group_size) <=
                             device_local_mem_bytes(dev);
    if (!allocate_buffers(s, err)) {
        material_sorter_destroy(s);
        return NULL;
    }
    return s;
}

MaterialSorter *material_sorter_create(Device *dev, uint32_t capacity, uint32_t num_materials,
                                       Error *err)
{
    return material_sorter_create_sized(dev, capacity, num_materials, 0, err);
}

/* Launches one work-group per tile; adds the device time when profiling. */
static void launch_tiles(MaterialSorter *s, cl_kernel kernel, size_t tiles)
{
    double ms = 0.0;
    device_run(s->dev, kernel, tiles * s->group_size, s->group_size, s->profile_ms ? &ms : NULL);
    if (s->profile_ms)
        *s->profile_ms += ms;
}

/* active_in -> keys and per-tile key counts: in local memory, else added with global atomics into
 * counts zeroed first. */
static void count_keys(MaterialSorter *s, cl_mem hit, cl_mem material_ids, cl_mem active_in,
                       uint32_t n, size_t tiles)
{
    if (!s->local_histogram) {
        cl_uint zero = 0;
        size_t bytes = ((size_t)s->num_materials + 1) * tiles * sizeof zero;
        double ms = 0.0;
        device_fill(s->dev, s->counts, &zero, sizeof zero, 0, bytes, s->profile_ms ? &ms : NULL);
        if (s->profile_ms)
            *s->profile_ms += ms;
    }
    cl_uint n_arg = n, num_materials = s->num_materials;
    cl_kernel kernel = s->local_histogram ? s->count_local : s->count_global;
    cl_uint i = KERNEL_ARGS(kernel, 0, KARG(active_in), KARG(n_arg), KARG(hit), KARG(material_ids),
                            KARG(num_materials), KARG(s->keys), KARG(s->counts));
    if (s->local_histogram)
        i = KERNEL_ARGS(kernel, i, KARG_LOCAL(histogram_local_bytes(num_materials)));
    KERNEL_ARGS(kernel, i, KARG_LOCAL(tile_local_bytes(s->group_size)));
    launch_tiles(s, kernel, tiles);
}

/* keys + scanned offsets -> active_out. */
static void scatter(MaterialSorter *s, cl_mem active_in, cl_mem active_out, uint32_t n,
                    size_t tiles)
{
    cl_uint n_arg = n;
    cl_kernel kernel = s->scatter;
    KERNEL_ARGS(kernel, 0, KARG(active_in), KARG(n_arg), KARG(s->keys), KARG(s->key_bits),
                KARG(s->counts), KARG(active_out), KARG_LOCAL(tile_local_bytes(s->group_size)),
                KARG_LOCAL(2 * s->group_size * sizeof(cl_uint)));
    launch_tiles(s, kernel, tiles);
}

void material_sorter_run(MaterialSorter *s, cl_mem hit, cl_mem material_ids, cl_mem active_in,
                         cl_mem active_out, uint32_t n)
{
    if (n > s->capacity)
        die("material sort: %u paths, above the %u it was created for", n, s->capacity);
    if (n == 0)
        return;
    size_t tiles = div_up(n, s->group_size * KEYS_PER_ITEM);
    count_keys(s, hit, material_ids, active_in, n, tiles);
    uint32_t num_counts = (uint32_t)(((size_t)s->num_materials + 1) * tiles);
    exclusive_scan_enqueue(s->scan, s->counts, num_counts, s->profile_ms);
    scatter(s, active_in, active_out, n, tiles);
}

void material_sorter_set_profile(MaterialSorter *s, double *ms_accumulator)
{
    s->profile_ms = ms_accumulator;
}

size_t material_sorter_group_size(const MaterialSorter *s) { return s->group_size; }

bool material_sorter_local_histogram(const MaterialSorter *s) { return s->local_histogram; }

int material_sorter_launches(const MaterialSorter *s, uint32_t n)
{
    if (n == 0)
        return 0;
    size_t tiles = div_up(n, s->group_size * KEYS_PER_ITEM);
    uint32_t num_counts = (uint32_t)(((size_t)s->num_materials + 1) * tiles);
    return (s->local_histogram ? 2 : 3) + exclusive_scan_launches(s->scan, num_counts);
}

void material_sorter_destroy(MaterialSorter *s)
{
    if (!s)
        return;
    cl_kernel kernels[] = {s->count_local, s->count_global, s->scatter};
    for (size_t i = 0; i < sizeof kernels / sizeof kernels[0]; i++)
        if (kernels[i])
            device_release_kernel(kernels[i]);
    cl_mem buffers[] = {s->keys, s->counts};
    for (size_t i = 0; i < sizeof buffers / sizeof buffers[0]; i++)
        if (buffers[i])
            device_release_buffer(buffers[i]);
    exclusive_scan_destroy(s->scan);
    free(s);
}
