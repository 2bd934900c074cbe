// fast/kernel.cpp -- the accelerator that main installs: the two functions the core's seam calls
// (Accelerator, ray.h), and the kernel behind them: blocks of kLanes triangles, the BVH walks,
// blocks of spheres, packets of eye rays.
//
// A search answers as the plain loop of geometry.cpp does, bit for bit: the spheres in scene
// order, then the triangles, each hit shrinking the interval, a tie kept by the earlier shape.
// Speed machinery, in two steps beyond the plain loop:
//   1. The watertight test's first step (shear the corners, compute the edge functions, reject
//      a triangle whose edges disagree; watertight.cpp, EdgesDisagree) runs on a whole block at
//      once, with GCC/Clang vector extensions: `Lanes` holds kLanes numbers, and every line
//      of kernel_blocks.h is the scalar line with `Lanes` for `real`, the same operations in the
//      same order, so each lane rounds exactly as the scalar code does. Only the triangles that
//      survive go on to the rest of the reference test: where their three edge functions have a
//      certain sign (none 0 or NaN), what IntersectSheared (watertight.cpp) does next is to call
//      RobustPlaneHit, so the kernel calls it with the same arguments; the others get the whole
//      reference function (IntersectWatertight), which decides their signs exactly.
//   2. With a BVH (commit_tree.cpp), a ray visits only the nodes whose boxes its line passes
//      (SlabInterval's steps, nearer child first) and skips those wholly beyond its nearest hit
//      so far. Every hit lies inside its triangle's window (plane.cpp), and a node's window holds
//      those of the triangles below it, so no box is skipped that holds a hit. Hits at equal t go
//      to the lower place in the scene, as in the list. The tree is eight wide with float boxes,
//      and its leaves' blocks are float copies filtered with a bound on float's rounding
//      (kernel_wide.h, kernel_filter.h say why neither refuses what the exact test would keep).
// One binary serves every x86-64 machine: the loop is compiled twice, for AVX2 and for the
// baseline (SSE2), and each call takes the one this processor can run (what target_clones does;
// written out, because clang 14's target_clones cannot be called from another file).
// The list's block test is in kernel_blocks.h, the tree's walk in kernel_wide.h; this file puts
// them together for one ray and dispatches. The spheres' blocks (kernel_spheres.h) get the same
// treatment: the first step of the stable sphere test on kLanes spheres at once, the reference
// test for the rest, and from 64 spheres a BVH of their own (kernel_walk.h).
#include "kernel_packet.h"
#include "kernel_walk.h"
#include "kernel_wide.h"

#include <cstdio>

// The wide tree's search (kernel_wide.h) for a ray whose exact search is w->exact.
template <int kz>
static RT_INLINE bool HitWide(const SceneLayout *layout, WideSearch *w, RayHit *hit) {
    const TriangleSearch *s = &w->exact;
    PowerPair scale = PowerOfTwoPair(layout->wideExponent);
    Double4 o;
    double omax = ScaledOrigin(s->ray, scale, &o);
    MakeWideRay(s->ray, &o, omax, scale, s->tMin, s->tMax, &w->nodes);
    MakeFilterRay<kz>(s->shear, &o, omax, w->nodes.culls, &w->filter);
    MakePlaneRay(s->ray, &w->plane);
    w->reach = false;
    return WalkWide<kz>(layout, w, hit);
}

// The search for one ray whose main axis is kz: the ray sheared here, so that its numbers are
// spread over the lanes from registers (sheared by the caller, out of line, they would be read
// back as one vector load of numbers just stored, which waits for the stores). kWideTree: the
// layout has the wide tree (else its blocks are one list).
template <int kz, bool kVectors, bool kWideTree>
static RT_INLINE bool HitSheared(const Scene *scene, const SceneLayout *layout, int skip,
                                 const Ray *ray, real tMin, real tMax, bool anyHit, RayHit *hit) {
    RayShear shear;
    ShearRayAxes<kz>(ray, &shear);
    WideSearch w; // (its exact part is all a list needs)
    TriangleSearch &s = w.exact;
    s.triangles = scene->triangles.data(), s.setUps = layout->setUps.data();
    s.ray = ray, s.shear = &shear, s.skip = skip, s.tMin = tMin, s.tMax = tMax, s.best = -1;
    s.anyHit = anyHit, s.originPad = OriginPad(ray);
    if (kWideTree)
        return HitWide<kz>(layout, &w, hit);
    Inverses(ray->dir, s.inverse);
    Splat(&s.lanes.ox, shear.origin.x), Splat(&s.lanes.oy, shear.origin.y);
    Splat(&s.lanes.oz, shear.origin.z), Splat(&s.lanes.sx, shear.sx);
    Splat(&s.lanes.sy, shear.sy);
    return TestBlocks<kz, kVectors>(layout->blocks.data(), 0, (int)layout->blocks.size(), &s, hit);
}

