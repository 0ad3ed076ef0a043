// SPDX-License-Identifier: MIT
/* The C API of gltf_loader.h over Debian's tinygltf 2.7.0 (a shared library built with its own
 * JSON, stb_image and file-system callbacks; TINYGLTF_IMPLEMENTATION is never defined here). The
 * file is read once by input_file_read (regular files only, size-limited); a GLB's header and
 * chunks are checked here so that a truncated file is named as such; tinygltf parses the JSON and
 * loads the buffers through pt's file callbacks, which remember a missing file so the message
 * names it and the JSON path that asked for it. Images are not decoded here: their encoded bytes
 * or paths go to the material mapping (scene/gltf_material_read.cc). */
#include "io/gltf_primitives.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include <sys/stat.h>

#include <cJSON.h>

extern "C" {
#include "io/input_file.h"
}

namespace {

bool g_quiet = false;

/* Vertices plus triangles of all decoded primitives together (about 3 GiB of mesh). */
const size_t DECODED_LIMIT = (size_t)1 << 26;

/* Extensions pt reads (materials: scene/gltf_material_read.cc); KHR_mesh_quantization only
 * widens the accessor types, which the decoder reads all of. */
const char *const SUPPORTED[] = {"KHR_lights_punctual",         "KHR_materials_emissive_strength",
                                 "KHR_materials_specular",      "KHR_materials_transmission",
                                 "KHR_materials_ior",           "KHR_materials_volume",
                                 "KHR_texture_transform",       "KHR_mesh_quantization",
                                 "KHR_draco_mesh_compression",  nullptr};

bool supported(const std::string &name)
{
    for (const char *const *s = SUPPORTED; *s; s++)
        if (name == *s)
            return true;
    return false;
}

/* pt's file callbacks for tinygltf: reads through input_file_read, and remembers the first file
 * that was missing or unreadable and why. */
struct FileLog {
    std::string failed, reason;
    ErrorCode code = ERR_NONE;
    bool uris_checked = false; /* gltf_io::check_json vetted the URIs: files may be opened */
};

/* Only a regular file "exists": opening a FIFO to find out would wait for a writer forever. */
bool file_exists(const std::string &name, void *user)
{
    FileLog *log = static_cast<FileLog *>(user);
    struct stat st;
    int found = log->uris_checked ? stat(name.c_str(), &st) : -1;
    bool missing = found != 0 && errno == ENOENT, regular = found == 0 && S_ISREG(st.st_mode);
    if (!regular && log->failed.empty()) {
        log->failed = name;
        log->reason = !log->uris_checked ? "not read (the JSON did not parse)"
                      : missing ? "no such file" : found != 0 ? strerror(errno)
                      : S_ISDIR(st.st_mode) ? "is a directory, not a file"
                      : "is not a regular file (a FIFO or device is never read)";
        log->code = missing ? ERR_FILE_MISSING : ERR_FILE_READ;
    }
    return regular;
}

std::string expand_path(const std::string &name, void *) { return name; }

bool read_file(std::vector<unsigned char> *out, std::string *err, const std::string &name, void *user)
{
    char *data;
    size_t size;
    Error e = {};
    if (!static_cast<FileLog *>(user)->uris_checked)
        return false;
    if (!input_file_read(name.c_str(), "a glTF buffer or image", INPUT_LIMIT_OBJ, &data, &size, &e)) {
        FileLog *log = static_cast<FileLog *>(user);
        if (log->failed.empty()) {
            log->failed = name;
            log->reason = e.message;
            log->code = e.code;
        }
        if (err)
            *err += e.message;
        return false;
    }
    out->assign(data, data + size);
    free(data);
    return true;
}

bool write_file(std::string *, const std::string &, const std::vector<unsigned char> &, void *)
{
    return false;
}

/* Keeps a data URI image's encoded bytes undecoded in image->image; an external image keeps only
 * its uri (the material mapping reads the file); one in a buffer view is copied after its range
 * is checked (gltf_io::read_image_views: tinygltf passes the view's bytes unchecked). */
bool keep_image_bytes(tinygltf::Image *image, const int, std::string *, std::string *, int, int,
                      const unsigned char *bytes, int size, void *)
{
    if (image->uri.empty() && image->bufferView < 0 && size > 0)
        image->image.assign(bytes, bytes + size);
    image->width = image->height = 0;
    return true;
}

uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The GLB container: 12-byte header (magic, version 2, length) then chunks (length, type, data). */
bool check_glb(const char *path, const unsigned char *b, size_t size, Error *err)
{
    if (size < 20) {
        error_set(err, ERR_OBJ_PARSE, path, 0, "%s: truncated GLB (%zu bytes, the header alone "
                  "needs 20)", path, size);
        return false;
    }
    uint32_t version = le32(b + 4), length = le32(b + 8);
    if (version != 2) {
        error_set(err, ERR_OBJ_PARSE, path, 0, "%s: GLB version %u (pt reads glTF 2.0)", path, version);
        return false;
    }
    if (length > size) {
        error_set(err, ERR_OBJ_PARSE, path, 0, "%s: truncated GLB: the header says %u bytes, the "
                  "file has %zu", path, length, size);
        return false;
    }
    if (length < 20) {
        error_set(err, ERR_OBJ_PARSE, path, 0, "%s: GLB without a JSON chunk (the header says %u "
                  "bytes)", path, length);
        return false;
    }
    size_t at = 12;
    for (int chunk = 0; at < length; chunk++) {
        if (length - at < 8) {
            error_set(err, ERR_OBJ_PARSE, path, 0, "%s: GLB chunk %d at byte %zu: truncated header",
                      path, chunk, at);
            return false;
        }
        uint32_t chunk_length = le32(b + at);
        if (chunk_length > length - at - 8) {
            error_set(err, ERR_OBJ_PARSE, path, 0, "%s: truncated GLB: chunk %d at byte %zu says %u "
                      "bytes, %zu remain", path, chunk, at, chunk_length, length - at - 8);
            return false;
        }
        if (chunk == 0 && le32(b + at + 4) != 0x4E4F534Au) {
            error_set(err, ERR_OBJ_PARSE, path, 0, "%s: GLB's first chunk is not JSON", path);
            return false;
        }
        at += 8 + (size_t)chunk_length;
    }
    return true;
}

/* In the error path only: the JSON path ("buffers[1].uri") whose uri names the file that failed. */
std::string json_path_of_file(const char *json, size_t size, const std::string &failed)
{
    std::string text(json, size), found;
    cJSON *root = cJSON_Parse(text.c_str());
    for (const char *section : {"buffers", "images"}) {
        const cJSON *array = cJSON_GetObjectItemCaseSensitive(root, section);
        int i = 0;
        for (const cJSON *e = array ? array->child : nullptr; e && found.empty(); e = e->next, i++) {
            const cJSON *uri = cJSON_GetObjectItemCaseSensitive(e, "uri");
            if (!cJSON_IsString(uri))
                continue;
            std::string u = uri->valuestring;
            if (!u.empty() && failed.size() >= u.size() &&
                failed.compare(failed.size() - u.size(), u.size(), u) == 0)
                found = std::string(section) + "[" + std::to_string(i) + "].uri";
        }
    }
    cJSON_Delete(root);
    return found;
}

std::string folder_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? std::string(path, (size_t)(slash - path)) : std::string(".");
}

