/* SPDX-License-Identifier: MIT */
/* sort_materials.cl: optional stage between intersect_closest and shade_surface that reorders the
 * live path list by the material each path hit, so that a shading work-group mostly runs one BSDF
 * branch and reads one material. A stable counting sort; host side: host/parallel/material_sort.c, which
 * runs, per bounce:
 *
 *   sort_materials_count_local  } reads active_in[n], hit[], material_ids[]; writes keys[n] (the
 *   sort_materials_count_global } hit's material id, num_materials on a miss) and how many of each
 *                                 key a tile holds, counts[key * tiles + tile]: in local memory,
 *                                 or with global atomics when the key table outgrows it
 *   scan_reduce_values          } (cl/parallel/scan.cl, host/parallel/exclusive_scan.c) counts become offsets in
 *   scan_exclusive_values       } place: where each (key, tile) starts in the output
 *   sort_materials_scatter      reads keys, active_in and the offsets; writes active_out[n]
 *
 * active_out holds the same slots, grouped by increasing key (misses last), and within a key in
 * their order in active_in: the compacted list is ascending, so one material's paths stay in slot
 * order. Next: shade_surface over active_out.
 * A tile is SORT_KEYS_PER_ITEM keys per work item; work-groups are a power of two of at most 256,
 * so a position within a tile fits SORT_INDEX_BITS and a key the remaining 20 bits. Every barrier
 * is reached by every work item: the loops around barriers run a trip count that is a kernel
 * argument or depends only on the work-group size. */

#define SORT_KEYS_PER_ITEM 16u
#define SORT_INDEX_BITS 12u /* 256 work items x 16 keys */
#define SORT_INDEX_MASK ((1u << SORT_INDEX_BITS) - 1u)
#define SORT_PAST_END 0xfffffu /* the key of tile positions at or past n: sorts after every key */

/* The sort key of a slot: the material id of its hit triangle, num_materials on a miss. An id at
 * or above num_materials (a broken scene) sorts with the misses rather than overrun the table. */
inline uint material_key(global const float4 *hit, global const uint *material_ids, uint slot,
                         uint num_materials)
{
    const uint prim = hit_prim(hit[slot]);
    return prim == HIT_NONE ? num_materials : min(material_ids[prim], num_materials);
}

/* Index of tile position p in a local tile: one pad word per 32 keeps the accesses of 16
 * consecutive positions per work item free of bank conflicts. */
inline uint padded(uint p) { return p + (p >> 5); }

/* Computes the keys of the tile's list entries into keys[] and into the local tile (positions at
 * or past n get SORT_PAST_END), in coalesced order, then waits for the whole tile. */
