// kernel_spheres.h -- the sphere half of the fast shape loop (kernel.cpp): the stable sphere
// test's first step on kLanes spheres at once, and the reference test for those whose line may
// meet them. Included by kernel.cpp alone (it uses kernel_blocks.h's Lanes, Load and LaneBits), so
// that each of the kernel's two compiled copies inlines all of it.
//
// The first step is LineMissesSphere (geometry.cpp): with f = o - c, the discriminant
// A r^2 - |f x d|^2 (SphereDiscriminant) is negative exactly when the ray's line passes the
// centre farther than the radius, and it is trusted only when A r^2 is a normal number. Every
// line below is that function's line with `Lanes` for `real`, the same operations in the same
// order (and the Makefile's -ffp-contract=off keeps them unfused), so each lane rounds exactly
// as the scalar code does. The spheres that remain go to IntersectSphere itself, in scene order.
#pragma once
#include "kernel_blocks.h"

// The per-ray numbers of LineMissesSphere, one copy in every lane.
struct SphereLaneRay {
    Lanes ox, oy, oz; // the origin
    Lanes dx, dy, dz; // the direction
    Lanes a;          // A = d.d, rounded as Dot rounds it
};

// x in every lane, written whole (Splat writes lane by lane, which GCC 12 takes for a read of
// lanes not yet written when the loop of TestChunks holds it).
static RT_INLINE void Fill(Lanes *v, real x) {
    real each[kLanes];
    for (int i = 0; i < kLanes; i++)
        each[i] = x;
    memcpy(v, each, sizeof *v);
}

// The ray's six numbers are read one at a time (`volatile` keeps each load whole and apart):
// GCC would read them as one vector, which cannot be taken from the caller's stores of them, a
// moment before, until they reach the cache (every search starts here).
static RT_INLINE void SplatSphereRay(const Ray *ray, SphereLaneRay *r) {
    const volatile vec3 &origin = ray->origin, &dir = ray->dir;
    vec3 o = {origin.x, origin.y, origin.z}, d = {dir.x, dir.y, dir.z};
    Fill(&r->ox, o.x), Fill(&r->oy, o.y), Fill(&r->oz, o.z);
    Fill(&r->dx, d.x), Fill(&r->dy, d.y), Fill(&r->dz, d.z);
    Fill(&r->a, Dot(d, d));
}

// The lanes whose line misses its sphere, as bits (lane i at bit i): LineMissesSphere's lines
// with `Lanes` for `real`, for each lane's origin o, centre c, direction d, A = d.d and r^2 (a
// block's spheres for one ray here, one sphere for a packet's rays in kernel_packet.h).
static RT_INLINE unsigned MissingLanes(const Lanes o[3], const Lanes c[3], const Lanes d[3],
                                       const Lanes *a, const Lanes *r2) {
    Lanes zero, tiny;
    Fill(&zero, 0), Fill(&tiny, std::numeric_limits<real>::min());
    Lanes fx = o[0] - c[0], fy = o[1] - c[1], fz = o[2] - c[2]; // f = o - c
    Lanes ux = fy * d[2] - fz * d[1];                           // f x d, as Cross writes it
    Lanes uy = fz * d[0] - fx * d[2];
    Lanes uz = fx * d[1] - fy * d[0];
    Lanes ar2 = *a * *r2;
    Lanes disc = ar2 - (ux * ux + uy * uy + uz * uz); // Dot: (x x + y y) + z z
    LaneMask misses = (disc < zero) & (ar2 >= tiny);
    return LaneBits(&misses);
}

// The lanes of block b whose line may meet the ray, as bits (lane i at bit i): those for which
// LineMissesSphere is false, and only lanes that hold a sphere.
static RT_INLINE unsigned MayMeet(const SphereBlock *b, const SphereLaneRay *r) {
    Lanes c[3], r2;
    Load(&c[0], b->center[0]), Load(&c[1], b->center[1]), Load(&c[2], b->center[2]);
    Load(&r2, b->r2);
    const Lanes o[3] = {r->ox, r->oy, r->oz}, d[3] = {r->dx, r->dy, r->dz};
    return ~MissingLanes(o, c, d, &r->a, &r2) & b->filled;
}

