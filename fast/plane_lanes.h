// plane_lanes.h -- tier 1 of the plane's t (plane.cpp, QuickPlaneT) for up to four rays of a
// packet and one triangle at once: the rays that survive the same triangle's edge test in a
// packet (kernel_packet.h) usually all meet its plane, so its t, error bound and checks are
// computed in the lanes of one vector of doubles, in double also in the float build, as tier 1
// computes them. Included by kernel.cpp alone, for its AVX2 copy.
//
// Every line is QuickPlaneT's (and PlainError's, WellInside's and FirstOrderHolds') with
// `PlaneLanes` for `double` and the triangle's numbers in every lane: the same operations in the
// same order, unfused, so every lane holds the very bits the scalar code computes. Where tier 1
// settles a ray alone (a hit or a miss), its answer is taken from the lanes; every other ray goes
// to RobustPlaneHit itself, which starts again.
#pragma once
#include "kernel_blocks.h"

#include <cfloat>

RT_LANES(PlaneLanes, double, 4);                         // 4 doubles
typedef decltype(PlaneLanes() < PlaneLanes()) PlaneMask; // per lane: all bits set, or none
const int kPlaneLanes = 4;

static RT_INLINE PlaneLanes Same(double x) { return PlaneLanes{x, x, x, x}; }
// fabs, lane by lane: the sign bit cleared. (The vector by pointer: passed by value, GCC notes
// that 32-byte arguments pass differently since GCC 4.6, whatever the pragma in kernel_blocks.h.)
static RT_INLINE PlaneLanes Magnitude(const PlaneLanes *v) {
    RT_LANES(Bits, long long, 4);
    Bits b;
    memcpy(&b, v, sizeof b);
    b &= Bits{} + 0x7fffffffffffffffll;
    PlaneLanes m;
    memcpy(&m, &b, sizeof m);
    return m;
}
static RT_INLINE bool Lane(const PlaneMask *m, int lane) { return (*m)[lane] != 0; }

// The rays of the lanes, widened to double as PlaneProblem widens them, with what else tier 1
// reads of each: its tMin and its origin's pad (OriginPad). (Its tMax, the limit for the
// triangle at hand, comes with each call.)
struct PlaneRays {
    PlaneLanes ox, oy, oz, dx, dy, dz;
    PlaneLanes tMin, originPad;
};

// What tier 1 computes first for each lane's ray, and what its checks share: a - o, n.d, t, |d|
// per axis, and n.d's rounding bound (PlainError's eD, which FirstOrderHolds adds to).
struct LaneT {
    PlaneLanes toAx, toAy, toAz, denominator, t;
    PlaneLanes absDx, absDy, absDz, eD;
};

// t = n.(a - o) / n.d, lane by lane, as FindPlaneT and QuickPlaneT compute it.
static RT_INLINE void LanePlaneT(const Triangle *tri, const TriangleSetUp *setUp,
                                 const PlaneRays *r, LaneT *l) {
    const dvec3 n = setUp->n;
    l->toAx = Same(tri->a.x) - r->ox, l->toAy = Same(tri->a.y) - r->oy;
    l->toAz = Same(tri->a.z) - r->oz;
    l->denominator = Same(n.x) * r->dx + Same(n.y) * r->dy + Same(n.z) * r->dz;
    l->t = (Same(n.x) * l->toAx + Same(n.y) * l->toAy + Same(n.z) * l->toAz) / l->denominator;
    l->absDx = Magnitude(&r->dx), l->absDy = Magnitude(&r->dy), l->absDz = Magnitude(&r->dz);
    PlaneLanes nx = Same(std::fabs(n.x)), ny = Same(std::fabs(n.y)), nz = Same(std::fabs(n.z));
    l->eD = GammaD(3) * (nx * l->absDx + ny * l->absDy + nz * l->absDz);
}

