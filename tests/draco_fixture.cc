// SPDX-License-Identifier: MIT
/* draco_fixture.cc: the plain and Draco-compressed glTF twins (tests/draco_fixture.h). */
#include "draco_fixture.h"

#include <draco/compression/encode.h>
#include <draco/core/encoder_buffer.h>
#include <draco/mesh/mesh.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

struct Sphere {
    std::vector<float> pos, nrm, uv;
    std::vector<uint32_t> idx;
};

Sphere make_sphere(int around)
{
    Sphere s;
    int rings = around / 2;
    for (int r = 0; r <= rings; r++)
        for (int a = 0; a <= around; a++) {
            double theta = M_PI * r / rings, phi = 2 * M_PI * a / around;
            double n[3] = {sin(theta) * cos(phi), cos(theta), -sin(theta) * sin(phi)};
            for (int c = 0; c < 3; c++) {
                s.pos.push_back((float)n[c]);
                s.nrm.push_back((float)n[c]);
            }
            s.uv.push_back((float)a / around);
            s.uv.push_back((float)r / rings);
        }
    for (int r = 0; r < rings; r++)
        for (int a = 0; a < around; a++) {
            uint32_t i0 = (uint32_t)(r * (around + 1) + a), i1 = i0 + 1,
                     i2 = i0 + (uint32_t)around + 1, i3 = i2 + 1;
            uint32_t t[6] = {i0, i2, i1, i1, i2, i3};
            s.idx.insert(s.idx.end(), t, t + 6);
        }
    return s;
}

bool write_file(const std::string &path, const void *data, size_t size)
{
    FILE *f = fopen(path.c_str(), "wb");
    if (!f)
        return false;
    bool ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok;
}

std::string accessor(int view, size_t count, int type, const char *kind)
{
    char s[160];
    if (view >= 0)
        snprintf(s, sizeof s, "{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"%s\"",
                 view, type, count, kind);
    else
        snprintf(s, sizeof s, "{\"componentType\":%d,\"count\":%zu,\"type\":\"%s\"", type, count, kind);
    return s;
}

bool write_plain(const std::string &dir, const Sphere &s)
{
    std::vector<unsigned char> bin;
    auto append = [&bin](const void *p, size_t n) {
        bin.insert(bin.end(), (const unsigned char *)p, (const unsigned char *)p + n);
    };
    size_t o_pos = 0, n_pos = s.pos.size() * 4;
    append(s.pos.data(), n_pos);
    size_t o_nrm = bin.size(), n_nrm = s.nrm.size() * 4;
    append(s.nrm.data(), n_nrm);
    size_t o_uv = bin.size(), n_uv = s.uv.size() * 4;
    append(s.uv.data(), n_uv);
    size_t o_idx = bin.size(), n_idx = s.idx.size() * 4;
    append(s.idx.data(), n_idx);
    size_t nv = s.pos.size() / 3;
    char views[512];
    snprintf(views, sizeof views,
             "[{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,"
             "\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},{\"buffer\":0,"
             "\"byteOffset\":%zu,\"byteLength\":%zu}]",
             o_pos, n_pos, o_nrm, n_nrm, o_uv, n_uv, o_idx, n_idx);
    std::string json =
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},"
        "\"indices\":3}]}],\"accessors\":[" +
        accessor(0, nv, 5126, "VEC3") + ",\"min\":[-1,-1,-1],\"max\":[1,1,1]}," +
        accessor(1, nv, 5126, "VEC3") + "}," + accessor(2, nv, 5126, "VEC2") + "}," +
        accessor(3, s.idx.size(), 5125, "SCALAR") + "}],\"bufferViews\":" + views +
        ",\"buffers\":[{\"uri\":\"plain.bin\",\"byteLength\":" + std::to_string(bin.size()) + "}]}";
    return write_file(dir + "/plain.bin", bin.data(), bin.size()) &&
           write_file(dir + "/plain.gltf", json.data(), json.size());
}

bool write_draco(const std::string &dir, const Sphere &s, int position_bits)
{
    draco::Mesh mesh;
    size_t nv = s.pos.size() / 3;
    mesh.set_num_points((uint32_t)nv);
    auto add = [&](draco::GeometryAttribute::Type type, int comps, const std::vector<float> &v) {
        draco::GeometryAttribute ga;
        ga.Init(type, nullptr, (int8_t)comps, draco::DT_FLOAT32, false, sizeof(float) * comps, 0);
        int id = mesh.AddAttribute(ga, true, (uint32_t)nv);
        draco::PointAttribute *att = mesh.attribute(id);
        for (size_t i = 0; i < nv; i++)
            att->SetAttributeValue(draco::AttributeValueIndex((uint32_t)i), &v[i * (size_t)comps]);
        return id;
    };
    int p = add(draco::GeometryAttribute::POSITION, 3, s.pos);
    int n = add(draco::GeometryAttribute::NORMAL, 3, s.nrm);
    int t = add(draco::GeometryAttribute::TEX_COORD, 2, s.uv);
    for (size_t f = 0; f < s.idx.size() / 3; f++) {
        draco::Mesh::Face face;
        for (int k = 0; k < 3; k++)
            face[k] = draco::PointIndex(s.idx[3 * f + (size_t)k]);
        mesh.AddFace(face);
    }
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, position_bits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 12);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 14);
    draco::EncoderBuffer buffer;
    if (!encoder.EncodeMeshToBuffer(mesh, &buffer).ok())
        return false;
    std::string json =
        "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
        "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,"
        "\"NORMAL\":1,\"TEXCOORD_0\":2},\"indices\":3,\"extensions\":{\"KHR_draco_mesh_compression\":"
        "{\"bufferView\":0,\"attributes\":{\"POSITION\":" +
        std::to_string(mesh.attribute(p)->unique_id()) + ",\"NORMAL\":" +
        std::to_string(mesh.attribute(n)->unique_id()) + ",\"TEXCOORD_0\":" +
        std::to_string(mesh.attribute(t)->unique_id()) + "}}}}]}],\"accessors\":[" +
        accessor(-1, nv, 5126, "VEC3") + ",\"min\":[-1,-1,-1],\"max\":[1,1,1]}," +
        accessor(-1, nv, 5126, "VEC3") + "}," + accessor(-1, nv, 5126, "VEC2") + "}," +
        accessor(-1, s.idx.size(), 5125, "SCALAR") +
        "}],\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":" +
        std::to_string(buffer.size()) + "}],\"buffers\":[{\"uri\":\"draco.bin\",\"byteLength\":" +
        std::to_string(buffer.size()) + "}]}";
    return write_file(dir + "/draco.bin", buffer.data(), buffer.size()) &&
           write_file(dir + "/draco.gltf", json.data(), json.size());
}

} // namespace

bool draco_fixture_write(const char *dir, int around, int position_bits)
{
    Sphere s = make_sphere(around);
    return write_plain(dir, s) && write_draco(dir, s, position_bits);
}
