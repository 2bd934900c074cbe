// app/mesh_normals.cpp -- a smooth mesh's corner normals, made once its file is read (mesh.cpp):
// the file's `vn` that each face's corners name, or for `smooth` the faces' normals averaged at
// each vertex; each triangle's turned to its outward side, and kept only where they agree with
// it. What a file's normals can get wrong is warned about once a mesh, naming the file: corners
// that lean behind their face (that triangle is drawn flat), and under `smooth`, faces wound
// against their neighbours (the averages there mix the two sides).
#include "app.h"

#include <algorithm>
#include <cstdint>

// The unit normal of a triangle's outward side, (b - a) x (c - a), its edges first brought near
// 1 by a power of two so that the product neither over- nor underflows; 0 without area.
static vec3 FaceNormal(const Triangle *t) {
    vec3 e1 = t->b - t->a, e2 = t->c - t->a;
    int k = UnitExponent({MaxComponent(e1), MaxComponent(e2), 0});
    return SafeNormalize(Cross(ScaleByPowerOfTwo(e1, k), ScaleByPowerOfTwo(e2, k)));
}

static bool IsZero(vec3 v) { return v.x == 0 && v.y == 0 && v.z == 0; }

// For `smooth`: at each vertex, the mean of the unit normals of the faces around it (each face
// counts once, whatever its size: a few long thin triangles do not outweigh the rest).
static std::vector<vec3> VertexNormals(const MeshCorners *m, const Triangle *first, size_t n) {
    std::vector<vec3> sum(m->vertices, vec3{0, 0, 0});
    for (size_t t = 0; t < n; t++) {
        vec3 face = FaceNormal(&first[t]);
        for (int i = 0; i < 3; i++)
            sum[m->vertex[3 * t + i]] = sum[m->vertex[3 * t + i]] + face;
    }
    for (vec3 &v : sum)
        v = SafeNormalize(v);
    return sum;
}

// How many edges of the triangles join two faces wound opposite ways: two faces that agree
// cross their shared edge in opposite directions (a to b, and b to a), and two that disagree in
// the same one. Each edge is a pair of vertex numbers, sorted, with the direction as the lowest
// bit; edges of more than two faces, or of one, are not counted.
static size_t EdgesWoundAgainst(const MeshCorners *m, size_t n) {
    std::vector<uint64_t> edges;
    edges.reserve(3 * n);
    for (size_t t = 0; t < n; t++)
        for (int i = 0; i < 3; i++) {
            uint64_t a = (uint64_t)m->vertex[3 * t + i],
                     b = (uint64_t)m->vertex[3 * t + (i + 1) % 3];
            if (a != b)
                edges.push_back((std::min(a, b) << 33) | (std::max(a, b) << 1) | (a < b ? 1 : 0));
        }
    std::sort(edges.begin(), edges.end());
    size_t against = 0;
    for (size_t k = 0; k < edges.size();) {
        size_t end = k;
        while (end < edges.size() && edges[end] >> 1 == edges[k] >> 1)
            end++;
        against += end - k == 2 && edges[k] == edges[k + 1];
        k = end;
    }
    return against;
}

// The rule for a triangle's corner normals c (none 0), its outward normal `face` (0 without area):
// turned to the outward side (where their sum points away from it, the file's winding and its
// normals disagree: all three flip), and kept only if each then leans to that side, c_i.face > 0.
// A corner that leans behind the face (or along it) would turn the shading normal away from the
// side the triangle is seen from over part of it, and Hanika's move out to the curved surface
// behind the face; such a triangle is drawn flat. False for it.
static bool AgreeWithFace(vec3 c[3], vec3 face) {
    if (Dot(c[0] + c[1] + c[2], face) < 0)
        c[0] = -c[0], c[1] = -c[1], c[2] = -c[2];
    return Dot(c[0], face) > 0 && Dot(c[1], face) > 0 && Dot(c[2], face) > 0;
}

// The mesh's warnings: `flattened` triangles made flat (AgreeWithFace), `against` edges between
// faces wound opposite ways (EdgesWoundAgainst); none for 0.
static void Warn(const std::string &name, size_t flattened, size_t against, Scene *scene) {
    if (flattened > 0)
        scene->warnings.push_back(
            name + ": warning: " + std::to_string(flattened) +
            (flattened == 1 ? " triangle has" : " triangles have") +
            " a corner normal that leans behind its face (or opposes the other corners'); drawn "
            "flat");
    if (against > 0)
        scene->warnings.push_back(
            name + ": warning: smooth: " + std::to_string(against) +
            (against == 1 ? " edge joins" : " edges join") +
            " faces wound opposite ways, so the normals averaged at their vertices mix a face's "
            "outside with its neighbour's inside; wind every face the same way (counter-clockwise "
            "seen from outside)");
}

void AddCornerNormals(const MeshCorners *m, MeshNormals how, size_t first, const char *meshName,
                      Scene *scene) {
    size_t n = scene->triangles.size() - first, flattened = 0;
    std::vector<vec3> atVertex;
    if (how == MESH_SMOOTH)
        atVertex = VertexNormals(m, &scene->triangles[first], n);
    std::vector<CornerNormals> made(n, CornerNormals{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
    bool any = false;
    for (size_t t = 0; t < n; t++) {
        vec3 c[3];
        for (int i = 0; i < 3; i++) {
            int k = how == MESH_SMOOTH ? m->vertex[3 * t + i] : m->normal[3 * t + i];
            c[i] = k < 0 ? vec3{0, 0, 0} : how == MESH_SMOOTH ? atVertex[k] : m->normals[k];
        }
        if (IsZero(c[0]) || IsZero(c[1]) || IsZero(c[2]))
            continue;
        vec3 face = FaceNormal(&scene->triangles[first + t]);
        if (!AgreeWithFace(c, face)) {
            flattened += !IsZero(face); // (a triangle without area is never hit)
            continue;
        }
        made[t] = {c[0], c[1], c[2]};
        any = true;
    }
    Warn(meshName, flattened, how == MESH_SMOOTH ? EdgesWoundAgainst(m, n) : 0, scene);
    if (!any)
        return;
    scene->cornerNormals.resize(first, CornerNormals{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
    scene->cornerNormals.insert(scene->cornerNormals.end(), made.begin(), made.end());
}
