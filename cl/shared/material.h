/* SPDX-License-Identifier: MIT */
/* shared/material.h: material types, texture slots, materials and textures. Part of cl/shared.h (read its rules); the host includes it through
 * shared.h, the kernels' program has it right after shared.h (Makefile CL_SOURCES). */
#ifndef PT_SHARED_MATERIAL_H
#define PT_SHARED_MATERIAL_H

/* ---- Materials and textures ---------------------------------------------------------------- */

/* Material types: X(NAME, "json name"). The values are the kernels' Material.type. */
#define MATERIAL_TYPES(X)                                                                          \
    X(DIFFUSE, "diffuse")       /* Lambert */                                                      \
    X(CONDUCTOR, "conductor")   /* GGX, complex Fresnel; roughness 0 = perfect mirror */           \
    X(DIELECTRIC, "dielectric") /* GGX (Walter 2007); roughness 0 = smooth glass */                \
    X(PRINCIPLED, "principled") /* glTF 2.0 metallic-roughness */                                  \
    X(MIX, "mix")               /* (1 - weight) a + weight b, resolved stochastically per hit */  \
    X(INTERFACE, "interface")   /* invisible: only the boundary of a medium (shared/medium.h) */
#define MATERIAL_TYPE_ENUM(name, json) MATERIAL_##name,
enum { MATERIAL_TYPES(MATERIAL_TYPE_ENUM) MATERIAL_TYPE_COUNT };
#undef MATERIAL_TYPE_ENUM

/* Texture slots of a Material: X(NAME, "json key"). A slot holds a texture index or NO_TEXTURE;
 * a textured colour multiplies the constant, a textured scalar replaces it (its red channel). */
#define MATERIAL_TEXTURE_SLOTS(X)                                                                  \
    X(BASE, "base")           /* albedo | reflectance | tint | base_color (rgb, multiplies) */     \
    X(EMISSION, "emission")   /* rgb, multiplies emission */                                       \
    X(ROUGHNESS, "roughness") /* scalar */                                                         \
    X(METALLIC, "metallic")   /* scalar */                                                         \
    X(OPACITY, "opacity")     /* scalar (an RGBA base texture's alpha is put here by the host) */  \
    X(WEIGHT, "weight")       /* scalar, mix */                                                    \
    X(NORMAL, "normal_map")   /* tangent-space normal, linear */                                   \
    X(BUMP, "bump_map")       /* height, red channel */
#define MATERIAL_TEXTURE_SLOT_ENUM(name, json) MATERIAL_TEX_##name,
enum { MATERIAL_TEXTURE_SLOTS(MATERIAL_TEXTURE_SLOT_ENUM) MATERIAL_TEX_COUNT };
#undef MATERIAL_TEXTURE_SLOT_ENUM

#define MATERIAL_FLAG_FRESNEL_ONE 1u  /* conductor without eta/k: Fresnel 1 */
#define MATERIAL_FLAG_CUTOUT 2u       /* opacity < 1 somewhere: rays may pass through */
#define MATERIAL_FLAG_BASE_ALPHA 4u   /* the BASE texture's alpha multiplies the opacity */
#define MATERIAL_FLAG_ALPHA_MASK 8u   /* opacity is 1 where it reaches base.w (the cutoff), else 0:
                                         glTF's alphaMode MASK */
#define MATERIAL_FLAG_MEDIUM_INTERFACE 16u /* the surface bounds media: interior / exterior apply */

#define NO_TEXTURE 0xffffffffu
/* Material features a scene may use (MATERIAL_FEATURE_*): shared/features.h. */

/* Mixes nest at most this deep (the host refuses deeper ones and cycles). */
#define MATERIAL_MIX_DEPTH_LIMIT 8u

/* One material as the kernels see it (shared/DESIGN.md "Materials"); textures are looked up at
 * the hit. Unused members of a type are 0 (textures NO_TEXTURE). */
