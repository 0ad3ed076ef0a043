/* SPDX-License-Identifier: MIT */
/* intersect_shadow.cl: not written yet. */
