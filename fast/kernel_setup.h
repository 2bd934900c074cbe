// kernel_setup.h -- a triangle's set-up (SetUpTriangle, plane.cpp) made as the kernel needs it,
// for the triangles the wide tree's block test lets through (kernel_wide.h): the tree keeps no
// set-ups, which would take three times the memory of everything else it holds. Included by
// kernel.cpp alone.
//
// Every number is SetUpTriangle's, to the bit: the same operations on the same numbers, in double
// lanes (x, y, z and one unused) where SetUpTriangle takes the three axes one by one, and in its
// order where it adds across them. A triangle outside the ordinary (edges that need scaling or
// are not finite, a normal so long or short that n.n would leave the range) gets SetUpTriangle
// itself. (tests/test_layout.cpp holds the two to the same bits.)
#pragma once
#include "lanes.h"
#include "../robust/robust.h"

RT_LANES(Double4, double, 4);
typedef decltype(Double4() < Double4()) Double4Mask;

// Lane by lane, the larger and the smaller (as `x > y ? x : y` picks).
static RT_INLINE Double4 Larger(const Double4 &x, const Double4 &y) { return Select(x > y, x, y); }
static RT_INLINE Double4 Magnitudes(const Double4 &x) {
    return Bitcast<Double4>(Bitcast<Double4Mask>(x) & 0x7fffffffffffffffll);
}

// The triangle's box, TriangleBox's: each axis's least and most of the corners, in its order
// (so that of -0 and +0 the same one wins), and its size, the largest |coordinate| (one number,
// however the six are compared: none is a NaN here).
static RT_INLINE void LaneBox(const Double4 *a, const Double4 *b, const Double4 *c, Box *box) {
    Double4 lo = Select(*a < *b, *a, *b), hi = Select(*a > *b, *a, *b);
    lo = Select(lo < *c, lo, *c), hi = Select(hi > *c, hi, *c);
    Double4 size = Larger(Magnitudes(lo), Magnitudes(hi));
    double most = size[0] > size[1] ? size[0] : size[1];
    for (int axis = 0; axis < 3; axis++)
        box->lo[axis] = (real)lo[axis], box->hi[axis] = (real)hi[axis];
    box->size = (real)(most > size[2] ? most : size[2]);
}

// The largest of lanes x, y, z.
static RT_INLINE double LargestOfThree(const Double4 &v) {
    double m = v[0] > v[1] ? v[0] : v[1];
    return m > v[2] ? m : v[2];
}

// SetUpTriangle's set-up of tri, into *setUp.
static RT_INLINE void MakeSetUp(const Triangle *tri, TriangleSetUp *setUp) {
    Double4 a = {tri->a.x, tri->a.y, tri->a.z, 0}, b = {tri->b.x, tri->b.y, tri->b.z, 0};
    Double4 c = {tri->c.x, tri->c.y, tri->c.z, 0};
    Double4 e1 = b - a, e2 = c - a, e3 = c - b;
    Double4 finite = (e1 - e1) + (e2 - e2) + (e3 - e3); // 0 where all three are finite, else NaN
    double m = LargestOfThree(Larger(Magnitudes(e1), Magnitudes(e2)));
    if (!(finite[0] == 0 && finite[1] == 0 && finite[2] == 0) || !(m >= 0x1p-64 && m <= 0x1p64))
        return SetUpTriangle(tri, setUp); // edges that are not finite, or to be scaled
    // n = e1 x e2 from its six products, yz - zy, zx - xz, xy - yx, and their sizes
    Double4 p = Double4{e1[1], e1[2], e1[0], 0} * Double4{e2[2], e2[0], e2[1], 0};
    Double4 q = Double4{e1[2], e1[0], e1[1], 0} * Double4{e2[1], e2[2], e2[0], 0};
    Double4 n = p - q, size = Magnitudes(n);
    Double4 e = GammaD(5) * (Magnitudes(p) + Magnitudes(q));
    double largest = LargestOfThree(size);
    if (!(largest >= 0x1p-500 && largest <= 0x1p500))
        return SetUpTriangle(tri, setUp); // no area, or a normal to scale before squaring
    LaneBox(&a, &b, &c, &setUp->box);
    setUp->scale = 0, setUp->hasArea = true;
    setUp->n = {n[0], n[1], n[2]}, setUp->nError = {e[0], e[1], e[2]};
    setUp->flat = size[0] > size[1] ? (size[0] > size[2] ? 0 : 2) : (size[1] > size[2] ? 1 : 2);
    setUp->normalKnown = LargestOfThree(e) <= kFirstOrderShare * largest;
    setUp->awayShare = setUp->normalKnown
                           ? (real)(4 * ((e[0] + e[1] + e[2]) / largest)) + 16 * kUnitRoundoff
                           : 0;
    double inverse = 1 / std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    setUp->normal = {(real)(inverse * n[0]), (real)(inverse * n[1]), (real)(inverse * n[2])};
}
