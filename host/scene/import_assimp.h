/* SPDX-License-Identifier: MIT */
/* import_assimp.h: the formats read through Assimp (io/assimp_reader.h: FBX, STL, 3DS, X3D,
 * old .blend, OFF) as a pt scene (scene/scene_import.h). Each Assimp mesh is one pt mesh
 * ("mesh<i>") with its material as MTL terms (DESIGN.md "MTL mapping": diffuse colour and
 * texture -> Kd/map_Kd, emission -> Ke, opacity -> d, metallic/roughness -> Pm/Pr, i.e.
 * principled); every node holding it is an object naming it with the node's world matrix
 * (instancing); lights: point, spot (cone angles from the axis), directional; ambient and area
 * lights dropped with a warning. The first camera a node holds is the camera (film aspect from
 * it); without one the bounds are framed from +z. Axes are the file's as Assimp gives them
 * (Assimp converts FBX's and 3DS's to +y up only where the format says; STL and OFF have no
 * up axis and are kept as written). */
#ifndef PT_IMPORT_ASSIMP_H
#define PT_IMPORT_ASSIMP_H

#include "scene/scene_import.h"

bool import_assimp(const char *path, ImportedScene *out, Error *err);

#endif
