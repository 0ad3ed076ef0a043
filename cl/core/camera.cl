/* SPDX-License-Identifier: MIT */
/* camera.cl: primary rays. Pinhole, or thin lens when the lens radius is positive; uniformly
 * jittered sub-pixel position (box filter). Image x goes right, y goes down. */

/* A thin lens (lens radius eye.w > 0): the camera draws its rays' origins on the aperture. */
inline bool camera_has_lens(constant RenderParams *p) { return p->camera.eye.w > 0.0f; }

/* jitter: sub-pixel position in [0,1)^2; lens: two uniforms for the aperture. */
inline void camera_ray(constant RenderParams *p, uint x, uint y, float2 jitter, float2 lens,
                       float3 *origin, float3 *dir)
{
    Camera cam = p->camera;
    float tan_half = cam.up.w, aspect = cam.forward.w;
    float sx = (2.0f * ((float)x + jitter.x) / (float)p->width - 1.0f) * tan_half * aspect;
    float sy = (1.0f - 2.0f * ((float)y + jitter.y) / (float)p->height) * tan_half;
    float3 d = normalize(xyz(cam.forward) + sx * xyz(cam.right) + sy * xyz(cam.up));
    float3 o = xyz(cam.eye);
    float lens_radius = cam.eye.w, focus_distance = cam.right.w;
    if (lens_radius > 0.0f) {
        /* Points at the focus distance (measured along the view axis) stay sharp. */
        float3 focus = o + d * (focus_distance / dot(d, xyz(cam.forward)));
        float2 l = lens_radius * sample_disk_concentric(lens.x, lens.y);
        o = o + l.x * xyz(cam.right) + l.y * xyz(cam.up);
        d = normalize(focus - o);
    }
    *origin = o;
    *dir = d;
}

/* The camera ray of sample `sample` of pixel `pixel` (row-major): the one place that draws the
 * camera's random numbers (jitter, lens), so every kernel that starts paths sees the same rays. */
inline void camera_sample(constant RenderParams *p, uint pixel, uint sample, float3 *origin,
                          float3 *dir)
{
    RngKey key = render_rng_key(p, pixel, sample);
    float2 jitter = rng_pair(key, DIM_CAMERA_JITTER_X);
    float2 lens = camera_has_lens(p) ? rng_pair(key, DIM_LENS_U) : (float2)(0.0f);
    camera_ray(p, pixel % p->width, pixel / p->width, jitter, lens, origin, dir);
}

/* The shutter fraction s in [0, 1) of sample `sample` of pixel `pixel` (time = open + s (close -
 * open), shared.h path_time): uniform, from its own dimension, so that motion blur changes no other
 * number of the path; 0 without a shutter interval. */
inline float camera_time(constant RenderParams *p, uint pixel, uint sample)
{
    if (!(p->shutter_close > p->shutter_open))
        return 0.0f;
    return rng_from_key(render_rng_key(p, pixel, sample), DIM_CAMERA_TIME);
}
