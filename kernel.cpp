// kernel.cpp -- the fast triangle loop: blocks of kLanes triangles, and the BVH walk.
//
// Speed machinery, behind the contract of HitWatertightTriangles (watertight.cpp): the same
// hits, bit for bit, found faster. Two steps beyond the plain loop:
//   1. The watertight test's first step (shear the corners, compute the edge functions, reject
//      a triangle whose edges disagree; watertight.cpp, EdgesDisagree) runs on a whole block at
//      once, with GCC/Clang vector extensions: `Lanes` holds kLanes numbers, and every line
//      below is the scalar line with `Lanes` for `real`, the same operations in the same order,
//      so each lane rounds exactly as the scalar code does. Only the triangles that survive go
//      on to the rest of the reference test: where their three edge functions have a certain
//      sign (none 0 or NaN), what IntersectSheared (watertight.cpp) does next is to call
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
#include "ray.h"

#if defined(__x86_64__) && defined(__GNUC__)
#define RT_DISPATCH 1
#define RT_AVX2 __attribute__((target("avx2")))
#else
#define RT_DISPATCH 0
#endif
#define RT_INLINE inline __attribute__((always_inline))

// The helpers below write their vectors through pointers and never return one: a 256-bit vector
// is returned differently with AVX than without, which clang refuses in the baseline copy and GCC
// warns of. They take them by value only where always inlined, so no call passes one.
#pragma GCC diagnostic ignored "-Wpsabi"

typedef real Lanes __attribute__((vector_size(32))); // kLanes numbers
typedef decltype(Lanes() < Lanes()) LaneMask;        // per lane: all bits set, or none

// The per-ray numbers of the watertight shear (RayShear), one copy in every lane.
struct LaneRay {
    Lanes ox, oy, oz; // the origin, axes renamed
    Lanes sx, sy;     // the shear
};

static RT_INLINE void Splat(Lanes *v, real x) {
    *v = Lanes{};
    for (int i = 0; i < kLanes; i++)
        (*v)[i] = x;
}

static RT_INLINE void Load(Lanes *v, const real *p) { memcpy(v, p, sizeof *v); }

// One corner of every lane sheared as ShearCorners does it: A = renamed corner - origin, then
// x = A.x - sx A.z, y = A.y - sy A.z. (RenameAxes<kz> reads axes kz + 1, kz + 2, kz, mod 3.)
template <int kz>
static RT_INLINE void ShearLanes(const TriangleBlock *b, int corner, const LaneRay *r, Lanes *x,
                                 Lanes *y) {
    Lanes Ax, Ay, Az;
    Load(&Ax, b->corner[3 * corner + (kz + 1) % 3]);
    Load(&Ay, b->corner[3 * corner + (kz + 2) % 3]);
    Load(&Az, b->corner[3 * corner + kz]);
    Ax = Ax - r->ox, Ay = Ay - r->oy, Az = Az - r->oz;
    *x = Ax - r->sx * Az;
    *y = Ay - r->sy * Az;
}

