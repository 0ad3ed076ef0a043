/* SPDX-License-Identifier: MIT */
/* accumulate_film.cl: not written yet. */
