// bench/peer_bvh2.cpp -- bvh v2 (Arsène Pérard-Gayot, MIT: github.com/madmann91/bvh) in make
// bench's peer rows (bench/peers.h says what each mode prints). bench/peers.sh builds it from a
// copy of its src/ folder that it is pointed to (BVH2=dir), never part of rt, as
// build/peers/bvh2: C++20, -O3 -march=native. One thread: its default builder and quality
// (DefaultBuilder, High: a sweep SAH build, then reinsertion), the triangles permuted and
// precomputed as its README does, its default (not robust) traversal. Its bytes: nodes, the
// primitive order and the precomputed triangles.
#include <bvh/v2/bvh.h>
#include <bvh/v2/default_builder.h>
#include <bvh/v2/node.h>
#include <bvh/v2/ray.h>
#include <bvh/v2/stack.h>
#include <bvh/v2/tri.h>
#include <bvh/v2/vec.h>

#include "peers.h"

typedef bvh::v2::Vec<float, 3> Vec3;
typedef bvh::v2::BBox<float, 3> BBox;
typedef bvh::v2::Tri<float, 3> Tri;
typedef bvh::v2::Node<float, 3> Node;
typedef bvh::v2::Bvh<Node> Bvh;
typedef bvh::v2::PrecomputedTri<float> PrecomputedTri;

struct Structure {
    Bvh bvh;
    std::vector<PrecomputedTri> tris; // in the tree's order
};

static void Build(const std::vector<float> &v, const std::vector<unsigned> &f, Structure *s) {
    auto corner = [&](unsigned k) { return Vec3(v[3 * k], v[3 * k + 1], v[3 * k + 2]); };
    std::vector<Tri> tris;
    for (size_t t = 0; t < f.size(); t += 3)
        tris.emplace_back(corner(f[t]), corner(f[t + 1]), corner(f[t + 2]));
    std::vector<BBox> boxes(tris.size());
    std::vector<Vec3> centers(tris.size());
    for (size_t i = 0; i < tris.size(); i++)
        boxes[i] = tris[i].get_bbox(), centers[i] = tris[i].get_center();
    bvh::v2::DefaultBuilder<Node>::Config config;
    s->bvh = bvh::v2::DefaultBuilder<Node>::build(boxes, centers, config);
    s->tris.resize(tris.size());
    for (size_t i = 0; i < tris.size(); i++)
        s->tris[i] = tris[s->bvh.prim_ids[i]];
}

static bool Trace(const Structure &s, const float o[3], const float d[3], double *t) {
    bvh::v2::Ray<float, 3> ray(Vec3(o[0], o[1], o[2]), Vec3(d[0], d[1], d[2]), 0, 1e30f);
    bvh::v2::SmallStack<Bvh::Index, 64> stack;
    bool hit = false;
    s.bvh.intersect<false, false>(ray, s.bvh.get_root().index, stack,
                                  [&](size_t begin, size_t end) {
                                      for (size_t i = begin; i < end; i++)
                                          if (auto found = s.tris[i].intersect(ray))
                                              ray.tmax = std::get<0>(*found), hit = true;
                                      return hit;
                                  });
    *t = ray.tmax;
    return hit;
}

int main(int argc, char **argv) {
    int rounds;
    int mode = peers::Mode(argc, argv, "peer_bvh2", &rounds);
    std::vector<float> v;
    std::vector<unsigned> f;
    if (mode < 0 || !peers::ReadObj(argv[2], &v, &f))
        return 2;
    auto start = std::chrono::steady_clock::now();
    Structure s;
    Build(v, f, &s);
    double buildMs = peers::Ms(start);
    if (mode == 1) {
        peers::PrintCracks(
            v, f, [&](const float *o, const float *d, double *t) { return Trace(s, o, d, t); });
        return 0;
    }
    printf("%.3f\n", buildMs);
    long hits = peers::TimeEyeRays(
        rounds, [&](const float *o, const float *d, double *t) { return Trace(s, o, d, t); });
    size_t bytes = s.bvh.nodes.size() * sizeof(Node) + s.bvh.prim_ids.size() * sizeof(size_t) +
                   s.tris.size() * sizeof(PrecomputedTri);
    printf("hits %ld\nbytes %zu\n", hits, bytes);
    return 0;
}
