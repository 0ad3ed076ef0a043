/* SPDX-License-Identifier: MIT */
/* microfacet.cl: the GGX (Trowbridge-Reitz) distribution, Smith masking-shadowing and the sampling
 * of visible normals, in the local shading frame (bsdf_common.cl). */
