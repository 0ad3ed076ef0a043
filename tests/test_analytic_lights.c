// SPDX-License-Identifier: MIT
/* Analytic lights (shared/DESIGN.md "Lights"), on scenes generated here: a diffuse plane (albedo
 * 0.8) at y = 0 seen from straight above by a pinhole camera, max_depth 2 (direct light only), so
 * a pixel's value is 0.8 / pi x the irradiance E at the plane point it sees. The point light's
 * I cos / r^2, the spot's profile, directional and sun E cos, the sun's penumbra; bad input. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

static const double PI = 3.14159265358979323846;
static const double ALBEDO = 0.8;
#define RES 32

static const char *write_plane(const char *dir)
{
    return test_write_file(dir, "plane.obj",
                           "v -20 0 -20\nv 20 0 -20\nv 20 0 20\nv -20 0 20\nf 1 4 3\nf 1 3 2\n");
}

/* scene.json: the plane (plus extra objects), camera at height cam_h looking down with the image's
 * top toward -z and half-width tan_half x cam_h on the plane, the given lights. */
static const char *write_scene(const char *dir, double cam_h, double tan_half, const char *extra,
                               const char *lights)
{
    write_plane(dir);
    char text[4096];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, %g, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], "
             "\"fov_y\": %.9g},\n \"film\": {\"width\": %d, \"height\": %d},\n"
             " \"objects\": [{\"obj\": \"plane.obj\"}%s],\n \"lights\": %s}\n",
             cam_h, 2.0 * atan(tan_half) * 180.0 / PI, RES, RES, extra, lights);
    return test_write_file(dir, "scene.json", text);
}

static float *render_with(const char *scene, int spp, unsigned seed, bool no_nee)
{
    RenderFixture f;
    render_fixture_open(&f, scene, 0, 0);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = spp, .max_depth = 2, .seed = seed, .no_nee = no_nee}, NULL);
    render_fixture_close(&f);
    return rgb;
}

static float *render(const char *scene, int spp, unsigned seed) { return render_with(scene, spp, seed, false); }

typedef double (*IrradianceFn)(double x, double z, const double *light);

/* The mean over pixel (i, j)'s footprint (box filter, as the camera's jitter) of 0.8 / pi x E, by
 * 8 x 8 subsamples. The image's x is +x, its top -z. */
static double expected_pixel(int i, int j, double cam_h, double tan_half, IrradianceFn e, const double *light)
{
    double sum = 0.0;
    for (int a = 0; a < 8; a++)
        for (int b = 0; b < 8; b++) {
            double sx = (2.0 * (i + (a + 0.5) / 8) / RES - 1.0) * tan_half;
            double sy = (1.0 - 2.0 * (j + (b + 0.5) / 8) / RES) * tan_half;
            sum += e(sx * cam_h, -sy * cam_h, light);
        }
    return ALBEDO / PI * sum / 64.0;
}

/* light: x height, y intensity. */
static double point_irradiance(double x, double z, const double *l)
{
    double r2 = x * x + z * z + l[0] * l[0];
    return l[1] * l[0] / (r2 * sqrt(r2)); /* I cos / r^2, cos = h / r */
}

/* light: height, intensity, cone, falloff (radians), pointing straight down. */
static double spot_irradiance(double x, double z, const double *l)
{
    double t = atan2(sqrt(x * x + z * z), l[0]);
    double profile = t <= l[3] ? 1.0 : t >= l[2] ? 0.0 : (l[2] - t) / (l[2] - l[3]);
    return point_irradiance(x, z, l) * profile;
}

