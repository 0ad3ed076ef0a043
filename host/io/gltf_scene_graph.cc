// SPDX-License-Identifier: MIT
/* gltf_scene_graph.cc: the node hierarchy of a glTF's scene flattened (gltf_loader.h): world
 * matrices (a node's matrix, or T R S, after its parent's), the nodes that place meshes, the first
 * perspective camera and the KHR_lights_punctual lights. A node reached twice (a cycle, or two
 * parents: glTF nodes form disjoint trees) is an error, which also bounds the work. */
#include "io/gltf_primitives.h" /* tinygltf, gltf_loader.h */

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

/* The largest entry of a world matrix (scale or translation): 1e300 is finite, but the vertices
 * it places overflow float and the scene had "no triangles"; as CAMERA_COORDINATE_LIMIT. */
const double WORLD_LIMIT = 1e15;

struct Walk {
    const tinygltf::Model &m;
    const char *path;
    GltfFile *out;
    Error *err;
    std::vector<char> seen;
    std::vector<GltfPlacement> placements;
    std::vector<GltfLight> lights;
    bool singular_warned;
};

bool finite_all(const std::vector<double> &v)
{
    for (double x : v)
        if (!std::isfinite(x))
            return false;
    return true;
}

/* The node's local matrix: `matrix` (column-major) or translation x rotation x scale. */
bool local_matrix(Walk &w, int n, Affine *out)
{
    const tinygltf::Node &node = w.m.nodes[n];
    struct {
        const char *name;
        const std::vector<double> &v;
        size_t size;
    } parts[] = {{"matrix", node.matrix, 16},
                 {"translation", node.translation, 3},
                 {"rotation", node.rotation, 4},
                 {"scale", node.scale, 3}};
    for (const auto &part : parts) {
        if (!part.v.empty() && part.v.size() != part.size) {
            error_set(w.err, ERR_OBJ_PARSE, w.path, 0, "%s: nodes[%d].%s has %zu numbers, not %zu",
                      w.path, n, part.name, part.v.size(), part.size);
            return false;
        }
        if (!finite_all(part.v)) {
            error_set(w.err, ERR_OBJ_NONFINITE, w.path, 0, "%s: nodes[%d].%s is not finite", w.path,
                      n, part.name);
            return false;
        }
    }
    if (!node.matrix.empty()) {
        double rows[16];
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++)
                rows[4 * r + c] = node.matrix[4 * c + r];
        if (!affine_from_rows16(rows, out)) {
            error_set(w.err, ERR_OBJ_PARSE, w.path, 0, "%s: nodes[%d].matrix is projective (its "
                      "last row is not 0 0 0 1)", w.path, n);
            return false;
        }
        return true;
    }
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    for (int i = 0; i < 3; i++) {
        if (!node.translation.empty())
            t[i] = node.translation[i];
        if (!node.scale.empty())
            s[i] = node.scale[i];
    }
    if (!node.rotation.empty()) {
        double len = 0;
        for (int i = 0; i < 4; i++)
            len += node.rotation[i] * node.rotation[i];
        len = sqrt(len);
        if (!(len > 0)) {
            error_set(w.err, ERR_OBJ_PARSE, w.path, 0, "%s: nodes[%d].rotation is not a rotation "
                      "(zero quaternion)", w.path, n);
            return false;
        }
        for (int i = 0; i < 4; i++)
            q[i] = node.rotation[i] / len;
    }
    double x = q[0], y = q[1], z = q[2], qw = q[3];
    double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * qw), 2 * (x * z + y * qw)},
                      {2 * (x * y + z * qw), 1 - 2 * (x * x + z * z), 2 * (y * z - x * qw)},
                      {2 * (x * z - y * qw), 2 * (y * z + x * qw), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            out->m[i][j] = r[i][j] * s[j];
        out->m[i][3] = t[i];
    }
    return true;
}

void unit(double v[3])
{
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++)
        v[i] = len > 0 ? v[i] / len : 0;
}

