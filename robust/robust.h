// robust/robust.h -- the robust wing: what rt computes beyond the handouts so that no answer
// depends on the scene's scale, and what the core calls at its `// robust:` lines.
//
// Here: the rescaling of a ray whose direction is too large or too small to square (rescale.cpp,
// taken by SearchList for such a ray, and by fast/ the same way); boxes along a ray (the
// window a triangle's hit lies in, which the BVH's boxes share); the plane's t and its error bound
// (plane.cpp); the watertight inside test's shear (watertight.cpp); and how a ray leaves a surface
// without hitting it again (OffsetRayOrigin, LeavingPoint, TerminatorOrigin: leave.cpp,
// PassesOver, StartLeaving: geometry.cpp, smooth.cpp and path_full.cpp).
#pragma once
#include "../ray.h"

// The number next to x toward +infinity (up) or -infinity: std::nextafter(x, +-infinity), bit
// for bit, without the library call. Away from 0 the neighbour is the bit pattern one step
// further from or nearer to 0; from 0 it is the smallest subnormal.
inline real NextAfter(real x, bool up) {
    if (x != x || (x == (up ? kInfinity : -kInfinity)))
        return x; // NaN, or already the end it moves toward
    if (x == 0)
        return up ? std::numeric_limits<real>::denorm_min()
                  : -std::numeric_limits<real>::denorm_min();
    RealBits bits;
    memcpy(&bits, &x, sizeof bits);
    bits = (x > 0) == up ? bits + 1 : bits - 1;
    memcpy(&x, &bits, sizeof x);
    return x;
}

// A vector in double, whatever `real` is: the plane's first tier computes in double.
struct dvec3 {
    double x, y, z;
};

// ---- rescale.cpp: directions too large or too small to square --------------------------------

// Beyond the handouts (SearchList, and fast/ the same way): a ray whose direction is too large or
// too small to square (not SearchedAsIs, numbers.h) is searched along a rescaled direction.

// A ray whose direction lies outside kDirectionWindow, rescaled to a largest component in [1, 2),
// with its interval, so that no shape test squares or divides a direction of 1e-200 or 1e200 out
// of range. Scaling d by 2^exponent scales every t by 2^-exponent exactly; ScaleBack undoes it.
// exponent = 0: the direction is inside the window, and the ray is searched as given (`ray` is
// not set).
struct ScaledRay {
    Ray ray;
    int exponent;
    real tMin, tMax;
};

// The rescaling itself, for a direction outside the window (ScaleRay): robust/rescale.cpp.
bool RescaleRay(const Ray *ray, ScaledRay *s);

// The ray rescaled where its direction lies outside the window, and (tMin, tMax) with it, cut so
// that every t' in it comes back inside (tMin, tMax). False for a direction that is zero or not
// finite: such a ray has no answer. (Inline: fast/'s searches and the watertight test start
// here, and almost every direction is inside the window.)
inline bool ScaleRay(const Ray *ray, real tMin, real tMax, ScaledRay *s) {
    s->exponent = 0, s->tMin = tMin, s->tMax = tMax;
    return SearchedAsIs(ray->dir) || RescaleRay(ray, s);
}

// The ray a search follows: the rescaled one, or the one given.
inline const Ray *SearchedRay(const ScaledRay *s, const Ray *given) {
    return s->exponent == 0 ? given : &s->ray;
}

// The hit's t in units of the original direction; false if that leaves (tMin, tMax) by
// overflowing or underflowing.
inline bool ScaleBack(const ScaledRay *s, real tMin, real tMax, RayHit *hit) {
    if (s->exponent == 0)
        return true;
    hit->t = ScaleByPowerOfTwo(hit->t, s->exponent);
    return hit->t > tMin && hit->t < tMax;
}

// ---- boxes and a triangle's set-up (plane.cpp, and the BVH of fast/) ------------------------

// An axis-aligned box, and its largest |coordinate| (TriangleBox and SlabInterval).
struct Box {
    real lo[3], hi[3];
    real size;
};