// The lanes whose triangles survive EdgesDisagree (watertight.cpp), as bits: the same edge
// functions, U = Cx By - Cy Bx, V = Ax Cy - Ay Cx, W = Bx Ay - By Ax, and a triangle is out when
// two of them have strictly opposite signs. *sure: the survivors whose three edge functions are
// neither 0 nor NaN (a NaN compares false both ways), so that the ray passes inside for certain.
template <int kz>
static RT_INLINE unsigned Survivors(const TriangleBlock *b, const LaneRay *r, unsigned *sure) {
    Lanes ax, ay, bx, by, cx, cy, zero;
    Splat(&zero, 0);
    ShearLanes<kz>(b, 0, r, &ax, &ay);
    ShearLanes<kz>(b, 1, r, &bx, &by);
    ShearLanes<kz>(b, 2, r, &cx, &cy);
    Lanes u = cx * by - cy * bx;
    Lanes v = ax * cy - ay * cx;
    Lanes w = bx * ay - by * ax;
    LaneMask out = ((u < zero) & (v > zero)) | ((u > zero) & (v < zero)) |
                   ((w < zero) & ((u > zero) | (v > zero))) |
                   ((w > zero) & ((u < zero) | (v < zero)));
    // Most blocks have no survivor: one test of all lanes at once, as four 64-bit words, before
    // the lanes are looked at one by one
    uint64_t word[4];
    memcpy(word, &out, sizeof word);
    if ((word[0] & word[1] & word[2] & word[3]) == ~uint64_t(0))
        return 0;
    LaneMask certain =
        ((u < zero) | (u > zero)) & ((v < zero) | (v > zero)) & ((w < zero) | (w > zero));
    unsigned live = 0, known = 0;
    for (int i = 0; i < kLanes; i++) {
        live |= (unsigned)(out[i] == 0) << i;
        known |= (unsigned)(certain[i] != 0) << i;
    }
    *sure = live & known;
    return live;
}

// The same lanes one by one, for a processor without AVX2: there a block of four doubles takes two
// SSE2 registers for every operation, and the scalar test, which stops after two edge functions
// for most triangles, is faster (measured: 1.5 s against 0.85 s for the assignment at 16 spp).
// The operations and their order are EdgesDisagree's, so the answer is the same.
template <int kz>
static RT_INLINE unsigned SurvivorsOneByOne(const TriangleBlock *b, const RayShear *k,
                                            unsigned *sure) {
    const int X = (kz + 1) % 3, Y = (kz + 2) % 3, Z = kz;
    unsigned live = 0;
    *sure = 0;
    for (int lane = 0; lane < kLanes; lane++) {
        real s[6];
        for (int corner = 0; corner < 3; corner++) {
            real Ax = b->corner[3 * corner + X][lane] - k->origin.x;
            real Ay = b->corner[3 * corner + Y][lane] - k->origin.y;
            real Az = b->corner[3 * corner + Z][lane] - k->origin.z;
            s[2 * corner] = Ax - k->sx * Az, s[2 * corner + 1] = Ay - k->sy * Az;
        }
        real u = s[4] * s[3] - s[5] * s[2], v = s[0] * s[5] - s[1] * s[4];
        if ((u < 0 && v > 0) || (u > 0 && v < 0))
            continue;
        real w = s[2] * s[1] - s[3] * s[0];
        if ((w < 0 && (u > 0 || v > 0)) || (w > 0 && (u < 0 || v < 0)))
            continue;
        live |= 1u << lane;
        bool certain = (u < 0 || u > 0) && (v < 0 || v > 0) && (w < 0 || w > 0);
        *sure |= (unsigned)certain << lane;
    }
    return live;
}

// The search so far: the ray, its interval, the nearest hit and its triangle's place.
struct Search {
    const Triangle *triangles;
    const TriangleSetUp *setUps; // the triangles' boxes and planes (SceneLayout)
    const Ray *ray;
    const RayShear *shear;
    SlabRay slab; // for the BVH's boxes (SlabInterval)
    LaneRay lanes;
    int skip;
    real tMin, tMax;
    int best; // place of the nearest triangle hit so far; -1: none (or only a sphere)
    bool anyHit;
};