/* Every pixel against expected_pixel: relative to the image's largest expectation. */
static void expect_image(const float *rgb, double cam_h, double tan_half, IrradianceFn e,
                         const double *light, double tolerance, const char *what)
{
    double peak = 0.0, worst = 0.0;
    int worst_i = 0, worst_j = 0;
    for (int j = 0; j < RES; j++)
        for (int i = 0; i < RES; i++)
            peak = fmax(peak, expected_pixel(i, j, cam_h, tan_half, e, light));
    cr_assert(peak > 0.0);
    double worst_want = 0.0, worst_got = 0.0;
    for (int j = 0; j < RES; j++)
        for (int i = 0; i < RES; i++) {
            double want = expected_pixel(i, j, cam_h, tan_half, e, light);
            for (int c = 0; c < 3; c++) {
                double d = fabs(rgb[3 * (j * RES + i) + c] - want) / peak;
                if (d > worst)
                    worst = d, worst_i = i, worst_j = j, worst_want = want, worst_got = rgb[3 * (j * RES + i) + c];
            }
        }
    cr_expect(worst < tolerance, "%s: pixel (%d, %d) is %g, the formula says %g (peak %g)", what,
              worst_i, worst_j, worst_got, worst_want, peak);
}

/* E = I cos / r^2: a point light 1 above the plane; the image spans 2 x 2 around its foot, where
 * E falls to 1/5.2 of its peak (1/r would leave 1/2.4). */
Test(analytic_lights, point_light_follows_inverse_square_cosine, .timeout = 120)
{
    const char *scene = write_scene(test_temp_dir(), 3.0, 1.0 / 3.0, "",
                                    "[{\"type\": \"point\", \"position\": [0, 1, 0], \"intensity\": [2, 2, 2]}]");
    float *rgb = render(scene, 256, 1);
    double light[2] = {1.0, 2.0};
    expect_image(rgb, 3.0, 1.0 / 3.0, point_irradiance, light, 0.01, "point light");
    free(rgb);
}

/* The spot's profile: falloff 20 degrees, cone 40, 1 above the plane; the image reaches 60
 * degrees from the axis, so it holds the full-intensity disc, the ramp and the dark outside. */
Test(analytic_lights, spot_profile_follows_design, .timeout = 120)
{
    const char *scene = write_scene(test_temp_dir(), 3.0, 1.8 / 3.0, "",
                                    "[{\"type\": \"spot\", \"position\": [0, 1, 0], \"intensity\": [3, 3, 3], "
                                    "\"direction\": [0, -2, 0], \"cone_angle\": 40, \"falloff_angle\": 20}]");
    float *rgb = render(scene, 256, 2);
    double light[4] = {1.0, 3.0, 40.0 * PI / 180.0, 20.0 * PI / 180.0};
    expect_image(rgb, 3.0, 1.8 / 3.0, spot_irradiance, light, 0.025, "spot light");
    /* Dark outside the cone: the image's corner is 60 degrees off the axis. */
    cr_expect(rgb[0] == 0.0f, "outside the cone: %g", rgb[0]);
    free(rgb);
}

/* The mean of the image against 0.8 / pi x E cos(theta). */
static void expect_uniform(const char *lights, double e_cos, int spp, double tolerance, bool no_nee)
{
    const char *scene = write_scene(test_temp_dir(), 3.0, 0.5, "", lights);
    float *rgb = render_with(scene, spp, 3, no_nee);
    double sum = 0.0;
    for (int k = 0; k < RES * RES * 3; k++)
        sum += rgb[k];
    double mean = sum / (RES * RES * 3), want = ALBEDO / PI * e_cos;
    cr_expect(fabs(mean - want) < tolerance * want, "%s%s: mean %g, E cos says %g", lights,
              no_nee ? " (BSDF only)" : "", mean, want);
    free(rgb);
}

/* A directional light at 60 degrees from the normal: E cos = E / 2. A sun of 90 degrees at 30
 * degrees from the normal: its radiance L = E / (pi sin^2 45) gives E at normal incidence, hence
 * exactly E cos on a plane that sees the whole disc (uniform L over the disc's solid angle,
 * L = E / (2 pi (1 - cos 45)), would give 0.85 E cos). BSDF-only sampling sees the same disc. */