// What a triangle's hit needs that does not depend on the ray (plane.cpp): the box that holds
// every hit (TriangleBox, the window), and the plane's normal as the first tier rounds it. The
// committed scene (fast/) keeps one for each triangle; the plain loop makes it as it goes. (The
// small members sit together after the box, so that no padding follows each.)
struct TriangleSetUp {
    Box box;
    int scale;          // the edges are multiplied by 2^scale before their cross product
    bool normalKnown;   // nError small against n: the first half of FirstOrderHolds (plane.cpp)
    unsigned char flat; // the axis of n's largest component: the one the plane most nearly faces
    bool hasArea;       // n is neither 0 nor beyond the range of numbers
    dvec3 n;            // (b - a) 2^scale x (c - a) 2^scale, rounded
    dvec3 nError;       // per component of n, a bound on its rounding error
    vec3 normal;        // n / |n|, for shading
    real awayShare;     // for RayHit::awayShare: > 0 where normalKnown, else 0
};

// Where a ray's line passes through an axis-aligned box, widened by kBoxAllowance of the
// coordinates' sizes: the box test of the BVH, and the window a triangle's hit must lie in.
// Both use this one function, with the same rounding, so a node's window always holds the
// windows of the triangles below it (each step is monotonic: a larger box, larger bounds). 128 u
// is about three times the widest error bound of a triangle's hit point (plane.cpp), so a hit on
// the triangle always lies inside its window.
const real kBoxAllowance = 128 * kUnitRoundoff;

// The per-ray half: origin, 1/d per axis (an infinity for a 0 component), the allowance for the
// origin's size, and which end of each slab the ray meets first (the sign of 1/d).
struct SlabRay {
    vec3 origin, inverse;
    real originPad;   // OriginPad: the widening that comes with the ray
    bool backward[3]; // 1/d < 0 on that axis: the ray meets hi before lo
};
// The widening that comes with the ray: kBoxAllowance of its origin's size, and 4 times the
// smallest normal number, which stands in for sizes whose allowance would underflow (the
// rounding of numbers below it is absolute, 2^-1074 in double, far below this floor).
inline real OriginPad(const Ray *ray) {
    return kBoxAllowance * MaxComponent(ray->origin) + 4 * std::numeric_limits<real>::min();
}
inline SlabRay MakeSlabRay(const Ray *ray) {
    SlabRay r = {ray->origin, {1 / ray->dir.x, 1 / ray->dir.y, 1 / ray->dir.z}, OriginPad(ray), {}};
    r.backward[0] = std::signbit(r.inverse.x), r.backward[1] = std::signbit(r.inverse.y);
    r.backward[2] = std::signbit(r.inverse.z);
    return r;
}

// One axis of SlabInterval: where the line enters (*first) and leaves (*last) the slab lo..hi,
// widened by pad on both sides.
inline void SlabEnds(real lo, real hi, real pad, real o, real inverse, bool backward, real *first,
                     real *last) {
    real a = ((lo - pad) - o) * inverse, b = ((hi + pad) - o) * inverse;
    *first = backward ? b : a, *last = backward ? a : b;
}

// The interval of t in which the line is inside the box lo..hi, whose largest |coordinate| is
// `size`, widened on every side by kBoxAllowance (size + the origin's size). A 0 * infinity (a
// ray along a box face) is NaN and restricts nothing, nor does a box of non-finite size. The
// ends are taken by the sign of 1/d, not compared, so the loop has no branch to mispredict.
inline void SlabInterval(const real lo[3], const real hi[3], real size, const SlabRay *r,
                         real *tNear, real *tFar) {
    real pad = kBoxAllowance * size + r->originPad;
    const real o[3] = {r->origin.x, r->origin.y, r->origin.z};
    const real inv[3] = {r->inverse.x, r->inverse.y, r->inverse.z};
    real near = -kInfinity, far = kInfinity;
    for (int i = 0; i < 3; i++) {
        real first, last;
        SlabEnds(lo[i], hi[i], pad, o[i], inv[i], r->backward[i], &first, &last);
        near = first > near ? first : near; // (NaN compares false: no restriction)
        far = last < far ? last : far;
    }
    *tNear = near, *tFar = far;
}

