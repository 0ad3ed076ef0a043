/* SPDX-License-Identifier: MIT */
/* generate_camera_rays.cl: not written yet. */
