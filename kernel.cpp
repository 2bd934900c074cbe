// kernel.cpp -- the fast shape loop: blocks of kLanes triangles, the BVH walk, blocks of spheres.
//
// Speed machinery, behind the contract of HitWatertightTriangles (watertight.cpp): the same
// hits, bit for bit, found faster. Two steps beyond the plain loop:
//   1. The watertight test's first step (shear the corners, compute the edge functions, reject
//      a triangle whose edges disagree; watertight.cpp, EdgesDisagree) runs on a whole block at
//      once, with GCC/Clang vector extensions: `Lanes` holds kLanes numbers, and every line
//      of kernel_blocks.h is the scalar line with `Lanes` for `real`, the same operations in the
//      same order, so each lane rounds exactly as the scalar code does. Only the triangles that
//      survive go on to the rest of the reference test: where their three edge functions have a
//      certain sign (none 0 or NaN), what IntersectSheared (watertight.cpp) does next is to call
//      RobustPlaneHit, so the kernel calls it with the same arguments; the others get the whole
//      reference function (IntersectWatertight), which decides their signs exactly.
//   2. With a BVH (commit.cpp), a ray visits only the nodes whose boxes its line passes
//      (SlabInterval, nearer child first) and skips those wholly beyond its nearest hit so far.
//      Every hit lies inside its triangle's window (plane.cpp), and a node's window holds those
//      of the triangles below it, so no box is skipped that holds a hit. Hits at equal t go to
//      the lower place in the scene, as in the list.
// One binary serves every x86-64 machine: the loop is compiled twice, for AVX2 and for the
// baseline (SSE2), and each call takes the one this processor can run (what target_clones does;
// written out, because clang 14's target_clones cannot be called from another file).
// The block test is in kernel_blocks.h, the walk in kernel_walk.h; this file puts them together
// for one ray and dispatches. The spheres' blocks (kernel_spheres.h) get the same treatment: the
// first step of the stable sphere test on kLanes spheres at once, the reference test for the rest.
#include "kernel_packet.h"
#include "kernel_walk.h"

// 1 / d on each axis, as MakeSlabRay divides (each lane rounds as the scalar division does),
// for OutOfReach: one vector division, made every search. (Behind a branch on whether the search
// needs them, they cost the Cornell box 3% of its time; and built in memory, its three numbers
// stored one by one and read back as one vector, which waits for the stores, another 3%.)
static RT_INLINE void Inverses(vec3 d, real inverse[3]) {
    Lanes one, lanes;
    Fill(&one, 1);
    lanes = one;
    lanes[0] = d.x, lanes[1] = d.y, lanes[2] = d.z;
    Lanes quotient = one / lanes;
    inverse[0] = quotient[0], inverse[1] = quotient[1], inverse[2] = quotient[2];
}

template <int kz, bool kWide>
static RT_INLINE bool HitLayout(const SceneLayout *layout, Search *s, RayHit *hit) {
    if (layout->nodes.empty())
        return TestBlocks<kz, kWide>(layout->blocks.data(), 0, (int)layout->blocks.size(), s, hit);
    return WalkTree<kz, kWide>(layout, s, hit);
}

// The search for one ray whose main axis is kz: the ray sheared here, so that its numbers are
// spread over the lanes from registers. (Sheared by the caller, out of line, they were read back
// as one 32-byte load of the five 8-byte numbers just stored, which waited for the stores: 8% of
// the time of a small mesh's eye rays.)
template <int kz, bool kWide>
static RT_INLINE bool HitSheared(const Scene *scene, int skip, const Ray *ray, real tMin, real tMax,
                                 bool anyHit, RayHit *hit) {
    RayShear shear;
    ShearRayAxes<kz>(ray, &shear);
    Search s = {scene->triangles.data(),
                scene->layout.setUps.data(),
                ray,
                &shear,
                {},
                skip,
                tMin,
                tMax,
                -1,
                anyHit,
                {},
                OriginPad(ray)};
    Inverses(ray->dir, s.inverse);
    Splat(&s.lanes.ox, shear.origin.x), Splat(&s.lanes.oy, shear.origin.y);
    Splat(&s.lanes.oz, shear.origin.z), Splat(&s.lanes.sx, shear.sx);
    Splat(&s.lanes.sy, shear.sy);
    return HitLayout<kz, kWide>(&scene->layout, &s, hit);
}

// The whole search for one ray, compiled into each of the two copies below.
template <bool kWide>
static RT_INLINE bool HitAll(const Scene *scene, int skip, const Ray *ray, real tMin, real tMax,
                             bool anyHit, RayHit *hit) {
    int kz = DominantAxis(ray->dir);
    if (kz == 0)
        return HitSheared<0, kWide>(scene, skip, ray, tMin, tMax, anyHit, hit);
    if (kz == 1)
        return HitSheared<1, kWide>(scene, skip, ray, tMin, tMax, anyHit, hit);
    return HitSheared<2, kWide>(scene, skip, ray, tMin, tMax, anyHit, hit);
}

