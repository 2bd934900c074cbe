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

// What every node visit of one ray reuses: SlabRay's numbers, one copy in every lane, and for
// each axis the plane of a box the ray meets first (entry) and last (exit). SlabInterval takes
// ((lo - pad) - o) / d and ((hi + pad) - o) / d and then picks first and last by the sign of
// 1/d; here the sign picks, once per ray, which of a node's arrays each plane is read from and
// the sign its pad takes (lo - pad is lo + (-pad), exactly: IEEE subtraction is the addition
// of the negation), so a visit computes the two it needs and selects nothing.
struct NodeRay {
    Quad origin[3], inverse[3], originPad, tMin;
    QuadMask entrySign[3], exitSign[3]; // the sign bit where the plane is lo (its pad subtracted)
    size_t entry[3], exit[3];           // where that plane's array is in a BvhNode, in bytes
};

static RT_INLINE void MakeNodeRay(const SlabRay *slab, real tMin, const BvhNode *anyNode,
                                  NodeRay *r) {
    const real origin[3] = {slab->origin.x, slab->origin.y, slab->origin.z};
    const real inverse[3] = {slab->inverse.x, slab->inverse.y, slab->inverse.z};
    Quad negativeZero;
    SplatQuad(&negativeZero, -real(0)); // the sign bit alone
    for (int i = 0; i < 3; i++) {
        SplatQuad(&r->origin[i], origin[i]), SplatQuad(&r->inverse[i], inverse[i]);
        const char *node = (const char *)anyNode; // (every node has its arrays at the same places)
        size_t lo = (const char *)anyNode->lo[i] - node, hi = (const char *)anyNode->hi[i] - node;
        QuadMask sign = (QuadMask)negativeZero, none = QuadMask{};
        bool backward = slab->backward[i]; // meets hi before lo
        r->entry[i] = backward ? hi : lo, r->entrySign[i] = backward ? none : sign;
        r->exit[i] = backward ? lo : hi, r->exitSign[i] = backward ? sign : none;
    }
    SplatQuad(&r->originPad, slab->originPad), SplatQuad(&r->tMin, tMin);
}

// Where the ray's line meets one plane of every child's box along axis i (entry or exit, as
// NodeRay picked it), moved out by the pad: SlabInterval's a or b, the same operations in order.
static RT_INLINE void PlaneDistance(const BvhNode *n, size_t plane, const QuadMask *sign,
                                    const Quad *pad, const Quad *o, const Quad *inv, Quad *t) {
    Quad p;
    LoadQuad(&p, (const real *)((const char *)n + plane));
    *t = ((p + (Quad)((QuadMask)*pad ^ *sign)) - *o) * *inv;
}

// Each child's window (SlabInterval) cut to the ray's interval [tMin, tMax]: the maximum and
// the minimum start there instead of at -infinity and infinity. A maximum is the same in any
// order and exact (up to the sign of a zero, which no comparison sees), so this is
// SlabInterval's window cut afterwards, and the three tests of whether it meets the interval
// (near <= far, near <= tMax, far >= tMin) become one: the cut window is not empty. (When
// tMin > tMax every window is empty, and no triangle could be hit anyway.) A window the ray
// starts inside now begins at tMin, so such children are visited in their order in the node,
// the later first, which changes no answer.
static RT_INLINE void ChildWindows(const BvhNode *n, const NodeRay *r, const Quad *tMax,
                                   Quad *tNear, Quad *tFar) {
    Quad size, allowance;
    LoadQuad(&size, n->size);
    SplatQuad(&allowance, kBoxAllowance);
    Quad pad = allowance * size + r->originPad;
    Quad near = r->tMin, far = *tMax;
    for (int i = 0; i < 3; i++) {
        Quad first, last;
        PlaneDistance(n, r->entry[i], &r->entrySign[i], &pad, &r->origin[i], &r->inverse[i],
                      &first);
        PlaneDistance(n, r->exit[i], &r->exitSign[i], &pad, &r->origin[i], &r->inverse[i], &last);
        near = first > near ? first : near; // (NaN compares false: no restriction)
        far = last < far ? last : far;
    }
    *tNear = near, *tFar = far;
}

// The children whose windows meet [tMin, tMax], as one bit a child, child k's at bit 8 k, so
// the walk takes them by counting zeros instead of looking at each lane. Vector extensions
// have no "movemask"; two shuffles gather a byte of each lane's compare (all ones or none)
// into one word, which GCC and clang compile to three instructions with AVX2. Without it the
// shuffles become a dozen moves through memory, and four scalar compares are cheaper.
typedef int QuadInts __attribute__((vector_size(kWidth * sizeof(int))));   // a node's child ints
typedef int LaneInts __attribute__((vector_size(sizeof(Quad))));           // a QuadMask as ints
typedef char QuadBytes __attribute__((vector_size(kWidth * sizeof(int)))); // QuadInts as bytes
typedef char ChildBytes __attribute__((vector_size(kWidth)));              // a byte a child

