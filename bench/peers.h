// bench/peers.h -- what every program of make bench's peer rows shares (bench/peer_*.cpp): the
// mesh, the rays, the clock, and the crack rays. Each program builds one library's structure over
// the same triangles and casts the same rays, so that rt's figures and each library's are
// measured alike:
//
//   peer_NAME time MESH.obj ROUNDS  the build's ms, each round's ms (512 x 512 eye rays), the
//                                   hits of the last round, the structure's bytes
//   peer_NAME cracks MESH.obj       for each crack set (cracks below): rays, and those that
//                                   slipped through
//
// The eye rays: from (0, 0, 1.8) through a screen of width 1.2 at z = 0.8 toward the unit
// sphere at the origin (tools/make_mesh's sphere), in float, as every library takes them; rt's
// double rays hold the very same numbers.
//
// A crack is a ray that a closed mesh should stop and does not: from the centre of the sphere
// toward each vertex and each edge's midpoint (every such ray must hit), and from the eye toward
// the vertices and edge midpoints of the cap that faces it (z > 0.8), where a ray
// must stop at the front, at t within a quarter of where it aims (t = 1), not pass through to
// the back (t > 2) or miss. These aim rays exactly at the edges where two triangles' tests must
// agree, the case a watertight test exists for.
#pragma once
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

namespace peers {

const int kSize = 512;

inline double Ms(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
        .count();
}

// The mesh's vertices (x, y, z) and faces (0-based indices), from v and f lines.
inline bool ReadObj(const char *path, std::vector<float> *v, std::vector<unsigned> *f) {
    FILE *file = fopen(path, "r");
    if (!file)
        return false;
    char line[256];
    while (fgets(line, sizeof line, file)) {
        float x, y, z;
        unsigned a, b, c;
        if (sscanf(line, "v %f %f %f", &x, &y, &z) == 3)
            v->insert(v->end(), {x, y, z});
        else if (sscanf(line, "f %u %u %u", &a, &b, &c) == 3)
            f->insert(f->end(), {a - 1, b - 1, c - 1});
    }
    fclose(file);
    return !f->empty();
}

// Ray (i, j) of the image.
inline void EyeRay(int i, int j, float o[3], float d[3]) {
    o[0] = 0, o[1] = 0, o[2] = 1.8f;
    d[0] = 1.2f * (i + 0.5f) / kSize - 0.6f, d[1] = 0.6f - 1.2f * (j + 0.5f) / kSize, d[2] = -1;
}

// A ray of a crack set, and what stops it: any hit (from inside), or a hit on the front.
struct CrackRay {
    float o[3], d[3];
};
struct CrackSet {
    const char *name;
    bool fromEye;
    std::vector<CrackRay> rays;
};

// The four crack sets of the mesh: vertices and edges, from inside and from the eye.
inline std::vector<CrackSet> CrackSets(const std::vector<float> &v,
                                       const std::vector<unsigned> &f) {
    std::vector<std::pair<unsigned, unsigned>> edges;
    for (size_t t = 0; t < f.size(); t += 3)
        for (int k = 0; k < 3; k++) {
            unsigned a = f[t + k], b = f[t + (k + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b)});
        }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::vector<CrackSet> sets = {{"vertices, from inside", false, {}},
                                  {"edges, from inside", false, {}},
                                  {"vertices, from the eye", true, {}},
                                  {"edges, from the eye", true, {}}};
    auto aim = [&](int set, const float p[3]) {
        bool eye = sets[set].fromEye;
        if (eye && !(p[2] > 0.8f))
            return;
        CrackRay r = {{0, 0, eye ? 1.8f : 0}, {p[0], p[1], eye ? p[2] - 1.8f : p[2]}};
        sets[set].rays.push_back(r);
    };
    for (size_t k = 0; k < v.size(); k += 3)
        aim(0, &v[k]), aim(2, &v[k]);
    for (auto &e : edges) {
        const float *a = &v[3 * e.first], *b = &v[3 * e.second];
        float m[3] = {(a[0] + b[0]) * 0.5f, (a[1] + b[1]) * 0.5f, (a[2] + b[2]) * 0.5f};
        aim(1, m), aim(3, m);
    }
    return sets;
}

// Whether a ray of the set slipped through: no hit, or (from the eye) one far beyond the front.
inline bool Crack(const CrackSet &set, bool hit, double t) {
    return !hit || (set.fromEye && !(t < 1.25));
}

// The usage line, and the mode of the arguments (0: time, 1: cracks, -1: neither).
inline int Mode(int argc, char **argv, const char *name, int *rounds) {
    *rounds = argc == 4 ? atoi(argv[3]) : 0;
    if (argc == 4 && !strcmp(argv[1], "time") && *rounds > 0)
        return 0;
    if (argc == 3 && !strcmp(argv[1], "cracks"))
        return 1;
    fprintf(stderr, "usage: %s time MESH.obj ROUNDS | %s cracks MESH.obj\n", name, name);
    return -1;
}

// Mode 1's lines: each crack set's name, its rays, and those that slipped through, for a program
// whose trace(o, d, &t) says whether the ray hit and where (inlined, as the call it stands for).
template <class Trace>
void PrintCracks(const std::vector<float> &v, const std::vector<unsigned> &f, Trace trace) {
    for (const CrackSet &set : CrackSets(v, f)) {
        long cracks = 0;
        for (const CrackRay &r : set.rays) {
            double t;
            bool hit = trace(r.o, r.d, &t);
            cracks += Crack(set, hit, t);
        }
        printf("%s\t%zu\t%ld\n", set.name, set.rays.size(), cracks);
    }
}

// Mode 0's rounds: the eye rays traced `rounds` times, each round's ms on a line; the hits of the
// last round.
template <class Trace> long TimeEyeRays(int rounds, Trace trace) {
    long hits = 0;
    for (int r = 0; r < rounds; r++) {
        auto start = std::chrono::steady_clock::now();
        hits = 0;
        for (int j = 0; j < kSize; j++)
            for (int i = 0; i < kSize; i++) {
                float o[3], d[3];
                double t;
                EyeRay(i, j, o, d);
                hits += trace(o, d, &t);
            }
        printf("%.3f\n", Ms(start));
    }
    return hits;
}

} // namespace peers