bool add_light(Walk &w, int n, const Affine &world)
{
    const tinygltf::Node &node = w.m.nodes[n];
    auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end() || !ext->second.Has("light"))
        return true;
    const tinygltf::Value &v = ext->second.Get("light");
    int index = v.IsNumber() ? v.GetNumberAsInt() : -1;
    if (index < 0 || (size_t)index >= w.m.lights.size()) {
        error_set(w.err, ERR_OBJ_PARSE, w.path, 0, "%s: nodes[%d].extensions.KHR_lights_punctual."
                  "light: lights[%d] does not exist (%zu lights)", w.path, n, index, w.m.lights.size());
        return false;
    }
    const tinygltf::Light &l = w.m.lights[index];
    GltfLight g;
    memset(&g, 0, sizeof g);
    g.light = index;
    g.node = n;
    g.type = l.type == "point" ? GLTF_LIGHT_POINT : l.type == "spot" ? GLTF_LIGHT_SPOT
             : l.type == "directional" ? GLTF_LIGHT_DIRECTIONAL : -1;
    if (g.type < 0) {
        error_set(w.err, ERR_OBJ_PARSE, w.path, 0, "%s: KHR_lights_punctual.lights[%d].type \"%s\" "
                  "is not point, spot or directional", w.path, index, l.type.c_str());
        return false;
    }
    for (int c = 0; c < 3; c++)
        g.color[c] = l.color.size() == 3 ? (float)l.color[c] : 1.0f;
    g.intensity = (float)l.intensity;
    g.range = (float)l.range;
    g.inner_cone = g.type == GLTF_LIGHT_SPOT ? (float)l.spot.innerConeAngle : 0.0f;
    g.outer_cone = g.type == GLTF_LIGHT_SPOT ? (float)l.spot.outerConeAngle : (float)(M_PI / 4);
    bool bad_color = !(g.color[0] >= 0 && g.color[1] >= 0 && g.color[2] >= 0) ||
                     !std::isfinite(g.color[0] + g.color[1] + g.color[2]);
    if (bad_color || !(g.intensity >= 0) || !std::isfinite(g.intensity) ||
        !(g.inner_cone >= 0 && g.inner_cone < g.outer_cone && g.outer_cone <= M_PI / 2)) {
        error_set(w.err, ERR_OBJ_PARSE, w.path, 0, "%s: KHR_lights_punctual.lights[%d]: %s", w.path,
                  index, bad_color ? "color is not a finite non-negative colour"
                  : !(g.intensity >= 0) || !std::isfinite(g.intensity) ? "intensity is not finite and >= 0"
                  : "spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
        return false;
    }
    const double origin[3] = {0, 0, 0}, minus_z[3] = {0, 0, -1};
    affine_point(&world, origin, g.position);
    affine_vector(&world, minus_z, g.direction);
    unit(g.direction);
    w.lights.push_back(g);
    return true;
}

void take_camera(Walk &w, int n, const Affine &world)
{
    const tinygltf::Node &node = w.m.nodes[n];
    GltfCamera *cam = &w.out->camera;
    if (cam->present || node.camera < 0 || (size_t)node.camera >= w.m.cameras.size() ||
        w.m.cameras[node.camera].type != "perspective")
        return;
    double yfov = w.m.cameras[node.camera].perspective.yfov;
    if (!(yfov > 0 && yfov < M_PI))
        return;
    const double origin[3] = {0, 0, 0}, minus_z[3] = {0, 0, -1}, plus_y[3] = {0, 1, 0};
    cam->present = true;
    cam->yfov = (float)yfov;
    cam->camera = node.camera;
    cam->node = n;
    affine_point(&world, origin, cam->eye);
    affine_vector(&world, minus_z, cam->forward);
    affine_vector(&world, plus_y, cam->up);
    unit(cam->forward);
    unit(cam->up);
}

