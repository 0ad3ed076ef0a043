/* SPDX-License-Identifier: MIT */
/* shade_surface.cl: not written yet. */