Test(analytic_lights, directional_and_sun_give_irradiance_times_cosine, .timeout = 120)
{
    double s = sin(PI / 3.0), c = cos(PI / 3.0);
    char lights[512];
    snprintf(lights, sizeof lights,
             "[{\"type\": \"directional\", \"direction\": [%.9g, %.9g, 0], \"irradiance\": [2, 2, 2]}]", s, -c);
    expect_uniform(lights, 2.0 * c, 4, 0.002, false);
    snprintf(lights, sizeof lights,
             "[{\"type\": \"sun\", \"direction\": [%.9g, %.9g, 0], \"irradiance\": [2, 2, 2], \"angle\": 90}]", c, -s);
    expect_uniform(lights, 2.0 * s, 64, 0.01, false);
    expect_uniform(lights, 2.0 * s, 256, 0.02, true);
}

/* Column means of a render under a sun shining straight down past the edge of a half-plane
 * occluder 1 above the plane (x < 0 in its shadow); the camera sits between the two at height
 * 0.5, seeing x in [-0.2, 0.2]. */
static void sun_edge_columns(double angle_degrees, double columns[RES])
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "occluder.obj", "v -20 1 -20\nv 0 1 -20\nv 0 1 20\nv -20 1 20\nf 1 4 3\nf 1 3 2\n");
    char lights[256];
    snprintf(lights, sizeof lights,
             "[{\"type\": \"sun\", \"direction\": [0, -1, 0], \"irradiance\": [1, 1, 1], \"angle\": %g}]",
             angle_degrees);
    float *rgb = render(write_scene(dir, 0.5, 0.4, ", {\"obj\": \"occluder.obj\"}", lights), 256, 4);
    for (int i = 0; i < RES; i++) {
        columns[i] = 0.0;
        for (int j = 0; j < RES; j++)
            columns[i] += rgb[3 * (j * RES + i) + 1];
        columns[i] /= RES * (ALBEDO / PI); /* the visible fraction of the sun */
    }
    free(rgb);
}

/* The visible fraction of a sun of half-angle a at plane point x, the occluder's edge d above x = 0:
 * the part of the disc beyond the edge's direction (small angles: the disc is flat). */
static double sun_visible(double x, double d, double a)
{
    double s = fmax(-1.0, fmin(1.0, atan(x / d) / a));
    return (PI - acos(s) + s * sqrt(1.0 - s * s)) / PI;
}

/* Angle 0 gives a hard edge (every column dark or fully lit); 10 degrees a penumbra of width
 * 2 tan(5 degrees) x 1 around the edge whose profile is the disc's visible fraction. */
Test(analytic_lights, sun_penumbra_width_follows_its_angle, .timeout = 240)
{
    double columns[RES];
    sun_edge_columns(0.0, columns);
    for (int i = 0; i < RES; i++)
        cr_expect(fabs(columns[i] - (i < RES / 2 ? 0.0 : 1.0)) < 1e-3, "angle 0: column %d is %g", i, columns[i]);
    sun_edge_columns(10.0, columns);
    double a = 5.0 * PI / 180.0;
    int in_penumbra = 0;
    for (int i = 0; i < RES; i++) {
        double want = 0.0;
        for (int k = 0; k < 8; k++)
            want += sun_visible((2.0 * (i + (k + 0.5) / 8) / RES - 1.0) * 0.4 * 0.5, 1.0, a) / 8;
        cr_expect(fabs(columns[i] - want) < 0.03, "angle 10: column %d is %g, the disc says %g", i,
                  columns[i], want);
        in_penumbra += columns[i] > 0.05 && columns[i] < 0.95;
    }
    /* 2 x tan(5 degrees) = 0.175 wide, 0.0125 a column: about 14 columns, most of them strictly inside. */
    cr_expect(in_penumbra >= 10 && in_penumbra <= 15, "%d columns in the penumbra", in_penumbra);
}

/* Bad input: one line naming the key and the value. */
static void expect_refused(const char *lights, const char *needle)
{
    const char *dir = test_temp_dir();
    write_plane(dir);
    char text[1024];
    snprintf(text, sizeof text, "{\"objects\": [{\"obj\": \"plane.obj\"}],\n \"lights\": %s}\n", lights);
    SceneDesc desc;
    Error err = {0};
    bool ok = scene_desc_load(test_write_file(dir, "scene.json", text), &desc, &err);
    cr_expect(!ok, "%s was accepted", lights);
    if (ok)
        scene_desc_free(&desc);
    else
        cr_expect(strstr(err.message, needle) && !strchr(err.message, '\n'),
                  "%s: message \"%s\" does not name \"%s\"", lights, err.message, needle);
}

