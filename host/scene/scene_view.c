// SPDX-License-Identifier: MIT
/* scene_view.c: how a loaded scene is seen and lit when its file does not say: the camera framed on
 * its bounds (scene_frame_camera) and the default rig (scene_default_rig_choice,
 * scene_add_default_rig; README "The first image"). scene.c loads; this looks. */
#include <math.h>

#include "base/error.h"
#include "base/vec3.h"
#include "scene/camera.h"
#include "scene/default_rig.h"
#include "scene/scene.h"

/* Whether a model long along the front axis has its top (its highest tenth) behind its centre:
 * an animal's head is its highest part (Spot, the dragon), so that end is taken as its front.
 * Only a one-level scene is looked at (its vertices are in world space). */
static bool top_is_behind(const SceneData *d, const ViewBasis *b)
{
    if (d->two_level || d->num_vertices == 0 || !camera_box_is_long(d->bounds_min, d->bounds_max, b))
        return false;
    float lo = INFINITY, hi = -INFINITY, center[3];
    for (int i = 0; i < 3; i++)
        center[i] = 0.5f * (d->bounds_min[i] + d->bounds_max[i]);
    for (uint32_t v = 0; v < d->num_vertices; v++) {
        float h = dot3(d->positions[v].s, b->up);
        lo = fminf(lo, h), hi = fmaxf(hi, h);
    }
    double along = 0.0;
    for (uint32_t v = 0; v < d->num_vertices; v++)
        if (dot3(d->positions[v].s, b->up) >= hi - 0.1f * (hi - lo))
            along += dot3(d->positions[v].s, b->front) - dot3(center, b->front);
    return along < 0.0;
}

void scene_frame_camera(Scene *scene, UpAxis up)
{
    ViewBasis basis = view_basis(up);
    float aspect = (float)scene->desc.width / (float)scene->desc.height;
    /* A scene lit by its own lights (no rig) is a set built to be seen from its front, as the
     * Cornell box's open side: straight on. A model for the rig: the 3/4 view. */
    FrameSide side = scene_default_rig_choice(scene) == RIG_NONE ? FRAME_FRONT
                     : top_is_behind(&scene->data, &basis)        ? FRAME_BACK
                                                                  : FRAME_THREE_QUARTER;
    scene->desc.camera = camera_frame_model_from(scene->data.bounds_min, scene->data.bounds_max, aspect,
                                                 &basis, side);
    scene->desc.camera_given = false;
}

/* The emitters' weight in the light table's unit (area x luminance) against the rig's sky over the
 * scene's bounding disc (pi R^2 x a radiance of 1): emitters below a tenth of that light the model
 * less than a tenth as well as the default sky would, e.g. glowing labels or indicator lamps. */
#define TINY_EMITTERS 0.1
static double emitter_weight(const SceneData *d)
{
    double sum = 0.0;
    for (uint32_t k = 0; k < d->num_emissive; k++) {
        const Triangle *t = &d->triangles[d->emissive_triangles[k]];
        const float *a = d->positions[t->v.s[0]].s, *b = d->positions[t->v.s[1]].s,
                    *c = d->positions[t->v.s[2]].s;
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double area = 0.5 * sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        sum += area * d->materials[d->material_ids[d->emissive_triangles[k]]].emission.s[3];
    }
    return sum;
}

RigChoice scene_default_rig_choice(const Scene *scene)
{
    const SceneData *d = &scene->data;
    const float *bg = scene->desc.background;
    if (d->num_analytic > 0 || d->environment.width > 0 || bg[0] > 0.0f || bg[1] > 0.0f || bg[2] > 0.0f)
        return RIG_NONE;
    for (uint32_t i = 0; i < d->num_media; i++) /* an emissive medium lights the scene */
        if (d->media[i].flags & MEDIUM_FLAG_EMITS)
            return RIG_NONE;
    bool bare = scene_is_bare_model(scene->desc.path);
    if (d->num_emissive == 0)
        return bare ? RIG_WITH_GROUND : RIG_SKY_AND_KEY;
    double r2 = 0.0;
    for (int i = 0; i < 3; i++)
        r2 += 0.25 * ((double)d->bounds_max[i] - d->bounds_min[i]) * ((double)d->bounds_max[i] - d->bounds_min[i]);
    return bare && emitter_weight(d) < TINY_EMITTERS * 3.14159265358979 * r2 ? RIG_WITH_GROUND : RIG_NONE;
}

bool scene_add_default_rig(Scene *scene, const RigOptions *options, Error *err)
{
    RigChoice choice = scene_default_rig_choice(scene);
    if (choice == RIG_NONE)
        return true;
    ViewBasis basis = view_basis(options->up);
    bool ground = choice == RIG_WITH_GROUND && !options->no_ground && !rig_model_is_flat(&scene->data, &basis);
    const char *path = scene->desc.path;
    if (scene->data.num_emissive > 0)
        warn("%s: its %u emissive triangles are too weak to light it (less than a tenth of a sky): "
             "lit by the default rig as well (a sky, a sun%s); --no-default-light keeps only its "
             "own light", path, scene->data.num_emissive, ground ? ", a ground" : "");
    else
        warn("%s has no light (no emissive triangles, no \"lights\", no environment map, a black "
             "background): lit by the default rig (a sky, a sun%s; README \"The first image\"); "
             "%s--no-default-light keeps it dark", path, ground ? ", a ground at its lowest point" : "",
             ground ? "--no-ground drops the ground, " : "");
    return rig_add_sky(&scene->data, &basis, err) && rig_add_sun(&scene->data, &basis, &scene->desc.camera, err) &&
           (!ground || rig_add_ground(&scene->data, &basis, err));
}

bool scene_add_default_light(Scene *scene)
{
    RigOptions options = {.up = UP_AXIS_Y};
    Error err = {0};
    uint32_t before = scene->data.num_analytic;
    if (!scene_add_default_rig(scene, &options, &err))
        warn("%s", err.message);
    return scene->data.num_analytic > before;
}