// The full test for the survivors of blocks [first, first + count). A triangle at the same t
// as the nearest so far counts only if it comes earlier in the scene (so the tMax it is tested
// against is one step above). True if anything was hit.
template <int kz, bool kWide>
static RT_INLINE bool TestBlocks(const TriangleBlock *blocks, int first, int count, Search *s,
                                 RayHit *hit) {
    bool found = false;
    for (const TriangleBlock *b = blocks + first; b < blocks + first + count; b++) {
        unsigned sure;
        unsigned live =
            kWide ? Survivors<kz>(b, &s->lanes, &sure) : SurvivorsOneByOne<kz>(b, s->shear, &sure);
        for (; live != 0; live &= live - 1) {
            int lane = __builtin_ctz(live), index = b->index[lane];
            if (index < 0 || index == s->skip)
                continue;
            real limit = s->best >= 0 && index < s->best ? NextAfter(s->tMax, true) : s->tMax;
            const Triangle *tri = &s->triangles[index];
            const TriangleSetUp *setUp = &s->setUps[index];
            if (!(sure >> lane & 1u
                      ? RobustPlaneHit(tri, setUp, s->ray, s->tMin, limit, hit)
                      : IntersectWatertight(tri, setUp, s->ray, s->shear, s->tMin, limit, hit)))
                continue;
            hit->index = s->best = index;
            s->tMax = hit->t;
            found = true;
            if (s->anyHit)
                return true;
        }
    }
    return found;
}

// The four children of a node tested at once: SlabInterval for each, lane by lane, with the
// same operations in the same order (so a child's window is exactly what SlabInterval gives).
typedef real Quad __attribute__((vector_size(kWidth * sizeof(real))));
typedef decltype(Quad() < Quad()) QuadMask;

static RT_INLINE void LoadQuad(Quad *v, const real *p) { memcpy(v, p, sizeof *v); }
static RT_INLINE void SplatQuad(Quad *v, real x) {
    *v = Quad{};
    for (int i = 0; i < kWidth; i++)
        (*v)[i] = x;
}
// *to = yes where m is set, else what *to holds
static RT_INLINE void Select(Quad *to, const QuadMask *m, const Quad *yes) {
    *to = (Quad)(((QuadMask)*yes & *m) | ((QuadMask)*to & ~*m));
}

static RT_INLINE void ChildWindows(const BvhNode *n, const SlabRay *r, Quad *tNear, Quad *tFar) {
    Quad size, allowance, originPad, pad, near, far;
    LoadQuad(&size, n->size);
    SplatQuad(&allowance, kBoxAllowance), SplatQuad(&originPad, r->originPad);
    pad = allowance * size + originPad;
    SplatQuad(&near, -kInfinity), SplatQuad(&far, kInfinity);
    const real origin[3] = {r->origin.x, r->origin.y, r->origin.z};
    const real inverse[3] = {r->inverse.x, r->inverse.y, r->inverse.z};
    for (int i = 0; i < 3; i++) {
        Quad lo, hi, o, inv;
        LoadQuad(&lo, n->lo[i]), LoadQuad(&hi, n->hi[i]);
        SplatQuad(&o, origin[i]), SplatQuad(&inv, inverse[i]);
        Quad a = ((lo - pad) - o) * inv, b = ((hi + pad) - o) * inv;
        Quad first = r->backward[i] ? b : a, last = r->backward[i] ? a : b;
        QuadMask nearer = first > near, closer = last < far;
        Select(&near, &nearer, &first); // (NaN compares false: no restriction)
        Select(&far, &closer, &last);
    }
    *tNear = near, *tFar = far;
}

// A child waiting to be visited, and where its window begins.
struct Pending {
    int child, blocks; // as in BvhNode
    real near;
};

// Deepest tree the walk can follow: commit.cpp's median splits past depth 48 halve the
// triangles, so even 2^31 of them stay well inside. Each node visited leaves at most three
// more children waiting than it takes away.
const int kMaxDepth = 128;

// The children of node n whose windows meet (tMin, tMax), onto the stack, the nearest on top.
static RT_INLINE void PushChildren(const BvhNode *n, const Search *s, Pending *stack, int *top) {
    Quad near, far;
    ChildWindows(n, &s->slab, &near, &far);
    Quad tMin, tMax;
    SplatQuad(&tMin, s->tMin), SplatQuad(&tMax, s->tMax);
    QuadMask open = (near <= far) & (near <= tMax) & (far >= tMin); // all four at once
    Pending hit[kWidth];
    int count = 0;
    for (int k = 0; k < kWidth; k++) {
        if (!open[k] || n->blocks[k] < 0)
            continue;
        int at = count++; // insertion by near, farthest first
        while (at > 0 && hit[at - 1].near < near[k])
            hit[at] = hit[at - 1], at--;
        hit[at] = {n->child[k], n->blocks[k], near[k]};
    }
    for (int k = 0; k < count; k++)
        stack[(*top)++] = hit[k];
}