typedef struct {
    float4 base;           /* rgb: diffuse albedo, conductor reflectance, dielectric tint or
                              principled base_color; w: alpha cutoff (MATERIAL_FLAG_ALPHA_MASK) */
    float4 emission;       /* rgb: emitted radiance times emission_strength (one-sided, front =
                              counter-clockwise side); w: luminance, times the emission texture's
                              mean luminance when textured (the light table's weight) */
    float4 eta;            /* rgb: conductor eta; w unused */
    float4 k;              /* rgb: conductor k; w unused */
    float4 absorption;     /* rgb: dielectric Beer-Lambert sigma per scene unit; w unused */
    float4 specular_color; /* rgb: principled specular_color; w unused */
    float roughness;       /* [0, 1]; GGX alpha = roughness^2 */
    float anisotropy;      /* [0, 1) */
    float metallic;        /* principled */
    float opacity;         /* [0, 1]; 1 = opaque */
    float ior;             /* dielectric and principled */
    float specular;        /* principled (KHR_materials_specular) */
    float weight;          /* mix: weight of b */
    float bump_scale;
    uint type;             /* MATERIAL_* */
    uint flags;            /* MATERIAL_FLAG_* */
    uint mix_a, mix_b;     /* mix: material indices */
    uint tex[MATERIAL_TEX_COUNT]; /* MATERIAL_TEX_* slots: texture index or NO_TEXTURE */
    uint interior;         /* MATERIAL_FLAG_MEDIUM_INTERFACE: medium slot behind the surface (0 none) */
    uint exterior;         /* ... and in front of it (MEDIUM_SLOT_WORLD: the world medium) */
    float subsurface;      /* principled: the share of the diffuse lobe that enters (interior: its
                              random-walk medium, host/scene/scene_media.c) */
    uint pad0;
} Material;

#define TEXTURE_RGBA8_SRGB 0u /* one uint per texel, r in the low byte, sRGB-encoded rgb */
#define TEXTURE_RGBA32F 1u    /* four uints per texel (float bits), linear */
/* Procedural fBm Perlin noise in object space: `offset` points to 9 uints, color0 rgb, color1 rgb,
 * frequency (float bits), octaves, seed (uint); width = height = 1. */
#define TEXTURE_NOISE 2u
/* One uint per texel as TEXTURE_RGBA8_SRGB, but every channel linear (value / 255): 8-bit images
 * read as data (normal, roughness, metallic, opacity maps) keep a quarter of RGBA32F's memory and
 * traffic. */
#define TEXTURE_RGBA8_LINEAR 3u
/* Entries of the scene's srgb_decode buffer (shared/render.h): one per 8-bit code. */
#define TEXTURE_SRGB_CODES 256

/* How a texture is sampled (TextureInfo.flags; 0: bilinear, repeating, rgba as stored, the
 * lookup's plain path). Wrap modes per axis as glTF's samplers (GL's REPEAT, CLAMP_TO_EDGE,
 * MIRRORED_REPEAT); NEAREST takes the texel under uv; TRANSFORM maps uv through an affine first
 * (KHR_texture_transform, already in pt's uv frame); the CHANNEL field moves r, g, b or a into x,
 * which a scalar parameter reads (glTF's metallicRoughness: roughness g, metallic b); SCALE
 * multiplies rgb (after the channel move: a glTF factor times its texture). */
#define TEXTURE_WRAP_REPEAT 0u
#define TEXTURE_WRAP_CLAMP 1u
#define TEXTURE_WRAP_MIRROR 2u
#define TEXTURE_FLAG_WRAP_S(flags) ((flags) & 3u)
#define TEXTURE_FLAG_WRAP_T(flags) (((flags) >> 2) & 3u)
#define TEXTURE_FLAG_NEAREST 16u
#define TEXTURE_FLAG_TRANSFORM 32u
#define TEXTURE_FLAG_SCALE 64u
#define TEXTURE_FLAG_CHANNEL(flags) (((flags) >> 7) & 3u)
#define TEXTURE_FLAGS_MAKE(wrap_s, wrap_t, channel) ((wrap_s) | (wrap_t) << 2 | (channel) << 7)

typedef struct {
    uint offset; /* first uint of the texture in the texel buffer */
    uint width;
    uint height;
    uint format; /* TEXTURE_* */
    uint flags;  /* TEXTURE_FLAG_*: how it is sampled */
    float scale; /* TEXTURE_FLAG_SCALE: multiplies rgb */
    float transform[6]; /* TEXTURE_FLAG_TRANSFORM: uv' = (t0 u + t1 v + t2, t3 u + t4 v + t5) */
} TextureInfo;

#endif