bool parse(const char *path, tinygltf::Model *model, Error *err)
{
    char *data;
    size_t size;
    if (!input_file_read(path, "a glTF file", INPUT_LIMIT_OBJ, &data, &size, err))
        return false;
    const unsigned char *bytes = reinterpret_cast<const unsigned char *>(data);
    bool glb = size >= 4 && memcmp(bytes, "glTF", 4) == 0;
    if (size > 0xffffffffu) {
        free(data);
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: %zu bytes (tinygltf reads at most 4 GiB)", path, size);
        return false;
    }
    if (glb && !check_glb(path, bytes, size, err)) {
        free(data);
        return false;
    }
    if (size == 0 || strspn(data, " \t\r\n") == size) {
        free(data);
        error_set(err, ERR_OBJ_PARSE, path, 0, "%s: empty file (neither glTF JSON nor GLB)", path);
        return false;
    }
    FileLog log;
    if (!gltf_io::check_json(path, glb ? data + 20 : data, glb ? le32(bytes + 12) : size,
                             &log.uris_checked, err)) {
        free(data);
        return false;
    }
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({file_exists, expand_path, read_file, write_file, &log});
    loader.SetImageLoader(keep_image_bytes, nullptr);
    std::string terr, twarn, base = folder_of(path), draco; /* io/gltf_primitives.h */
    const char *in = data;
    size_t in_size = size;
    if (gltf_io::draco_prepare(bytes, size, glb, draco))
        in = draco.data(), in_size = draco.size();
    const unsigned char *in_bytes = reinterpret_cast<const unsigned char *>(in);
    bool ok = glb ? loader.LoadBinaryFromMemory(model, &terr, &twarn, in_bytes, (unsigned)in_size, base)
                  : loader.LoadASCIIFromString(model, &terr, &twarn, in, (unsigned)in_size, base);
    if (!ok) {
        if (!log.failed.empty()) {
            const char *json = glb ? data + 20 : data;
            size_t json_size = glb ? le32(bytes + 12) : size;
            std::string where = json_path_of_file(json, json_size, log.failed);
            error_set(err, log.code, path, 0, "%s: %s \"%s\": %s", path,
                      where.empty() ? "buffers" : where.c_str(), log.failed.c_str(),
                      log.reason.c_str());
        } else {
            size_t nl = terr.find('\n');
            error_set(err, ERR_OBJ_PARSE, path, 0, "%s: %s", path,
                      terr.empty() ? "not a glTF 2.0 file" : terr.substr(0, nl).c_str());
        }
    }
    free(data);
    return ok && gltf_io::read_image_views(*model, path, err);
}

