/* SPDX-License-Identifier: MIT */
/* scan.cl: stream compaction ("parallel active index", as in Cycles): turns the per-slot alive
 * flags left by shade_surface into a dense, ascending list of live slot indices and its length, so
 * the next bounce launches only live paths. Host side: host/parallel/compact.c, which runs, per bounce:
 *
 *   scan_count_flags      reads flags[n]; writes one alive bit per slot (mask) and a count per tile
 *   scan_reduce_values    } only when the tile counts do not fit one work-group (over 2^24 flags
 *   scan_exclusive_values } with groups of 256): the tile counts become tile offsets, level by level
 *   scan_scatter_indices  reads the mask and the tile counts (summing those before its tile) or
 *                         offsets; writes indices[count] and the count
 *
 * A flag tile is 32 slots per work item, so each work item owns one 32-bit mask word. The mask is
 * why this is fast: the flags (4 bytes a slot) are read once, and the scatter reads 1 bit a slot.
 * Work-group size: any power of two the host picks (at most 2048, for the ushort staging in the
 * scatter); local memory comes in as kernel arguments. Every barrier is reached by every work
 * item: loops around barriers run a trip count that depends only on the work-group size, and
 * branches on data never contain one. */

#define SCAN_FLAGS_PER_ITEM 32u /* one mask word per work item */

/* Exclusive prefix sum of one value per work item over the work-group. scratch: 2 size uints,
 * size a power of two. Every work item must call it. Returns the sum of the values of the work
 * items before this one; *total gets the sum of all. Ends with a barrier, so the caller may reuse
 * scratch. Hillis-Steele with two buffers: log2(size) steps of one barrier each. That is more
 * additions than Blelloch's upsweep/downsweep but half the barriers, and barrier latency is what
 * the scatter waits on (on an H100 the scatter of 2^24 flags took 32 us with Blelloch, 26 us with
 * this and ushort staging). The work stays linear because each item first reduces its own 32
 * flags or per_item values serially. */
