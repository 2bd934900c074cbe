// kernel_walk.h -- the BVH walk of the fast triangle loop (kernel.cpp): a node's four child
// boxes tested at once, the open children visited nearest first, their blocks tested by
// TestBlocks (kernel_blocks.h). Included by kernel.cpp alone, like kernel_blocks.h.
#pragma once
#include "kernel_blocks.h"
#include "kernel_spheres.h"

// The four children of a node tested at once: SlabInterval for each, lane by lane, with the
// same operations in the same order (so a child's window is exactly what SlabInterval gives).
RT_LANES(Quad, real, kChildren);
typedef decltype(Quad() < Quad()) QuadMask;

static RT_INLINE void LoadQuad(Quad *v, const real *p) { memcpy(v, p, sizeof *v); }
static RT_INLINE void SplatQuad(Quad *v, real x) {
    *v = Quad{};
    for (int i = 0; i < kChildren; i++)
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

// (Made from the ray itself, with MakeSlabRay's operations, rather than from a SlabRay: a
// SlabRay, built with one 32-byte store and copied with 16-byte loads that straddle it, would
// make every ray wait for its stores.)
static RT_INLINE void MakeNodeRay(const Ray *ray, real tMin, const BvhNode *anyNode, NodeRay *r) {
    const real origin[3] = {ray->origin.x, ray->origin.y, ray->origin.z};
    const real dir[3] = {ray->dir.x, ray->dir.y, ray->dir.z};
    Quad negativeZero;
    SplatQuad(&negativeZero, -real(0)); // the sign bit alone
    for (int i = 0; i < 3; i++) {
        real inverse = 1 / dir[i];
        SplatQuad(&r->origin[i], origin[i]), SplatQuad(&r->inverse[i], inverse);
        const char *node = (const char *)anyNode; // (every node has its arrays at the same places)
        size_t lo = (const char *)anyNode->lo[i] - node, hi = (const char *)anyNode->hi[i] - node;
        QuadMask sign = Bitcast<QuadMask>(negativeZero), none = QuadMask{};
        bool backward = std::signbit(inverse); // meets hi before lo
        r->entry[i] = backward ? hi : lo, r->entrySign[i] = backward ? none : sign;
        r->exit[i] = backward ? lo : hi, r->exitSign[i] = backward ? sign : none;
    }
    SplatQuad(&r->originPad, OriginPad(ray)), SplatQuad(&r->tMin, tMin);
}

// Where the ray's line meets one plane of every child's box along axis i (entry or exit, as
// NodeRay picked it), moved out by the pad: SlabInterval's a or b, the same operations in order.
static RT_INLINE void PlaneDistance(const BvhNode *n, size_t plane, const QuadMask *sign,
                                    const Quad *pad, const Quad *o, const Quad *inv, Quad *t) {
    Quad p;
    LoadQuad(&p, (const real *)((const char *)n + plane));
    *t = ((p + Bitcast<Quad>(Bitcast<QuadMask>(*pad) ^ *sign)) - *o) * *inv;
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
        near = Select(first > near, first, near); // (NaN compares false: no restriction)
        far = Select(last < far, last, far);
    }
    *tNear = near, *tFar = far;
}