bool check_extensions(const char *path, const tinygltf::Model &m, Error *err)
{
    for (size_t i = 0; i < m.extensionsRequired.size(); i++)
        if (!supported(m.extensionsRequired[i])) {
            error_set(err, ERR_OBJ_PARSE, path, 0, "%s: extensionsRequired[%zu]: \"%s\" is not "
                      "implemented by pt", path, i, m.extensionsRequired[i].c_str());
            return false;
        }
    std::string unknown;
    for (const std::string &name : m.extensionsUsed)
        if (!supported(name))
            unknown += (unknown.empty() ? "" : ", ") + name;
    if (!unknown.empty() && !g_quiet)
        warn("%s: extensionsUsed: pt ignores %s", path, unknown.c_str());
    return true;
}

/* What pt reads nothing of: one warning per kind of feature (as for unknown extensions), so that
 * a rest pose or a perspective view is not a surprise. */
void warn_dropped(const char *path, const tinygltf::Model &m)
{
    if (g_quiet)
        return;
    size_t morphed = 0, orthographic = 0;
    for (const tinygltf::Mesh &mesh : m.meshes) {
        bool targets = !mesh.weights.empty();
        for (const tinygltf::Primitive &prim : mesh.primitives)
            targets = targets || !prim.targets.empty();
        morphed += targets;
    }
    for (const tinygltf::Camera &camera : m.cameras)
        orthographic += camera.type == "orthographic";
    if (!m.skins.empty())
        warn("%s: skins: pt ignores %zu skin%s (meshes are drawn in their bind pose)", path,
             m.skins.size(), m.skins.size() == 1 ? "" : "s");
    if (morphed)
        warn("%s: morph targets: pt ignores those of %zu mesh%s (drawn without weights)", path,
             morphed, morphed == 1 ? "" : "es");
    if (!m.animations.empty())
        warn("%s: animations: pt ignores %zu animation%s (the scene is drawn at rest)", path,
             m.animations.size(), m.animations.size() == 1 ? "" : "s");
    if (orthographic)
        warn("%s: cameras: pt ignores %zu orthographic camera%s (it renders perspective views)",
             path, orthographic, orthographic == 1 ? "" : "s");
}