template <bool kWide>
static RT_INLINE unsigned OpenChildren(const BvhNode *n, const Quad *near, const Quad *far) {
    if (!kWide) {
        unsigned bits = 0;
        for (int k = 0; k < kWidth; k++)
            bits |= (unsigned)((*near)[k] <= (*far)[k] && n->blocks[k] >= 0) << (8 * k);
        return bits;
    }
    QuadMask open = *near <= *far; // all four at once
    LaneInts lanes;
    memcpy(&lanes, &open, sizeof lanes);
    const int R = sizeof(real) / sizeof(int); // a lane's ints: each is all ones, or none
    QuadInts blocks, child = __builtin_shufflevector(lanes, lanes, 0, R, 2 * R, 3 * R);
    memcpy(&blocks, n->blocks, sizeof blocks);
    child &= blocks > -1; // a missing child's box is no box
    QuadBytes bytes;
    memcpy(&bytes, &child, sizeof bytes);
    ChildBytes each = __builtin_shufflevector(bytes, bytes, 0, 4, 8, 12);
    unsigned bits;
    memcpy(&bits, &each, sizeof bits);
    return bits & 0x01010101u;
}

// A child waiting to be visited, and where its window begins.
struct Pending {
    int child, blocks; // as in BvhNode
    real near;
};

// Deepest tree the walk can follow: build.cpp's median splits past depth 48 (kMaxSahDepth) halve the
// triangles, so even 2^31 of them stay well inside. Each node visited leaves at most three
// more children waiting (its nearest is visited next).
const int kMaxDepth = 128;

// Three or four open children (bits as OpenChildren gives them) onto the stack by insertion,
// farthest first (a later child above an earlier one at the same near), and the nearest off
// it again as *next. (The stack has room for the fourth for this moment: kWidth above.)
static RT_INLINE void SortChildren(const BvhNode *n, unsigned open, const Quad *near,
                                   Pending *stack, int *top, Pending *next) {
    Pending *sorted = stack + *top;
    int count = 0;
    for (; open != 0; open &= open - 1) {
        int k = __builtin_ctz(open) / 8, at = count++;
        while (at > 0 && sorted[at - 1].near < (*near)[k])
            sorted[at] = sorted[at - 1], at--;
        sorted[at] = {n->child[k], n->blocks[k], (*near)[k]};
    }
    *next = sorted[count - 1];
    *top += count - 1;
}

// The open children of node n (OpenChildren): the nearest as *next, to be visited at once,
// the others onto the stack, the nearer on top, so they come off nearest first. Among windows
// that begin at the same t the later child goes first. False if none is open. One or two open
// children (nine visits in ten on a large mesh) take no loop: one is next, and of two the
// nearer is next and the other waits.
template <bool kWide>
static RT_INLINE bool VisitNode(const BvhNode *n, const NodeRay *r, const Quad *tMax,
                                Pending *stack, int *top, Pending *next) {
    Quad near, far;
    ChildWindows(n, r, tMax, &near, &far);
    unsigned open = OpenChildren<kWide>(n, &near, &far);
    if (open == 0)
        return false;
    unsigned rest = open & (open - 1);
    int k = __builtin_ctz(open) / 8;
    if (rest == 0) {
        *next = {n->child[k], n->blocks[k], near[k]};
        return true;
    }
    if ((rest & (rest - 1)) != 0) {
        SortChildren(n, open, &near, stack, top, next);
        return true;
    }
    int later = __builtin_ctz(rest) / 8;
    int first = near[later] <= near[k] ? later : k, second = first == k ? later : k;
    stack[(*top)++] = {n->child[second], n->blocks[second], near[second]};
    *next = {n->child[first], n->blocks[first], near[first]};
    return true;
}

// The BVH walk: a child whose window (SlabInterval) misses (tMin, tMax) is skipped, the others
// are visited nearest first, so the nearest hit shrinks tMax early, and a child whose window
// begins beyond it by the time its turn comes is skipped too. (A window that begins exactly at
// tMax is visited: it may hold a tie that an earlier triangle wins.) A node's nearest open
// child is visited next without going through the stack: tMax has not moved since its window
// was checked.
template <int kz, bool kWide>
static RT_INLINE bool WalkTree(const SceneLayout *layout, Search *s, RayHit *hit) {
    Pending stack[3 * kMaxDepth + kWidth];
    int top = 0;
    // (In the search, not a local: with a local, GCC 12 merged HitAll's five shear splats into
    // one 32-byte load of the RayShear its caller had just stored as 8-byte numbers, a
    // store-forwarding stall that cost the assignment scene 9% of its time.)
    s->slab = MakeSlabRay(s->ray);
    NodeRay r;
    MakeNodeRay(&s->slab, s->tMin, &layout->nodes[0], &r);
    const BvhNode *nodes = layout->nodes.data();
    Quad tMax; // s->tMax in every lane, kept up to date as hits shrink it
    SplatQuad(&tMax, s->tMax);
    bool found = false;
    Pending next = {0, 0, -kInfinity}; // the root, whose children are all the triangles
    for (;;) {
        if (next.blocks == 0) {
            if (VisitNode<kWide>(&nodes[next.child], &r, &tMax, stack, &top, &next))
                continue;
        } else if (TestBlocks<kz, kWide>(layout->blocks.data(), next.child, next.blocks, s, hit)) {
            found = true;
            if (s->anyHit)
                return true;
            SplatQuad(&tMax, s->tMax);
        }
        do { // the nearest waiting child that may still hold a hit
            if (top == 0)
                return found;
            next = stack[--top];
        } while (next.near > s->tMax);
    }
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