// The BVH walk: a child whose window (SlabInterval) misses (tMin, tMax) is skipped, the others
// are visited nearest first, so the nearest hit shrinks tMax early, and a child whose window
// begins beyond it by the time its turn comes is skipped too. (A window that begins exactly at
// tMax is visited: it may hold a tie that an earlier triangle wins.)
template <int kz, bool kWide>
static RT_INLINE bool WalkTree(const SceneLayout *layout, Search *s, RayHit *hit) {
    Pending stack[3 * kMaxDepth + kWidth];
    int top = 0;
    s->slab = MakeSlabRay(s->ray);
    bool found = false;
    PushChildren(&layout->nodes[0], s, stack, &top);
    while (top > 0) {
        Pending p = stack[--top];
        if (p.near > s->tMax)
            continue;
        if (p.blocks == 0) {
            PushChildren(&layout->nodes[p.child], s, stack, &top);
        } else if (TestBlocks<kz, kWide>(layout->blocks.data(), p.child, p.blocks, s, hit)) {
            found = true;
            if (s->anyHit)
                return true;
        }
    }
    return found;
}

template <int kz, bool kWide>
static RT_INLINE bool HitLayout(const SceneLayout *layout, Search *s, RayHit *hit) {
    if (layout->nodes.empty())
        return TestBlocks<kz, kWide>(layout->blocks.data(), 0, (int)layout->blocks.size(), s, hit);
    return WalkTree<kz, kWide>(layout, s, hit);
}

// The whole search for one ray, compiled into each of the two copies below.
template <bool kWide>
static RT_INLINE bool HitAll(const Scene *scene, int skip, const Ray *ray, const RayShear *shear,
                             real tMin, real tMax, bool anyHit, RayHit *hit) {
    Search s = {scene->triangles.data(),
                scene->layout.setUps.data(),
                ray,
                shear,
                {},
                {},
                skip,
                tMin,
                tMax,
                -1,
                anyHit};
    Splat(&s.lanes.ox, shear->origin.x), Splat(&s.lanes.oy, shear->origin.y);
    Splat(&s.lanes.oz, shear->origin.z), Splat(&s.lanes.sx, shear->sx);
    Splat(&s.lanes.sy, shear->sy);
    if (shear->kz == 0)
        return HitLayout<0, kWide>(&scene->layout, &s, hit);
    if (shear->kz == 1)
        return HitLayout<1, kWide>(&scene->layout, &s, hit);
    return HitLayout<2, kWide>(&scene->layout, &s, hit);
}

static bool HitBaseline(const Scene *scene, int skip, const Ray *ray, const RayShear *shear,
                        real tMin, real tMax, bool anyHit, RayHit *hit) {
    return HitAll<false>(scene, skip, ray, shear, tMin, tMax, anyHit, hit);
}

#if RT_DISPATCH
RT_AVX2 static bool HitAvx2(const Scene *scene, int skip, const Ray *ray, const RayShear *shear,
                            real tMin, real tMax, bool anyHit, RayHit *hit) {
    return HitAll<true>(scene, skip, ray, shear, tMin, tMax, anyHit, hit);
}
#endif

bool HitCommittedTriangles(const Scene *scene, int skip, const Ray *ray, const RayShear *shear,
                           real tMin, real tMax, bool anyHit, RayHit *hit) {
#if RT_DISPATCH
    if (scene->layout.wide)
        return HitAvx2(scene, skip, ray, shear, tMin, tMax, anyHit, hit);
#endif
    return HitBaseline(scene, skip, ray, shear, tMin, tMax, anyHit, hit);
}

bool KernelCanBeWide() {
#if RT_DISPATCH
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}
