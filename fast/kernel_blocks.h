// kernel_blocks.h -- the block test of the fast triangle loop (kernel.cpp): the watertight
// test's first step on kLanes triangles at once, and the reference test for the survivors.
// Included by kernel.cpp alone: the kernel is one translation unit, so that each of its two
// compiled copies (AVX2 and baseline) inlines all of it.
#pragma once
#include "fast.h"
#include "lanes.h"

// The helpers below write their vectors through pointers and never return one: a 256-bit vector
// is returned differently with AVX than without, which clang refuses in the baseline copy. They
// take them by value only where always inlined, so no call passes one.

RT_LANES(Lanes, real, kLanes);                // kLanes numbers
typedef decltype(Lanes() < Lanes()) LaneMask; // per lane: all bits set, or none

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

// One bit a lane, lane i's at bit i, of a mask whose lanes are each all ones or none. Vector
// extensions have no "movemask": each lane is narrowed to one byte, the bytes read as one word,
// and one multiplication moves each byte's low bit to its own place. (Byte k's bit, at 8k, is
// multiplied by 2^(top - 7k) among other powers; every product lands on a bit of its own, so no
// carry disturbs the kLanes bits from `top` up.) With AVX2 that is a few instructions where a
// loop over the lanes was about forty; without shuffles, the loop it is.
static RT_INLINE unsigned LaneBits(const LaneMask *mask) {
#if !RT_SHUFFLES
    unsigned bits = 0;
    for (int i = 0; i < kLanes; i++)
        bits |= (unsigned)((*mask)[i] != 0) << i;
    return bits;
#else
    typedef int MaskInts __attribute__((vector_size(sizeof(Lanes)))); // a LaneMask as ints
    typedef int FourInts __attribute__((vector_size(16)));
    typedef char SixteenBytes __attribute__((vector_size(16)));
    MaskInts ints;
    memcpy(&ints, mask, sizeof ints);
#ifdef RT_FLOAT // eight lanes of one int: each half of the ints to bytes, then the halves joined
    typedef char FourBytes __attribute__((vector_size(4)));
    FourInts low = __builtin_shufflevector(ints, ints, 0, 1, 2, 3);
    FourInts high = __builtin_shufflevector(ints, ints, 4, 5, 6, 7);
    SixteenBytes lowBytes, highBytes;
    memcpy(&lowBytes, &low, 16), memcpy(&highBytes, &high, 16);
    FourBytes a = __builtin_shufflevector(lowBytes, lowBytes, 0, 4, 8, 12);
    FourBytes b = __builtin_shufflevector(highBytes, highBytes, 0, 4, 8, 12);
    uint32_t lo, hi;
    memcpy(&lo, &a, 4), memcpy(&hi, &b, 4);
    uint64_t word = (uint64_t)hi << 32 | lo;
    return (unsigned)(((word & 0x0101010101010101u) * 0x0102040810204080u) >> 56);
#else           // four lanes of two ints: one int of each, then one byte of each
    typedef char FourBytes __attribute__((vector_size(4)));
    FourInts one = __builtin_shufflevector(ints, ints, 0, 2, 4, 6);
    SixteenBytes bytes;
    memcpy(&bytes, &one, sizeof bytes);
    FourBytes each = __builtin_shufflevector(bytes, bytes, 0, 4, 8, 12);
    uint32_t word;
    memcpy(&word, &each, sizeof word);
    return (unsigned)(((uint64_t)(word & 0x01010101u) * 0x01020408u >> 24) & 0xf);
#endif
#endif
}

// The lanes whose triangles survive EdgesDisagree (watertight.cpp), as bits: the same edge
// functions, U = Cx By - Cy Bx, V = Ax Cy - Ay Cx, W = Bx Ay - By Ax, and a triangle is out when
// two of them have strictly opposite signs, that is, when one of the three is negative and one
// positive (no number is both, and a NaN compares false both ways, as in the scalar test).
// *sure: the survivors whose three edge functions are neither 0 nor NaN, so that the ray
// passes inside for certain.
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
    LaneMask uNeg = u < zero, vNeg = v < zero, wNeg = w < zero;
    LaneMask uPos = u > zero, vPos = v > zero, wPos = w > zero;
    LaneMask out = (uNeg | vNeg | wNeg) & (uPos | vPos | wPos);
    unsigned live = ~LaneBits(&out) & ((1u << kLanes) - 1);
    if (live == 0) // most blocks
        return 0;
    LaneMask certain = (uNeg | uPos) & (vNeg | vPos) & (wNeg | wPos);
    *sure = live & LaneBits(&certain);
    return live;
}

