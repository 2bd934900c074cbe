// kernel.cpp -- the fast triangle loop: blocks of kLanes triangles, and the BVH walk.
//
// Speed machinery, behind the contract of HitWatertightTriangles (watertight.cpp): the same
// hits, bit for bit, found faster. Two steps beyond the plain loop:
//   1. The watertight test's first step (shear the corners, compute the edge functions, reject
//      a triangle whose edges disagree; watertight.cpp, EdgesDisagree) runs on a whole block at
//      once, with GCC/Clang vector extensions: `Lanes` holds kLanes numbers, and every line
//      below is the scalar line with `Lanes` for `real`, the same operations in the same order,
//      so each lane rounds exactly as the scalar code does. Only the triangles that survive go
//      on to the full test, which is the reference function itself (IntersectWatertight).
//   2. With a BVH (commit.cpp), a ray visits only the nodes whose boxes its line passes
//      (SlabInterval, nearer child first) and skips those wholly beyond its nearest hit so far.
//      Every hit lies inside its triangle's window (plane.cpp), and a node's window holds those
//      of the triangles below it, so no box is skipped that holds a hit. Hits at equal t go to
//      the lower place in the scene, as in the list.
// One binary serves every x86-64 machine: target_clones compiles the loop twice, for AVX2 and
// for the baseline (SSE2), and the loader picks one when the program starts.
#include "ray.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__)
#define RT_TARGET_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RT_TARGET_CLONES
#endif
#define RT_INLINE inline __attribute__((always_inline))

// The helpers below pass `Lanes` by value, which without AVX is passed differently from with it;
// GCC warns of that. They are always inlined into the one cloned function, so no call ever
// passes a `Lanes` across the two.
#pragma GCC diagnostic ignored "-Wpsabi"

typedef real Lanes __attribute__((vector_size(32))); // kLanes numbers
typedef decltype(Lanes() < Lanes()) LaneMask;        // per lane: all bits set, or none

// The per-ray numbers of the watertight shear (RayShear), one copy in every lane.
struct LaneRay {
    Lanes ox, oy, oz; // the origin, axes renamed
    Lanes sx, sy;     // the shear
};

static RT_INLINE Lanes Splat(real x) {
    Lanes v;
    for (int i = 0; i < kLanes; i++)
        v[i] = x;
    return v;
}

static RT_INLINE Lanes Load(const real *p) {
    Lanes v;
    memcpy(&v, p, sizeof v);
    return v;
}

// One corner of every lane sheared as ShearCorners does it: A = renamed corner - origin, then
// x = A.x - sx A.z, y = A.y - sy A.z. (RenameAxes<kz> reads axes kz + 1, kz + 2, kz, mod 3.)
template <int kz>
static RT_INLINE void ShearLanes(const TriangleBlock *b, int corner, const LaneRay *r, Lanes *x,
                                 Lanes *y) {
    Lanes Ax = Load(b->corner[3 * corner + (kz + 1) % 3]) - r->ox;
    Lanes Ay = Load(b->corner[3 * corner + (kz + 2) % 3]) - r->oy;
    Lanes Az = Load(b->corner[3 * corner + kz]) - r->oz;
    *x = Ax - r->sx * Az;
    *y = Ay - r->sy * Az;
}

// The lanes whose triangles survive EdgesDisagree (watertight.cpp), as bits: the same edge
// functions, U = Cx By - Cy Bx, V = Ax Cy - Ay Cx, W = Bx Ay - By Ax, and a triangle is out when
// two of them have strictly opposite signs.
template <int kz> static RT_INLINE unsigned Survivors(const TriangleBlock *b, const LaneRay *r) {
    Lanes ax, ay, bx, by, cx, cy, zero = Splat(0);
    ShearLanes<kz>(b, 0, r, &ax, &ay);
    ShearLanes<kz>(b, 1, r, &bx, &by);
    ShearLanes<kz>(b, 2, r, &cx, &cy);
    Lanes u = cx * by - cy * bx;
    Lanes v = ax * cy - ay * cx;
    Lanes w = bx * ay - by * ax;
    LaneMask out = ((u < zero) & (v > zero)) | ((u > zero) & (v < zero)) |
                   ((w < zero) & ((u > zero) | (v > zero))) |
                   ((w > zero) & ((u < zero) | (v < zero)));
    unsigned live = 0;
    for (int i = 0; i < kLanes; i++)
        live |= (unsigned)(out[i] == 0) << i;
    return live;
}