// The same lanes one by one, with LineMissesSphere's scalar operations in the same order; only
// the filled lanes are computed.
static RT_INLINE unsigned MayMeetOneByOne(const SphereBlock *b, const Ray *ray) {
    vec3 d = ray->dir;
    real a = Dot(d, d);
    unsigned live = 0;
    for (unsigned left = b->filled; left != 0; left &= left - 1) {
        int lane = LowestBit(left);
        vec3 c = {b->center[0][lane], b->center[1][lane], b->center[2][lane]};
        vec3 fxd = Cross(ray->origin - c, d);
        real ar2 = a * b->r2[lane];
        bool misses = ar2 - Dot(fxd, fxd) < 0 && ar2 >= std::numeric_limits<real>::min();
        live |= (unsigned)!misses << lane;
    }
    return live;
}

// The blocks a search tests at a time: their masks are made first, one bit a sphere in one 64-bit
// word (64 spheres, in double or float), so that no vector is still needed (and kept in memory)
// while IntersectSphere runs.
const int kChunkBlocks = 64 / kLanes;

// What a search of the spheres keeps from one block (or chunk) to the next, with the numbers of
// the ray that SphereT reuses, made when first needed (`prepared`): A = d.d, and whether the ray
// is one IntersectSphere takes unscaled (its direction within the window) with tMin >= 0.
struct SphereSearch {
    const Sphere *spheres;
    const Ray *ray;
    int skip;
    real tMin, tMax;
    int best; // place of the nearest sphere hit so far; -1: none
    bool anyHit;
    real a;
    bool bounds, prepared;
};

static RT_INLINE SphereSearch StartSphereSearch(const Scene *scene, int skip, const Ray *ray,
                                                real tMin, real tMax, bool anyHit) {
    SphereSearch s = {scene->spheres.data(), ray, skip, tMin, tMax, -1, anyHit, 0, false, false};
    return s;
}

static RT_INLINE void PrepareSphereT(SphereSearch *s) {
    s->a = Dot(s->ray->dir, s->ray->dir);
    s->bounds = s->tMin >= 0 && WithinWindow(MaxComponent(s->ray->dir), kDirectionWindow);
    s->prepared = true;
}

// Where IntersectSphere will put its hit on a sphere that the first step passed, found first so
// that the spheres can be taken nearest first: SolveSphere's t (geometry.cpp), by its very
// operations in the same order, where IntersectSphere needs no rescaling (the direction, the
// radius and o - c within its windows, and tMin >= 0); infinity where it will find no root after
// tMin; 0 where it would rescale (then it is simply tested). IntersectSphere's own answer is
// this t, or no hit at all (beyond tMax, or a point it refuses), so a sphere whose t lies beyond
// the nearest hit so far is refused unopened.
static RT_INLINE real SphereT(const SphereSearch *s, const Sphere *sphere) {
    vec3 f = s->ray->origin - sphere->center, d = s->ray->dir;
    real r = sphere->radius;
    if (!s->bounds || !WithinWindow(r, kLengthWindow) ||
        !(MaxComponent(f) <= PowerOfTwo(kLengthWindow)))
        return 0;
    real A = s->a, halfB = Dot(f, d), C = Dot(f, f) - r * r;
    if (halfB > 0 && C > 0) // behind the ray
        return kInfinity;
    vec3 fxd = Cross(f, d);
    real disc = A * (r * r) - Dot(fxd, fxd), sqrtDisc = std::sqrt(disc);
    if (!(disc >= 0))
        return kInfinity;
    real q = -(halfB + std::copysign(sqrtDisc, halfB));
    if (q == 0)
        return kInfinity;
    real t0 = C / q, t1 = q / A;
    if (t0 > t1)
        std::swap(t0, t1);
    return t0 > s->tMin ? t0 : t1 > s->tMin ? t1 : kInfinity;
}

// The reference test (IntersectSphere) for sphere `index`, as the plain loop (HitList,
// geometry.cpp) would have it: a sphere at the same t as the nearest so far counts only if it
// comes earlier in the scene (so the tMax it is tested against is one step above). A hit lowers
// tMax to its t.
static RT_INLINE bool TestSphere(SphereSearch *s, int index, RayHit *hit) {
    real limit = s->best >= 0 && index < s->best ? NextAfter(s->tMax, true) : s->tMax;
    if (!IntersectSphere(&s->spheres[index], s->ray, s->tMin, limit, hit))
        return false;
    hit->index = s->best = index;
    s->tMax = hit->t;
    return true;
}