// The whole search for one ray, compiled into each of the copies below.
template <bool kVectors, bool kWideTree>
static RT_INLINE bool HitAll(const Scene *scene, const SceneLayout *layout, int skip,
                             const Ray *ray, real tMin, real tMax, bool anyHit, RayHit *hit) {
    int kz = DominantAxis(ray->dir);
    if (kz == 0)
        return HitSheared<0, kVectors, kWideTree>(scene, layout, skip, ray, tMin, tMax, anyHit,
                                                  hit);
    if (kz == 1)
        return HitSheared<1, kVectors, kWideTree>(scene, layout, skip, ray, tMin, tMax, anyHit,
                                                  hit);
    return HitSheared<2, kVectors, kWideTree>(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}

// The list's search and the wide tree's, each a function of its own (so that neither carries the
// other's stack and registers), in both copies.
static bool ListBaseline(const Scene *scene, const SceneLayout *layout, int skip, const Ray *ray,
                         real tMin, real tMax, bool anyHit, RayHit *hit) {
    return HitAll<false, false>(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}
static bool WideBaseline(const Scene *scene, const SceneLayout *layout, int skip, const Ray *ray,
                         real tMin, real tMax, bool anyHit, RayHit *hit) {
    return HitAll<false, true>(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}

#if RT_DISPATCH
RT_AVX2 static bool ListAvx2(const Scene *scene, const SceneLayout *layout, int skip,
                             const Ray *ray, real tMin, real tMax, bool anyHit, RayHit *hit) {
    return HitAll<true, false>(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}
RT_AVX2 static bool WideAvx2(const Scene *scene, const SceneLayout *layout, int skip,
                             const Ray *ray, real tMin, real tMax, bool anyHit, RayHit *hit) {
    return HitAll<true, true>(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}
#endif

bool HitCommittedTriangles(const Scene *scene, const SceneLayout *layout, int skip, const Ray *ray,
                           real tMin, real tMax, bool anyHit, RayHit *hit) {
    bool wide = !layout->wideNodes.empty();
#if RT_DISPATCH
    if (layout->vectors)
        return (wide ? WideAvx2 : ListAvx2)(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
#endif
    return (wide ? WideBaseline : ListBaseline)(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}

// The sphere blocks (kernel_spheres.h), one chunk or many, each in both copies. Out of line, so
// that the search of one chunk, the common one, needs few registers saved.
static RT_NOINLINE bool OneChunkBaseline(const Scene *scene, const SceneLayout *layout, int skip,
                                         const Ray *ray, real tMin, real *tMax, bool anyHit,
                                         RayHit *hit) {
    return TestOneChunk<false>(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}

static RT_NOINLINE bool ChunksBaseline(const Scene *scene, const SceneLayout *layout, int skip,
                                       const Ray *ray, real tMin, real *tMax, bool anyHit,
                                       RayHit *hit) {
    return TestChunks<false>(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}

#if RT_DISPATCH
RT_AVX2 static RT_NOINLINE bool OneChunkAvx2(const Scene *scene, const SceneLayout *layout,
                                             int skip, const Ray *ray, real tMin, real *tMax,
                                             bool anyHit, RayHit *hit) {
    return TestOneChunk<true>(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}

RT_AVX2 static RT_NOINLINE bool ChunksAvx2(const Scene *scene, const SceneLayout *layout, int skip,
                                           const Ray *ray, real tMin, real *tMax, bool anyHit,
                                           RayHit *hit) {
    return TestChunks<true>(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}
#endif

// The spheres' tree (kernel_walk.h), in both copies.
static RT_NOINLINE bool SphereTreeBaseline(const Scene *scene, const SceneLayout *layout, int skip,
                                           const Ray *ray, real tMin, real *tMax, bool anyHit,
                                           RayHit *hit) {
    return WalkSpheres<false>(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}

#if RT_DISPATCH
RT_AVX2 static RT_NOINLINE bool SphereTreeAvx2(const Scene *scene, const SceneLayout *layout,
                                               int skip, const Ray *ray, real tMin, real *tMax,
                                               bool anyHit, RayHit *hit) {
    return WalkSpheres<true>(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}
#endif

bool HitCommittedSpheres(const Scene *scene, const SceneLayout *layout, int skip, const Ray *ray,
                         real tMin, real *tMax, bool anyHit, RayHit *hit) {
    if (layout->sphereCount == 0) // (a mesh scene: no call, no lanes made for nothing)
        return false;
    if (!layout->sphereNodes.empty()) {
#if RT_DISPATCH
        if (layout->vectors)
            return SphereTreeAvx2(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
#endif
        return SphereTreeBaseline(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
    }
    bool one = layout->sphereCount <= (size_t)(kChunkBlocks * kLanes);
#if RT_DISPATCH
    if (layout->vectors)
        return one ? OneChunkAvx2(scene, layout, skip, ray, tMin, tMax, anyHit, hit)
                   : ChunksAvx2(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
#endif
    return one ? OneChunkBaseline(scene, layout, skip, ray, tMin, tMax, anyHit, hit)
               : ChunksBaseline(scene, layout, skip, ray, tMin, tMax, anyHit, hit);
}

// Packets of rays from the eye (kernel_packet.h), in the AVX2 copy only: lane by lane they would
// repeat the one-ray loop's work with more bookkeeping.
#if RT_DISPATCH
RT_AVX2 static void PacketAvx2(const Scene *scene, const SceneLayout *layout, PacketSearch *p) {
    int kz = p->packet->kz;
    if (kz == 0)
        SearchPacket<0>(scene, layout, p);
    else if (kz == 1)
        SearchPacket<1>(scene, layout, p);
    else
        SearchPacket<2>(scene, layout, p);
}
#endif

bool HitCommittedPacket(const Scene *scene, const SceneLayout *layout, const RayPacket *packet,
                        RayHit *hits, bool *found) {
#if RT_DISPATCH
    int count = packet->count;
    if (!layout->vectors || !layout->wideNodes.empty() || !layout->sphereNodes.empty() ||
        count < 1 || count > kLanes || packet->kz < 0 || packet->kz > 2)
        return false;
    PacketSearch p;
    p.packet = packet, p.active = (1u << count) - 1, p.hits = hits;
    PacketAvx2(scene, layout, &p);
    for (int r = 0; r < count; r++)
        found[r] = p.found[r];
    return true;
#else
    (void)scene, (void)layout, (void)packet, (void)hits, (void)found;
    return false;
#endif
}

#if RT_DISPATCH
RT_AVX2 static void SetUpAvx2(const Triangle *tri, TriangleSetUp *setUp) { MakeSetUp(tri, setUp); }
#endif

void KernelSetUp(const Triangle *tri, bool vectors, TriangleSetUp *setUp) {
#if RT_DISPATCH
    if (vectors)
        return SetUpAvx2(tri, setUp);
#endif
    (void)vectors;
    MakeSetUp(tri, setUp);
}

bool KernelHasVectors() {
#if RT_DISPATCH
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

const char *KernelName() {
#if RT_DISPATCH
    return KernelHasVectors() ? "avx2" : "sse2";
#elif RT_VECTORS && defined(__aarch64__)
    return "neon";
#elif RT_VECTORS
    return "vector extensions";
#else
    return "scalar";
#endif
}

// ---- the accelerator's two functions (Accelerator, ray.h) ----------------------------------

// Whether the layout answers for this search: made from this very scene (not a copy), which
// still holds as many shapes as it did, and the robust sphere and triangle tests, the only ones
// the kernel has. (The handouts' methods are the plain loop, as written.)
static const SceneLayout *Answering(const Accelerator *self, const Scene *scene, Methods methods) {
    const SceneLayout *layout = (const SceneLayout *)self->layout;
    bool same = layout->scene == scene && layout->triangleCount == scene->triangles.size() &&
                layout->sphereCount == scene->spheres.size();
    bool robust = methods.sphere == SPHERE_STABLE && methods.triangle == TRIANGLE_WATERTIGHT;
    return same && robust ? layout : nullptr;
}

// SearchList's steps (geometry.cpp): the ray rescaled where it must be (robust/), the spheres,
// then the triangles, t scaled back; the blocks and the BVH in place of the list.
bool SearchLayout(const Accelerator *self, const Scene *scene, Methods methods, const Ray *given,
                  const SelfHit *from, real tMax, bool anyHit, RayHit *hit) {
    const SceneLayout *layout = Answering(self, scene, methods);
    if (!layout)
        return SearchList(scene, methods, given, from, tMax, anyHit, hit);
    ScaledRay s;
    if (!ScaleRay(given, from->tMin, tMax, &s))
        return false;
    const Ray *ray = SearchedRay(&s, given);
    int skipSphere = from->shape == SHAPE_SPHERE ? from->index : -1;
    int skipTriangle = from->shape == SHAPE_TRIANGLE ? from->index : -1;
    bool found = HitCommittedSpheres(scene, layout, skipSphere, ray, s.tMin, &s.tMax, anyHit, hit);
    if (!(found && anyHit))
        found =
            HitCommittedTriangles(scene, layout, skipTriangle, ray, s.tMin, s.tMax, anyHit, hit) ||
            found;
    return found && ScaleBack(&s, from->tMin, tMax, hit);
}

// Whether a packet costs less than its rays one by one. A packet tests each shape once for all
// its rays, where one ray tests a block of kLanes shapes at once, and a packet's test of one
// shape costs a little more than one ray's test of a block; what the packet saves is each ray's
// own set-up and the blocks' empty lanes, which matter in small scenes only. A packet of one ray is
// one ray's search with more bookkeeping.
const size_t kPacketShapes = 64;
static bool PacketPays(const SceneLayout *layout, int count) {
    return count >= 2 && layout->vectors && layout->wideNodes.empty() &&
           layout->sphereNodes.empty() &&
           layout->triangleCount + layout->sphereCount <= kPacketShapes;
}

// rays[0..count) as one packet, if the kernel can take them (each searched for as it is, with
// one renaming of the axes for all): found[] and hits[] written. False, nothing written, if not.
static bool HitPacket(const Scene *scene, const SceneLayout *layout, const Ray *rays, int count,
                      RayHit *hits, bool *found) {
    RayPacket packet = {rays, count, DominantAxis(rays[0].dir)};
    for (int r = 0; r < count; r++) {
        vec3 d = rays[r].dir;
        if (!SearchedAsIs(d) || DominantAxis(d) != packet.kz) // (ScaleRay would rescale it)
            return false;
    }
    return HitCommittedPacket(scene, layout, &packet, hits, found);
}

void SearchEyeRays(const Accelerator *self, const Scene *scene, Methods methods, const Ray *rays,
                   int count, RayHit *hits, bool *found, bool *answered) {
    const SceneLayout *layout = Answering(self, scene, methods);
    for (int first = 0; layout && first < count; first += kLanes) { // a packet is kLanes rays
        int n = count - first < kLanes ? count - first : kLanes;
        if (!PacketPays(layout, n) ||
            !HitPacket(scene, layout, rays + first, n, hits + first, found + first))
            continue;
        for (int k = first; k < first + n; k++)
            answered[k] = true;
    }
}

// Every eye ray answered: in packets where they pay, the others one at a time, as FindEyeRayHits's
// plain loop would search them.
void AnswerEyeRays(const Accelerator *self, const Scene *scene, Methods methods, const Ray *rays,
                   int count, RayHit *hits, bool *found) {
    bool answered[kEyeRaysTogether] = {};
    if (count >= 2) // (a packet of one ray is that ray's search with more bookkeeping)
        SearchEyeRays(self, scene, methods, rays, count, hits, found, answered);
    for (int k = 0; k < count; k++)
        if (!answered[k])
            found[k] = SearchLayout(self, scene, methods, &rays[k], &kNoSelfHit, kInfinity, false,
                                    &hits[k]);
}

// What --stats says of the triangles.
static std::string DescribeTriangles(const Scene *scene, const SceneLayout *layout,
                                     double buildSeconds) {
    char text[200];
    if (scene->triangles.empty()) // (--layout bvh too: there is nothing to build a tree over)
        return "triangles: none";
    if (scene->accelerator != &layout->accelerator) {
        snprintf(text, sizeof text, "triangles: %zu, tested one by one (the plain loop)",
                 scene->triangles.size());
        return text;
    }
    char tree[64] = "one list";
    bool wide = !layout->wideNodes.empty();
    if (wide)
        snprintf(tree, sizeof tree, "a BVH of %zu nodes of %d", layout->wideNodes.size(), kWide);
    snprintf(text, sizeof text, "triangles: %zu in %zu blocks of %d, %s (built in %.3g ms), %s",
             scene->triangles.size(), wide ? layout->wideBlocks.size() : layout->blocks.size(),
             wide ? kWide : kLanes, tree, buildSeconds * 1e3,
             layout->vectors ? "blocks tested in AVX2 vectors" : "blocks tested lane by lane");
    return text;
}

// What --stats says of the spheres, where they have a tree.
static std::string DescribeSpheres(const Scene *scene, const SceneLayout *layout) {
    if (scene->accelerator != &layout->accelerator || layout->sphereNodes.empty())
        return "";
    char text[120];
    snprintf(text, sizeof text, "; spheres: %zu in a BVH of %zu nodes of %d", scene->spheres.size(),
             layout->sphereNodes.size(), kChildren);
    return text;
}

std::string DescribeLayout(const Scene *scene, const SceneLayout *layout, double buildSeconds) {
    return DescribeTriangles(scene, layout, buildSeconds) + DescribeSpheres(scene, layout);
}
