/* SPDX-License-Identifier: MIT */
/* bvh_quantized.h: the 2-wide tree of bvh.h with 32-byte nodes (cl/shared.h, BvhNodeQuantized). */
#ifndef PT_BVH_QUANTIZED_H
#define PT_BVH_QUANTIZED_H

#include "accel/bvh.h"

/* A quantised copy of bvh's nodes, same indices and triangle order (free() it). Every quantised
 * child box holds the exact one with a margin (box_test.cl, BOX_EXIT_SCALE, says why). Dies
 * if bvh has BVH_QUANTIZED_MAX_TRIANGLES triangles or more. */
BvhNodeQuantized *bvh_quantize(const Bvh *bvh);

/* Child c (0: left, 1: right) of a quantised node, decoded exactly (in double): its box, or an
 * inverted one (lo > hi) for an empty child. For tests. */
void bvh_quantized_child_box(const BvhNodeQuantized *node, int c, double lo[3], double hi[3]);

#endif
