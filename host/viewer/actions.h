/* SPDX-License-Identifier: MIT */
/* viewer_actions.h: the single-key actions of 'pt view' (host/viewer/actions.c). */
#ifndef PT_VIEWER_ACTIONS_H
#define PT_VIEWER_ACTIONS_H

#include <stdbool.h>

#include "viewer/state.h"

/* F: the thin lens focuses on the surface under the cursor; false (and a message) on a miss. */
bool viewer_focus_under_cursor(Viewer *v);
/* [ and ]: the aperture shrinks or grows by factors of 1.5 (steps < 0 or > 0), down to 0. */
void viewer_change_aperture(Viewer *v, int steps);
/* , and .: the environment map's rotation changes by 15 degrees per step (the scene's
 * environment.rotation, DESIGN's sense); false (and a message) when the scene has no map. The
 * caller restarts the film with the new rotation. */
bool viewer_turn_environment(Viewer *v, int steps);
/* --bloom on the linear film rgb (the viewer's film size), in place; true without --bloom. */
bool viewer_bloom(Viewer *v, float *rgb, Error *err);
/* S: PNG + EXR of the film as out/<scene>-view-N, N the first free number; prints the names. */
void viewer_save_film(Viewer *v);
/* The linear film (the mean per pixel, as 'pt render -o FILE.exr' writes it) as an EXR. */
bool viewer_write_film_exr(Viewer *v, const char *path, Error *err);
/* True when path ends in .exr (any case): --screenshot then writes the film, not the window. */
bool viewer_is_exr_name(const char *path);
/* C: the camera as a JSON fragment for a scene file. */
void viewer_print_camera(const Viewer *v);

/* The denoised view (viewer/denoised_frames.c). Ctrl+D: on (loading OIDN the first time; a
 * warning and no change when it is missing) or off. */
void viewer_toggle_denoise(Viewer *v);
/* Once a frame after sampling: shows a finished result of this film, hands the film to the
 * denoising thread when due. film_still: the film gains no more samples (paused, converged). */
void viewer_update_denoised(Viewer *v, bool film_still);
/* The display shows a denoised image of the current film. */
bool viewer_showing_denoised(const Viewer *v);

#endif