inline uint group_exclusive_sum(uint value, local uint *scratch, uint *total)
{
    const uint lid = get_local_id(0);
    const uint size = get_local_size(0);
    uint inclusive = value;
    uint buffer = 0;
    scratch[lid] = value;
    for (uint offset = 1; offset < size; offset <<= 1) {
        barrier(CLK_LOCAL_MEM_FENCE);
        if (lid >= offset)
            inclusive += scratch[buffer + lid - offset];
        buffer ^= size;
        scratch[buffer + lid] = inclusive;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    *total = scratch[buffer + size - 1];
    barrier(CLK_LOCAL_MEM_FENCE);
    return inclusive - value;
}

/* Sum of one value per work item over the work-group (a tree reduction, sequential addressing
 * so that active work items read adjacent words). scratch: get_local_size(0) uints, a power of
 * two. Every work item must call it; every one gets the sum. Ends with a barrier. */
inline uint group_sum(uint value, local uint *scratch)
{
    const uint lid = get_local_id(0);
    scratch[lid] = value;
    for (uint width = get_local_size(0) >> 1; width > 0; width >>= 1) {
        barrier(CLK_LOCAL_MEM_FENCE);
        if (lid < width)
            scratch[lid] += scratch[lid + width];
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    const uint sum = scratch[0];
    barrier(CLK_LOCAL_MEM_FENCE);
    return sum;
}

/* One bit per flag, bit j = flags[j] != 0, for flags[4 quad .. 4 quad + 3] of a tile that starts
 * at flags[first]; slots at or past n read as dead. */
inline uint alive_nibble(global const uint *flags, uint first, uint n, uint quad, bool full_tile)
{
    uint4 f;
    if (full_tile) {
        /* Buffers start 16-byte aligned and tiles are multiples of 4 slots: one vector load. */
        f = ((global const uint4 *)(flags + first))[quad];
    } else {
        const uint left = n - first; /* slots of this tile below n; first < n */
        const uint slot = 4 * quad;
        f.x = slot < left ? flags[first + slot] : 0u;
        f.y = slot + 1 < left ? flags[first + slot + 1] : 0u;
        f.z = slot + 2 < left ? flags[first + slot + 2] : 0u;
        f.w = slot + 3 < left ? flags[first + slot + 3] : 0u;
    }
    return (f.x != 0u ? 1u : 0u) | (f.y != 0u ? 2u : 0u) | (f.z != 0u ? 4u : 0u) |
           (f.w != 0u ? 8u : 0u);
}

/* Tile t covers flags[32 size t, 32 size (t + 1)). Writes mask[size t + i] (bit j: slot
 * 32 (size t + i) + j alive) and tile_counts[t]. nibbles: 8 size bytes; scratch: size uints. */
kernel void scan_count_flags(global const uint *flags, uint n, global uint *mask,
                             global uint *tile_counts, local uchar *nibbles, local uint *scratch)
{
    const uint lid = get_local_id(0);
    const uint size = get_local_size(0);
    const uint tile = get_group_id(0);
    const uint first = tile * size * SCAN_FLAGS_PER_ITEM;
    const bool full_tile = n - first >= size * SCAN_FLAGS_PER_ITEM;

    /* Read in coalesced uint4s (work item i takes quads i, i + size, ...), then regroup through
     * local memory so that each work item holds 8 consecutive quads: one mask word. */
    for (uint k = 0; k < SCAN_FLAGS_PER_ITEM / 4; k++) {
        const uint quad = k * size + lid;
        nibbles[quad] = (uchar)alive_nibble(flags, first, n, quad, full_tile);
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    uint word = 0;
    for (uint j = 0; j < SCAN_FLAGS_PER_ITEM / 4; j++)
        word |= (uint)nibbles[lid * (SCAN_FLAGS_PER_ITEM / 4) + j] << (4 * j);
    mask[tile * size + lid] = word;

    const uint tile_count = group_sum(popcount(word), scratch);
    if (lid == 0)
        tile_counts[tile] = tile_count;
}

/* Sums values[per_item size t, per_item size (t + 1)) (below m) into tile_sums[t]: the next level
 * up, when a level has more values than one work-group scans. scratch: size uints. */
kernel void scan_reduce_values(global const uint *values, uint m, uint per_item,
                               global uint *tile_sums, local uint *scratch)
{
    const uint lid = get_local_id(0);
    const uint size = get_local_size(0);
    const uint tile = get_group_id(0);
    const uint first = tile * size * per_item;
    const uint left = m - first;
    uint sum = 0;
    for (uint k = 0; k < per_item; k++) {
        const uint i = k * size + lid; /* coalesced; the order of a sum does not matter */
        if (i < left)
            sum += values[first + i];
    }
    const uint tile_sum = group_sum(sum, scratch);
    if (lid == 0)
        tile_sums[tile] = tile_sum;
}

/* Replaces each tile of values (per_item size of them) by its exclusive prefix sum plus
 * tile_offsets[t], the exclusive prefix of the tiles before it. The last tile writes the grand
 * total to total[0]. The top level runs as one work-group with tile_offsets = {0}.
 * tile_values: per_item size uints; scratch: 2 size uints. */
kernel void scan_exclusive_values(global uint *values, uint m, uint per_item,
                                  global const uint *tile_offsets, global uint *total,
                                  local uint *tile_values, local uint *scratch)
{
    const uint lid = get_local_id(0);
    const uint size = get_local_size(0);
    const uint tile = get_group_id(0);
    const uint first = tile * size * per_item;
    const uint left = m - first;

    /* Stage the tile through local memory: coalesced global access, then each work item scans
     * per_item consecutive values. */
    for (uint k = 0; k < per_item; k++) {
        const uint i = k * size + lid;
        tile_values[i] = i < left ? values[first + i] : 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    uint sum = 0;
    for (uint j = 0; j < per_item; j++)
        sum += tile_values[lid * per_item + j];
    uint tile_sum;
    uint running = tile_offsets[tile] + group_exclusive_sum(sum, scratch, &tile_sum);
    /* Each work item rewrites only the values it read itself: no barrier needed before. */
    for (uint j = 0; j < per_item; j++) {
        const uint value = tile_values[lid * per_item + j];
        tile_values[lid * per_item + j] = running;
        running += value;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint k = 0; k < per_item; k++) {
        const uint i = k * size + lid;
        if (i < left)
            values[first + i] = tile_values[i];
    }
    if (lid == 0 && tile == get_num_groups(0) - 1)
        total[0] = tile_offsets[tile] + tile_sum;
}

/* Writes the slot index of every set mask bit of tile t to indices[offset_t + rank], in ascending
 * order, where offset_t is the number of alive slots before the tile. With sum_counts == 0,
 * tile_sums holds the offsets (scanned by scan_exclusive_values). With sum_counts != 0 it holds the
 * plain tile counts, and each work-group adds up those before its own: at most 8 size cached
 * reads, cheaper than a scan launch; the last tile then writes the total to total[0].
 * The indices are gathered in local memory first (as offsets within the tile, which fit a ushort)
 * so that the global writes are contiguous: writing them straight from the bit loop made the
 * scatter 4 to 10 times slower on an H100. staged: 32 size ushorts; scratch: 2 size uints. */
kernel void scan_scatter_indices(global const uint *mask, global const uint *tile_sums,
                                 uint sum_counts, global uint *total, global uint *indices,
                                 uint n, uint complement, local ushort *staged, local uint *scratch)
{
    const uint lid = get_local_id(0);
    const uint size = get_local_size(0);
    const uint tile = get_group_id(0);
    uint word = mask[tile * size + lid];
    const uint tile_first = tile * size * SCAN_FLAGS_PER_ITEM;
    if (complement) {
        /* The dead slots below n: clear bits become set ones, and the slots before this tile that
         * are dead number tile_first minus the live ones (the offsets below). */
        const uint word_first = tile_first + lid * SCAN_FLAGS_PER_ITEM;
        const uint valid = word_first >= n ? 0u : min(n - word_first, SCAN_FLAGS_PER_ITEM);
        word = ~word & (valid == 32u ? 0xffffffffu : (1u << valid) - 1u);
    }

    const uint tiles_before = sum_counts ? tile : 0u;
    uint partial = 0;
    for (uint t = lid; t < tiles_before; t += size) /* no barrier inside */
        partial += tile_sums[t];
    const uint sum_before = group_sum(partial, scratch); /* 0 when not summing */
    const uint live_before = sum_counts ? sum_before : tile_sums[tile];
    const uint tile_offset = complement ? tile_first - live_before : live_before;

    uint tile_count;
    uint rank = group_exclusive_sum(popcount(word), scratch, &tile_count);
    /* Lowest set bit first keeps the order stable; mask bits past n are zero. */
    while (word != 0u) {
        const uint bit = 31u - clz(word & (0u - word));
        staged[rank++] = (ushort)(lid * SCAN_FLAGS_PER_ITEM + bit);
        word &= word - 1u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    global uint *out = indices + tile_offset;
    for (uint i = lid; i < tile_count; i += size)
        out[i] = tile_first + staged[i];
    if (!complement && sum_counts && lid == 0 && tile == get_num_groups(0) - 1)
        total[0] = tile_offset + tile_count;
}
