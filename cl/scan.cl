/* SPDX-License-Identifier: MIT */
/* scan.cl: not written yet. */
