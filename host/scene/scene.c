// SPDX-License-Identifier: MIT
#include "scene/scene.h"

#include <cJSON.h>
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scene/camera.h"

#define SCENE_FILE_LIMIT ((long)64 << 20) /* a scene description is small; refuse anything huge */

/* What every check needs to report an error: the file, its text (to find a key's line) and err. */
typedef struct {
    const char *file;
    const char *text;
    Error *err;
} Parser;

/* ---- Error reporting ------------------------------------------------------------------------ */

static int line_at(const char *text, size_t offset)
{
    int line = 1;
    for (size_t i = 0; i < offset && text[i]; i++)
        line += text[i] == '\n';
    return line;
}

/* Finds `"name"` followed by a colon at or after from; returns its offset or -1. */
static long find_key(const char *text, size_t from, const char *name, size_t name_len)
{
    for (const char *s = strchr(text + from, '"'); s; s = strchr(s + 1, '"')) {
        if (strncmp(s + 1, name, name_len) != 0 || s[1 + name_len] != '"')
            continue;
        const char *after = s + 2 + name_len;
        while (isspace((unsigned char)*after))
            after++;
        if (*after == ':')
            return (long)(s - text);
    }
    return -1;
}

/* The line of a key path such as "camera.fov_y" or "objects[1].obj", found by searching the text
 * for each component in turn (cJSON keeps no positions). An index [n] skips to the n-th match of
 * the next component. Returns the deepest line found, 0 when none: good enough for messages. */
static int key_line(const char *text, const char *path)
{
    if (!text)
        return 0;
    size_t from = 0;
    int line = 0, skip = 0;
    while (*path) {
        size_t len = strcspn(path, ".[");
        long at = -1;
        for (int i = 0; i <= skip; i++) {
            at = find_key(text, from, path, len);
            if (at < 0)
                return line;
            from = (size_t)at + len + 2;
        }
        line = line_at(text, (size_t)at);
        path += len;
        skip = 0;
        if (*path == '[') {
            skip = atoi(path + 1);
            path += strcspn(path, "]");
            path += *path == ']';
        }
        path += *path == '.';
    }
    return line;
}

/* Records "file:line: key: message" (the line when it can be found). Always returns false. */
__attribute__((format(printf, 4, 5))) static bool fail(Parser *p, ErrorCode code, const char *key,
                                                       const char *fmt, ...)
{
    char message[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof message, fmt, ap);
    va_end(ap);
    int line = key_line(p->text, key);
    if (line > 0)
        error_set(p->err, code, p->file, line, "%s:%d: %s: %s", p->file, line, key, message);
    else
        error_set(p->err, code, p->file, 0, "%s: %s: %s", p->file, key, message);
    return false;
}

/* ---- Typed values --------------------------------------------------------------------------- */

static bool read_float(Parser *p, const cJSON *item, const char *key, float *out)
{
    if (!cJSON_IsNumber(item))
        return fail(p, ERR_JSON_TYPE, key, "expected a number");
    double v = item->valuedouble;
    if (!isfinite(v) || fabs(v) > FLT_MAX)
        return fail(p, ERR_JSON_VALUE, key, "%g is not a finite number", v);
    *out = (float)v;
    return true;
}

static bool read_int(Parser *p, const cJSON *item, const char *key, int *out)
{
    if (!cJSON_IsNumber(item) || item->valuedouble != floor(item->valuedouble))
        return fail(p, ERR_JSON_TYPE, key, "expected an integer");
    double v = item->valuedouble;
    if (!isfinite(v) || v > INT_MAX || v < INT_MIN)
        return fail(p, ERR_JSON_VALUE, key, "%g is out of range", v);
    *out = (int)v;
    return true;
}

static bool read_vec3(Parser *p, const cJSON *item, const char *key, float out[3])
{
    if (!cJSON_IsArray(item) || cJSON_GetArraySize(item) != 3)
        return fail(p, ERR_JSON_TYPE, key, "expected an array of 3 numbers");
    for (int i = 0; i < 3; i++) {
        const cJSON *e = cJSON_GetArrayItem(item, i);
        if (!cJSON_IsNumber(e))
            return fail(p, ERR_JSON_TYPE, key, "expected an array of 3 numbers");
        if (!isfinite(e->valuedouble) || fabs(e->valuedouble) > FLT_MAX)
            return fail(p, ERR_JSON_VALUE, key, "element %d (%g) is not a finite number", i,
                        e->valuedouble);
        out[i] = (float)e->valuedouble;
    }
    return true;
}

