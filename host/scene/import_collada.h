/* SPDX-License-Identifier: MIT */
/* import_collada.h: a COLLADA file (io/collada_reader.h) as a pt scene (scene/scene_import.h).
 * What maps to what:
 *  - up_axis: Z_UP turns (x, y, z) into (x, z, -y), X_UP (x, y, z) into (-y, x, z), so +y is up
 *    as in pt; Y_UP is kept. <unit> is not applied (pt has no units; cameras and lights scale
 *    with the geometry).
 *  - Each geometry is one mesh, shared by every node that instances it with the same material
 *    binding (another binding makes a second mesh "<id>#<k>"); objects carry the node's world
 *    matrix. A mesh's materials are its bound <material>s, by id.
 *  - Common-profile materials become the mesh's MTL-like materials (DESIGN.md "MTL mapping":
 *    lambert -> Kd, phong/blinn -> Kd, Ks, Ns, emission -> Ke, transparency -> d). In a CS184
 *    scene (a file with CGL/CMU462 techniques) they are Lambert with the diffuse colour, which is
 *    what CS184 renders.
 *  - CGL BSDFs: diffuse -> diffuse; mirror -> conductor (roughness 0, reflectance); microfacet
 *    -> conductor (eta, k, roughness sqrt(alpha) since pt's GGX alpha is r^2); glass ->
 *    dielectric (ior, roughness sqrt, tint = transmittance); emission -> black diffuse emitting
 *    `radiance`. Analytic spheres -> io/mesh_shapes.h spheres (normals interpolated).
 *  - Lights: point -> point (intensity = colour; attenuation dropped with a warning: pt's fall
 *    off with the inverse square), spot -> spot (cone_angle = falloff_angle / 2), directional
 *    -> directional (irradiance = colour), ambient dropped with a warning. A CGL area light is
 *    a one-sided emissive 1 x 1 square facing the node's -z (CS184's AreaLight); since CS184
 *    shows its emissive "light" meshes only to camera rays, a scene with CGL area lights drops
 *    the objects with CGL emission (warned), which otherwise would light the room twice.
 *  - Camera: the first instanced camera; fov_y from yfov, else from xfov and aspect_ratio; the
 *    film gets the aspect ratio (640 wide). A CS184 scene is framed as CS184 frames it: looking
 *    at the centre of the geometry's bounds along the file camera's direction, from 1.5 times
 *    the bounds' diagonal, +y up. Without a camera, the bounds are framed from +z.
 * Why our own reader and not Assimp for .dae: on the CS184 scenes Assimp 5.2.5 loads the meshes
 * but drops every <extra> (no spheres, area lights, glass, mirrors or microfacets), so half of
 * such a scene would be missing; see the closing note of issue 37. */
#ifndef PT_IMPORT_COLLADA_H
#define PT_IMPORT_COLLADA_H

#include "scene/scene_import.h"

bool import_collada(const char *path, ImportedScene *out, Error *err);

#endif