bool is_points_or_lines(int mode)
{
    return mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP;
}

/* Decodes every placed primitive but POINTS and LINES ones, which are skipped with one warning
 * (a file of nothing else is an error): the total is bounded so that a small file whose
 * primitives share one accessor cannot decode without bound. */
bool decode_placed(const char *path, const tinygltf::Model &model, GltfFile *out, Error *err)
{
    size_t total = 0;
    int skipped = 0, decoded = 0, first_skipped = -1;
    for (int p = 0; p < out->num_primitives; p++) {
        GltfPrimitive *prim = &out->primitives[p];
        if (!prim->placed)
            continue;
        if (is_points_or_lines(model.meshes[prim->mesh_index].primitives[prim->primitive_index].mode)) {
            prim->skipped = true;
            first_skipped = skipped++ ? first_skipped : p;
            continue;
        }
        decoded++;
        if (!gltf_io::decode_primitive(model, prim->mesh_index, prim->primitive_index, path,
                                       &prim->mesh, err))
            return false;
        total += prim->mesh.num_positions + prim->mesh.num_triangles;
        if (total > DECODED_LIMIT) {
            error_set(err, ERR_TOO_LARGE, path, 0, "%s: meshes[%d]: the primitives decode to "
                      "more than %zu vertices and triangles", path, prim->mesh_index, DECODED_LIMIT);
            return false;
        }
    }
    if (skipped) {
        const GltfPrimitive *first = &out->primitives[first_skipped];
        int mode = model.meshes[first->mesh_index].primitives[first->primitive_index].mode;
        const char *names[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
        if (!decoded) {
            error_set(err, ERR_OBJ_PARSE, path, 0, "%s: meshes[%d].primitives[%d].mode: %s, and "
                      "every other placed primitive is points or lines too: pt renders triangles",
                      path, first->mesh_index, first->primitive_index, names[mode]);
            return false;
        }
        if (!g_quiet)
            warn("%s: %d POINTS or LINES primitive%s skipped (the first: meshes[%d].primitives[%d], "
                 "%s): pt renders triangles", path, skipped, skipped == 1 ? "" : "s",
                 first->mesh_index, first->primitive_index, names[mode]);
    }
    return true;
}

} // namespace

/* gltf_scene_graph.cc: nodes, cameras and lights. */
bool gltf_walk_scene(const tinygltf::Model &m, const char *path, GltfFile *out, Error *err);

extern "C" void gltf_loader_set_quiet(bool quiet)
{
    g_quiet = quiet;
}

extern "C" bool gltf_load(const char *path, GltfFile *out, Error *err)
{
    memset(out, 0, sizeof *out);
    snprintf(out->path, sizeof out->path, "%s", path);
    tinygltf::Model *model = new (std::nothrow) tinygltf::Model;
    if (!model) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory", path);
        return false;
    }
    out->model = model;
    bool ok;
    try {
        /* Only the meshes that nodes place are decoded, each once. */
        ok = parse(path, model, err) && check_extensions(path, *model, err) &&
             gltf_walk_scene(*model, path, out, err) && decode_placed(path, *model, out, err);
        if (ok)
            warn_dropped(path, *model);
    } catch (const std::bad_alloc &) {
        ok = false;
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory", path);
    } catch (const std::exception &e) {
        ok = false;
        error_set(err, ERR_OBJ_PARSE, path, 0, "%s: %s", path, e.what());
    }
    if (!ok)
        gltf_free(out);
    return ok;
}

extern "C" void gltf_free(GltfFile *file)
{
    for (int p = 0; p < file->num_primitives; p++)
        mesh_free(&file->primitives[p].mesh);
    free(file->primitives);
    free(file->mesh_first);
    free(file->placements);
    free(file->lights);
    delete static_cast<tinygltf::Model *>(file->model);
    memset(file, 0, sizeof *file);
}
