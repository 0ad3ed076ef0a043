/* SPDX-License-Identifier: MIT */
/* medium_boundary.cl: a path at the boundary of media: the medium slot on either side of a
 * surface whose material bounds media, and Beer-Lambert absorption in media that only absorb. */

/* Beer-Lambert: what of c survives `distance` inside the medium in slot `medium` when it only
 * absorbs (a dielectric's absorption, a medium without scattering); outside any (0), c itself. */
PT_INLINE float3 through_medium(const SceneView *scene, uint medium, float3 c, float distance)
{
    if (PT_FEATURE(ABSORPTION) && medium != 0u)
        c *= dielectric_transmittance(xyz(medium_at_slot(scene, medium)->sigma_a), distance);
    return c;
}

/* The medium slot a ray leaving the surface toward w runs in: the surface's exterior (w on the
 * side geometric_normal points to) or interior when its material tm bounds media, else the
 * path's own (shared/medium.h). */
PT_INLINE uint medium_toward(constant RenderParams *p, Material tm, float3 geometric_normal,
                             float3 w, uint medium)
{
    /* A scene without media has no medium interface: its programs carry none of this. */
    if (!(PT_FEATURE(ABSORPTION) || PT_FEATURE(MEDIA)) ||
        !(tm.flags & MATERIAL_FLAG_MEDIUM_INTERFACE))
        return medium;
    uint next = dot(w, geometric_normal) > 0.0f ? tm.exterior : tm.interior;
    return next == MEDIUM_SLOT_WORLD ? p->scene.world_medium : next;
}
