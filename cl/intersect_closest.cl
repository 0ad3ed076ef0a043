/* SPDX-License-Identifier: MIT */
/* intersect_closest.cl: not written yet. */
