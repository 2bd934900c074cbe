// kernel_wide.h -- the walk of the triangles' wide BVH (WideNode, WideBlock: fast.h), for the
// fast triangle loop (kernel.cpp): eight child boxes in float tested at once, the open children
// visited nearest first, a leaf's blocks of eight triangles filtered in float, and only the
// triangles that pass tested exactly, by the very functions the plain loop calls (TestBlocks'
// steps, kernel_blocks.h). Included by kernel.cpp alone.
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
#include "kernel_blocks.h"
#include "kernel_setup.h"

#include <cfloat>

RT_LANES(Wide, float, kWide);                // eight floats
typedef decltype(Wide() < Wide()) WideMask;  // per lane: all bits set, or none

static RT_INLINE void LoadWide(Wide *v, const float *p) { memcpy(v, p, sizeof *v); }
// (Eight copies in an array, copied: GCC 12 makes one broadcast of that, where a list of eight
// x, or lanes written one by one, can become a chain of inserts.)
static RT_INLINE void SplatWide(Wide *v, float x) {
    float lanes[kWide];
    for (int i = 0; i < kWide; i++)
        lanes[i] = x;
    memcpy(v, lanes, sizeof *v);
}
static RT_INLINE Wide AbsWide(const Wide *v) {
    return Bitcast<Wide>(Bitcast<WideMask>(*v) & 0x7fffffff);
}

// One bit a lane of a mask whose lanes are all ones or none. Vector extensions have no
// "movemask": each half keeps its lanes' own bits (1, 2, 4, 8 and 16, 32, 64, 128), the halves
// are joined, and two swaps of halves gather the four lanes into one, a few instructions with
// AVX2. Without shuffles, a loop over the lanes.
static RT_INLINE unsigned WideBits(const WideMask *mask) {
#if RT_SHUFFLES
    typedef int FourInts __attribute__((vector_size(16)));
    FourInts low = __builtin_shufflevector(*mask, *mask, 0, 1, 2, 3);
    FourInts high = __builtin_shufflevector(*mask, *mask, 4, 5, 6, 7);
    FourInts x = (low & FourInts{1, 2, 4, 8}) | (high & FourInts{16, 32, 64, 128});
    x |= __builtin_shufflevector(x, x, 2, 3, 0, 1);
    x |= __builtin_shufflevector(x, x, 1, 0, 3, 2);
    return (unsigned)x[0];
#else
    unsigned bits = 0;
    for (int i = 0; i < kWide; i++)
        bits |= (unsigned)((*mask)[i] != 0) << i;
    return bits;
#endif
}

// The float next to f toward +infinity (up) or -infinity, for f not NaN and not already that
// infinity: the bit pattern one step further from 0 or nearer to it, and from 0 the smallest
// subnormal. (std::nextafter, without the library call.)
static RT_INLINE float FloatStep(float f, bool up) {
    if (f == 0)
        return up ? FLT_TRUE_MIN : -FLT_TRUE_MIN;
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    bits = (f > 0) == up ? bits + 1 : bits - 1;
    memcpy(&f, &bits, sizeof f);
    return f;
}

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
// ρ's share for float's roundings, per unit of 2 + |o|.
const double kWideRounding = 0x1p-19;

static RT_INLINE void WalkEverything(WideRay *r) {
    for (int i = 0; i < 3; i++) {
        SplatWide(&r->entryOrigin[i], 0), SplatWide(&r->exitOrigin[i], 0);
        SplatWide(&r->inverse[i], 1);
        r->entry[i] = offsetof(WideNode, lo) + i * sizeof(float) * kWide;
        r->exit[i] = offsetof(WideNode, hi) + i * sizeof(float) * kWide;
    }
    SplatWide(&r->tMin, -INFINITY);
    r->tMax = INFINITY, r->scale = {0, 0}, r->culls = false;
}