// The children whose windows meet [tMin, tMax], as one bit a child, child k's at bit 8 k, so
// the walk takes them by counting zeros instead of looking at each lane. Vector extensions
// have no "movemask"; two shuffles gather a byte of each lane's compare (all ones or none)
// into one word, which GCC and clang compile to three instructions with AVX2. Without it the
// shuffles become a dozen moves through memory, and four scalar compares are cheaper.
template <bool kVectors>
static RT_INLINE unsigned OpenChildren(const BvhNode *n, const Quad *near, const Quad *far) {
#if RT_SHUFFLES
    if (kVectors) {
        typedef int QuadInts __attribute__((vector_size(kChildren * sizeof(int)))); // child ints
        typedef int LaneInts __attribute__((vector_size(sizeof(Quad)))); // a QuadMask as ints
        typedef char QuadBytes __attribute__((vector_size(kChildren * sizeof(int)))); // as bytes
        typedef char ChildBytes __attribute__((vector_size(kChildren))); // a byte a child
        QuadMask open = *near <= *far;                                   // all four at once
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
#endif
    unsigned bits = 0;
    for (int k = 0; k < kChildren; k++)
        bits |= (unsigned)((*near)[k] <= (*far)[k] && n->blocks[k] >= 0) << (8 * k);
    return bits;
}

// A child waiting to be visited, and where its window begins.
struct Pending {
    int child, blocks; // as in BvhNode
    real near;
};

// Deepest tree the walk can follow: the median splits past depth 48 (commit.cpp, kMaxSahDepth)
// halve the triangles, so even 2^31 of them stay well inside. Each node visited leaves at most
// three more children waiting (its nearest is visited next).
const int kMaxDepth = 128;

// Three or four open children (bits as OpenChildren gives them) onto the stack by insertion,
// farthest first (a later child above an earlier one at the same near), and the nearest off
// it again as *next. (The stack has room for the fourth for this moment: kChildren above.)
static RT_INLINE void SortChildren(const BvhNode *n, unsigned open, const Quad *near,
                                   Pending *stack, int *top, Pending *next) {
    Pending *sorted = stack + *top;
    int count = 0;
    for (; open != 0; open &= open - 1) {
        int k = LowestBit(open) / 8, at = count++;
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
template <bool kVectors>
static RT_INLINE bool VisitNode(const BvhNode *n, const NodeRay *r, const Quad *tMax,
                                Pending *stack, int *top, Pending *next) {
    Quad near, far;
    ChildWindows(n, r, tMax, &near, &far);
    unsigned open = OpenChildren<kVectors>(n, &near, &far);
    if (open == 0)
        return false;
    unsigned rest = open & (open - 1);
    int k = LowestBit(open) / 8;
    if (rest == 0) {
        *next = {n->child[k], n->blocks[k], near[k]};
        return true;
    }
    if ((rest & (rest - 1)) != 0) {
        SortChildren(n, open, &near, stack, top, next);
        return true;
    }
    int later = LowestBit(rest) / 8;
    int first = near[later] <= near[k] ? later : k, second = first == k ? later : k;
    stack[(*top)++] = {n->child[second], n->blocks[second], near[second]};
    *next = {n->child[first], n->blocks[first], near[first]};
    return true;
}

// The BVH walk, over the triangles' tree or the spheres': a child whose window (SlabInterval)
// misses (tMin, *tMax) is skipped, the others are visited nearest first, so the nearest hit
// shrinks *tMax early, and a child whose window begins beyond it by the time its turn comes is
// skipped too. (A window that begins exactly at *tMax is visited: it may hold a tie that an
// earlier shape wins.) A node's nearest open child is visited next without going through the
// stack: *tMax has not moved since its window was checked. leaf(first, count) tests a leaf's
// blocks, lowers *tMax to any hit's t, and says whether it found one.
template <bool kVectors, typename Leaf>
static RT_INLINE bool WalkNodes(const BvhNode *nodes, const Ray *ray, real tMin, real *tMax,
                                bool anyHit, const Leaf &leaf) {
    Pending stack[3 * kMaxDepth + kChildren];
    int top = 0;
    NodeRay r;
    MakeNodeRay(ray, tMin, &nodes[0], &r);
    Quad tMaxes; // *tMax in every lane, kept up to date as hits shrink it
    SplatQuad(&tMaxes, *tMax);
    bool found = false;
    Pending next = {0, 0, -kInfinity}; // the root, whose children are all the shapes
    for (;;) {
        if (next.blocks == 0) {
            if (VisitNode<kVectors>(&nodes[next.child], &r, &tMaxes, stack, &top, &next))
                continue;
        } else if (leaf(next.child, next.blocks)) {
            found = true;
            if (anyHit)
                return true;
            SplatQuad(&tMaxes, *tMax);
        }
        do { // the nearest waiting child that may still hold a hit
            if (top == 0)
                return found;
            next = stack[--top];
        } while (next.near > *tMax);
    }
}

// ---- the spheres' tree -------------------------------------------------------------------

// A leaf's spheres: the first step on a block at a time (MayMeet), the reference test for the
// rest (TestLiveSpheres, which keeps the plain loop's answer, ties included).
template <bool kVectors>
static RT_INLINE bool TestSphereBlocks(const SphereBlock *blocks, int first, int count,
                                       const SphereLaneRay *lanes, SphereSearch *s, RayHit *hit) {
    bool found = false;
    for (const SphereBlock *b = blocks + first; b < blocks + first + count; b++) {
        unsigned live = kVectors ? MayMeet(b, lanes) : MayMeetOneByOne(b, s->ray);
        if (live == 0)
            continue;
        int places[kLanes], n = 0;
        for (; live != 0; live &= live - 1)
            places[n++] = b->index[LowestBit(live)];
        found = (s->anyHit ? TestLiveSpheres<true>(s, places, n, hit)
                           : TestLiveSpheres<false>(s, places, n, hit)) ||
                found;
        if (found && s->anyHit)
            return true;
    }
    return found;
}

template <bool kVectors>
static RT_INLINE bool WalkSpheres(const Scene *scene, const SceneLayout *layout, int skip,
                                  const Ray *ray, real tMin, real *tMax, bool anyHit, RayHit *hit) {
    SphereSearch s = StartSphereSearch(scene, skip, ray, tMin, *tMax, anyHit);
    SphereLaneRay lanes; // (with vectors)
    if (kVectors)
        SplatSphereRay(ray, &lanes);
    const SphereBlock *blocks = layout->sphereBlocks.data();
    SphereSearch *search = &s;
    const SphereLaneRay *each = &lanes;
    bool found = WalkNodes<kVectors>(layout->sphereNodes.data(), ray, tMin, &s.tMax, anyHit,
                                     [blocks, each, search, hit](int first, int count) {
                                         return TestSphereBlocks<kVectors>(blocks, first, count,
                                                                           each, search, hit);
                                     });
    *tMax = s.tMax;
    return found;
}