// The same lanes one by one, for a processor without AVX2: there a block of four doubles takes two
// SSE2 registers for every operation, and the scalar test, which stops after two edge functions
// for most triangles, is faster.
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
struct TriangleSearch {
    const Triangle *triangles;
    const TriangleSetUp *setUps; // the triangles' boxes and planes (SceneLayout)
    const Ray *ray;
    const RayShear *shear;
    LaneRay lanes;
    int skip;
    real tMin, tMax;
    int best; // place of the nearest triangle hit so far; -1: none (or only a sphere)
    bool anyHit;
    real inverse[3], originPad; // 1 / d by axis and OriginPad, for OutOfReach
};

// 1 / d on each axis, as MakeSlabRay divides (each lane rounds as the scalar division does),
// for OutOfReach: one vector division, made every search, and built in registers (three numbers
// stored one by one and read back as one vector would wait for the stores).
static RT_INLINE void Inverses(vec3 d, real inverse[3]) {
    Lanes one, lanes;
    Splat(&one, 1);
    lanes = one;
    lanes[0] = d.x, lanes[1] = d.y, lanes[2] = d.z;
    Lanes quotient = one / lanes;
    inverse[0] = quotient[0], inverse[1] = quotient[1], inverse[2] = quotient[2];
}

// A triangle whose window (plane.cpp) lies wholly at or beyond `limit`, or at or before tMin:
// it cannot be hit, since every hit lies in its triangle's window, and the window lies inside
// the box's slab on any one axis (SlabInterval, whose steps on each axis are these, with the
// same rounding). The axis is the one the triangle's plane most nearly faces
// (TriangleSetUp::flat): a wall facing an axis has no thickness there, so its slab is a narrow
// band of t around where the line crosses it, and a triangle crossed behind the origin or beyond
// the nearest hit is refused for about a tenth of the plane test it saves: the ceiling behind a
// lamp that a shadow ray aims at, the wall behind a ray that leaves a sphere. (The ray's main
// axis, tried first, let most of them through: on the Cornell box 206,505 plane tests for 74,438
// hits; across the flat axis 75,113.) Along an axis the ray does not move on (d = 0, 1/d
// infinite) the slab is everything or nothing, as it is in SlabInterval: the line stays at o
// there, and a NaN (o exactly on the widened face) refuses nothing. A 1/d that overflows from a
// tiny d moves the line far less along that axis than the pad, since ScaleRay keeps the largest |d|
// near 1.
static RT_INLINE bool OutOfReach(const Box *box, int axis, const TriangleSearch *s, real limit) {
    real pad = kBoxAllowance * box->size + s->originPad, first, last;
    SlabEnds(box->lo[axis], box->hi[axis], pad, Component(s->ray->origin, axis), s->inverse[axis],
             std::signbit(s->inverse[axis]), &first, &last);
    return first >= limit || last <= s->tMin;
}

// The full test of one triangle that passed the first step, at place `index` (not to be
// skipped), with its set-up: the reach test, then the rest of the reference test. A triangle at
// the same t as the nearest so far counts only if it comes earlier in the scene (so the tMax it
// is tested against is one step above). `sure`: its three edge functions are known to be of one
// sign and none 0, so what IntersectSheared does next is RobustPlaneHit, called here with the
// same arguments. True if hit (the search's nearest then).
static RT_INLINE bool TestSurvivor(TriangleSearch *s, int index, const TriangleSetUp *setUp,
                                   bool sure, RayHit *hit) {
    real limit = s->best >= 0 && index < s->best ? NextAfter(s->tMax, true) : s->tMax;
    const Triangle *tri = &s->triangles[index];
    if (OutOfReach(&setUp->box, setUp->flat, s, limit))
        return false;
    if (!(sure ? RobustPlaneHit(tri, setUp, s->ray, s->tMin, limit, hit)
               : IntersectWatertight(tri, setUp, s->ray, s->shear, s->tMin, limit, hit)))
        return false;
    hit->index = s->best = index;
    s->tMax = hit->t;
    return true;
}

// The full test for the survivors of blocks [first, first + count). True if anything was hit.
template <int kz, bool kVectors>
static RT_INLINE bool TestBlocks(const TriangleBlock *blocks, int first, int count,
                                 TriangleSearch *s, RayHit *hit) {
    bool found = false;
    for (const TriangleBlock *b = blocks + first; b < blocks + first + count; b++) {
        unsigned sure;
        unsigned live = kVectors ? Survivors<kz>(b, &s->lanes, &sure)
                                 : SurvivorsOneByOne<kz>(b, s->shear, &sure);
        for (; live != 0; live &= live - 1) {
            int lane = LowestBit(live), index = b->index[lane];
            if (index < 0 || index == s->skip ||
                !TestSurvivor(s, index, &s->setUps[index], sure >> lane & 1u, hit))
                continue;
            found = true;
            if (s->anyHit)
                return true;
        }
    }
    return found;
}