// The origin in the wide tree's units, o 2^exponent, and its largest |coordinate|.
static RT_INLINE double ScaledOrigin(const Ray *ray, int exponent, double o[3]) {
    PowerPair p = PowerOfTwoPair(exponent);
    o[0] = Times(ray->origin.x, p), o[1] = Times(ray->origin.y, p), o[2] = Times(ray->origin.z, p);
    double most = std::fabs(o[0]) > std::fabs(o[1]) ? std::fabs(o[0]) : std::fabs(o[1]);
    return most > std::fabs(o[2]) ? most : std::fabs(o[2]);
}

// *r for the ray (its direction's largest component within kDirectionWindow: ScaleRay),
// searched in (tMin, tMax); o, omax: ScaledOrigin's.
static RT_INLINE void MakeWideRay(const Ray *ray, const double o[3], double omax, int exponent,
                                  real tMin, real tMax, WideRay *r) {
    if (!(omax <= kWideFarthest))
        return WalkEverything(r);
    const double d[3] = {ray->dir.x, ray->dir.y, ray->dir.z};
    int j = -BinaryExponent(MaxComponent(ray->dir)); // d 2^j: largest in [1, 2)
    double dj = PowerOfTwoD(j);
    double rho = Times(OriginPad(ray), PowerOfTwoPair(exponent)) + kWideRounding * (2 + omax);
    for (int i = 0; i < 3; i++) {
        double scaled = d[i] * dj, inverse = 1 / scaled;
        if (scaled != 0 && !(std::fabs(scaled) >= kWideSmallest))
            inverse = NAN; // (NaN: this axis restricts nothing)
        bool backward = std::signbit(inverse);
        size_t lo = offsetof(WideNode, lo) + i * sizeof(float) * kWide;
        size_t hi = offsetof(WideNode, hi) + i * sizeof(float) * kWide;
        float loOrigin = (float)(o[i] + rho), hiOrigin = (float)(o[i] - rho);
        SplatWide(&r->inverse[i], (float)inverse);
        SplatWide(&r->entryOrigin[i], backward ? hiOrigin : loOrigin);
        SplatWide(&r->exitOrigin[i], backward ? loOrigin : hiOrigin);
        r->entry[i] = backward ? hi : lo, r->exit[i] = backward ? lo : hi;
    }
    r->scale = PowerOfTwoPair(exponent - j), r->culls = true; // (P 2^e - o 2^e) / (d 2^j)
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

// ---- a leaf's blocks ------------------------------------------------------------------------

// What the block test needs of the ray, in every lane: the watertight shear's origin (axes
// renamed) and shear (RayShear), and in the double build the bound on what float changes.
struct FilterRay {
    Wide ox, oy, oz, sx, sy;
    Wide across, square; // (double build) the error bound's terms: 8 e and 4 e^2 (FilterBlock)
};

// In the float build: the shear itself, as the exact test computes it. In double: the origin
// in the blocks' units (o 2^exponent) and the shear, in float; a ray walked without boxes is
// also tested without the filter (an infinite bound lets every triangle through).
template <int kz>
static RT_INLINE void MakeFilterRay(const RayShear *shear, const double o[3], double omax,
                                    bool culls, FilterRay *f) {
    const int X = (kz + 1) % 3, Y = (kz + 2) % 3;
    SplatWide(&f->sx, (float)shear->sx), SplatWide(&f->sy, (float)shear->sy);
    if (kExactWideBlocks) {
        SplatWide(&f->ox, (float)shear->origin.x), SplatWide(&f->oy, (float)shear->origin.y);
        SplatWide(&f->oz, (float)shear->origin.z);
        return;
    }
    SplatWide(&f->ox, (float)o[X]), SplatWide(&f->oy, (float)o[Y]), SplatWide(&f->oz, (float)o[kz]);
    double e = kWideRounding * (2 + omax);
    SplatWide(&f->across, culls ? (float)(8 * e) : INFINITY);
    SplatWide(&f->square, culls ? (float)(4 * e * e) : INFINITY);
}

// One corner of every lane sheared as ShearCorners does it (watertight.cpp): A = renamed
// corner - origin, then x = A.x - sx A.z, y = A.y - sy A.z.
template <int kz>
static RT_INLINE void ShearWide(const WideBlock *b, int corner, const FilterRay *r, Wide *x,
                                Wide *y) {
    Wide Ax, Ay, Az;
    LoadWide(&Ax, b->corner[3 * corner + (kz + 1) % 3]);
    LoadWide(&Ay, b->corner[3 * corner + (kz + 2) % 3]);
    LoadWide(&Az, b->corner[3 * corner + kz]);
    Ax = Ax - r->ox, Ay = Ay - r->oy, Az = Az - r->oz;
    *x = Ax - r->sx * Az;
    *y = Ay - r->sy * Az;
}

// The lanes whose triangles survive the watertight test's first step (EdgesDisagree), as bits:
// the edge functions U = Cx By - Cy Bx, V = Ax Cy - Ay Cx, W = Bx Ay - By Ax, and a triangle is
// out where one is below -E and another above E. In the float build E = 0 and these are the
// exact test's numbers (Survivors, kernel_blocks.h). In double, the float corners and origin
// differ from the exact test's sheared corners (times 2^exponent) by at most e = 2^-19 (2 + |o|)
// each (the top of this file counts the roundings: fewer than 10 u (2 + |o|)), so each edge
// function differs from the one whose sign the exact test decides by at most e (4m + 2e) plus
// float's two roundings of it, 2 gamma(2) m^2, where m is the largest |coordinate| of the
// sheared corners: E = m (2^-20 m + 8e) + 4e^2 holds that with room for its own rounding. A
// triangle out here is out there. *sure: the survivors whose three edge functions are beyond E
// with one sign, so that the exact test passes them to the plane test for certain.
template <int kz>
static RT_INLINE unsigned FilterBlock(const WideBlock *b, const FilterRay *r, unsigned *sure) {
    Wide ax, ay, bx, by, cx, cy, bound;
    ShearWide<kz>(b, 0, r, &ax, &ay);
    ShearWide<kz>(b, 1, r, &bx, &by);
    ShearWide<kz>(b, 2, r, &cx, &cy);
    Wide u = cx * by - cy * bx;
    Wide v = ax * cy - ay * cx;
    Wide w = bx * ay - by * ax;
    if (kExactWideBlocks) {
        SplatWide(&bound, 0);
    } else {
        Wide x = AbsWide(&ax), y = AbsWide(&ay);
        Wide m = Select(x > y, x, y);
        for (const Wide *c : {&bx, &by, &cx, &cy}) {
            Wide size = AbsWide(c);
            m = Select(size > m, size, m);
        }
        bound = m * (m * float(0x1p-20) + r->across) + r->square;
    }
    Wide below = -bound;
    WideMask uNeg = u < below, vNeg = v < below, wNeg = w < below;
    WideMask uPos = u > bound, vPos = v > bound, wPos = w > bound;
    WideMask out = (uNeg | vNeg | wNeg) & (uPos | vPos | wPos);
    unsigned live = ~WideBits(&out) & ((1u << kWide) - 1);
    if (live == 0) // most blocks
        return 0;
    WideMask certain = (uNeg & vNeg & wNeg) | (uPos & vPos & wPos);
    *sure = live & WideBits(&certain);
    return live;
}

// The search of the wide tree: the exact search's state (kernel_blocks.h), the ray for the
// nodes and for the blocks.
struct WideSearch {
    Search exact;
    WideRay nodes;
    FilterRay filter;
};

// A leaf's blocks (`code`: WideNode::child), each filtered, and its survivors tested exactly
// with the set-up made here (the layout keeps none for the tree: TestSurvivor, kernel_blocks.h).
// After a hit the nodes' tMax follows the exact one (rounded up). True if anything was hit.
template <int kz>
static RT_INLINE bool TestWideLeaf(const WideBlock *blocks, int code, WideSearch *w,
                                   RayHit *hit) {
    Search *s = &w->exact;
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
            if (!TestSurvivor(s, index, &setUp, sure >> lane & 1u, hit))
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
