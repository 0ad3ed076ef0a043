// SPDX-License-Identifier: MIT
/* gltf_json_check.cc: what is checked on a glTF's JSON text before tinygltf reads it (see
 * gltf_primitives.h): its nesting depth (tinygltf converts the JSON to Values recursively, so
 * 100,000 nested arrays in an "extras" overflowed the stack), that indices are integers an int
 * holds (tinygltf converts them unchecked), and that every external URI of
 * buffers and images stays inside the file's folder (glTF URIs are relative: base/fs.h
 * fs_resolve_inside, unless --allow-outside-paths), before any of them is opened. */
#include "io/gltf_primitives.h"

#include <cstdio>
#include <cstring>
#include <string>

#include <cJSON.h>

extern "C" {
#include "base/fs.h"
#include "base/json_depth.h"
}

namespace {

/* %XX decoded, as tinygltf decodes a URI before it opens the file. */
std::string url_decode(const char *s)
{
    std::string out;
    for (; *s; s++) {
        unsigned hex;
        if (s[0] == '%' && s[1] && s[2] && sscanf(s + 1, "%2x", &hex) == 1) {
            out += (char)hex;
            s += 2;
        } else {
            out += *s;
        }
    }
    return out;
}

bool check_uris(const char *path, const cJSON *root, Error *err)
{
    for (const char *section : {"buffers", "images"}) {
        const cJSON *array = cJSON_GetObjectItemCaseSensitive(root, section);
        int i = 0;
        for (const cJSON *e = cJSON_IsArray(array) ? array->child : nullptr; e; e = e->next, i++) {
            const cJSON *uri = cJSON_GetObjectItemCaseSensitive(e, "uri");
            if (!cJSON_IsString(uri) || strncmp(uri->valuestring, "data:", 5) == 0)
                continue;
            char what[64], resolved[4096];
            snprintf(what, sizeof what, "%s[%d].uri", section, i);
            std::string decoded = url_decode(uri->valuestring);
            if (decoded.find('\0') != std::string::npos) { /* "a.bin%00.png" would open a.bin */
                error_set(err, ERR_OBJ_PARSE, path, 0, "%s: %s \"%s\" decodes to a NUL byte", path,
                          what, uri->valuestring);
                return false;
            }
            if (!fs_resolve_inside(path, decoded.c_str(), what, resolved, sizeof resolved, err))
                return false;
        }
    }
    return true;
}

/* Keys whose numbers tinygltf stores in an int (an index, a mode, a component type): a value that
 * is not an integer in [0, 2^31 - 1] would be converted with undefined behaviour, truncated to
 * another index, or overflow where pt adds to it. */
const char *const INT_KEYS[] = {"index", "source", "sampler", "bufferView", "buffer", "mesh",
                                "camera", "skin", "material", "indices", "texCoord", "scene",
                                "node", "light", "mode", "componentType", "byteStride", "children",
                                "nodes", "joints", "POSITION", "NORMAL", "TEXCOORD_0", nullptr};

bool int_key(const char *key)
{
    for (const char *const *k = INT_KEYS; *k && key; k++)
        if (strcmp(key, *k) == 0)
            return true;
    return false;
}

/* Every number under an INT_KEYS key (or in an array under one) of the tree at `node`, whose
 * JSON path is `at`; depth is bounded by json_depth_check. */
bool check_ints(const char *path, const cJSON *node, const std::string &at, bool is_int, Error *err)
{
    if (cJSON_IsNumber(node) && is_int) {
        double v = node->valuedouble;
        if (!(v >= 0 && v <= 2147483647.0 && v == (double)(long long)v)) {
            error_set(err, ERR_OBJ_PARSE, path, 0, "%s: %s = %.17g is not an index (an integer from "
                      "0 to 2147483647)", path, at.c_str(), v);
            return false;
        }
        return true;
    }
    int i = 0;
    for (const cJSON *c = node->child; c; c = c->next, i++) {
        bool object = cJSON_IsObject(node);
        if (object && strcmp(c->string, "extras") == 0) /* the application's own data */
            continue;
        std::string sub = object ? (at.empty() ? "" : at + ".") + c->string
                                 : at + "[" + std::to_string(i) + "]";
        if (!check_ints(path, c, sub, object ? int_key(c->string) : is_int, err))
            return false;
    }
    return true;
}

} // namespace

namespace gltf_io {

bool check_json(const char *path, const char *json, size_t size, bool *uris_checked, Error *err)
{
    *uris_checked = false;
    if (!json_depth_check(path, json, size, err))
        return false;
    cJSON *root = cJSON_ParseWithLength(json, size);
    if (!root) /* tinygltf names what is wrong with the JSON; no file is opened (*uris_checked) */
        return true;
    bool ok = check_ints(path, root, "", false, err) && check_uris(path, root, err);
    cJSON_Delete(root);
    *uris_checked = ok;
    return ok;
}

} // namespace gltf_io
