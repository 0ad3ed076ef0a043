// SPDX-License-Identifier: MIT
/* import_pbrt_spectra.c: pbrt-v4's spectrum-valued parameters as pt's linear sRGB. pt renders in
 * RGB, so a spectrum becomes three numbers:
 * - "rgb" values are taken as they are (pbrt-v4 turns an RGB light into RGB x its colour space's
 *   illuminant and divides that illuminant's luminance back out, so RGB L = [1 1 1] is white of
 *   radiance 1 in both);
 * - "blackbody" T and sampled or named light spectra: the colour of the spectrum at luminance 1, as
 *   pbrt-v4 normalises light spectra to luminance 1 before "scale";
 * - sampled reflectance / eta / k spectra: each channel the spectrum's mean weighted by that
 *   channel's colour-matching function (a flat spectrum stays flat);
 * - the named metal spectra (metal-Au-eta, ...): a table of RGB eta / k (the values Mitsuba and
 *   most RGB renderers use); named glasses: their index at the sodium d line (587.6 nm);
 * - any other string names a spectrum file (.spd pairs), integrated as a sampled spectrum.
 * CIE 1931 matching functions: the multi-lobe fit of Wyman, Sloan and Shirley (JCGT 2013). */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/input_file.h"
#include "scene/import_pbrt_internal.h"

static double lobe(double x, double mu, double s1, double s2)
{
    double t = (x - mu) / (x < mu ? s1 : s2);
    return exp(-0.5 * t * t);
}

/* Linear sRGB matching functions at wavelength nm. */
static void rgb_matching(double nm, double rgb[3])
{
    double x = 1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) -
               0.065 * lobe(nm, 501.1, 20.4, 26.2);
    double y = 0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1);
    double z = 1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8);
    rgb[0] = 3.2406 * x - 1.5372 * y - 0.4986 * z;
    rgb[1] = -0.9689 * x + 1.8758 * y + 0.0415 * z;
    rgb[2] = 0.0557 * x - 0.2040 * y + 1.0570 * z;
}

/* A piecewise-linear spectrum (wavelength, value pairs, sorted) at nm; constant beyond its ends. */
static double sampled_at(const double *pairs, int n, double nm)
{
    if (nm <= pairs[0])
        return pairs[1];
    for (int i = 1; i < n; i++)
        if (nm <= pairs[2 * i]) {
            double t = (nm - pairs[2 * i - 2]) / (pairs[2 * i] - pairs[2 * i - 2]);
            return pairs[2 * i - 1] + t * (pairs[2 * i + 1] - pairs[2 * i - 1]);
        }
    return pairs[2 * n - 1];
}

static double planck(double nm, double kelvin)
{
    const double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
    double l = nm * 1e-9;
    return 2.0 * h * c * c / (pow(l, 5) * (exp(h * c / (l * kb * kelvin)) - 1.0));
}

/* spectrum(nm) integrated against the matching functions: normalised per channel (reflectance
 * kinds) or to luminance 1 (lights). */
static void integrate(const double *pairs, int n, double kelvin, bool light, float out[3])
{
    double sum[3] = {0, 0, 0}, norm[3] = {0, 0, 0}, luminance = 0.0;
    for (double nm = 380.0; nm <= 780.0; nm += 1.0) {
        double s = pairs ? sampled_at(pairs, n, nm) : planck(nm, kelvin), c[3];
        rgb_matching(nm, c);
        for (int k = 0; k < 3; k++)
            sum[k] += s * c[k], norm[k] += c[k];
        luminance += s * (0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1));
    }
    for (int k = 0; k < 3; k++) {
        double v = light ? (luminance > 0.0 ? sum[k] / (0.2126 * sum[0] + 0.7152 * sum[1] + 0.0722 * sum[2]) : 0.0)
                         : sum[k] / norm[k];
        out[k] = (float)fmax(v, 0.0);
    }
}

typedef struct {
    const char *name;
    float rgb[3];
} NamedSpectrum;

static const NamedSpectrum named[] = {
    {"metal-Au-eta", {0.143f, 0.374f, 1.442f}},   {"metal-Au-k", {3.983f, 2.385f, 1.603f}},
    {"metal-Ag-eta", {0.155f, 0.117f, 0.138f}},   {"metal-Ag-k", {4.828f, 3.122f, 2.147f}},
    {"metal-Al-eta", {1.657f, 0.880f, 0.521f}},   {"metal-Al-k", {9.224f, 6.270f, 4.837f}},
    {"metal-Cu-eta", {0.200f, 0.924f, 1.102f}},   {"metal-Cu-k", {3.912f, 2.452f, 2.142f}},
    {"metal-CuZn-eta", {0.444f, 0.527f, 1.094f}}, {"metal-CuZn-k", {3.695f, 2.765f, 1.829f}},
    {"metal-MgO-eta", {1.732f, 1.737f, 1.746f}},  {"metal-MgO-k", {0.0f, 0.0f, 0.0f}},
    {"metal-TiO2-eta", {2.575f, 2.701f, 2.972f}}, {"metal-TiO2-k", {0.0f, 0.0f, 0.0f}},
    {"glass-BK7", {1.5168f, 1.5168f, 1.5168f}},   {"glass-BAF10", {1.6700f, 1.6700f, 1.6700f}},
    {"glass-FK51A", {1.4866f, 1.4866f, 1.4866f}}, {"glass-LASF9", {1.8503f, 1.8503f, 1.8503f}},
    {"glass-F5", {1.6034f, 1.6034f, 1.6034f}},    {"glass-F10", {1.6200f, 1.6200f, 1.6200f}},
    {"glass-F11", {1.6209f, 1.6209f, 1.6209f}},
};