Test(analytic_lights, bad_input_is_named)
{
    expect_refused("[{\"type\": \"spot\", \"position\": [0, 1, 0], \"intensity\": 1, \"direction\": [0, -1, 0], "
                   "\"cone_angle\": 20, \"falloff_angle\": 30}]",
                   "lights[0].falloff_angle: 30 is larger than cone_angle 20");
    expect_refused("[{\"type\": \"directional\", \"direction\": [0, 0, 0], \"irradiance\": [1, 1, 1]}]",
                   "lights[0].direction: [0, 0, 0]");
    expect_refused("[{\"type\": \"point\", \"position\": [0, 1, 0], \"intensity\": [1, -1, 1]}]",
                   "lights[0].intensity: [1, -1, 1]");
    expect_refused("[{\"type\": \"sun\", \"direction\": [0, -1, 0], \"irradiance\": [-2, 1, 1]}]",
                   "lights[0].irradiance: [-2, 1, 1]");
    expect_refused("[{\"type\": \"area\"}]", "unknown light type \"area\"");
    expect_refused("[{\"type\": \"point\", \"intensity\": [1, 1, 1]}]", "lights[0].position: missing");
    expect_refused("[{\"position\": [0, 1, 0]}]", "lights[0].type: missing");
    expect_refused("[{\"type\": \"point\", \"position\": [0, 1, 0], \"intensity\": 1, \"angle\": 2}]",
                   "angle");
    expect_refused("[{\"type\": \"spot\", \"position\": [0, 1, 0], \"intensity\": 1, \"direction\": [0, -1, 0], "
                   "\"cone_angle\": 0}]",
                   "lights[0].cone_angle: 0 is out of range");
    expect_refused("{\"type\": \"point\"}", "lights: expected an array");
}

static double image_mean(const char *scene, int spp, unsigned seed)
{
    float *rgb = render(scene, spp, seed);
    double sum = 0.0;
    for (int k = 0; k < RES * RES * 3; k++)
        sum += rgb[k];
    free(rgb);
    return sum / (RES * RES * 3);
}

/* An emissive quad and a point light share the alias table: each is picked with its share of the
 * power and divided by it, so the image of both is the sum of the images of each alone. */
Test(analytic_lights, one_table_with_triangles_adds_up, .timeout = 240)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "lamp.mtl", "newmtl lamp\nKd 0 0 0\nKe 4 4 4\nnewmtl off\nKd 0 0 0\n");
    const char *quad = "v 0.5 1 -0.25\nv 1 1 -0.25\nv 1 1 0.25\nv 0.5 1 0.25\nf 1 2 3\nf 1 3 4\n";
    char text[512];
    snprintf(text, sizeof text, "mtllib lamp.mtl\nusemtl lamp\n%s", quad);
    test_write_file(dir, "lamp.obj", text);
    /* The same quad, dark: it hides the same part of the plane from the camera. */
    snprintf(text, sizeof text, "mtllib lamp.mtl\nusemtl off\n%s", quad);
    test_write_file(dir, "off.obj", text);
    const char *point = "[{\"type\": \"point\", \"position\": [-0.5, 1, 0], \"intensity\": [1, 1, 1]}]";
    double both = image_mean(write_scene(dir, 3.0, 0.5, ", {\"obj\": \"lamp.obj\"}", point), 64, 5);
    double lamp = image_mean(write_scene(dir, 3.0, 0.5, ", {\"obj\": \"lamp.obj\"}", "[]"), 64, 6);
    double alone = image_mean(write_scene(dir, 3.0, 0.5, ", {\"obj\": \"off.obj\"}", point), 4, 7);
    cr_assert(lamp > 0.2 * alone && alone > 0.2 * lamp, "lamp %g, point %g: not comparable", lamp, alone);
    cr_expect(fabs(both - (lamp + alone)) < 0.01 * (lamp + alone), "both %g, lamp %g + point %g = %g",
              both, lamp, alone, lamp + alone);
}