// A triangle's bounding box (Box). A corner that is not finite makes the box infinite: it holds
// every point, so no window or node that holds it can exclude a hit.
inline Box TriangleBox(const Triangle *tri) {
    vec3 a = tri->a, b = tri->b, c = tri->c;
    if (!IsFinite(a) || !IsFinite(b) || !IsFinite(c))
        return {{-kInfinity, -kInfinity, -kInfinity}, {kInfinity, kInfinity, kInfinity}, kInfinity};
    auto least = [](real x, real y, real z) { return x < y ? (x < z ? x : z) : (y < z ? y : z); };
    auto most = [](real x, real y, real z) { return x > y ? (x > z ? x : z) : (y > z ? y : z); };
    Box box = {{least(a.x, b.x, c.x), least(a.y, b.y, c.y), least(a.z, b.z, c.z)},
               {most(a.x, b.x, c.x), most(a.y, b.y, c.y), most(a.z, b.z, c.z)},
               0};
    real lo = MaxComponent({box.lo[0], box.lo[1], box.lo[2]});
    real hi = MaxComponent({box.hi[0], box.hi[1], box.hi[2]});
    box.size = lo > hi ? lo : hi;
    return box;
}

// ---- plane.cpp: where a ray meets a triangle's plane -------------------------------------------

// Fills *setUp for tri: its box, its normal from edges scaled by a power of two, that
// normal's error bound, and whether the first tier's bound may be trusted (plane.cpp).
void SetUpTriangle(const Triangle *tri, TriangleSetUp *setUp);

// Whether every edge of tri (b - a, c - a, c - b, in double) is a finite vector: one that is not
// makes the triangle unhittable (SetUpTriangle's hasArea is false).
bool EdgesFinite(const Triangle *tri);

// The hit record of a triangle whose interior the ray passes through (plane.cpp): t from the
// triangle's plane, accurate for triangles of any length, and the point o + t d; false if t is
// outside (tMin, tMax) or within its rounding error of 0 (the ray has just left this plane).
// `setUp` is the triangle's SetUpTriangle, or null to compute it here.
bool RobustPlaneHit(const Triangle *tri, const TriangleSetUp *setUp, const Ray *ray, real tMin,
                    real tMax, RayHit *hit);

// Tier 1 of the plane's t (plane.cpp), whose numbers fast/'s packets share (fast/plane_lanes.h):
// the unit roundoff of double and gamma(n) for it (Higham 2002, §3.1; Gamma has them for `real`).
constexpr double kU = std::numeric_limits<double>::epsilon() / 2;
constexpr double GammaD(int n) { return n * kU / (1 - n * kU); }

// Tier 2 is taken when tier 1's bound is wider than this share of t: then the hit point
// o + t d, which inherits the error of t, would sit farther off the surface than a few roundings
// of its coordinates, and probes would print digits that are not known. In double, 32 u is about
// twice what tier 1 gives a ray that meets an axis-aligned wall head-on (some 15 u), so ordinary
// hits stay in tier 1. In float it is 32 u of float: tier 1 still computes in double, but the hit
// point is kept in float, and a t known to a few float roundings is all that point can use.
const double kPlainRelativeError = 32 * (double)kUnitRoundoff;

// Tier 1's bound is first order; FirstOrderHolds believes it only while the normal's
// error and n.d's error are each within this share of what they are errors of. (Then what the
// bound leaves out is at most about 2^-9 of what it keeps, which its factor of 2 covers:
// FirstOrderHolds says how.)
const double kFirstOrderShare = 1.0 / 1024;

// t and a bound on |t - t*|, where t* is the exact t of the exact plane through a, b, c.
struct PlaneT {
    double t, error;
};

// What tier 1 alone makes of a ray (QuickPlaneT): a miss, a hit, or unsure, for
// RobustPlaneHit to decide from the start.
enum QuickAnswer { PLANE_MISS, PLANE_HIT, PLANE_UNSURE };

// Tier 1's last step, for a t whose first-order bound `error` holds: a miss where even twice the
// bound keeps t beyond tMax, behind the ray or at tMin; unsure where t might be 0 or the bound is
// wider than kPlainRelativeError of t; else t and its bound into *plane, and a hit when t, rounded
// to real, lies in (tMin, tMax) clear of its bound. (QuickPlaneT and fast/'s copy of it, alike.)
inline QuickAnswer DecidePlaneT(double t, double error, real tMin, real tMax, PlaneT *plane) {
    if (!(t - 2 * error < (double)tMax) || !(t + error > 0) || !(t + 2 * error > (double)tMin))
        return PLANE_MISS; // beyond or behind
    if (!(t - error > 0) || error > kPlainRelativeError * std::fabs(t))
        return PLANE_UNSURE;
    *plane = {t, error};
    return (real)t > tMin && (real)t < tMax && t > error ? PLANE_HIT : PLANE_MISS;
}

