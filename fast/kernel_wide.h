// kernel_wide.h -- the walk of the triangles' wide BVH (WideNode, WideBlock: fast.h), for the
// fast triangle loop (kernel.cpp): eight child boxes in float tested at once, the open children
// visited nearest first, a leaf's blocks of eight triangles filtered in float, and only the
// triangles that pass tested exactly, by the very functions the plain loop calls (TestBlocks'
// steps, kernel_blocks.h; the block test is kernel_filter.h). Included by kernel.cpp alone.
//
// Why float loses no hit. The exact search (the list, the plain loop) finds every hit inside its
// triangle's window (plane.cpp): SlabInterval of the triangle's box, widened by kBoxAllowance of
// the box's size and OriginPad of the ray's origin, as `real` rounds it. A node's float box is
// that box, rounded outward (commit_tree.cpp), and the walk widens it again, per ray, by the pad
// ρ (WideRay): OriginPad, plus 2^-19 (2 + |o|) in the scaled units, where every coordinate is
// below 2. What float can get wrong is each plane's distance t = (plane - o) / d: o rounded to
// float, o -+ ρ rounded, the subtraction, 1/d rounded to float, the product. Each is a rounding of
// at most u = 2^-24 of (2 + |o|) or of t, which moves the plane by at most u (2 + |o|); with
// `real`'s own rounding of SlabInterval (far smaller in double) they are fewer than 8 of these,
// and ρ holds 32. So the float window holds the exact window. A direction component below 2^-40
// of the largest (|1/d| would leave float's range in products) is not tested on its axis at
// all, and a ray that starts more than 2^40 of the scene's size away is walked without boxes:
// both are wider than needed, never narrower.
#pragma once
#include "kernel_filter.h"
#include "kernel_plane.h"
#include "kernel_setup.h"

// x as a float no greater (down) or no less than x.
static RT_INLINE float FloatBelow(double x) {
    float f = (float)x;
    return (double)f > x ? FloatStep(f, false) : f;
}
static RT_INLINE float FloatAbove(double x) {
    float f = (float)x;
    return (double)f < x ? FloatStep(f, true) : f;
}

// 2^k as a double, for |k| up to 1022.
static RT_INLINE double PowerOfTwoD(int k) {
    uint64_t bits = (uint64_t)(k + 1023) << 52;
    double x;
    memcpy(&x, &bits, sizeof x);
    return x;
}

// 2^k for |k| up to 2044, as two factors: x 2^k is x times one, then the other (a scene of
// subnormal coordinates has an exponent above 1023).
struct PowerPair {
    double first, second;
};
static RT_INLINE PowerPair PowerOfTwoPair(int k) {
    return {PowerOfTwoD(k / 2), PowerOfTwoD(k - k / 2)};
}
static RT_INLINE double Times(double x, PowerPair p) { return x * p.first * p.second; }

// The ray as the wide nodes see it, in their units (coordinates times 2^wideExponent, t times
// `scale`, which also brings the direction's largest component into [1, 2)): for each axis the
// entry and exit planes' places in a WideNode (chosen by the sign of 1/d, as SlabInterval
// chooses), the origin moved out by ρ toward each (o + ρ for a lo plane, o - ρ for a hi one),
// and 1/d; the interval, rounded outward.
struct WideRay {
    Wide entryOrigin[3], exitOrigin[3], inverse[3], tMin;
    size_t entry[3], exit[3];
    float tMax;
    PowerPair scale;
    bool culls; // false: the ray starts too far away, and every box is entered
};

// Beyond these, a ray is walked without boxes (|o| in scaled units), or without the box test
// on one axis (a component of the scaled direction): see the top of this file.
const double kWideFarthest = 0x1p40, kWideSmallest = 0x1p-40;

// The walk for a ray that starts too far away: every box entered. The x axis alone is tested,
// from 0 with 1/d = 1, which takes every box whose lo.x <= hi.x, that is every child but a
// missing one (the others' NaN restricts nothing); every window then begins at its lo.x.
static RT_INLINE void WalkEverything(WideRay *r) {
    for (int i = 0; i < 3; i++) {
        SplatWide(&r->entryOrigin[i], 0), SplatWide(&r->exitOrigin[i], 0);
        SplatWide(&r->inverse[i], i == 0 ? 1 : NAN);
        r->entry[i] = offsetof(WideNode, lo) + i * sizeof(float) * kWide;
        r->exit[i] = offsetof(WideNode, hi) + i * sizeof(float) * kWide;
    }
    SplatWide(&r->tMin, -INFINITY);
    r->tMax = INFINITY, r->scale = {0, 0}, r->culls = false;
}

