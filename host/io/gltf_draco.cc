// SPDX-License-Identifier: MIT
/* gltf_draco.cc: glTF primitives compressed with KHR_draco_mesh_compression, decoded by
 * Debian's libdraco (io/gltf_primitives.h decode_draco_primitive). The extension names a buffer
 * view holding a Draco mesh and maps glTF attribute names to Draco's unique attribute ids; the
 * decoder dequantizes positions, normals (octahedral) and uvs back to floats, so the mesh is its
 * uncompressed twin within the quantisation the encoder chose. The glTF accessors of a Draco
 * primitive describe the decoded data and have no buffer view: they are not read. */
#include "io/gltf_primitives.h"

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

#include <cJSON.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace gltf_io {
namespace {

const size_t DRACO_POINTS_LIMIT = (size_t)1 << 28;

bool fail(const char *path, const char *where, Error *err, ErrorCode code, const std::string &what)
{
    error_set(err, code, path, 0, "%s: %s: %s", path, where, what.c_str());
    return false;
}

/* The decoded attribute named `name` in the extension's attribute map, per point, `comps`
 * floats each; false with *present false when the map does not name it. */
bool read_draco_attribute(const draco::Mesh &dm, const tinygltf::Value &attributes,
                          const char *name, int comps, std::vector<float> &out, bool *present,
                          std::string &why)
{
    *present = attributes.Has(name);
    if (!*present)
        return true;
    const tinygltf::Value &id = attributes.Get(name);
    if (!id.IsInt()) {
        why = std::string("attributes.") + name + " is not an integer";
        return false;
    }
    const draco::PointAttribute *att = dm.GetAttributeByUniqueId((uint32_t)id.Get<int>());
    if (!att) {
        why = std::string("attributes.") + name + ": no Draco attribute with id " +
              std::to_string(id.Get<int>());
        return false;
    }
    if (att->num_components() < comps) {
        why = std::string("attributes.") + name + ": " + std::to_string(att->num_components()) +
              " components, " + std::to_string(comps) + " needed";
        return false;
    }
    size_t n = dm.num_points();
    out.resize(n * (size_t)comps);
    for (size_t i = 0; i < n; i++) {
        draco::AttributeValueIndex v = att->mapped_index(draco::PointIndex((uint32_t)i));
        if (v.value() >= att->size() ||
            !att->ConvertValue<float>(v, (int8_t)comps, &out[i * (size_t)comps])) {
            why = std::string("attributes.") + name + ": point " + std::to_string(i) +
                  " has no value";
            return false;
        }
        for (int c = 0; c < comps; c++)
            if (!std::isfinite(out[i * (size_t)comps + (size_t)c])) {
                why = std::string("attributes.") + name + ": point " + std::to_string(i) +
                      " is not finite";
                return false;
            }
    }
    return true;
}

uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

void put_le32(std::string &s, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        s.push_back((char)((v >> (8 * i)) & 0xff));
}

/* Removes "indices" from the primitives that carry KHR_draco_mesh_compression; true when it
 * removed any. */
bool strip_draco_indices(cJSON *root)
{
    bool changed = false;
    cJSON *meshes = cJSON_GetObjectItemCaseSensitive(root, "meshes"), *mesh;
    cJSON_ArrayForEach(mesh, meshes)
    {
        cJSON *prims = cJSON_GetObjectItemCaseSensitive(mesh, "primitives"), *prim;
        cJSON_ArrayForEach(prim, prims)
        {
            cJSON *ext = cJSON_GetObjectItemCaseSensitive(prim, "extensions");
            if (cJSON_GetObjectItemCaseSensitive(ext, "KHR_draco_mesh_compression") &&
                cJSON_GetObjectItemCaseSensitive(prim, "indices")) {
                cJSON_DeleteItemFromObjectCaseSensitive(prim, "indices");
                changed = true;
            }
        }
    }
    return changed;
}

} // namespace