// PlainError (plane.cpp), lane by lane: t's first-order bound.
static RT_INLINE PlaneLanes LaneError(const TriangleSetUp *setUp, const PlaneRays *r,
                                      const LaneT *l) {
    const dvec3 n = setUp->n, e = setUp->nError;
    PlaneLanes nx = Same(std::fabs(n.x)), ny = Same(std::fabs(n.y)), nz = Same(std::fabs(n.z));
    PlaneLanes eN = GammaD(4) * (nx * Magnitude(&l->toAx) + ny * Magnitude(&l->toAy) +
                                 nz * Magnitude(&l->toAz));
    PlaneLanes cx = l->toAx - l->t * r->dx, cy = l->toAy - l->t * r->dy;
    PlaneLanes cz = l->toAz - l->t * r->dz, absT = Magnitude(&l->t);
    return 2 * ((eN + absT * l->eD +
                 (Same(e.x) * Magnitude(&cx) + Same(e.y) * Magnitude(&cy) +
                  Same(e.z) * Magnitude(&cz))) /
                Magnitude(&l->denominator)) +
           GammaD(1) * absT;
}

// WellInside (plane.cpp), lane by lane: o + t d within half the window's widening of the box.
static RT_INLINE PlaneMask LaneWellInside(const TriangleSetUp *setUp, const PlaneRays *r,
                                          const LaneT *l) {
    const Box *box = &setUp->box;
    PlaneLanes pad = 0.5 * ((double)kBoxAllowance * box->size + r->originPad);
    PlaneLanes qx = r->ox + l->t * r->dx, qy = r->oy + l->t * r->dy, qz = r->oz + l->t * r->dz;
    PlaneMask inside = (qx >= box->lo[0] - pad) & (qx <= box->hi[0] + pad);
    inside &= (qy >= box->lo[1] - pad) & (qy <= box->hi[1] + pad);
    return inside & (qz >= box->lo[2] - pad) & (qz <= box->hi[2] + pad);
}

// FirstOrderHolds (plane.cpp), lane by lane: n.d's error, with the normal's, small against n.d.
// (The normal's own half, setUp->normalKnown, is the same for every lane.)
static RT_INLINE PlaneMask LaneFirstOrderHolds(const TriangleSetUp *setUp, const LaneT *l) {
    const dvec3 e = setUp->nError;
    PlaneLanes eD = l->eD + (Same(e.x) * l->absDx + Same(e.y) * l->absDy + Same(e.z) * l->absDz);
    return eD <= kFirstOrderShare * Magnitude(&l->denominator);
}

// QuickPlaneT's answer for each of `count` rays (at most kPlaneLanes) against tMax, with its t
// and bound where it is PLANE_HIT. The lanes past `count` repeat the first ray.
static RT_INLINE void QuickPlaneLanes(const Triangle *tri, const TriangleSetUp *setUp,
                                      const PlaneRays *r, const PlaneLanes *tMax, int count,
                                      QuickAnswer *answer, PlaneT *plane) {
    LaneT l;
    LanePlaneT(tri, setUp, r, &l);
    PlaneLanes t = l.t, error = LaneError(setUp, r, &l), zero = Same(0);
    PlaneMask finite = Magnitude(&t) <= Same(DBL_MAX);
    PlaneMask inside = LaneWellInside(setUp, r, &l), trusted = LaneFirstOrderHolds(setUp, &l);
    // The answers, in QuickPlaneT's order
    PlaneMask inRange = (t - 2 * error < *tMax) & (t + error > zero) & (t + 2 * error > r->tMin);
    PlaneMask tight = (t - error > zero) & ~(error > kPlainRelativeError * Magnitude(&t));
    for (int lane = 0; lane < count; lane++) {
        double tl = t[lane], el = error[lane];
        if (!Lane(&finite, lane))
            answer[lane] = PLANE_MISS;
        else if (!Lane(&inside, lane) || !setUp->normalKnown || !Lane(&trusted, lane))
            answer[lane] = PLANE_UNSURE;
        else if (!Lane(&inRange, lane))
            answer[lane] = PLANE_MISS;
        else if (!Lane(&tight, lane))
            answer[lane] = PLANE_UNSURE;
        else
            answer[lane] =
                (real)tl > (real)r->tMin[lane] && (real)tl < (real)(*tMax)[lane] && tl > el
                    ? PLANE_HIT
                    : PLANE_MISS;
        plane[lane] = {tl, el};
    }
}