// The origin in the wide tree's units, o 2^exponent (p: 2^exponent as a PowerPair), lane by
// lane, and its largest |coordinate|.
static RT_INLINE double ScaledOrigin(const Ray *ray, PowerPair p, Double4 *o) {
    // (the fourth lane repeats z: a 0 there takes a move that valgrind 3.19 cannot follow)
    *o = Double4{ray->origin.x, ray->origin.y, ray->origin.z, ray->origin.z} * p.first * p.second;
    return LargestOfThree(Magnitudes(*o));
}

// *r for the ray (its direction's largest component within kDirectionWindow: ScaleRay),
// searched in (tMin, tMax); o, omax: ScaledOrigin's. (The three axes in the lanes of one vector:
// one division for the three 1/d.)
static RT_INLINE void MakeWideRay(const Ray *ray, const Double4 *o, double omax, PowerPair p,
                                  real tMin, real tMax, WideRay *r) {
    if (!(omax <= kWideFarthest))
        return WalkEverything(r);
    int j = -BinaryExponent(MaxComponent(ray->dir)); // d 2^j: largest in [1, 2)
    Double4 d = Double4{ray->dir.x, ray->dir.y, ray->dir.z, 1} * PowerOfTwoD(j);
    Double4 inverse = 1 / d, nan = {NAN, NAN, NAN, NAN}; // (NaN: the axis restricts nothing)
    inverse = Select((Magnitudes(d) < kWideSmallest) & (d != 0), nan, inverse);
    double rho = Times(OriginPad(ray), p) + kWideRounding * (2 + omax);
    Double4 lo = *o + rho, hi = *o - rho; // the origin moved toward a lo plane, a hi plane
    for (int i = 0; i < 3; i++) {
        bool backward = std::signbit(inverse[i]);
        size_t loPlane = offsetof(WideNode, lo) + i * sizeof(float) * kWide;
        size_t hiPlane = offsetof(WideNode, hi) + i * sizeof(float) * kWide;
        float loOrigin = (float)lo[i], hiOrigin = (float)hi[i];
        SplatWide(&r->inverse[i], (float)inverse[i]);
        SplatWide(&r->entryOrigin[i], backward ? hiOrigin : loOrigin);
        SplatWide(&r->exitOrigin[i], backward ? loOrigin : hiOrigin);
        r->entry[i] = backward ? hiPlane : loPlane, r->exit[i] = backward ? loPlane : hiPlane;
    }
    r->scale = {p.first, p.second * PowerOfTwoD(-j)}, r->culls = true; // t 2^exponent 2^-j
    SplatWide(&r->tMin, FloatBelow(Times(tMin, r->scale)));
    r->tMax = FloatAbove(Times(tMax, r->scale));
}

// ---- a node ---------------------------------------------------------------------------------

// The children of node n whose windows meet the ray's interval [tMin, tMax] (scaled), as one bit
// a child, and where each window begins (*near). Each window is SlabInterval's steps on the
// float box: per axis the entry and exit planes' t, the latest entry and the earliest exit, cut
// to the interval (a NaN restricts nothing, as in SlabInterval). A missing child's empty box
// gives entry +infinity and exit -infinity on the ray's main axis, so it is never open.
static RT_INLINE unsigned OpenWideChildren(const WideNode *n, const WideRay *r, float tMax,
                                           Wide *near) {
    Wide first = r->tMin, last;
    SplatWide(&last, tMax);
    const char *node = (const char *)n;
    for (int i = 0; i < 3; i++) {
        Wide entry, exit;
        LoadWide(&entry, (const float *)(node + r->entry[i]));
        LoadWide(&exit, (const float *)(node + r->exit[i]));
        entry = (entry - r->entryOrigin[i]) * r->inverse[i];
        exit = (exit - r->exitOrigin[i]) * r->inverse[i];
        first = Select(entry > first, entry, first);
        last = Select(exit < last, exit, last);
    }
    *near = first;
    WideMask open = first <= last;
    return WideBits(&open);
}

// A child waiting to be visited (WideNode::child's code) and where its window begins.
struct WidePending {
    int child;
    float near;
};

// Deepest wide tree the walk can follow: each wide level takes at least one level of the binary
// tree, which is at most 48 deep by the heuristic and then halves (commit_tree.cpp). Each visit
// leaves at most kWide - 1 children waiting.
const int kMaxWideDepth = 128;

