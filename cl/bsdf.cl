/* SPDX-License-Identifier: MIT */
/* bsdf.cl: not written yet. */