/* A spectrum file (pbrt's .spd: wavelength, value pairs, # comments), named relative to the main
 * file and kept inside its folder. */
static bool spectrum_file(PbrtImport *imp, PbrtParam *q, bool light, float out[3])
{
    char path[1024];
    Error e = {0};
    if (!fs_resolve_inside(imp->path, q->strings[0], q->name, path, sizeof path, &e))
        return pbrt_check_path(imp, q->strings[0], q->name, q->line);
    char *text;
    size_t size;
    if (!input_file_read(path, "a spectrum file", (size_t)1 << 20, &text, &size, &e)) {
        error_set(imp->err, e.code, imp->file, q->line, "%s:%d: \"%s\": not a named spectrum, and %.800s",
                  imp->file, q->line, q->name, e.message);
        return false;
    }
    double pairs[2 * 4096];
    int n = 0;
    bool ok = true;
    for (char *c = text; *c && ok;) {
        if (*c == '#') {
            while (*c && *c != '\n')
                c++;
        } else if (isspace((unsigned char)*c)) {
            c++;
        } else {
            char *end;
            double v = strtod(c, &end);
            ok = end != c && isfinite(v) && n < 2 * 4096;
            if (ok)
                pairs[n++] = v;
            c = end;
        }
    }
    free(text);
    ok = ok && n >= 2 && n % 2 == 0;
    for (int i = 1; ok && i < n / 2; i++)
        ok = pairs[2 * i] > pairs[2 * i - 2];
    if (!ok)
        return pbrt_fail(imp, q->line, "\"%s\": \"%s\" is not a spectrum file (increasing "
                         "wavelength, value pairs)", q->name, q->strings[0]);
    integrate(pairs, n / 2, 0.0, light, out);
    return true;
}

bool pbrt_spectrum_rgb(PbrtImport *imp, PbrtParam *q, const char *kind, float out[3])
{
    bool light = strcmp(kind, "illuminant") == 0;
    switch (q->type) {
    case PBRT_RGB:
        if (q->count != 3)
            return pbrt_fail(imp, q->line, "\"%s\": an rgb value needs 3 numbers", q->name);
        for (int k = 0; k < 3; k++)
            out[k] = (float)q->numbers[k];
        break;
    case PBRT_FLOAT:
    case PBRT_INTEGER:
        if (q->count != 1)
            return pbrt_fail(imp, q->line, "\"%s\": expected one number", q->name);
        out[0] = out[1] = out[2] = (float)q->numbers[0];
        break;
    case PBRT_BLACKBODY:
        if (q->count != 1 || !(q->numbers[0] > 0.0) || q->numbers[0] > 1e6)
            return pbrt_fail(imp, q->line, "\"%s\": blackbody takes one temperature in (0, 1e6] K", q->name);
        integrate(NULL, 0, q->numbers[0], true, out);
        break;
    case PBRT_SPECTRUM:
        if (q->strings) {
            for (size_t i = 0; i < sizeof named / sizeof named[0]; i++)
                if (strcmp(q->strings[0], named[i].name) == 0) {
                    memcpy(out, named[i].rgb, sizeof named[i].rgb);
                    return true;
                }
            if (strncmp(q->strings[0], "stdillum-", 9) == 0 || strncmp(q->strings[0], "illum-", 6) == 0) {
                out[0] = out[1] = out[2] = 1.0f; /* named illuminants: white at luminance 1 */
                return true;
            }
            if (!spectrum_file(imp, q, light, out))
                return false;
            break;
        }
        for (int i = 1; i < q->count / 2; i++)
            if (!(q->numbers[2 * i] > q->numbers[2 * i - 2]))
                return pbrt_fail(imp, q->line, "\"%s\": spectrum wavelengths must increase", q->name);
        integrate(q->numbers, q->count / 2, 0.0, light, out);
        break;
    default:
        return pbrt_fail(imp, q->line, "\"%s\": expected rgb, spectrum, blackbody or float, not %s",
                         q->name, pbrt_param_type_name(q->type));
    }
    /* A sampled reflectance's channels may exceed 1 where the matching functions' negative lobes
     * fall (a narrow-band blue): pbrt's reflectances stay in [0, 1], so do these. */
    for (int k = 0; k < 3 && q->type == PBRT_SPECTRUM && strcmp(kind, "reflectance") == 0; k++)
        out[k] = fminf(out[k], 1.0f);
    for (int k = 0; k < 3; k++)
        if (!isfinite(out[k]) || (out[k] < 0.0f && strcmp(kind, "eta") != 0))
            return pbrt_fail(imp, q->line, "\"%s\": [%g %g %g] must be finite and >= 0", q->name,
                             out[0], out[1], out[2]);
    return true;
}
