/* SPDX-License-Identifier: MIT */
/* sampling.cl: not written yet. */
