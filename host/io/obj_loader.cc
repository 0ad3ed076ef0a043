// SPDX-License-Identifier: MIT
/* The C API of obj_loader.h over Debian's tinyobjloader (2.0.0rc10, float build). The file is read
 * once: obj_lines checks it line by line (tinyobjloader reads "nan" as 0 and keeps no line
 * numbers), then tinyobjloader parses the same bytes with its own triangulation off, and every
 * face is triangulated here by ear clipping. Nothing from tinyobjloader is trusted blindly: counts
 * and indices are checked again before they are used. The MTL files are read by mtl_reader.cc. */
#include "io/mtl_reader.h" /* tinyobjloader, error.h, mesh.h; the MTL side */

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <istream>
#include <new>
#include <streambuf>
#include <string>
#include <vector>

extern "C" {
#include "io/input_file.h"
#include "io/obj_loader.h"
#include "io/obj_lines.h"
#include "io/triangulate.h"
}

namespace {

using mtl_reader::MaterialExtras;
using mtl_reader::MaterialLibraryReader;
using mtl_reader::copy_material;
using mtl_reader::folder_of;
using mtl_reader::read_whole_file;
using mtl_reader::warn_lines;

/* Lets tinyobjloader read the bytes already in memory. */
struct MemoryBuffer : std::streambuf {
    explicit MemoryBuffer(std::string &text) { setg(&text[0], &text[0], &text[0] + text.size()); }
};

void *alloc_array(size_t count, size_t size)
{
    void *memory = calloc(count ? count : 1, size);
    if (!memory)
        throw std::bad_alloc();
    return memory;
}

/* Copies a float attribute, refusing values that are not finite (keyword names the record). */
bool copy_floats(const std::vector<float> &from, size_t width, const char *keyword,
                 const std::string &text, const char *path, float **to, Error *err)
{
    *to = static_cast<float *>(alloc_array(from.size(), sizeof(float)));
    for (size_t i = 0; i < from.size(); i++) {
        if (!std::isfinite(from[i])) {
            int line = obj_lines_find_record(text.data(), text.size(), keyword, i / width);
            error_set(err, ERR_OBJ_NONFINITE, path, line, "%s:%d: '%s' record is not finite", path,
                      line, keyword);
            return false;
        }
        (*to)[i] = from[i];
    }
    return true;
}

/* A corner index from tinyobjloader must lie in [lowest, count). */
bool index_ok(int index, int lowest, size_t count)
{
    return index >= lowest && (index < 0 || static_cast<size_t>(index) < count);
}

/* Triangulates every face into out->corners / material_ids; checks every index first. */
bool emit_triangles(const std::vector<tinyobj::shape_t> &shapes, const std::string &text,
                    const char *path, Mesh *out, Error *err)
{
    size_t max_triangles = 0;
    for (const tinyobj::shape_t &shape : shapes)
        for (unsigned char corners : shape.mesh.num_face_vertices)
            max_triangles += corners >= 3 ? corners - 2u : 0u;
    out->corners = static_cast<int32_t *>(alloc_array(9 * max_triangles, sizeof(int32_t)));
    out->material_ids = static_cast<int32_t *>(alloc_array(max_triangles, sizeof(int32_t)));
    std::vector<float> points;
    std::vector<uint32_t> triangles;
    for (const tinyobj::shape_t &shape : shapes) {
        const tinyobj::mesh_t &mesh = shape.mesh;
        size_t first = 0;
        for (size_t face = 0; face < mesh.num_face_vertices.size(); face++) {
            size_t n = mesh.num_face_vertices[face];
            if (first + n > mesh.indices.size()) {
                error_set(err, ERR_OBJ_PARSE, path, 0, "%s: tinyobjloader's faces are inconsistent",
                          path);
                return false;
            }
            const tinyobj::index_t *corner = &mesh.indices[first];
            first += n;
            size_t ordinal = out->num_faces++;
            points.resize(3 * n);
            for (size_t k = 0; k < n; k++) {
                if (!index_ok(corner[k].vertex_index, 0, out->num_positions) ||
                    !index_ok(corner[k].texcoord_index, -1, out->num_texcoords) ||
                    !index_ok(corner[k].normal_index, -1, out->num_normals)) {
                    int line = obj_lines_find_record(text.data(), text.size(), "f", ordinal);
                    error_set(err, ERR_OBJ_INDEX, path, line,
                              "%s:%d: face index out of range (corner %zu resolves to %d/%d/%d)",
                              path, line, k + 1, corner[k].vertex_index + 1,
                              corner[k].texcoord_index + 1, corner[k].normal_index + 1);
                    return false;
                }
                memcpy(&points[3 * k], &out->positions[3 * corner[k].vertex_index],
                       3 * sizeof(float));
            }
            if (n < 3)
                continue; /* tinyobjloader drops these; obj_lines has warned */
            triangles.resize(3 * (n - 2));
            size_t count = triangulate_polygon(points.data(), n, triangles.data());
            int material = face < mesh.material_ids.size() ? mesh.material_ids[face] : -1;
            if (material < -1 || material >= static_cast<int>(out->num_materials))
                material = -1;
            for (size_t t = 0; t < count; t++) {
                int32_t *emitted = out->corners + 9 * out->num_triangles;
                for (int c = 0; c < 3; c++) {
                    const tinyobj::index_t &index = corner[triangles[3 * t + c]];
                    emitted[3 * c + 0] = index.vertex_index;
                    emitted[3 * c + 1] = index.texcoord_index;
                    emitted[3 * c + 2] = index.normal_index;
                }
                out->material_ids[out->num_triangles++] = material;
            }
        }
    }
    return true;
}

/* The record counts tinyobjloader saw must be the ones obj_lines saw, or line numbers would lie. */
bool counts_agree(const tinyobj::attrib_t &attrib, const ObjRecordCounts &counts,
                  size_t tinyobj_faces, const char *path, Error *err)
{
    if (attrib.vertices.size() == 3 * counts.positions &&
        attrib.texcoords.size() == 2 * counts.texcoords &&
        attrib.normals.size() == 3 * counts.normals && tinyobj_faces == counts.faces)
        return true;
    error_set(
        err, ERR_OBJ_PARSE, path, 0,
        "%s: tinyobjloader read %zu v, %zu vt, %zu vn, %zu f; the file has %zu, %zu, %zu, %zu",
        path, attrib.vertices.size() / 3, attrib.texcoords.size() / 2, attrib.normals.size() / 3,
        tinyobj_faces, counts.positions, counts.texcoords, counts.normals, counts.faces);
    return false;
}

bool parse_error(const char *path, const std::string &message, Error *err)
{
    std::string first = message.substr(0, message.find('\n'));
    size_t at = first.rfind("line ");
    int line = at == std::string::npos ? 0 : atoi(first.c_str() + at + 5);
    error_set(err, ERR_OBJ_PARSE, path, line, "%s:%d: %s", path, line,
              first.empty() ? "tinyobjloader cannot parse it" : first.c_str());
    return false;
}

bool copy_error(const Error &from, Error *to)
{
    if (!error_is_set(to))
        *to = from;
    return false;
}

bool load(const char *path, Mesh *out, Error *err)
{
    std::string text;
    if (!read_whole_file(path, "an OBJ file", INPUT_LIMIT_OBJ, &text, err))
        return false;
    ObjRecordCounts counts;
    if (!obj_lines_check(text.data(), text.size(), path, &counts, err))
        return false;
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warnings, errors;
    MemoryBuffer buffer(text);
    std::istream stream(&buffer);
    MaterialLibraryReader library(folder_of(path));
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &stream, &library,
                          false, false)) {
        if (error_is_set(&library.error))
            return copy_error(library.error, err);
        return parse_error(path, errors, err);
    }
    if (error_is_set(&library.error))
        return copy_error(library.error, err);
    warn_lines(path, warnings + errors);
    size_t faces = 0;
    for (const tinyobj::shape_t &shape : shapes)
        faces += shape.mesh.num_face_vertices.size();
    if (!counts_agree(attrib, counts, faces, path, err))
        return false;

    out->num_positions = counts.positions;
    out->num_texcoords = counts.texcoords;
    out->num_normals = counts.normals;
    if (!copy_floats(attrib.vertices, 3, "v", text, path, &out->positions, err) ||
        !copy_floats(attrib.texcoords, 2, "vt", text, path, &out->texcoords, err) ||
        !copy_floats(attrib.normals, 3, "vn", text, path, &out->normals, err))
        return false;
    out->num_materials = materials.size();
    out->materials = static_cast<ObjMaterial *>(alloc_array(materials.size(), sizeof(ObjMaterial)));
    for (size_t i = 0; i < materials.size(); i++)
        if (!copy_material(materials[i],
                           i < library.extras.size() ? library.extras[i] : MaterialExtras(path),
                           &out->materials[i], err))
            return false;
    return emit_triangles(shapes, text, path, out, err);
}

} // namespace

extern "C" bool obj_load(const char *path, Mesh *out, Error *err)
{
    memset(out, 0, sizeof *out);
    bool loaded = false;
    try {
        loaded = load(path, out, err);
    } catch (const std::bad_alloc &) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory while loading", path);
    } catch (const std::exception &e) {
        /* No exception may cross the C API: whatever tinyobjloader or the library throws becomes
         * an Error naming the file. */
        error_set(err, ERR_OBJ_PARSE, path, 0, "%s: cannot load: %s", path, e.what());
    } catch (...) {
        error_set(err, ERR_OBJ_PARSE, path, 0, "%s: cannot load (unknown exception)", path);
    }
    if (!loaded)
        mesh_free(out);
    return loaded;
}

extern "C" void obj_loader_set_quiet(bool quiet) { mtl_reader::quiet_unused = quiet; }