inline void stage_tile_keys(global const uint *active_in, uint n, global const float4 *hit,
                            global const uint *material_ids, uint num_materials,
                            global uint *keys, local uint *tile_keys)
{
    const uint size = get_local_size(0);
    const uint first = get_group_id(0) * size * SORT_KEYS_PER_ITEM;
    for (uint k = 0; k < SORT_KEYS_PER_ITEM; k++) {
        const uint p = k * size + get_local_id(0);
        uint key = SORT_PAST_END;
        if (first + p < n) {
            key = material_key(hit, material_ids, active_in[first + p], num_materials);
            keys[first + p] = key;
        }
        tile_keys[padded(p)] = key;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
}

/* The counting stages take SORT_KEYS_PER_ITEM consecutive tile positions per work item and add
 * each run of one key with one atomic: coherent rays give long runs, and an atomic per entry would
 * queue the work items of a warp on one counter. A run of SORT_PAST_END ends the last tile and is
 * not counted. */

/* Length of the run of one key that starts at position j of this work item's chunk of the tile,
 * clipped to the chunk. */
inline uint run_length_at(local const uint *tile_keys, uint j)
{
    const uint chunk = get_local_id(0) * SORT_KEYS_PER_ITEM;
    const uint key = tile_keys[padded(chunk + j)];
    uint length = 1;
    while (j + length < SORT_KEYS_PER_ITEM && tile_keys[padded(chunk + j + length)] == key)
        length++;
    return length;
}

/* Per-tile key counts in a local table of num_materials + 1 uints (histogram). tile_keys:
 * padded(tile size) uints. */
kernel void sort_materials_count_local(global const uint *active_in, uint n,
                                       global const float4 *hit, global const uint *material_ids,
                                       uint num_materials, global uint *keys, global uint *counts,
                                       local uint *histogram, local uint *tile_keys)
{
    const uint lid = get_local_id(0);
    const uint size = get_local_size(0);
    for (uint k = lid; k <= num_materials; k += size)
        histogram[k] = 0u;
    stage_tile_keys(active_in, n, hit, material_ids, num_materials, keys, tile_keys);

    uint j = 0;
    while (j < SORT_KEYS_PER_ITEM) {
        const uint key = tile_keys[padded(lid * SORT_KEYS_PER_ITEM + j)];
        const uint length = run_length_at(tile_keys, j);
        if (key != SORT_PAST_END)
            atomic_add(histogram + key, length);
        j += length;
    }
    barrier(CLK_LOCAL_MEM_FENCE);

    /* Key-major, so that the exclusive scan of counts gives each (key, tile) its output start. */
    const uint tile = get_group_id(0);
    const uint tiles = get_num_groups(0);
    for (uint k = lid; k <= num_materials; k += size)
        counts[k * tiles + tile] = histogram[k];
}

/* The same with the counts added straight into the tile's column of counts, zeroed by the host
 * (a fill: zeroing its own column here, 4 bytes every tiles words, made the sort of 2M paths with
 * 20000 materials 35% slower on an H100), for key tables larger than local memory: many keys, so
 * few collisions. tile_keys as above. */
kernel void sort_materials_count_global(global const uint *active_in, uint n,
                                        global const float4 *hit, global const uint *material_ids,
                                        uint num_materials, global uint *keys, global uint *counts,
                                        local uint *tile_keys)
{
    const uint lid = get_local_id(0);
    const uint tile = get_group_id(0);
    const uint tiles = get_num_groups(0);
    stage_tile_keys(active_in, n, hit, material_ids, num_materials, keys, tile_keys);

    uint j = 0;
    while (j < SORT_KEYS_PER_ITEM) {
        const uint key = tile_keys[padded(lid * SORT_KEYS_PER_ITEM + j)];
        const uint length = run_length_at(tile_keys, j);
        if (key != SORT_PAST_END)
            atomic_add(counts + key * tiles + tile, length);
        j += length;
    }
}

/* One pass of a split radix sort of the tile by the bit at shift: elements with a clear bit first,
 * order kept within each side. element[] holds this work item's SORT_KEYS_PER_ITEM consecutive
 * tile positions and holds them again afterwards; the tile in local memory is the sorted result.
 * One bit a pass: four bits a pass (16 digit counters per work item, a scan of 16 size counts)
 * has a quarter of the work-group scans but was slower on an H100 (2M paths, 8 materials: 110 us
 * per sort against 62) and on PoCL. */
inline void split_by_bit(uint element[SORT_KEYS_PER_ITEM], local uint *tile_keys,
                         local uint *scratch, uint shift)
{
    const uint lid = get_local_id(0);
    uint zeros = 0;
    for (uint j = 0; j < SORT_KEYS_PER_ITEM; j++)
        zeros += ((element[j] >> shift) & 1u) ^ 1u;
    uint total_zeros;
    /* Its barriers also order the previous pass's reads of the tile before the writes below. */
    const uint zeros_before = group_exclusive_sum(zeros, scratch, &total_zeros);
    uint zero_position = zeros_before;
    uint one_position = total_zeros + lid * SORT_KEYS_PER_ITEM - zeros_before;
    for (uint j = 0; j < SORT_KEYS_PER_ITEM; j++) {
        const bool one = (element[j] >> shift) & 1u;
        tile_keys[padded(one ? one_position : zero_position)] = element[j];
        one_position += one ? 1u : 0u;
        zero_position += one ? 0u : 1u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint j = 0; j < SORT_KEYS_PER_ITEM; j++)
        element[j] = tile_keys[padded(lid * SORT_KEYS_PER_ITEM + j)];
}

/* First position in [0, position] of the sorted tile whose element is at least key_first: where
 * the run of the element at position starts (binary search; no barrier inside). */
inline uint run_start(local const uint *tile_keys, uint position, uint key_first)
{
    uint low = 0, high = position;
    while (low < high) {
        const uint middle = (low + high) >> 1;
        if (tile_keys[padded(middle)] < key_first)
            low = middle + 1u;
        else
            high = middle;
    }
    return low;
}

/* Sorts each tile in local memory by key, stably, then writes each entry to its key's offset for
 * the tile plus its rank within the tile's run of that key. A tile element is key << 12 | position,
 * so the sorted tile is ascending as plain uints and runs can be found by binary search. key_bits:
 * bits of num_materials (the largest key). tile_keys: padded(tile size) uints; scratch: 2 size
 * uints. */
kernel void sort_materials_scatter(global const uint *active_in, uint n, global const uint *keys,
                                   uint key_bits, global const uint *offsets,
                                   global uint *active_out, local uint *tile_keys,
                                   local uint *scratch)
{
    const uint lid = get_local_id(0);
    const uint size = get_local_size(0);
    const uint tile = get_group_id(0);
    const uint tiles = get_num_groups(0);
    const uint first = tile * size * SORT_KEYS_PER_ITEM;
    const uint valid = min(n - first, size * SORT_KEYS_PER_ITEM);

    /* Coalesced loads into local memory, then each work item takes consecutive positions. */
    for (uint k = 0; k < SORT_KEYS_PER_ITEM; k++) {
        const uint p = k * size + lid;
        const uint key = p < valid ? keys[first + p] : SORT_PAST_END;
        tile_keys[padded(p)] = key << SORT_INDEX_BITS | p;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    uint element[SORT_KEYS_PER_ITEM];
    for (uint j = 0; j < SORT_KEYS_PER_ITEM; j++)
        element[j] = tile_keys[padded(lid * SORT_KEYS_PER_ITEM + j)];
    for (uint bit = 0; bit < key_bits; bit++)
        split_by_bit(element, tile_keys, scratch, SORT_INDEX_BITS + bit);

    /* Strided positions: consecutive work items write consecutive outputs of a run. */
    for (uint k = 0; k < SORT_KEYS_PER_ITEM; k++) {
        const uint p = k * size + lid;
        const uint element_p = tile_keys[padded(p)];
        const uint position = element_p & SORT_INDEX_MASK;
        if (position < valid) {
            const uint key = element_p >> SORT_INDEX_BITS;
            const uint rank = p - run_start(tile_keys, p, key << SORT_INDEX_BITS);
            active_out[offsets[key * tiles + tile] + rank] = active_in[first + position];
        }
    }
}
