// kernel_filter.h -- the block test of the wide tree (kernel_wide.h), and its lanes: eight
// triangles of a WideBlock at once, in float, as the watertight test's first step (EdgesDisagree,
// watertight.cpp) computes it. Included by kernel.cpp alone, through kernel_wide.h.
//
// In the float build the blocks hold the triangles' own corners and every lane computes what the
// scalar test computes, so the test is the exact one (kernel_blocks.h's Survivors, eight wide). In
// double the corners and the ray are float copies (times 2^wideExponent), and a triangle is
// refused only where the edge functions disagree by more than what float's rounding can change
// (FilterBlock says how much): the exact test would refuse it too.
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

// The share, per unit of 2 + |o| (o the ray's origin in the scaled units, where every corner is
// below 2), that bounds what float's roundings move a plane or a corner: 32 u of float, where
// fewer than 10 are spent (kernel_wide.h and FilterBlock count them). (A subnormal's rounding is
// absolute, at most 2^-150, far below 2^-19 of 2.)
const double kWideRounding = 0x1p-19;

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
static RT_INLINE void MakeFilterRay(const RayShear *shear, const Double4 *o, double omax,
                                    bool culls, FilterRay *f) {
    const int X = (kz + 1) % 3, Y = (kz + 2) % 3;
    SplatWide(&f->sx, (float)shear->sx), SplatWide(&f->sy, (float)shear->sy);
    if (kExactWideBlocks) {
        SplatWide(&f->ox, (float)shear->origin.x), SplatWide(&f->oy, (float)shear->origin.y);
        SplatWide(&f->oz, (float)shear->origin.z);
        return;
    }
    SplatWide(&f->ox, (float)(*o)[X]), SplatWide(&f->oy, (float)(*o)[Y]);
    SplatWide(&f->oz, (float)(*o)[kz]);
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
// exact test's numbers (Survivors, kernel_blocks.h). In double, a sheared corner in float differs
// from the exact test's (times 2^exponent) by at most e = 2^-19 (2 + |o|): the corner's, the
// origin's and the shear's rounding to float, float's three operations, each at most u of
// 2 + |o| (|shear| <= 1), and the exact test's own roundings in double, far smaller, are under
// 10 u of it, where e holds 32. So each edge
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
