// robust/watertight.cpp -- the watertight ray/triangle test (Woop, Benthin & Wald, JCGT 2(1),
// 2013): rt's IntersectTriangle.
//
// The second handout's inside test, seen along the ray. The handout takes the hit point p and
// asks whether the cross products (b - a) x (p - a), (c - b) x (p - b), (a - c) x (p - c) agree
// in sign on the normal's largest coordinate. Here the ray itself is turned into the z axis (kz,
// the direction's largest coordinate, plays the part of the handout's largest one), so each cross
// product becomes a 2D edge function of the corners, U, V, W, with p at the origin. A corner
// shared by two triangles is transformed to the same numbers in both, so a shared edge's function
// is the same number with the opposite sign: no ray slips between them. Where the sign is not
// certain (0, or NaN from overflow) it is recomputed exactly. Where the ray meets the triangle,
// t, comes from plane.cpp. No epsilon anywhere.
#include "robust.h"

#include <algorithm>

// The sign of a.x * b.y - a.y * b.x (-1, 0 or 1), exact, also where the rounded difference of
// products is 0 or NaN (inf - inf). In float the products are exact in double, and no float
// squared leaves double's range. In double, Kahan's difference of products with fused
// multiply-adds is within 2 ulp of the exact value (Jeannerod, Louvet & Muller, Math. Comp.
// 2013), so its sign, and whether it is 0, are exact; the caller has scaled the corners so that
// no product over- or underflows.
static real EdgeSign(real ax, real ay, real bx, real by) {
#ifdef RT_FLOAT
    double e = (double)ax * (double)by - (double)ay * (double)bx;
#else
    real product = ay * bx;
    real productError = std::fma(-ay, bx, product);
    real e = std::fma(ax, by, -product) + productError;
#endif
    return e > 0 ? real(1) : e < 0 ? real(-1) : real(0);
}

// The per-ray half of the watertight test (Woop, Benthin & Wald 2013, §3): kz is the largest
// |d| component, and the shear turns the ray into the +z axis. It depends on the ray only, so
// the shape loop computes it once for all the triangles. (The paper also swaps kx and ky when
// d[kz] < 0, to keep the winding for back-face culling. That negates u, v and w together, which
// changes nothing for a two-sided test, so it is left out.) ShearRayAxes (robust.h) computes it for
// one kz.
void ShearRay(const Ray *ray, RayShear *shear) {
    int kz = DominantAxis(ray->dir);
    if (kz == 0)
        ShearRayAxes<0>(ray, shear);
    else if (kz == 1)
        ShearRayAxes<1>(ray, shear);
    else
        ShearRayAxes<2>(ray, shear);
}

// A triangle seen from the ray (ShearCorners): corners moved to the ray origin, axes renamed and
// sheared so the ray is the +z axis. x and y are final; z is not yet scaled by 1 / d[kz].
struct ShearedTriangle {
    real ax, ay, bx, by, cx, cy;
    real az, bz, cz;
};

// The signs of the three edge functions of the sheared triangle (IntersectSheared), exact.
// Called only when a rounded one came out 0 or NaN, so it is kept out of line. In double the
// corners are first scaled by a power of two so the largest coordinate is near 1: products of
// corners 1e-200 or 1e200 from the ray origin then neither underflow nor overflow (float needs
// no scaling: its products are computed in double).
static void ExactEdgeSigns(ShearedTriangle s, real *u, real *v, real *w) {
#ifndef RT_FLOAT
    real largest = std::max({std::fabs(s.ax), std::fabs(s.ay), std::fabs(s.bx), std::fabs(s.by),
                             std::fabs(s.cx), std::fabs(s.cy)});
    if (largest > 0 && std::isfinite(largest)) {
        int k = -BinaryExponent(largest);
        real *coordinate[6] = {&s.ax, &s.ay, &s.bx, &s.by, &s.cx, &s.cy};
        for (real *c : coordinate)
            *c = ScaleByPowerOfTwo(*c, k);
    }
#endif
    *u = EdgeSign(s.cx, s.cy, s.bx, s.by);
    *v = EdgeSign(s.ax, s.ay, s.cx, s.cy);
    *w = EdgeSign(s.bx, s.by, s.ax, s.ay);
}

// The corners of a triangle as the ray sees them: moved to the ray origin, renamed, sheared.
template <int kz>
static inline ShearedTriangle ShearCorners(const Triangle *tri, const RayShear *k) {
    vec3 A = RenameAxes<kz>(tri->a) - k->origin;
    vec3 B = RenameAxes<kz>(tri->b) - k->origin;
    vec3 C = RenameAxes<kz>(tri->c) - k->origin;
    return {A.x - k->sx * A.z,
            A.y - k->sy * A.z,
            B.x - k->sx * B.z,
            B.y - k->sy * B.z,
            C.x - k->sx * C.z,
            C.y - k->sy * C.z,
            A.z,
            B.z,
            C.z};
}

