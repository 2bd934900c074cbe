// kernel_plane.h -- RobustPlaneHit (plane.cpp) for the triangles the wide tree's search tests
// (kernel_wide.h): tier 1 here, with what depends on the ray alone made once per search, and
// plane.cpp's own SlowPlaneT for what tier 1 leaves unsure. Included by kernel.cpp alone.
//
// Every line of QuickTier1 is QuickPlaneT's (with PlainError's, PlaneError's, WellInside's and
// FirstOrderHolds'): the same operations on the same numbers in the same order, unfused, so it
// settles exactly the rays QuickPlaneT settles, with the same t and bound (plane_lanes.h does the
// same for four rays at once). A change there is a change here; the layout tests hold the two to
// the same bits.
#pragma once
#include "../robust/robust.h"

// The ray as tier 1 reads it, in double: origin, direction, |d| per axis, OriginPad.
struct PlaneRay {
    double o[3], d[3], absD[3];
    double originPad;
};

static RT_INLINE void MakePlaneRay(const Ray *ray, PlaneRay *r) {
    const real o[3] = {ray->origin.x, ray->origin.y, ray->origin.z};
    const real d[3] = {ray->dir.x, ray->dir.y, ray->dir.z};
    for (int i = 0; i < 3; i++)
        r->o[i] = o[i], r->d[i] = d[i], r->absD[i] = std::fabs(r->d[i]);
    r->originPad = OriginPad(ray);
}

// a.x b.x + a.y b.y + a.z b.z, in that order (DotD).
static RT_INLINE double Dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// QuickPlaneT's answer for tri (which has area) and the ray, against (tMin, tMax); its t and bound
// where it is PLANE_HIT.
static RT_INLINE QuickAnswer QuickTier1(const Triangle *tri, const TriangleSetUp *setUp,
                                        const PlaneRay *r, real tMin, real tMax, PlaneT *plane) {
    const double a[3] = {tri->a.x, tri->a.y, tri->a.z};
    const double n[3] = {setUp->n.x, setUp->n.y, setUp->n.z};
    const double e[3] = {setUp->nError.x, setUp->nError.y, setUp->nError.z};
    const double toA[3] = {a[0] - r->o[0], a[1] - r->o[1], a[2] - r->o[2]};
    double denominator = Dot3(n, r->d);
    double t = Dot3(n, toA) / denominator;
    if (!std::isfinite(t)) // the ray is parallel to the plane, or n is 0
        return PLANE_MISS;
    // PlainError: t's first-order bound
    const double absN[3] = {std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2])};
    const double absToA[3] = {std::fabs(toA[0]), std::fabs(toA[1]), std::fabs(toA[2])};
    double eN = GammaD(4) * Dot3(absN, absToA), eD = GammaD(3) * Dot3(absN, r->absD);
    const double corner[3] = {std::fabs(toA[0] - t * r->d[0]), std::fabs(toA[1] - t * r->d[1]),
                              std::fabs(toA[2] - t * r->d[2])};
    double error = 2 * ((eN + std::fabs(t) * eD + Dot3(e, corner)) / std::fabs(denominator)) +
                   GammaD(1) * std::fabs(t);
    // WellInside: o + t d within half the window's widening of the box
    const Box *box = &setUp->box;
    double pad = 0.5 * ((double)kBoxAllowance * box->size + r->originPad);
    for (int i = 0; i < 3; i++) {
        double q = r->o[i] + t * r->d[i];
        if (!(q >= box->lo[i] - pad && q <= box->hi[i] + pad))
            return PLANE_UNSURE;
    }
    // FirstOrderHolds: n.d's error, with the normal's, small against n.d
    double eFirst = GammaD(3) * Dot3(absN, r->absD) + Dot3(e, r->absD);
    if (!setUp->normalKnown || !(eFirst <= kFirstOrderShare * std::fabs(denominator)))
        return PLANE_UNSURE;
    return DecidePlaneT(t, error, tMin, tMax, plane);
}

// RobustPlaneHit(tri, setUp, ray, tMin, tMax, hit), its first tier here.
static RT_INLINE bool KernelPlaneHit(const Triangle *tri, const TriangleSetUp *setUp,
                                     const Ray *ray, const PlaneRay *r, real tMin, real tMax,
                                     RayHit *hit) {
    if (!setUp->hasArea)
        return false; // no area: no plane, no normal
    PlaneT plane;
    QuickAnswer quick = QuickTier1(tri, setUp, r, tMin, tMax, &plane);
    if (quick == PLANE_MISS ||
        (quick == PLANE_UNSURE && !SlowPlaneT(tri, setUp, ray, tMin, tMax, &plane)))
        return false;
    return PlaneHitRecord(tri, setUp, ray, plane, hit);
}
