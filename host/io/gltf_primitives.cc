// SPDX-License-Identifier: MIT
/* gltf_primitives.cc: see gltf_primitives.h. tinygltf parses the JSON and loads the buffers but
 * checks no range and leaves sparse accessors to the reader: every offset, count and index is
 * checked here before it is used, in size_t arithmetic that cannot wrap. */
#include "io/gltf_primitives.h"

#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace gltf_io {
namespace {

/* An accessor may not describe more elements than this (pt indexes vertices with 32 bits; an
 * accessor without a buffer view costs memory without costing file bytes: its zeros are a base
 * for sparse values, which no real file spreads over more than 2^20 elements; 2^24 of them took
 * seconds per file under the fuzzer, a libFuzzer timeout). */
const size_t MAX_ELEMENTS = (size_t)1 << 28;
const size_t ZEROS_LIMIT = (size_t)1 << 20;

struct Reader {
    const tinygltf::Model &model;
    const char *path;
    Error *err;
    char where[160]; /* the JSON path of the reference being read */

    bool fail(ErrorCode code, const char *fmt, ...) __attribute__((format(printf, 3, 4)))
    {
        char detail[512];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(detail, sizeof detail, fmt, ap);
        va_end(ap);
        error_set(err, code, path, 0, "%s: %s: %s", path, where, detail);
        return false;
    }
};

size_t component_size(int type)
{
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

const char *type_name(int comps)
{
    switch (comps) {
    case 1: return "SCALAR";
    case 2: return "VEC2";
    case 3: return "VEC3";
    case 4: return "VEC4";
    default: return "a matrix";
    }
}

template <typename T> T load(const unsigned char *p)
{
    T v;
    memcpy(&v, p, sizeof v);
    return v;
}

/* One component as the specification decodes it: normalized signed types clamp at -1. T is
 * float for attributes, double for indices (exact up to 2^32 - 1, which a float is not). */
template <typename T> T component(const unsigned char *p, int type, bool normalized)
{
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        float v = load<int8_t>(p);
        return normalized ? fmaxf(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? load<uint8_t>(p) / 255.0f : load<uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        float v = load<int16_t>(p);
        return normalized ? fmaxf(v / 32767.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return normalized ? load<uint16_t>(p) / 65535.0f : load<uint16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return normalized ? (T)(load<uint32_t>(p) / 4294967295.0) : (T)load<uint32_t>(p);
    default: return load<float>(p);
    }
}

uint32_t index_value(const unsigned char *p, int type)
{
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load<uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<uint16_t>(p);
    default: return load<uint32_t>(p);
    }
}

/* The bytes of bufferViews[view] from byte `offset` on, for `count` elements of `size` bytes
 * `stride` apart; checks the view against its buffer and the elements against the view. */
bool view_range(Reader &r, int view, size_t offset, size_t count, size_t size, size_t stride,
                const char *what, const unsigned char **out)
{
    const tinygltf::Model &m = r.model;
    if (view < 0 || (size_t)view >= m.bufferViews.size())
        return r.fail(ERR_OBJ_PARSE, "%s: bufferViews[%d] does not exist (%zu buffer views)", what,
                      view, m.bufferViews.size());
    const tinygltf::BufferView &bv = m.bufferViews[view];
    if (bv.buffer < 0 || (size_t)bv.buffer >= m.buffers.size())
        return r.fail(ERR_OBJ_PARSE, "bufferViews[%d].buffer: buffers[%d] does not exist", view,
                      bv.buffer);
    size_t buffer_size = m.buffers[bv.buffer].data.size();
    if (bv.byteOffset > buffer_size || bv.byteLength > buffer_size - bv.byteOffset)
        return r.fail(ERR_OBJ_PARSE,
                      "bufferViews[%d]: bytes [%zu, +%zu) lie outside buffers[%d] (%zu bytes)",
                      view, bv.byteOffset, bv.byteLength, bv.buffer, buffer_size);
    if (count > 0 && (offset > bv.byteLength || size > bv.byteLength - offset ||
                      (count - 1) > (bv.byteLength - offset - size) / stride))
        return r.fail(ERR_OBJ_PARSE,
                      "%s: %zu elements of %zu bytes (stride %zu) from byte %zu lie outside "
                      "bufferViews[%d] (%zu bytes)",
                      what, count, size, stride, offset, view, bv.byteLength);
    *out = m.buffers[bv.buffer].data.data() + bv.byteOffset + offset;
    return true;
}

/* glTF's count is at least 1 (an empty accessor is a writer's bug: its data pointer is null). */
bool count_in_range(Reader &r, int index, const tinygltf::Accessor &a)
{
    if (a.count < 1)
        return r.fail(ERR_OBJ_PARSE, "accessors[%d].count is 0 (the specification's minimum is 1)",
                      index);
    if (a.count > MAX_ELEMENTS)
        return r.fail(ERR_TOO_LARGE, "accessors[%d].count %zu is above pt's limit %zu", index,
                      a.count, MAX_ELEMENTS);
    return true;
}

/* Accessor `index` as floats (or doubles), `comps` per element (its type must have that many),
 * sparse substitution applied. */
template <typename T> bool read_values(Reader &r, int index, int comps, std::vector<T> &out)
{
    const tinygltf::Model &m = r.model;
    if (index < 0 || (size_t)index >= m.accessors.size())
        return r.fail(ERR_OBJ_PARSE, "accessors[%d] does not exist (%zu accessors)", index,
                      m.accessors.size());
    const tinygltf::Accessor &a = m.accessors[index];
    size_t csize = component_size(a.componentType);
    if (!csize)
        return r.fail(ERR_OBJ_PARSE, "accessors[%d].componentType %d is not a glTF component type",
                      index, a.componentType);
    if (tinygltf::GetNumComponentsInType((uint32_t)a.type) != comps)
        return r.fail(ERR_OBJ_PARSE, "accessors[%d] is not %s", index, type_name(comps));
    if (!count_in_range(r, index, a))
        return false;
    if (a.bufferView < 0 && a.count > ZEROS_LIMIT) /* zeros cost memory but no file bytes */
        return r.fail(ERR_TOO_LARGE, "accessors[%d].count %zu without a buffer view is above pt's "
                      "limit %zu", index, a.count, ZEROS_LIMIT);
    size_t size = csize * comps, stride = size;
    char what[48];
    snprintf(what, sizeof what, "accessors[%d]", index);
    const unsigned char *src = nullptr;
    if (a.bufferView >= 0) { /* checked before the allocation: a count the view cannot hold */
        if (a.bufferView < (int)m.bufferViews.size() && m.bufferViews[a.bufferView].byteStride)
            stride = m.bufferViews[a.bufferView].byteStride;
        if (stride < size)
            return r.fail(ERR_OBJ_PARSE, "bufferViews[%d].byteStride %zu is below accessors[%d]'s "
                          "element size %zu", a.bufferView, stride, index, size);
        if (!view_range(r, a.bufferView, a.byteOffset, a.count, size, stride, what, &src))
            return false;
    }
    out.assign(a.count * comps, (T)0); /* no buffer view: zeros (then sparse values) */
    if (src) {
        T *dst = out.data();
        if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && stride == size && sizeof(T) == 4) {
            memcpy(dst, src, a.count * size);
        } else {
            for (size_t e = 0; e < a.count; e++, src += stride)
                for (int c = 0; c < comps; c++)
                    *dst++ = component<T>(src + c * csize, a.componentType, a.normalized);
        }
    }
    if (!a.sparse.isSparse)
        return true;
    size_t n = a.sparse.count > 0 ? (size_t)a.sparse.count : 0;
    if (n > a.count)
        return r.fail(ERR_OBJ_PARSE, "accessors[%d].sparse.count %d exceeds its count %zu", index,
                      a.sparse.count, a.count);
    int itype = a.sparse.indices.componentType;
    size_t isize = itype == TINYGLTF_COMPONENT_TYPE_BYTE ? 0 : component_size(itype);
    if (!isize || itype == TINYGLTF_COMPONENT_TYPE_FLOAT || itype == TINYGLTF_COMPONENT_TYPE_SHORT)
        return r.fail(ERR_OBJ_PARSE, "accessors[%d].sparse.indices.componentType %d is not an "
                      "unsigned integer type", index, itype);
    const unsigned char *ind, *val;
    snprintf(what, sizeof what, "accessors[%d].sparse.indices", index);
    if (!view_range(r, a.sparse.indices.bufferView, (size_t)(unsigned)a.sparse.indices.byteOffset,
                    n, isize, isize, what, &ind))
        return false;
    snprintf(what, sizeof what, "accessors[%d].sparse.values", index);
    if (!view_range(r, a.sparse.values.bufferView, (size_t)(unsigned)a.sparse.values.byteOffset, n,
                    size, size, what, &val))
        return false;
    for (size_t s = 0; s < n; s++, ind += isize, val += size) {
        uint32_t e = index_value(ind, itype);
        if (e >= a.count)
            return r.fail(ERR_OBJ_INDEX, "accessors[%d].sparse.indices[%zu] = %u is beyond the "
                          "accessor's %zu elements", index, s, e, a.count);
        for (int c = 0; c < comps; c++)
            out[(size_t)e * comps + c] = component<T>(val + c * csize, a.componentType, a.normalized);
    }
    return true;
}

/* The primitive's index accessor as 32-bit indices. */
bool read_indices(Reader &r, int index, std::vector<uint32_t> &out)
{
    const tinygltf::Model &m = r.model;
    if (index < 0 || (size_t)index >= m.accessors.size())
        return r.fail(ERR_OBJ_PARSE, "accessors[%d] does not exist (%zu accessors)", index,
                      m.accessors.size());
    const tinygltf::Accessor &a = m.accessors[index];
    int t = a.componentType;
    if (t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        return r.fail(ERR_OBJ_PARSE, "accessors[%d].componentType %d: indices must be unsigned "
                      "byte, short or int", index, t);
    if (a.type != TINYGLTF_TYPE_SCALAR || a.normalized)
        return r.fail(ERR_OBJ_PARSE, "accessors[%d]: indices must be SCALAR, not normalized", index);
    if (a.sparse.isSparse || a.bufferView < 0) { /* rare: the general path, exact in doubles */
        std::vector<double> values;
        if (!read_values(r, index, 1, values))
            return false;
        out.resize(values.size());
        for (size_t i = 0; i < values.size(); i++)
            out[i] = (uint32_t)values[i];
        return true;
    }
    if (!count_in_range(r, index, a))
        return false;
    size_t size = component_size(t), stride = size;
    if (a.bufferView < (int)m.bufferViews.size() && m.bufferViews[a.bufferView].byteStride)
        stride = m.bufferViews[a.bufferView].byteStride; /* not allowed for indices; tolerated */
    const unsigned char *src;
    char what[48];
    snprintf(what, sizeof what, "accessors[%d]", index);
    if (!view_range(r, a.bufferView, a.byteOffset, a.count, size, stride, what, &src))
        return false;
    out.resize(a.count);
    if (t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT && stride == 4)
        memcpy(out.data(), src, a.count * 4);
    else
        for (size_t i = 0; i < a.count; i++, src += stride)
            out[i] = index_value(src, t);
    return true;
}

void *alloc_array(size_t count, size_t size)
{
    return calloc(count ? count : 1, size);
}

/* The triangles of the primitive's mode as vertex index triples, degenerate ones dropped. */
bool assemble(Reader &r, int mode, const std::vector<uint32_t> &idx, size_t num_vertices,
              std::vector<uint32_t> &tris)
{
    size_t n = idx.size();
    for (size_t i = 0; i < n; i++)
        if (idx[i] >= num_vertices)
            return r.fail(ERR_OBJ_INDEX, "index %u at position %zu is beyond the %zu vertices of "
                          "attributes.POSITION", idx[i], i, num_vertices);
    tris.reserve(mode == TINYGLTF_MODE_TRIANGLES ? n : 3 * n);
    auto emit = [&tris](uint32_t a, uint32_t b, uint32_t c) {
        if (a != b && b != c && a != c) {
            tris.push_back(a);
            tris.push_back(b);
            tris.push_back(c);
        }
    };
    if (mode == TINYGLTF_MODE_TRIANGLES)
        for (size_t i = 0; i + 2 < n; i += 3)
            emit(idx[i], idx[i + 1], idx[i + 2]);
    else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) /* every other triangle's winding swapped */
        for (size_t i = 0; i + 2 < n; i++)
            emit(idx[i], idx[i + 1 + i % 2], idx[i + 2 - i % 2]);
    else /* TRIANGLE_FAN */
        for (size_t i = 0; i + 2 < n; i++)
            emit(idx[i + 1], idx[i + 2], idx[0]);
    return true;
}

const char *mode_name(int mode)
{
    static const char *const names[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
    return mode >= 0 && mode < 4 ? names[mode] : "not a glTF mode";
}

/* Reads attribute `name` (comps per element) when present; its count must equal POSITION's. */
bool read_attribute(Reader &r, const tinygltf::Primitive &prim, const char *prefix,
                    const char *name, int comps, size_t expected, std::vector<float> &out,
                    bool *present)
{
    auto it = prim.attributes.find(name);
    *present = it != prim.attributes.end();
    if (!*present)
        return true;
    snprintf(r.where, sizeof r.where, "%s.attributes.%s", prefix, name);
    if (!read_values(r, it->second, comps, out))
        return false;
    if (expected != (size_t)-1 && out.size() != expected * comps)
        return r.fail(ERR_OBJ_PARSE, "%zu elements where POSITION has %zu", out.size() / comps,
                      expected);
    return true;
}

} // namespace

bool decode_primitive(const tinygltf::Model &model, int mesh, int primitive, const char *path,
                      Mesh *out, Error *err)
{
    Reader r{model, path, err, {0}};
    char prefix[64];
    snprintf(prefix, sizeof prefix, "meshes[%d].primitives[%d]", mesh, primitive);
    const tinygltf::Primitive &prim = model.meshes[mesh].primitives[primitive];
    int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        snprintf(r.where, sizeof r.where, "%s.mode", prefix);
        return r.fail(ERR_OBJ_PARSE, "%d (%s) is not supported: pt renders triangles, strips and "
                      "fans", mode, mode_name(mode));
    }
    if (prim.extensions.count("KHR_draco_mesh_compression")) /* io/gltf_draco.h */
        return decode_draco_primitive(model, mesh, primitive, path, out, err);
    std::vector<float> pos, nrm, uv;
    bool has_pos, has_nrm, has_uv;
    if (!read_attribute(r, prim, prefix, "POSITION", 3, (size_t)-1, pos, &has_pos))
        return false;
    if (!has_pos) {
        snprintf(r.where, sizeof r.where, "%s.attributes.POSITION", prefix);
        return r.fail(ERR_OBJ_PARSE, "missing (a primitive needs positions)");
    }
    size_t nv = pos.size() / 3;
    for (size_t i = 0; i < pos.size(); i++)
        if (!std::isfinite(pos[i]))
            return r.fail(ERR_OBJ_NONFINITE, "vertex %zu is not finite", i / 3);
    if (!read_attribute(r, prim, prefix, "NORMAL", 3, nv, nrm, &has_nrm) ||
        !read_attribute(r, prim, prefix, "TEXCOORD_0", 2, nv, uv, &has_uv))
        return false;
    std::vector<uint32_t> idx;
    if (prim.indices >= 0) {
        snprintf(r.where, sizeof r.where, "%s.indices", prefix);
        if (!read_indices(r, prim.indices, idx))
            return false;
    } else {
        idx.resize(nv);
        for (size_t i = 0; i < nv; i++)
            idx[i] = (uint32_t)i;
    }
    snprintf(r.where, sizeof r.where, "%s%s", prefix, prim.indices >= 0 ? ".indices" : "");
    return mesh_from_arrays(model, path, r.where, mode, pos, has_nrm ? &nrm : nullptr, has_uv ? &uv : nullptr,
                            idx, out, err);
}