// The 2D edge functions U, V, W of the sheared corners (see IntersectSheared), rounded.
// True if two have strictly opposite signs: the ray passes outside an edge. Rounding is
// monotonic (x >= y gives fl(x) >= fl(y)), so a rounded a b - c d has the sign of the exact one
// or is 0. A true here is therefore never wrong, and a 0 is left to the exact recomputation.
// Two that disagree end the test before the third is computed. (These are the second handout's
// cross products, (b - a) x (p - a) and the others, taken in the sheared plane where the ray is
// the z axis: p is the origin there, so no hit point has to be computed, or rounded, first.)
static inline bool EdgesDisagree(const ShearedTriangle *s, real *u, real *v, real *w) {
    *u = s->cx * s->by - s->cy * s->bx;
    *v = s->ax * s->cy - s->ay * s->cx;
    if ((*u < 0 && *v > 0) || (*u > 0 && *v < 0))
        return true;
    *w = s->bx * s->ay - s->by * s->ax;
    return (*w < 0 && (*u > 0 || *v > 0)) || (*w > 0 && (*u < 0 || *v < 0));
}

// Watertight ray/triangle intersection (Woop, Benthin & Wald, "Watertight Ray/Triangle
// Intersection", JCGT 2(1), 2013). Move the ray origin to 0, rename the axes and shear so the
// ray is the +z axis (ShearRay); the ray then hits the triangle iff the 2D edge functions
//   U = Cx By - Cy Bx,  V = Ax Cy - Ay Cx,  W = Bx Ay - By Ax
// of the sheared corners agree in sign. t then comes from the triangle's plane (plane.cpp).
// Why watertight: a corner shared by two triangles is transformed to the same numbers in both,
// so a shared edge's function is the same number with the opposite sign, and the one case in
// which rounding can lie, a value of exactly 0, is recomputed exactly. No epsilon anywhere.
template <int kz>
static bool IntersectSheared(const Triangle *tri, const TriangleSetUp *setUp, const Ray *ray,
                             const RayShear *k, real tMin, real tMax, RayHit *hit) {
    // Translate the corners to the ray origin and shear them so the ray is the +z axis
    ShearedTriangle s = ShearCorners<kz>(tri, k);

    // The 2D edge functions
    real u, v, w;
    if (EdgesDisagree(&s, &u, &v, &w))
        return false;
    // Rounding is monotonic, also into the subnormals and to infinity, so a rounded edge function
    // has its exact sign, or is 0, or is NaN (two products that both overflowed): those two are
    // decided exactly, and only their signs are kept
    if (u == 0 || v == 0 || w == 0 || std::isnan(u) || std::isnan(v) || std::isnan(w))
        ExactEdgeSigns(s, &u, &v, &w);

    // Reject if the signs differ (the ray passes outside an edge) or the ray is in the plane
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0))
        return false;
    if (u == 0 && v == 0 && w == 0)
        return false;

    // Inside: where, from the triangle's plane (plane.cpp). The paper's own
    // t = (U Az + V Bz + W Cz) / (U + V + W) loses about u L^2 / w for a triangle of length L and
    // width w, more than the 1.5 units to the floor of a corridor 1e8 long.
    return RobustPlaneHit(tri, setUp, ray, tMin, tMax, hit);
}

bool IntersectWatertight(const Triangle *tri, const TriangleSetUp *setUp, const Ray *ray,
                         const RayShear *shear, real tMin, real tMax, RayHit *hit) {
    if (shear->kz == 0)
        return IntersectSheared<0>(tri, setUp, ray, shear, tMin, tMax, hit);
    if (shear->kz == 1)
        return IntersectSheared<1>(tri, setUp, ray, shear, tMin, tMax, hit);
    return IntersectSheared<2>(tri, setUp, ray, shear, tMin, tMax, hit);
}

// The watertight test for any ray: its direction rescaled where it is too large or too small to
// square (ScaleRay), the shear computed, the test, and t scaled back.
bool IntersectTriangle(const Triangle *tri, const Ray *ray, real tMin, real tMax, RayHit *hit) {
    ScaledRay s;
    RayShear shear;
    RayHit found;
    if (!ScaleRay(ray, tMin, tMax, &s))
        return false;
    const Ray *searched = SearchedRay(&s, ray);
    ShearRay(searched, &shear);
    if (!IntersectWatertight(tri, nullptr, searched, &shear, s.tMin, s.tMax, &found) ||
        !ScaleBack(&s, tMin, tMax, &found))
        return false;
    *hit = found;
    return true;
}