/* Checks that item is an object whose keys are all in `keys` (NULL-terminated), none twice. */
static bool check_object(Parser *p, const cJSON *item, const char *path, const char *const *keys)
{
    if (!cJSON_IsObject(item))
        return fail(p, ERR_JSON_TYPE, path[0] ? path : "(top level)", "expected an object");
    for (const cJSON *child = item->child; child; child = child->next) {
        char key[256];
        snprintf(key, sizeof key, "%s%s%s", path, path[0] ? "." : "", child->string);
        bool known = false;
        for (int i = 0; keys[i] && !known; i++)
            known = strcmp(child->string, keys[i]) == 0;
        if (!known)
            return fail(p, ERR_JSON_UNKNOWN_KEY, key, "unknown key");
        for (const cJSON *other = item->child; other != child; other = other->next)
            if (strcmp(other->string, child->string) == 0)
                return fail(p, ERR_JSON_SYNTAX, key, "duplicate key");
    }
    return true;
}

static const cJSON *member(const cJSON *object, const char *name)
{
    return cJSON_GetObjectItemCaseSensitive(object, name);
}

/* ---- Sections ------------------------------------------------------------------------------- */

/* Camera coordinates within +-CAMERA_COORDINATE_LIMIT (read_vec3 has already rejected non-finite
 * ones). */
static bool check_camera_coordinates(Parser *p, const float v[3], const char *key)
{
    for (int i = 0; i < 3; i++)
        if (fabs(v[i]) > CAMERA_COORDINATE_LIMIT)
            return fail(p, ERR_JSON_VALUE, key, "element %d (%g) is too large: camera coordinates "
                        "must lie within +-%g", i, v[i], CAMERA_COORDINATE_LIMIT);
    return true;
}

/* The camera must define a view: eye != target, and up not along the view direction. In double:
 * within the coordinate limit, no product below overflows. */
static bool check_camera_frame(Parser *p, const CameraDesc *c)
{
    if (!check_camera_coordinates(p, c->eye, "camera.eye") ||
        !check_camera_coordinates(p, c->target, "camera.target") ||
        !check_camera_coordinates(p, c->up, "camera.up"))
        return false;
    double dir[3], up[3];
    for (int i = 0; i < 3; i++)
        dir[i] = (double)c->target[i] - (double)c->eye[i], up[i] = c->up[i];
    double dist = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double up_len = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
    if (!(dist > 0.0))
        return fail(p, ERR_JSON_VALUE, "camera.target", "[%g, %g, %g] is the same point as camera.eye",
                    c->target[0], c->target[1], c->target[2]);
    if (!(up_len > 0.0))
        return fail(p, ERR_JSON_VALUE, "camera.up", "[%g, %g, %g] has no direction", c->up[0],
                    c->up[1], c->up[2]);
    double cross[3] = {dir[1] * up[2] - dir[2] * up[1], dir[2] * up[0] - dir[0] * up[2],
                       dir[0] * up[1] - dir[1] * up[0]};
    double sine = sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]) /
                  (dist * up_len);
    if (!(sine > 1e-6))
        return fail(p, ERR_JSON_VALUE, "camera.up", "[%g, %g, %g] is parallel to the view direction",
                    c->up[0], c->up[1], c->up[2]);
    return true;
}

static bool parse_camera(Parser *p, const cJSON *obj, CameraDesc *c)
{
    static const char *const keys[] = {"eye", "target", "up", "fov_y", "aperture", "focus_distance",
                                       NULL};
    if (!check_object(p, obj, "camera", keys))
        return false;
    const cJSON *item;
    if (!member(obj, "eye"))
        return fail(p, ERR_JSON_VALUE, "camera.eye", "missing");
    if (!member(obj, "target"))
        return fail(p, ERR_JSON_VALUE, "camera.target", "missing");
    if (!read_vec3(p, member(obj, "eye"), "camera.eye", c->eye) ||
        !read_vec3(p, member(obj, "target"), "camera.target", c->target))
        return false;
    if ((item = member(obj, "up")) && !read_vec3(p, item, "camera.up", c->up))
        return false;
    if ((item = member(obj, "fov_y")) && !read_float(p, item, "camera.fov_y", &c->fov_y))
        return false;
    if (!(c->fov_y > 0.0f && c->fov_y < 180.0f))
        return fail(p, ERR_JSON_VALUE, "camera.fov_y", "%g is out of range (0, 180)", c->fov_y);
    if ((item = member(obj, "aperture")) && !read_float(p, item, "camera.aperture", &c->aperture))
        return false;
    if (c->aperture < 0.0f)
        return fail(p, ERR_JSON_VALUE, "camera.aperture", "%g is negative", c->aperture);
    if ((item = member(obj, "focus_distance")) &&
        !read_float(p, item, "camera.focus_distance", &c->focus_distance))
        return false;
    if (c->focus_distance < 0.0f)
        return fail(p, ERR_JSON_VALUE, "camera.focus_distance", "%g is negative", c->focus_distance);
    return check_camera_frame(p, c);
}