// The search so far: the ray, its interval, the nearest hit and its triangle's place.
struct Search {
    const Triangle *triangles;
    const Box *boxes; // the triangles' boxes (SceneLayout)
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
template <int kz>
static RT_INLINE bool TestBlocks(const TriangleBlock *blocks, int first, int count, Search *s,
                                 RayHit *hit) {
    bool found = false;
    for (const TriangleBlock *b = blocks + first; b < blocks + first + count; b++) {
        for (unsigned live = Survivors<kz>(b, &s->lanes); live != 0; live &= live - 1) {
            int index = b->index[__builtin_ctz(live)];
            if (index < 0 || index == s->skip)
                continue;
            real limit =
                s->best >= 0 && index < s->best ? std::nextafter(s->tMax, kInfinity) : s->tMax;
            if (!IntersectWatertight(&s->triangles[index], &s->boxes[index], s->ray, s->shear,
                                     s->tMin, limit, hit))
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

static RT_INLINE Quad LoadQuad(const real *p) {
    Quad v;
    memcpy(&v, p, sizeof v);
    return v;
}
static RT_INLINE Quad SplatQuad(real x) {
    Quad v;
    for (int i = 0; i < kWidth; i++)
        v[i] = x;
    return v;
}
static RT_INLINE Quad Select(QuadMask m, Quad yes, Quad no) {
    return (Quad)(((QuadMask)yes & m) | ((QuadMask)no & ~m));
}

static RT_INLINE void ChildWindows(const BvhNode *n, const SlabRay *r, Quad *tNear, Quad *tFar) {
    Quad pad = SplatQuad(kBoxAllowance) * LoadQuad(n->size) + SplatQuad(r->originPad);
    const real o[3] = {r->origin.x, r->origin.y, r->origin.z};
    const real inv[3] = {r->inverse.x, r->inverse.y, r->inverse.z};
    Quad near = SplatQuad(-kInfinity), far = SplatQuad(kInfinity);
    for (int i = 0; i < 3; i++) {
        Quad a = ((LoadQuad(n->lo[i]) - pad) - SplatQuad(o[i])) * SplatQuad(inv[i]);
        Quad b = ((LoadQuad(n->hi[i]) + pad) - SplatQuad(o[i])) * SplatQuad(inv[i]);
        Quad first = r->backward[i] ? b : a, last = r->backward[i] ? a : b;
        near = Select(first > near, first, near); // (NaN compares false: no restriction)
        far = Select(last < far, last, far);
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
    Pending hit[kWidth];
    int count = 0;
    for (int k = 0; k < kWidth; k++) {
        if (n->blocks[k] < 0 || !(near[k] <= far[k] && near[k] <= s->tMax && far[k] >= s->tMin))
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
template <int kz>
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
        } else if (TestBlocks<kz>(layout->blocks.data(), p.child, p.blocks, s, hit)) {
            found = true;
            if (s->anyHit)
                return true;
        }
    }
    return found;
}

template <int kz>
static RT_INLINE bool HitLayout(const SceneLayout *layout, Search *s, RayHit *hit) {
    if (layout->nodes.empty())
        return TestBlocks<kz>(layout->blocks.data(), 0, (int)layout->blocks.size(), s, hit);
    return WalkTree<kz>(layout, s, hit);
}

RT_TARGET_CLONES
bool HitCommittedTriangles(const Scene *scene, int skip, const Ray *ray, const RayShear *shear,
                           real tMin, real tMax, bool anyHit, RayHit *hit) {
    Search s = {scene->triangles.data(),
                scene->layout.boxes.data(),
                ray,
                shear,
                {},
                {Splat(shear->origin.x), Splat(shear->origin.y), Splat(shear->origin.z),
                 Splat(shear->sx), Splat(shear->sy)},
                skip,
                tMin,
                tMax,
                -1,
                anyHit};
    if (shear->kz == 0)
        return HitLayout<0>(&scene->layout, &s, hit);
    if (shear->kz == 1)
        return HitLayout<1>(&scene->layout, &s, hit);
    return HitLayout<2>(&scene->layout, &s, hit);
}

const char *KernelInstructions() {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__)
    return __builtin_cpu_supports("avx2") ? "avx2" : "sse2";
#else
    return "portable";
#endif
}