static bool HitBaseline(const Scene *scene, int skip, const Ray *ray, real tMin, real tMax,
                        bool anyHit, RayHit *hit) {
    return HitAll<false>(scene, skip, ray, tMin, tMax, anyHit, hit);
}

#if RT_DISPATCH
RT_AVX2 static bool HitAvx2(const Scene *scene, int skip, const Ray *ray, real tMin, real tMax,
                            bool anyHit, RayHit *hit) {
    return HitAll<true>(scene, skip, ray, tMin, tMax, anyHit, hit);
}
#endif

bool HitCommittedTriangles(const Scene *scene, int skip, const Ray *ray, real tMin, real tMax,
                           bool anyHit, RayHit *hit) {
#if RT_DISPATCH
    if (scene->layout.wide)
        return HitAvx2(scene, skip, ray, tMin, tMax, anyHit, hit);
#endif
    return HitBaseline(scene, skip, ray, tMin, tMax, anyHit, hit);
}

// The sphere blocks (kernel_spheres.h), one chunk or many, each in both copies. Out of line, so
// that the search of one chunk, the common one, needs few registers saved.
static RT_NOINLINE bool OneChunkBaseline(const Scene *scene, int skip, const Ray *ray, real tMin,
                                         real *tMax, bool anyHit, RayHit *hit) {
    return TestOneChunk<false>(scene, skip, ray, tMin, tMax, anyHit, hit);
}

static RT_NOINLINE bool ChunksBaseline(const Scene *scene, int skip, const Ray *ray, real tMin,
                                       real *tMax, bool anyHit, RayHit *hit) {
    return TestChunks<false>(scene, skip, ray, tMin, tMax, anyHit, hit);
}

#if RT_DISPATCH
RT_AVX2 static RT_NOINLINE bool OneChunkAvx2(const Scene *scene, int skip, const Ray *ray,
                                             real tMin, real *tMax, bool anyHit, RayHit *hit) {
    return TestOneChunk<true>(scene, skip, ray, tMin, tMax, anyHit, hit);
}

RT_AVX2 static RT_NOINLINE bool ChunksAvx2(const Scene *scene, int skip, const Ray *ray, real tMin,
                                           real *tMax, bool anyHit, RayHit *hit) {
    return TestChunks<true>(scene, skip, ray, tMin, tMax, anyHit, hit);
}
#endif

bool HitCommittedSpheres(const Scene *scene, int skip, const Ray *ray, real tMin, real *tMax,
                         bool anyHit, RayHit *hit) {
    if (scene->layout.sphereCount == 0) // (a mesh scene: no call, no lanes made for nothing)
        return false;
    bool one = scene->layout.sphereCount <= (size_t)(kChunkBlocks * kLanes);
#if RT_DISPATCH
    if (scene->layout.wide)
        return one ? OneChunkAvx2(scene, skip, ray, tMin, tMax, anyHit, hit)
                   : ChunksAvx2(scene, skip, ray, tMin, tMax, anyHit, hit);
#endif
    return one ? OneChunkBaseline(scene, skip, ray, tMin, tMax, anyHit, hit)
               : ChunksBaseline(scene, skip, ray, tMin, tMax, anyHit, hit);
}

// Packets of rays from the eye (kernel_packet.h), in the AVX2 copy only: lane by lane they would
// repeat the one-ray loop's work with more bookkeeping.
#if RT_DISPATCH
RT_AVX2 static void PacketAvx2(const Scene *scene, PacketSearch *p) {
    int kz = p->packet->kz;
    if (kz == 0)
        SearchPacket<0>(scene, p);
    else if (kz == 1)
        SearchPacket<1>(scene, p);
    else
        SearchPacket<2>(scene, p);
}
#endif

bool HitCommittedPacket(const Scene *scene, const RayPacket *packet, RayHit *hits, bool *found) {
#if RT_DISPATCH
    int count = packet->count;
    if (!scene->layout.wide || !scene->layout.nodes.empty() || count < 1 || count > kLanes ||
        packet->kz < 0 || packet->kz > 2)
        return false;
    PacketSearch p;
    p.packet = packet, p.active = (1u << count) - 1, p.hits = hits;
    PacketAvx2(scene, &p);
    for (int r = 0; r < count; r++)
        found[r] = p.found[r];
    return true;
#else
    (void)scene, (void)packet, (void)hits, (void)found;
    return false;
#endif
}

bool KernelCanBeWide() {
#if RT_DISPATCH
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}