// The open children (bits) of node n onto the stack, farthest first, so that they come off
// nearest first, and the nearest as *next, visited at once. One open child (most visits on a
// large mesh) is next; of two, the nearer; more are sorted by insertion. Among windows that
// begin at the same t the later child goes first.
static RT_INLINE void OrderChildren(const WideNode *n, unsigned open, const Wide *near,
                                    WidePending *stack, int *top, int *next) {
    int k = LowestBit(open);
    unsigned rest = open & (open - 1);
    if (rest == 0) {
        *next = n->child[k];
        return;
    }
    if ((rest & (rest - 1)) == 0) {
        int later = LowestBit(rest);
        bool laterFirst = (*near)[later] <= (*near)[k];
        int first = laterFirst ? later : k, second = laterFirst ? k : later;
        stack[(*top)++] = {n->child[second], (*near)[second]};
        *next = n->child[first];
        return;
    }
    WidePending *sorted = stack + *top;
    int count = 0;
    for (; open != 0; open &= open - 1) {
        int c = LowestBit(open), at = count++;
        while (at > 0 && sorted[at - 1].near < (*near)[c])
            sorted[at] = sorted[at - 1], at--;
        sorted[at] = {n->child[c], (*near)[c]};
    }
    *next = sorted[count - 1].child;
    *top += count - 1;
}

// The search of the wide tree: the exact search's state (kernel_blocks.h), the ray for the
// nodes, for the blocks and for tier 1 of the plane's t (kernel_plane.h).
struct WideSearch {
    TriangleSearch exact;
    WideRay nodes;
    FilterRay filter;
    PlaneRay plane;
    bool reach; // exact.inverse is made (at the first survivor: OutOfReach's 1/d)
};

// TestSurvivor's steps (kernel_blocks.h) for a triangle of the wide tree, where the edge
// functions' signs are sure with RobustPlaneHit's first tier in the kernel (KernelPlaneHit).
static RT_INLINE bool TestWideSurvivor(WideSearch *w, int index, const TriangleSetUp *setUp,
                                       bool sure, RayHit *hit) {
    TriangleSearch *s = &w->exact;
    real limit = s->best >= 0 && index < s->best ? NextAfter(s->tMax, true) : s->tMax;
    const Triangle *tri = &s->triangles[index];
    if (!w->reach)
        Inverses(s->ray->dir, s->inverse), w->reach = true;
    if (OutOfReach(&setUp->box, setUp->flat, s, limit))
        return false;
    if (!(sure ? KernelPlaneHit(tri, setUp, s->ray, &w->plane, s->tMin, limit, hit)
               : IntersectWatertight(tri, setUp, s->ray, s->shear, s->tMin, limit, hit)))
        return false;
    hit->index = s->best = index;
    s->tMax = hit->t;
    return true;
}

// A leaf's blocks (`code`: WideNode::child), each filtered, and its survivors tested exactly
// with the set-up made here (the layout keeps none for the tree: TestSurvivor, kernel_blocks.h).
// After a hit the nodes' tMax follows the exact one (rounded up). True if anything was hit.
template <int kz>
static RT_INLINE bool TestWideLeaf(const WideBlock *blocks, int code, WideSearch *w, RayHit *hit) {
    TriangleSearch *s = &w->exact;
    bool found = false;
    const WideBlock *b = blocks + LeafFirst(code), *end = b + LeafCount(code);
    for (; b < end; b++) {
        unsigned sure, live = FilterBlock<kz>(b, &w->filter, &sure);
        for (; live != 0; live &= live - 1) {
            int lane = LowestBit(live), index = b->index[lane];
            if (index < 0 || index == s->skip)
                continue;
            TriangleSetUp setUp;
            MakeSetUp(&s->triangles[index], &setUp);
            if (!TestWideSurvivor(w, index, &setUp, sure >> lane & 1u, hit))
                continue;
            found = true;
            if (w->nodes.culls)
                w->nodes.tMax = FloatAbove(Times(s->tMax, w->nodes.scale));
            if (s->anyHit)
                return true;
        }
    }
    return found;
}

// The walk: a child whose window misses the interval is skipped, the others are visited
// nearest first, so the nearest hit shrinks tMax early, and a child whose window begins beyond
// it by the time its turn comes is skipped too (one that begins exactly at tMax is visited: it
// may hold a tie that an earlier triangle wins).
template <int kz>
static RT_INLINE bool WalkWide(const SceneLayout *layout, WideSearch *w, RayHit *hit) {
    const WideNode *nodes = layout->wideNodes.data();
    const WideBlock *blocks = layout->wideBlocks.data();
    WidePending stack[(kWide - 1) * kMaxWideDepth + 1];
    int top = 0, next = 0; // the root
    bool found = false;
    for (;;) {
        if (next >= 0) {
            Wide near;
            unsigned open = OpenWideChildren(&nodes[next], &w->nodes, w->nodes.tMax, &near);
            if (open != 0) {
                OrderChildren(&nodes[next], open, &near, stack, &top, &next);
                continue;
            }
        } else if (TestWideLeaf<kz>(blocks, next, w, hit)) {
            found = true;
            if (w->exact.anyHit)
                return true;
        }
        WidePending waiting;
        do { // the nearest waiting child that may still hold a hit
            if (top == 0)
                return found;
            waiting = stack[--top];
        } while (waiting.near > w->nodes.tMax);
        next = waiting.child;
    }
}
