// bench/peer_tinybvh.cpp -- tinybvh (Jacco Bikker, MIT: github.com/jbikker/tinybvh) in make
// bench's peer rows (bench/peers.h says what each mode prints). bench/peers.sh builds it from a
// copy of tiny_bvh.h that it is pointed to (TINYBVH=dir), never part of rt, twice:
//   build/peers/tinybvh            its fastest CPU layout, BVH8_CPU (AVX2, eight wide: Build, then
//                                  Intersect), with the flags its README gives (-O3 -mavx2 -mfma)
//   build/peers/tinybvh_watertight its BVH (two wide) with its watertight triangle test
//                                  (WATERTIGHT_TRITEST), built with -ffp-contract=off, without
//                                  which fused multiply-adds break that test's watertightness
// Its bytes are its traversal data (BVH8_CPU's blocks, or the BVH's nodes); the builder's own
// intermediate trees, which it keeps beside them, are not counted.
#define TINYBVH_IMPLEMENTATION
#include "tiny_bvh.h"

#include "peers.h"

#include <cmath>

#ifdef WATERTIGHT_TRITEST
typedef tinybvh::BVH Structure;
static size_t Bytes(const Structure &bvh) { return (size_t)bvh.allocatedNodes * 32; }
#else
typedef tinybvh::BVH8_CPU Structure;
static size_t Bytes(const Structure &bvh) { return (size_t)bvh.allocatedBlocks * 16; }
#endif

// The triangles as tinybvh takes them: three corners a triangle, each four floats.
static std::vector<tinybvh::bvhvec4> Corners(const std::vector<float> &v,
                                             const std::vector<unsigned> &f) {
    std::vector<tinybvh::bvhvec4> corners(f.size());
    for (size_t k = 0; k < f.size(); k++)
        corners[k] = tinybvh::bvhvec4(v[3 * f[k]], v[3 * f[k] + 1], v[3 * f[k] + 2], 0);
    return corners;
}

// tinybvh makes the direction a unit vector: t comes back in units of d here.
static bool Trace(const Structure &bvh, const float o[3], const float d[3], double *t) {
    tinybvh::Ray ray(tinybvh::bvhvec3(o[0], o[1], o[2]), tinybvh::bvhvec3(d[0], d[1], d[2]));
    bvh.Intersect(ray);
    double length = std::sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
    *t = ray.hit.t / length;
    return ray.hit.t < BVH_FAR;
}

int main(int argc, char **argv) {
    int rounds;
    int mode = peers::Mode(argc, argv, "peer_tinybvh", &rounds);
    std::vector<float> v;
    std::vector<unsigned> f;
    if (mode < 0 || !peers::ReadObj(argv[2], &v, &f))
        return 2;
    auto start = std::chrono::steady_clock::now(); // (as Embree's, from the mesh's own arrays)
    std::vector<tinybvh::bvhvec4> corners = Corners(v, f);
    Structure bvh;
    bvh.Build(corners.data(), (uint32_t)(f.size() / 3));
    double buildMs = peers::Ms(start);
    if (mode == 1) {
        peers::PrintCracks(
            v, f, [&](const float *o, const float *d, double *t) { return Trace(bvh, o, d, t); });
        return 0;
    }
    printf("%.3f\n", buildMs);
    long hits = peers::TimeEyeRays(
        rounds, [&](const float *o, const float *d, double *t) { return Trace(bvh, o, d, t); });
    printf("hits %ld\nbytes %zu\n", hits, Bytes(bvh));
    return 0;
}