static bool parse_positive_int(Parser *p, const cJSON *obj, const char *name, const char *key,
                               int min, int max, int *out)
{
    const cJSON *item = member(obj, name);
    if (!item)
        return true;
    if (!read_int(p, item, key, out))
        return false;
    if (*out < min || *out > max)
        return fail(p, ERR_JSON_VALUE, key, "%d is out of range [%d, %d]", *out, min, max);
    return true;
}

static bool parse_film(Parser *p, const cJSON *obj, SceneDesc *d)
{
    static const char *const keys[] = {"width", "height", NULL};
    return check_object(p, obj, "film", keys) &&
           parse_positive_int(p, obj, "width", "film.width", 1, FILM_SIZE_LIMIT, &d->width) &&
           parse_positive_int(p, obj, "height", "film.height", 1, FILM_SIZE_LIMIT, &d->height);
}

static bool parse_render(Parser *p, const cJSON *obj, SceneDesc *d)
{
    static const char *const keys[] = {"spp", "max_depth", NULL};
    return check_object(p, obj, "render", keys) &&
           parse_positive_int(p, obj, "spp", "render.spp", 1, INT_MAX, &d->spp) &&
           parse_positive_int(p, obj, "max_depth", "render.max_depth", 1, MAX_DEPTH_LIMIT,
                              &d->max_depth);
}

/* Joins a path from the scene file onto the scene file's folder (absolute paths stay as they are). */
static bool resolve_path(Parser *p, const char *key, const char *relative, char out[1024])
{
    const char *slash = strrchr(p->file, '/');
    int folder_len = relative[0] == '/' || !slash ? 0 : (int)(slash - p->file) + 1;
    int n = snprintf(out, 1024, "%.*s%s", folder_len, p->file, relative);
    if (n < 0 || n >= 1024)
        return fail(p, ERR_JSON_VALUE, key, "path \"%s\" is too long", relative);
    return true;
}

static bool parse_objects(Parser *p, const cJSON *array, SceneDesc *d)
{
    static const char *const keys[] = {"obj", NULL};
    if (!array)
        return fail(p, ERR_JSON_VALUE, "objects", "empty: the scene needs at least one object");
    if (!cJSON_IsArray(array))
        return fail(p, ERR_JSON_TYPE, "objects", "expected an array of objects");
    int count = cJSON_GetArraySize(array);
    if (count == 0)
        return fail(p, ERR_JSON_VALUE, "objects", "empty: the scene needs at least one object");
    d->objects = calloc((size_t)count, sizeof *d->objects);
    if (!d->objects)
        return fail(p, ERR_TOO_LARGE, "objects", "out of memory");
    int i = 0;
    for (const cJSON *e = array->child; e; e = e->next, i++) {
        char key[64];
        snprintf(key, sizeof key, "objects[%d]", i);
        if (!check_object(p, e, key, keys))
            return false;
        snprintf(key, sizeof key, "objects[%d].obj", i);
        const cJSON *obj = member(e, "obj");
        if (!obj)
            return fail(p, ERR_JSON_VALUE, key, "missing");
        if (!cJSON_IsString(obj))
            return fail(p, ERR_JSON_TYPE, key, "expected a file name (string)");
        if (!obj->valuestring[0])
            return fail(p, ERR_JSON_VALUE, key, "empty file name");
        if (!resolve_path(p, key, obj->valuestring, d->objects[i]))
            return false;
        d->num_objects = i + 1;
    }
    return true;
}

static bool parse_background(Parser *p, const cJSON *item, float background[3])
{
    if (!read_vec3(p, item, "background", background))
        return false;
    for (int i = 0; i < 3; i++)
        if (background[i] < 0.0f)
            return fail(p, ERR_JSON_VALUE, "background", "[%g, %g, %g] has a negative radiance",
                        background[0], background[1], background[2]);
    return true;
}

static bool parse_scene(Parser *p, const cJSON *root, SceneDesc *d)
{
    static const char *const keys[] = {"camera", "film", "render", "objects", "background", NULL};
    if (!check_object(p, root, "", keys))
        return false;
    const cJSON *item;
    d->camera_given = (item = member(root, "camera")) != NULL;
    if (item && !parse_camera(p, item, &d->camera))
        return false;
    if ((item = member(root, "film")) && !parse_film(p, item, d))
        return false;
    if ((item = member(root, "render")) && !parse_render(p, item, d))
        return false;
    if ((item = member(root, "background")) && !parse_background(p, item, d->background))
        return false;
    return parse_objects(p, member(root, "objects"), d);
}

/* ---- Files ---------------------------------------------------------------------------------- */

