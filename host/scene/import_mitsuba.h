/* SPDX-License-Identifier: MIT */
/* import_mitsuba.h: Mitsuba 3 XML scenes (.xml) as pt scenes (scene/scene_import.h): shapes,
 * BSDFs, textures, emitters, the sensor, film, sampler and integrator mapped onto pt's JSON scene;
 * the mapping and what it drops are in README.md "Mitsuba 3 scenes". */
#ifndef PT_IMPORT_MITSUBA_H
#define PT_IMPORT_MITSUBA_H

#include <stdbool.h>

#include "scene/scene_import.h"

bool mitsuba_import(const char *path, ImportedScene *out, Error *err);

/* pt render scene.xml -D NAME=VALUE: a parameter that overrides the scene's <default name=NAME>
 * (Mitsuba's `mitsuba -D`). Kept for the process; false (err set) when not NAME=VALUE. */
bool mitsuba_import_define(const char *name_value, Error *err);
/* Forgets every -D (tests). */
void mitsuba_import_clear_defines(void);

#endif
