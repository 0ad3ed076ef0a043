/* SPDX-License-Identifier: MIT */
/* shared/features.h: the program features, in one list. Part of cl/shared.h (read its rules); the
 * host includes it through shared.h, the kernels' program has it right after shared.h (Makefile
 * CL_SOURCES).
 *
 * pt builds its kernels for the scene (host/render/session.c program_features): the code of a
 * feature the scene lacks leaves the program, because it costs every scene registers and branches
 * (measured on the H200: the analytic-light and environment branches cost 4-8% of shade_surface
 * on scenes that have neither; every material lobe inlined made a diffuse-only box's shading 50%
 * slower). The list expands into the bits of the host's ProgramFeatures set, the build options
 * -DPT_FEATURE_<NAME>=0/1 (host/device/program_features.c), the summary's words and, below, the
 * kernels' PT_FEATURE(NAME). */
#ifndef PT_SHARED_FEATURES_H
#define PT_SHARED_FEATURES_H

/* X(NAME, "summary word"). Material features first: their bits are the mask that
 * host/scene/materials.c material_features() returns (MATERIAL_FEATURE_<NAME> below). */
#define MATERIAL_FEATURES(X)                                                                       \
    X(ROUGH_CONDUCTOR, "rough-conductor")     /* a conductor that is not a perfect mirror */       \
    X(CONDUCTOR_FRESNEL, "conductor-fresnel") /* a conductor with eta/k (not Fresnel 1) */         \
    X(ROUGH_DIELECTRIC, "rough-dielectric")   /* a dielectric that is not smooth */                \
    X(PRINCIPLED, "principled")                                                                    \
    X(MIX, "mix")                                                                                  \
    X(SURFACE_DETAIL, "surface-detail")     /* normal or bump map, or anisotropy */                \
    X(BUMP_MAP, "bump-map")                 /* a bump map (three lookups per hit) */               \
    X(TEXTURED_SCALARS, "textured-scalars") /* roughness, metallic or mix weight from a texture */ \
    X(ABSORPTION, "absorption")             /* a dielectric with Beer-Lambert absorption */        \
    X(TEXTURE, "texture")                   /* any texture (without, no lookup is compiled) */     \
    X(NOISE_TEXTURE, "noise-texture")       /* a procedural texture (fBm, inlined at lookups) */   \
    X(SRGB_TEXTURE, "srgb-texture")         /* an 8-bit sRGB image (decoded per texel) */          \
    X(FLOAT_TEXTURE, "float-texture")       /* a float image */                                    \
    X(TEXTURE_SAMPLER, "texture-sampler")   /* glTF sampling: wrap modes, nearest, uv transform */ \
    X(EMISSION_TEXTURE, "emission-texture")                                                        \
    X(REFRACTION, "refraction") /* a dielectric: roulette follows radiance's eta^2 (shade_surface) */
/* Scene features. INSTANCES and TLAS are not only optimisations: they must match the layout that
 * scene_accel_build builds (a two-level walk over a one-level tree reads past its arrays).
 * INSTANCES: hits name an instance, which shading and lights place through its transform. With
 * TLAS too, the BVH has two levels; without it, the instances' triangles are baked into one
 * world-space BVH whose hits scene_trace maps back to (instance, triangle) (host/accel/scene_bvh.h
 * BVH_FLAT). TLAS without INSTANCES changes nothing. */
#define SCENE_FEATURES(X)                                                                          \
    X(ENV, "env")                 /* an environment map (cl/light/light_env.cl) */                 \
    X(ANALYTIC, "analytic")       /* analytic lights (cl/light/light_analytic.cl) */               \
    X(CUTOUT, "cutout")           /* cut-out materials: a material read per hit in traversal */    \
    X(INSTANCES, "instances")     /* instances (shared/geometry.h "Instances") */                  \
    X(TLAS, "tlas")               /* with INSTANCES: the two-level walk (top-level BVH, BLASes) */ \
    X(MOTION, "motion")           /* moving instances (path_time) */                               \
    X(BLACK_HOLES, "black-holes") /* the integrate_geodesic stage */                               \
    X(MEDIA, "media")             /* media that scatter or emit: tracking (cl/medium/) */          \
    X(GRID_MEDIA, "grid-media")   /* grid media: density lookups and the majorant walk */
#define PROGRAM_FEATURES(X) MATERIAL_FEATURES(X) SCENE_FEATURES(X)

/* FEATURE_<NAME>: the feature's bit in a ProgramFeatures set. */
#define PT_FEATURE_INDEX_ENUM(name, word) PT_FEATURE_INDEX_##name,
enum { PROGRAM_FEATURES(PT_FEATURE_INDEX_ENUM) PROGRAM_FEATURE_COUNT };
#undef PT_FEATURE_INDEX_ENUM
#define PT_FEATURE_BIT_ENUM(name, word) FEATURE_##name = 1 << PT_FEATURE_INDEX_##name,
enum { PROGRAM_FEATURES(PT_FEATURE_BIT_ENUM) };
#undef PT_FEATURE_BIT_ENUM
/* The material features' names of host/scene/materials.c (the same bits). */
#define PT_MATERIAL_FEATURE_ENUM(name, word) MATERIAL_FEATURE_##name = FEATURE_##name,
enum { MATERIAL_FEATURES(PT_MATERIAL_FEATURE_ENUM) };
#undef PT_MATERIAL_FEATURE_ENUM

#define PT_FEATURE_BIT_OR(name, word) | FEATURE_##name
#define MATERIAL_FEATURE_ALL (0u MATERIAL_FEATURES(PT_FEATURE_BIT_OR))
#define PROGRAM_FEATURES_ALL (0u PROGRAM_FEATURES(PT_FEATURE_BIT_OR))

/* A set of FEATURE_* bits: what a program is built for. */
typedef uint ProgramFeatures;

#ifdef __OPENCL_C_VERSION__
/* The one way kernels ask: if (PT_FEATURE(ENV)) in code, #if PT_FEATURE(INSTANCES) only around
 * whole kernels, struct layouts and code that names what only exists with the feature. pt's
 * builds name every feature (-DPT_FEATURES_GIVEN -DPT_FEATURE_<NAME>=0/1), so a misspelt name
 * does not compile in code; a program built without those options has every feature. The
 * preprocessor cannot define a macro per list entry, hence the options rather than a mask
 * (#if cannot read the enum's bits). */
#ifdef PT_FEATURES_GIVEN
#define PT_FEATURE(name) (PT_FEATURE_##name)
#else
#define PT_FEATURE(name) 1
#endif
#endif

#endif