bool walk(Walk &w, int n, const Affine &parent, int depth)
{
    if (n < 0 || (size_t)n >= w.m.nodes.size()) {
        error_set(w.err, ERR_OBJ_PARSE, w.path, 0, "%s: nodes[%d] does not exist (%zu nodes)",
                  w.path, n, w.m.nodes.size());
        return false;
    }
    if (w.seen[n]) {
        error_set(w.err, ERR_OBJ_PARSE, w.path, 0, "%s: nodes[%d] is reached twice (a cycle, or "
                  "two parents: glTF nodes form trees)", w.path, n);
        return false;
    }
    if (depth > 1000) { /* the walk recurses: bound the stack */
        error_set(w.err, ERR_TOO_LARGE, w.path, 0, "%s: nodes[%d] is nested more than 1000 deep",
                  w.path, n);
        return false;
    }
    w.seen[n] = 1;
    Affine local, world;
    if (!local_matrix(w, n, &local))
        return false;
    world = affine_mul(&parent, &local);
    if (!affine_is_finite(&world)) {
        error_set(w.err, ERR_OBJ_NONFINITE, w.path, 0, "%s: nodes[%d]: its world matrix is not "
                  "finite", w.path, n);
        return false;
    }
    double largest = 0;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            largest = fmax(largest, fabs(world.m[r][c]));
    const tinygltf::Node &node = w.m.nodes[n];
    if (node.mesh >= 0 && largest > WORLD_LIMIT) { /* finite in double, infinite once a vertex */
        error_set(w.err, ERR_OBJ_NONFINITE, w.path, 0, "%s: nodes[%d]: its world matrix has an "
                  "entry of %g (pt's limit is %g: vertices are floats)", w.path, n, largest,
                  WORLD_LIMIT);
        return false;
    }
    if (node.mesh >= 0) {
        Affine inverse;
        if ((size_t)node.mesh >= w.m.meshes.size()) {
            error_set(w.err, ERR_OBJ_PARSE, w.path, 0, "%s: nodes[%d].mesh: meshes[%d] does not "
                      "exist (%zu meshes)", w.path, n, node.mesh, w.m.meshes.size());
            return false;
        }
        if (affine_invert(&world, &inverse)) {
            w.placements.push_back(GltfPlacement{world, node.mesh, n});
            for (int p = w.out->mesh_first[node.mesh]; p < w.out->mesh_first[node.mesh + 1]; p++)
                w.out->primitives[p].placed = true;
        } else if (!w.singular_warned) { /* a zero scale hides a node: nothing to draw */
            w.singular_warned = true;
            warn("%s: nodes[%d]: singular world matrix (a zero scale): its mesh is not drawn",
                 w.path, n);
        }
    }
    take_camera(w, n, world);
    if (!add_light(w, n, world))
        return false;
    for (int child : node.children)
        if (!walk(w, child, world, depth + 1))
            return false;
    return true;
}

template <typename T> bool copy_out(const std::vector<T> &from, T **to, int *count)
{
    *to = static_cast<T *>(malloc((from.size() ? from.size() : 1) * sizeof(T)));
    if (!*to)
        return false;
    if (!from.empty())
        memcpy(*to, from.data(), from.size() * sizeof(T));
    *count = (int)from.size();
    return true;
}

} // namespace

/* The default scene (or scene 0; with no scenes, every root node) walked depth-first. */
bool gltf_walk_scene(const tinygltf::Model &m, const char *path, GltfFile *out, Error *err)
{
    out->num_meshes = (int)m.meshes.size();
    out->mesh_first = static_cast<int *>(calloc(m.meshes.size() + 1, sizeof(int)));
    size_t total = 0;
    for (size_t i = 0; i < m.meshes.size(); i++) {
        out->mesh_first[i] = (int)total;
        total += m.meshes[i].primitives.size();
    }
    if (total > (1u << 24)) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: %zu mesh primitives", path, total);
        return false;
    }
    out->mesh_first[m.meshes.size()] = (int)total;
    out->primitives = static_cast<GltfPrimitive *>(calloc(total ? total : 1, sizeof(GltfPrimitive)));
    if (!out->primitives)
        throw std::bad_alloc();
    out->num_primitives = (int)total;
    for (size_t i = 0; i < m.meshes.size(); i++)
        for (size_t p = 0; p < m.meshes[i].primitives.size(); p++) {
            GltfPrimitive *g = &out->primitives[out->mesh_first[i] + p];
            g->mesh_index = (int)i;
            g->primitive_index = (int)p;
            g->material = m.meshes[i].primitives[p].material;
        }
    Walk w{m, path, out, err, std::vector<char>(m.nodes.size(), 0), {}, {}, false};
    std::vector<int> roots;
    int scene = m.defaultScene >= 0 ? m.defaultScene : m.scenes.empty() ? -1 : 0;
    if (scene >= (int)m.scenes.size()) {
        error_set(err, ERR_OBJ_PARSE, path, 0, "%s: scene: scenes[%d] does not exist", path, scene);
        return false;
    }
    if (scene >= 0) {
        roots = m.scenes[scene].nodes;
    } else { /* no scene: the nodes that are nobody's child */
        std::vector<char> child(m.nodes.size(), 0);
        for (const tinygltf::Node &node : m.nodes)
            for (int c : node.children)
                if (c >= 0 && (size_t)c < child.size())
                    child[c] = 1;
        for (size_t i = 0; i < m.nodes.size(); i++)
            if (!child[i])
                roots.push_back((int)i);
    }
    Affine identity = affine_identity();
    for (int root : roots)
        if (!walk(w, root, identity, 0))
            return false;
    if (!copy_out(w.placements, &out->placements, &out->num_placements) ||
        !copy_out(w.lights, &out->lights, &out->num_lights))
        throw std::bad_alloc();
    return true;
}
