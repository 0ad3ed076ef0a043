/* SPDX-License-Identifier: MIT */
/* tonemap.h: the display transforms of PNG output and the viewer (--tonemap). The list is written
 * once here; the curves themselves live in io/display_curve.h (one expression shared by C and the
 * viewer's GLSL). */
#ifndef PT_TONEMAP_H
#define PT_TONEMAP_H

#include <stdbool.h>
#include <string.h>

/* X(ENUM, "name"): every tone-map curve pt has, in the order `pt help` lists them. */
#define TONEMAP_CURVES(X)                                                                       \
    X(AGX, "agx")                                                                               \
    X(ACES, "aces")                                                                             \
    X(FILMIC, "filmic")                                                                         \
    X(PBR_NEUTRAL, "pbr-neutral")                                                               \
    X(REINHARD, "reinhard")                                                                     \
    X(CLAMP, "clamp")

typedef enum {
#define TONEMAP_ENUM(e, name) TONEMAP_##e,
    TONEMAP_CURVES(TONEMAP_ENUM)
#undef TONEMAP_ENUM
    TONEMAP_COUNT
} Tonemap;

/* The default: AgX, Blender's default view transform since 4.0, so a Blender user sees the look
 * they know: highlights roll off and desaturate toward white instead of clipping to a hue
 * (io/display_curve.h has its definition and source). */
#define TONEMAP_DEFAULT TONEMAP_AGX

static inline const char *tonemap_name(Tonemap t)
{
    static const char *const names[] = {
#define TONEMAP_NAME(e, name) name,
        TONEMAP_CURVES(TONEMAP_NAME)
#undef TONEMAP_NAME
    };
    return (unsigned)t < TONEMAP_COUNT ? names[t] : "?";
}

/* false when name is not a curve pt has. */
static inline bool tonemap_from_name(const char *name, Tonemap *out)
{
    for (int t = 0; t < TONEMAP_COUNT; t++)
        if (!strcmp(name, tonemap_name((Tonemap)t))) {
            *out = (Tonemap)t;
            return true;
        }
    return false;
}

/* How linear radiance becomes display values (PNG, viewer): exposure in stops, then the curve,
 * then the sRGB encoding. Bloom (render/bloom.h) happens before, on the linear image. */
typedef struct {
    float exposure;  /* stops: radiance x 2^exposure */
    Tonemap tonemap;
} DisplaySettings;

#endif