// What RobustPlaneHit does where tier 1 alone cannot decide (QuickPlaneT: PLANE_UNSURE): both
// tiers from the start, t in (tMin, tMax) and its bound into *plane; false if there is none. For
// fast/, which runs tier 1 itself (and the triangle has area).
bool SlowPlaneT(const Triangle *tri, const TriangleSetUp *setUp, const Ray *ray, real tMin,
                real tMax, PlaneT *plane);

// RobustPlaneHit's record for the t it settled on: the point o + t d, which lies on the plane to
// within its bound (the rounding of o + t d itself, and t's error times |d|), the normal turned
// toward the ray. False, and *hit untouched, where the point leaves the range of numbers.
inline bool PlaneHitRecord(const Triangle *tri, const TriangleSetUp *setUp, const Ray *ray,
                           PlaneT plane, RayHit *hit) {
    real t = (real)plane.t;
    vec3 along = t * ray->dir;
    if (!IsFinite(ray->origin + along)) // t finite, but the point beyond the range of numbers
        return false;
    SetFaceNormal(ray, setUp->normal, hit); // (a miss leaves *hit as it was)
    hit->t = t;
    hit->point = ray->origin + along;
    real tError = (real)plane.error + Gamma(1) * t;
    hit->pointError = Gamma(2) * (Abs(hit->point) + Abs(along)) + tError * Abs(ray->dir);
    hit->material = tri->material;
    hit->shape = SHAPE_TRIANGLE;
    hit->awayShare = setUp->awayShare;
    return true;
}

// ---- watertight.cpp: the watertight triangle test ----------------------------------------------

// The axis of d's largest component (of equal ones, the later axis), which the watertight
// test's shear turns into z (ShearRay).
inline int DominantAxis(vec3 d) {
    vec3 ad = Abs(d);
    return ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
}

// The per-ray half of the watertight test, shared by every triangle the ray meets: kz, the axis
// of the direction's largest component, renamed z; the ray origin with its axes renamed
// (kz + 1, kz + 2, kz); and the shear that turns the direction into the +z axis.
struct RayShear {
    int kz;
    vec3 origin;
    real sx, sy; // d[kx]/d[kz] and d[ky]/d[kz]
};
void ShearRay(const Ray *ray, RayShear *shear);

// v with its axes renamed (kx, ky, kz) = (kz + 1, kz + 2, kz) mod 3. A rotation keeps the
// triangles' winding, whatever kz is. kz is a compile-time constant, so every component below is
// a plain field, not an indexed load (the fast kernel is compiled once per axis).
template <int kz> inline vec3 RenameAxes(vec3 v) {
    if constexpr (kz == 0)
        return {v.y, v.z, v.x};
    else if constexpr (kz == 1)
        return {v.z, v.x, v.y};
    else
        return v;
}

// ShearRay for a ray whose kz is known (watertight.cpp explains the shear).
template <int kz> inline void ShearRayAxes(const Ray *ray, RayShear *shear) {
    vec3 d = RenameAxes<kz>(ray->dir);
    *shear = {kz, RenameAxes<kz>(ray->origin), d.x / d.z, d.y / d.z};
}

// The watertight test of one triangle for a ray whose shear is computed: as IntersectTriangle.
// `setUp` as for RobustPlaneHit.
bool IntersectWatertight(const Triangle *tri, const TriangleSetUp *setUp, const Ray *ray,
                         const RayShear *shear, real tMin, real tMax, RayHit *hit);

// ---- geometry.cpp and path_full.cpp: rays that leave a surface ---------------------------------