// The reference test for the spheres at places[0..count) (at most kChunkBlocks * kLanes) whose
// line the first step could not refuse: a lone one at once; of several, those whose t is not
// known ahead (SphereT) in their order, then the others nearest first, until one lies beyond the
// nearest hit, where the rest can only be farther. Each hit is the plain loop's, ties included
// (TestSphere), so the order changes no answer. Out of line, and with few enough arguments to be
// reached by a jump: most searches have no such sphere, and they then need no registers saved.
template <bool kAnyHit>
static RT_NOINLINE bool TestLiveSpheres(SphereSearch *s, const int *places, int count,
                                        RayHit *hit) {
    struct Later {
        real t;
        int index;
    } later[64];
    int waiting = 0;
    bool found = false;
    if (count > 1 && !s->prepared)
        PrepareSphereT(s);
    for (int k = 0; k < count; k++) {
        int index = places[k];
        if (index == s->skip)
            continue;
        real t = count == 1 ? 0 : SphereT(s, &s->spheres[index]);
        if (t > 0) { // kept in order of t, by insertion
            int at = waiting++;
            for (; at > 0 && later[at - 1].t > t; at--)
                later[at] = later[at - 1];
            later[at] = {t, index};
        } else if (TestSphere(s, index, hit)) {
            found = true;
            if (kAnyHit)
                return true;
        }
    }
    for (int k = 0; k < waiting && !(later[k].t > s->tMax); k++)
        if (TestSphere(s, later[k].index, hit)) {
            found = true;
            if (kAnyHit)
                return true;
        }
    return found;
}

// The spheres whose bits are set in `live` (bit i: the sphere at place first + i).
static RT_INLINE bool HitLive(SphereSearch *s, uint64_t live, int first, RayHit *hit) {
    int places[64], count = 0;
    for (; live != 0; live &= live - 1)
        places[count++] = first + LowestBit(live);
    return s->anyHit ? TestLiveSpheres<true>(s, places, count, hit)
                     : TestLiveSpheres<false>(s, places, count, hit);
}

// The bits of the spheres in blocks [first, last) that pass the first step, sphere
// first * kLanes + j at bit j (at most kChunkBlocks blocks).
template <bool kVectors>
static RT_INLINE uint64_t ChunkMask(const SphereBlock *blocks, int first, int last,
                                    const Ray *ray) {
    uint64_t live = 0;
    if (kVectors) {
        SphereLaneRay lanes;
        SplatSphereRay(ray, &lanes);
        for (int k = first; k < last; k++)
            live |= (uint64_t)MayMeet(&blocks[k], &lanes) << (k - first) * kLanes;
    } else {
        for (int k = first; k < last; k++)
            live |= (uint64_t)MayMeetOneByOne(&blocks[k], ray) << (k - first) * kLanes;
    }
    return live;
}

// The plain loop's spheres (HitList, geometry.cpp) for a scene of at most kChunkBlocks blocks (most
// scenes): the masks, and only if a sphere passed, one call.
template <bool kVectors>
static RT_INLINE bool TestOneChunk(const Scene *scene, const SceneLayout *layout, int skip,
                                   const Ray *ray, real tMin, real *tMax, bool anyHit,
                                   RayHit *hit) {
    int n = Blocks((int)layout->sphereCount);
    const SphereBlock *blocks = layout->sphereBlocks.data();
    // One block (4 spheres in double, 8 in float: the assignment's 3, the Cornell box's 2) with
    // no loop at all
    uint64_t live =
        n == 1 ? ChunkMask<kVectors>(blocks, 0, 1, ray) : ChunkMask<kVectors>(blocks, 0, n, ray);
    if (live == 0)
        return false;
    SphereSearch s = StartSphereSearch(scene, skip, ray, tMin, *tMax, anyHit);
    bool found = HitLive(&s, live, 0, hit);
    *tMax = s.tMax;
    return found;
}

// The same for any number of blocks, a chunk at a time.
template <bool kVectors>
static RT_INLINE bool TestChunks(const Scene *scene, const SceneLayout *layout, int skip,
                                 const Ray *ray, real tMin, real *tMax, bool anyHit, RayHit *hit) {
    const SphereBlock *blocks = layout->sphereBlocks.data();
    int n = Blocks((int)layout->sphereCount);
    SphereSearch s = StartSphereSearch(scene, skip, ray, tMin, *tMax, anyHit);
    bool found = false;
    for (int chunk = 0; chunk < n && !(found && anyHit); chunk += kChunkBlocks) {
        uint64_t live = ChunkMask<kVectors>(blocks, chunk, std::min(n, chunk + kChunkBlocks), ray);
        found = (live != 0 && HitLive(&s, live, chunk * kLanes, hit)) || found;
    }
    *tMax = s.tMax;
    return found;
}