bool draco_prepare(const unsigned char *data, size_t size, bool glb, std::string &patched)
{
    const char *json = (const char *)data;
    size_t json_size = size;
    if (glb) { /* check_glb has checked the header and the JSON chunk's bounds */
        json_size = le32(data + 12);
        json = (const char *)data + 20;
    }
    /* Cheap test first: most files never name the extension. */
    static const char name[] = "KHR_draco_mesh_compression";
    bool named = false;
    for (size_t i = 0; !named && i + sizeof name - 1 <= json_size; i++)
        named = memcmp(json + i, name, sizeof name - 1) == 0;
    if (!named)
        return false;
    cJSON *root = cJSON_ParseWithLength(json, json_size);
    if (!root)
        return false; /* tinygltf reports the syntax error */
    char *printed = strip_draco_indices(root) ? cJSON_PrintUnformatted(root) : nullptr;
    cJSON_Delete(root);
    if (!printed)
        return false;
    std::string text(printed);
    cJSON_free(printed);
    if (!glb) {
        patched = text;
        return true;
    }
    while (text.size() % 4)
        text.push_back(' ');
    size_t rest = 20 + json_size; /* the chunks after JSON (BIN), copied as they are */
    patched.assign((const char *)data, 8);
    put_le32(patched, (uint32_t)(12 + 8 + text.size() + (size - rest)));
    put_le32(patched, (uint32_t)text.size());
    put_le32(patched, 0x4E4F534Au); /* "JSON" */
    patched += text;
    patched.append((const char *)data + rest, size - rest);
    return true;
}

bool decode_draco_primitive(const tinygltf::Model &model, int mesh, int primitive,
                            const char *path, Mesh *out, Error *err)
{
    char where[160];
    snprintf(where, sizeof where, "meshes[%d].primitives[%d].extensions.KHR_draco_mesh_compression",
             mesh, primitive);
    const tinygltf::Primitive &prim = model.meshes[mesh].primitives[primitive];
    int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP)
        return fail(path, where, err, ERR_OBJ_PARSE,
                    "mode " + std::to_string(mode) + ": Draco primitives are triangles or strips");
    const tinygltf::Value &ext = prim.extensions.at("KHR_draco_mesh_compression");
    if (!ext.IsObject() || !ext.Has("bufferView") || !ext.Get("bufferView").IsInt() ||
        !ext.Has("attributes") || !ext.Get("attributes").IsObject())
        return fail(path, where, err, ERR_OBJ_PARSE,
                    "needs \"bufferView\" (an integer) and \"attributes\" (an object)");
    int view = ext.Get("bufferView").Get<int>();
    if (view < 0 || (size_t)view >= model.bufferViews.size())
        return fail(path, where, err, ERR_OBJ_PARSE,
                    "bufferView " + std::to_string(view) + " does not exist");
    const tinygltf::BufferView &bv = model.bufferViews[view];
    if (bv.buffer < 0 || (size_t)bv.buffer >= model.buffers.size() ||
        bv.byteOffset > model.buffers[bv.buffer].data.size() ||
        bv.byteLength > model.buffers[bv.buffer].data.size() - bv.byteOffset)
        return fail(path, where, err, ERR_OBJ_PARSE,
                    "bufferViews[" + std::to_string(view) + "] lies outside its buffer");
    draco::DecoderBuffer buffer;
    buffer.Init((const char *)model.buffers[bv.buffer].data.data() + bv.byteOffset, bv.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
        return fail(path, where, err, ERR_OBJ_PARSE,
                    std::string("Draco cannot decode it: ") + decoded.status().error_msg());
    std::unique_ptr<draco::Mesh> dm = std::move(decoded).value();
    if (!dm || dm->num_points() > DRACO_POINTS_LIMIT || dm->num_faces() > DRACO_POINTS_LIMIT)
        return fail(path, where, err, ERR_TOO_LARGE, "more points or faces than pt's limit");
    const tinygltf::Value &attributes = ext.Get("attributes");
    std::vector<float> pos, nrm, uv;
    bool has_pos, has_nrm, has_uv;
    std::string why;
    if (!read_draco_attribute(*dm, attributes, "POSITION", 3, pos, &has_pos, why) ||
        !read_draco_attribute(*dm, attributes, "NORMAL", 3, nrm, &has_nrm, why) ||
        !read_draco_attribute(*dm, attributes, "TEXCOORD_0", 2, uv, &has_uv, why))
        return fail(path, where, err, ERR_OBJ_PARSE, why);
    if (!has_pos)
        return fail(path, where, err, ERR_OBJ_PARSE, "attributes.POSITION missing");
    std::vector<uint32_t> idx((size_t)dm->num_faces() * 3);
    for (uint32_t f = 0; f < dm->num_faces(); f++) {
        const draco::Mesh::Face &face = dm->face(draco::FaceIndex(f));
        for (int k = 0; k < 3; k++)
            idx[3 * (size_t)f + (size_t)k] = face[k].value();
    }
    /* Draco stores faces, whatever the primitive's mode was before compression. */
    return mesh_from_arrays(model, path, where, TINYGLTF_MODE_TRIANGLES, pos,
                            has_nrm ? &nrm : nullptr, has_uv ? &uv : nullptr, idx, out, err);
}

} // namespace gltf_io