// Self-intersection ("shadow acne") is prevented by one method for every ray that leaves a
// surface (pbrt-v4 §6.8.6): a point within `error` (per axis) of the true surface, moved along
// the unit normal by the error box's extent in that direction, sum |n_i| error_i, is on the side
// the new ray goes to, whatever the scene's scale. Rounding the moved point outward (NextAfter)
// keeps the addition itself from undoing the move. The new ray then uses tMin = 0, and the
// intersectors' own "t above its rounding error" tests do the rest. (Inline: every ray that
// leaves a surface starts here.)
inline vec3 OffsetRayOrigin(vec3 point, vec3 error, vec3 normal, vec3 dir) {
    real distance = Dot(Abs(normal), error);
    vec3 offset = distance * normal;
    if (Dot(dir, normal) < 0)
        offset = -offset;
    vec3 moved = point + offset;
    real *coord[3] = {&moved.x, &moved.y, &moved.z};
    real push[3] = {offset.x, offset.y, offset.z};
    for (int i = 0; i < 3; i++) {
        if (push[i] > 0)
            *coord[i] = NextAfter(*coord[i], true);
        else if (push[i] < 0)
            *coord[i] = NextAfter(*coord[i], false);
    }
    return moved;
}

// The hit point moved off its surface so (the hit's own point and error bound).
inline vec3 OffsetRayOrigin(const RayHit *hit, vec3 dir) {
    return OffsetRayOrigin(hit->point, hit->pointError, hit->normal, dir);
}

// Where a ray that leaves `hit` in direction dir starts: the hit point moved off its surface
// (OffsetRayOrigin), and for a triangle, where the hit lies too near an edge, a point moved in
// from the edges first, so that the ray starts inside every closed mesh the triangle is part of
// (leave.cpp). The triangle's corners are the scene's; a smooth mesh's triangle is left as a
// flat one (TerminatorOrigin is the curved surface's).
vec3 LeavingPoint(const Scene *scene, const RayHit *hit, vec3 dir);

// On a smooth mesh's triangle, the origin moved out from the hit to where the curved surface would
// be, on the side `toward` points to (Hanika's shift, leave.cpp), and off it as OffsetRayOrigin
// moves a point. False where there is no such move: a flat triangle, a flat or concave region,
// or corner normals that would put the origin on the face's other side (or within rounding of
// it). The move is checked against nothing else: the caller proves the way there free of other
// shapes (DeparturePoint, smooth.cpp).
bool TerminatorOrigin(const Scene *scene, const RayHit *hit, vec3 toward, vec3 *origin);

// Whether a ray in direction dir from a point that LeavingPoint moved off triangle hit, to the
// side `side` points to, goes so plainly away from it that the shape loop may pass over it. The
// moved origin is on that side of the exact plane, or on it (OffsetRayOrigin's bound, which
// holds while the normal is known to 2^-10: normalKnown). A ray going away from the plane on
// that side can then meet it only at t <= 0, which RobustPlaneHit's sound bound refuses; passing
// over the triangle, as --self-hit skip does, changes no answer wherever that bound holds (a
// layout test checks closed meshes of triangles around spheres of radius 1e-305 to 1e300) and
// saves the search that refusal: the whole plane test. Going away is certain where the rounded
// n.d, on that side, exceeds awayShare of sum |d_i| (SetUpTriangle says why). A sphere is never
// passed over: a ray leaving it inward meets it again.
inline bool PassesOver(const RayHit *hit, vec3 side, vec3 dir) {
    if (!(hit->shape == SHAPE_TRIANGLE && hit->awayShare > 0))
        return false;
    real away = Dot(side, hit->normal) < 0 ? -Dot(dir, hit->normal) : Dot(dir, hit->normal);
    return away > hit->awayShare * (std::fabs(dir.x) + std::fabs(dir.y) + std::fabs(dir.z));
}

// Where such a ray starts its search: from t = 0, passing over the triangle it leaves where
// PassesOver, else over nothing. A smooth mesh's triangle is never passed over: its ray may start
// off the plane, moved out to the curved surface (TerminatorOrigin), where the plane's side no
// longer tells whether it can be met again.
inline SelfHit StartLeaving(const Scene *scene, const RayHit *hit, vec3 side, vec3 dir) {
    return PassesOver(hit, side, dir) && !HasCornerNormals(scene, hit)
               ? SelfHit{0, SHAPE_TRIANGLE, hit->index}
               : kNoSelfHit;
}