static char *read_text(const char *path, Error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        ErrorCode code = errno == ENOENT ? ERR_FILE_MISSING : ERR_FILE_READ;
        error_set(err, code, path, 0, "%s: %s", path, strerror(errno));
        return NULL;
    }
    char *text = NULL;
    long size = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
    if (size > SCENE_FILE_LIMIT) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: %ld bytes is too large for a scene", path, size);
    } else if (size < 0 || fseek(f, 0, SEEK_SET) != 0 || !(text = malloc((size_t)size + 1)) ||
               fread(text, 1, (size_t)size, f) != (size_t)size) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: cannot read", path);
        free(text);
        text = NULL;
    } else {
        text[size] = '\0';
        if (strlen(text) != (size_t)size) {
            int line = line_at(text, strlen(text));
            error_set(err, ERR_JSON_SYNTAX, path, line, "%s:%d: NUL byte in the scene file", path,
                      line);
            free(text);
            text = NULL;
        }
    }
    fclose(f);
    return text;
}

static bool parse_json_file(SceneDesc *d, Error *err)
{
    char *text = read_text(d->path, err);
    if (!text)
        return false;
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, 1);
    if (!root) {
        size_t offset = end ? (size_t)(end - text) : 0;
        const char *line_start = text + offset;
        while (line_start > text && line_start[-1] != '\n')
            line_start--;
        int line = line_at(text, offset), column = (int)(text + offset - line_start) + 1;
        error_set(err, ERR_JSON_SYNTAX, d->path, line, "%s:%d:%d: malformed JSON", d->path, line,
                  column);
        free(text);
        return false;
    }
    Parser p = {.file = d->path, .text = text, .err = err};
    bool ok = parse_scene(&p, root, d);
    cJSON_Delete(root);
    free(text);
    return ok;
}

static bool has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    if (n < e)
        return false;
    for (size_t i = 0; i < e; i++)
        if (tolower((unsigned char)path[n - e + i]) != ext[i])
            return false;
    return true;
}

static void set_defaults(SceneDesc *d)
{
    memset(d, 0, sizeof *d);
    d->camera = (CameraDesc){.up = {0.0f, 1.0f, 0.0f}, .fov_y = 40.0f};
    d->width = d->height = 512;
    d->spp = 64;
    d->max_depth = 8;
}

bool scene_desc_load(const char *path, SceneDesc *out, Error *err)
{
    set_defaults(out);
    struct stat st;
    if (stat(path, &st) != 0) {
        ErrorCode code = errno == ENOENT ? ERR_FILE_MISSING : ERR_FILE_READ;
        error_set(err, code, path, 0, "%s: %s", path, strerror(errno));
        return false;
    }
    /* A folder stands for the scene.json inside it. */
    size_t len = strlen(path);
    while (len > 1 && path[len - 1] == '/')
        len--;
    int n = S_ISDIR(st.st_mode) ? snprintf(out->path, sizeof out->path, "%.*s/scene.json", (int)len, path)
                                : snprintf(out->path, sizeof out->path, "%s", path);
    if (n < 0 || (size_t)n >= sizeof out->path) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: path too long", path);
        return false;
    }
    if (!has_extension(out->path, ".obj"))
        return parse_json_file(out, err) || (scene_desc_free(out), false);
    /* A bare OBJ: one object, default settings, camera framed later on the bounds. */
    out->objects = calloc(1, sizeof *out->objects);
    if (!out->objects) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory", path);
        return false;
    }
    snprintf(out->objects[0], sizeof out->objects[0], "%s", out->path);
    out->num_objects = 1;
    return true;
}

void scene_desc_free(SceneDesc *desc)
{
    free(desc->objects);
    desc->objects = NULL;
    desc->num_objects = 0;
}

bool scene_load(const char *path, Scene *out, Error *err)
{
    memset(out, 0, sizeof *out);
    scene_data_init(&out->data);
    if (!scene_desc_load(path, &out->desc, err))
        return false;
    for (int i = 0; i < out->desc.num_objects; i++) {
        ObjMesh mesh;
        memset(&mesh, 0, sizeof mesh);
        bool ok = obj_load(out->desc.objects[i], &mesh, err) &&
                  scene_data_append_obj(&out->data, &mesh, out->desc.objects[i], err);
        obj_free(&mesh);
        if (!ok) {
            scene_free(out);
            return false;
        }
    }
    if (!scene_data_finish(&out->data, out->desc.path, err)) {
        scene_free(out);
        return false;
    }
    if (!out->desc.camera_given)
        out->desc.camera = camera_frame_bounds(out->data.bounds_min, out->data.bounds_max);
    return true;
}

void scene_free(Scene *scene)
{
    scene_desc_free(&scene->desc);
    scene_data_free(&scene->data);
}