bool mesh_from_arrays(const tinygltf::Model &model, const char *path, const char *where, int mode,
                      const std::vector<float> &pos,
                      const std::vector<float> *normals, const std::vector<float> *uvs,
                      const std::vector<uint32_t> &idx, Mesh *out, Error *err)
{
    static const std::vector<float> none;
    Reader r{model, path, err, {0}};
    snprintf(r.where, sizeof r.where, "%s", where);
    bool has_nrm = normals != nullptr, has_uv = uvs != nullptr;
    const std::vector<float> &nrm = has_nrm ? *normals : none, &uv = has_uv ? *uvs : none;
    size_t nv = pos.size() / 3;
    std::vector<uint32_t> tris;
    if (!assemble(r, mode, idx, nv, tris))
        return false;
    size_t nt = tris.size() / 3;
    out->positions = (float *)alloc_array(pos.size(), sizeof(float));
    out->normals = (float *)alloc_array(nrm.size(), sizeof(float));
    out->texcoords = (float *)alloc_array(uv.size(), sizeof(float));
    out->corners = (int32_t *)alloc_array(9 * nt, sizeof(int32_t));
    out->material_ids = (int32_t *)alloc_array(nt, sizeof(int32_t));
    if (!out->positions || !out->normals || !out->texcoords || !out->corners || !out->material_ids) {
        mesh_free(out);
        memset(out, 0, sizeof *out);
        return r.fail(ERR_TOO_LARGE, "out of memory for %zu triangles", nt);
    }
    memcpy(out->positions, pos.data(), pos.size() * sizeof(float));
    out->num_positions = nv;
    if (has_nrm) {
        memcpy(out->normals, nrm.data(), nrm.size() * sizeof(float));
        out->num_normals = nv;
    }
    if (has_uv) { /* glTF's v = 0 is the image's top row, pt's (OBJ's) the bottom row */
        for (size_t i = 0; i < nv; i++) {
            out->texcoords[2 * i] = uv[2 * i];
            out->texcoords[2 * i + 1] = 1.0f - uv[2 * i + 1];
        }
        out->num_texcoords = nv;
    }
    for (size_t t = 0; t < nt; t++) {
        int32_t *c = &out->corners[9 * t];
        for (int k = 0; k < 3; k++) {
            int32_t v = (int32_t)tris[3 * t + k];
            c[3 * k] = v;
            c[3 * k + 1] = has_uv ? v : -1;
            c[3 * k + 2] = has_nrm ? v : -1;
        }
        out->material_ids[t] = -1;
    }
    out->num_triangles = out->num_faces = nt;
    return true;
}

bool read_image_views(tinygltf::Model &model, const char *path, Error *err)
{
    Reader r{model, path, err, {0}};
    for (size_t i = 0; i < model.images.size(); i++) {
        tinygltf::Image &image = model.images[i];
        if (image.bufferView < 0 || !image.uri.empty())
            continue;
        snprintf(r.where, sizeof r.where, "images[%zu].bufferView", i);
        const unsigned char *bytes;
        size_t length = (size_t)image.bufferView < model.bufferViews.size()
                            ? model.bufferViews[image.bufferView].byteLength : 0;
        if (!view_range(r, image.bufferView, 0, 1, length, length ? length : 1, "the image", &bytes))
            return false;
        image.image.assign(bytes, bytes + length);
    }
    return true;
}

} // namespace gltf_io
