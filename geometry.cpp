// geometry.cpp -- where rays meet shapes, and nothing else.
//
// rt's robust sphere (the assignment's quadratic, made stable: Ray Tracing Gems ch. 7), the second
// handout's nearest hit over a list of shapes, which serves every ray, and how a ray leaves a
// surface without hitting it again (pbrt-v4 §6.8's error bounds, or a handout's rule). Triangles:
// watertight.cpp decides inside or outside, plane.cpp says where; the handouts' own forms of
// both shapes are in handout.cpp. Compiled with -ffp-contract=off: see the Makefile.
#include "ray.h"
#include "robust.h"

#include <algorithm>

// The quadratic's discriminant halfB^2 - A C in the form A r^2 - |f x d|^2 (see SolveSphere):
// |f x d| / |d| is how far the ray's line passes from the centre, so it is negative exactly
// when the line misses the sphere.
static inline real SphereDiscriminant(vec3 f, vec3 d, real a, real r2) {
    vec3 fxd = Cross(f, d);
    return a * r2 - Dot(fxd, fxd);
}

// The assignment handout's sphere: solve |o + t d - c|^2 = r^2, that is A t^2 + B t + C = 0 with
// A = d.d, B = 2 d.(o - c), C = (o - c).(o - c) - r^2 (IntersectSphereTextbook is that form as the
// slide writes it). Read with the handout beside it: the same names, with B kept as halfB = B/2
// (Ray Tracing in One Weekend's half-b form), and each line the robust form changes marked with
// the handout's line. Two changes, from Ray Tracing Gems ch. 7 (Haines et al. 2019), because the
// textbook form fails for small spheres far away and for the near root:
//   the discriminant B^2/4 - AC equals A r^2 - |f x d|^2 (f = o - c): how far the line passes
//     from the centre, instead of the difference of two huge nearly equal numbers (Hearn & Baker);
//   the roots q = -(halfB + sign(halfB) sqrt(disc)), t0 = C / q, t1 = q / A: never subtract
//     nearly equal numbers (Press et al., Numerical Recipes §5.6).
// Writes the nearest root in (tMin, tMax) and the hit point relative to the centre. The caller
// has scaled f, d and r so that no square over- or underflows (IntersectSphere).
static bool SolveSphere(vec3 f, vec3 d, real r, real tMin, real tMax, real *tHit, vec3 *local) {
    real A = Dot(d, d);
    real halfB = Dot(f, d); // handout: B = 2 d.(o - c)
    real C = Dot(f, f) - r * r;

    // A sphere behind the ray: the origin outside (C > 0) and moving away (halfB > 0) means both
    // roots are negative (their product C/A > 0, their sum -B/A < 0)
    if (halfB > 0 && C > 0 && tMin >= 0)
        return false;

    // No hit if the line passes farther from the centre than the radius (NaN lands here too)
    real disc = SphereDiscriminant(f, d, A, r * r); // handout: B^2 - 4AC (here / 4)
    if (!(disc >= 0))
        return false;

    // Both roots, without cancellation
    real sqrtDisc = std::sqrt(disc);
    real q = -(halfB + std::copysign(sqrtDisc, halfB));
    if (q == 0) // the ray starts on the surface and is tangent to it
        return false;
    real t0 = C / q, t1 = q / A; // handout: (-B -+ sqrt(B^2 - 4AC)) / 2A
    if (t0 > t1)
        std::swap(t0, t1);

    // The least root above tMin (the second handout: the least non-negative root)
    bool nearRoot = true;
    real t = t0;
    if (!(t > tMin)) {
        t = t1;
        nearRoot = false;
        if (!(t > tMin))
            return false;
    }
    if (!(t < tMax))
        return false;

    // The hit point, relative to the centre: the line's closest point to the centre, then half a
    // chord back (near root) or on (far root), t = -halfB/A -+ sqrt(disc)/A. Unlike f + t d, this
    // never subtracts nearly equal numbers, so it stays right when the sphere is tiny and far
    // away. Then put it back on the sphere (pbrt-v4 §6.8.5): what error remains lies along the
    // surface, not across it, a few roundings of the coordinates.
    vec3 offLine = f - (halfB / A) * d;                             // handout: point = o + t d
    vec3 p = offLine + ((nearRoot ? -sqrtDisc : sqrtDisc) / A) * d; // (relative to c)
    *local = (r / Length(p)) * p;
    *tHit = t;
    return true;
}

// The sphere test for a ray and sphere of any size. SolveSphere squares lengths (d.d, r^2,
// |f x d|^2), which overflow for a light 1e153 away and underflow for a sphere of radius
// 1e-200. So outside the windows of numbers.h it runs in rescaled units: d times 2^kd (largest
// component in [1, 2)) and every length in units of about the radius (times 2^kr, r in [1, 2)).
// Each root is then t' = t 2^(kr - kd). Powers of two are exact, so where nothing over- or
// underflowed this gives the very bits of the unscaled arithmetic. No root is discarded as "too
// close to 0": a ray that leaves this sphere starts outside its rounding error (OffsetRayOrigin),
// so C has the right sign and the root it would re-hit is negative; a probe that starts a hair
// outside the sphere still sees it (a hit at t = 3e-11).
bool IntersectSphere(const Sphere *s, const Ray *ray, real tMin, real tMax, RayHit *hit) {
    if (!(s->radius > 0) || !std::isfinite(s->radius))
        return false;
    int kd = 0, kr = 0;
    if (!WithinWindow(MaxComponent(ray->dir), kDirectionWindow) ||
        !WithinWindow(s->radius, kLengthWindow) ||
        !(MaxComponent(ray->origin - s->center) <= PowerOfTwo(kLengthWindow)))
        kd = UnitExponent(ray->dir), kr = -BinaryExponent(s->radius);
    vec3 d = ScaleByPowerOfTwo(ray->dir, kd);
    vec3 f = ScaleByPowerOfTwo(ray->origin - s->center, kr);
    real r = ScaleByPowerOfTwo(s->radius, kr);
    real t;
    vec3 local;
    if (!(MaxComponent(d) > 0) || // a zero direction (or NaN): no answer
        !SolveSphere(f, d, r, ScaleByPowerOfTwo(tMin, kr - kd), ScaleByPowerOfTwo(tMax, kr - kd),
                     &t, &local))
        return false;
    t = ScaleByPowerOfTwo(t, kd - kr);
    if (!(t > tMin && t < tMax)) // scaling back under- or overflowed
        return false;
    // A point at the very centre is no point of the sphere: f = o - c rounded so far (an origin
    // some 1e178 radii away, float 1e30) that the ray seemed to pass through the centre. It has
    // no normal to give, so it is no hit.
    if (!(MaxComponent(local) > 0))
        return false;
    hit->t = t;
    vec3 world = ScaleByPowerOfTwo(local, -kr);
    hit->point = s->center + world;
    hit->pointError = Gamma(5) * Abs(world) + Gamma(1) * Abs(hit->point);
    SetFaceNormal(ray, (1 / r) * local, hit);
    hit->material = s->material;
    hit->shape = SHAPE_SPHERE;
    hit->awayShare = 0; // never passed over
    return true;
}

// A ray's direction rescaled to a largest component in [1, 2) when it lies outside
// kDirectionWindow (numbers.h), and its interval with it, so that no shape test squares or divides
// a direction of 1e-200 or 1e200 out of range. Scaling d by 2^k scales every t by 2^-k exactly;
// ScaleBack undoes it. False for a direction that is zero (or not finite): such a ray has no
// answer.
struct ScaledRay {
    Ray ray;
    int k;
    real tMin, tMax;
};

// Where ScaledInterval cuts the search at one end of the interval, `end`, whose next number
// inward is `inward`. Where scaling back rounds (k < 0 and t below the normal numbers), a t'
// past halfway between end 2^-k and inward 2^-k comes back as `inward` (rounding to nearest)
// and one short of it as `end`, so the cut is halfway; elsewhere scaling back is exact, and the
// cut is inward 2^-k. (Exact: for k < 0 both are scaled up, and the halfway point of two numbers
// that came from neighbours in t has a bit to spare in t'.)
static real CutAt(real end, real inward, int k) {
    real a = ScaleByPowerOfTwo(end, -k), b = ScaleByPowerOfTwo(inward, -k);
    if (k >= 0 || !std::isfinite(a) || !std::isfinite(b))
        return b;
    return a + (b - a) / 2;
}

// The scaled ray's interval: (tMin 2^-k, tMax 2^-k), cut so that every t' in it comes back
// (ScaleBack, t = t' 2^k) inside (tMin, tMax). Between normal numbers the scaling is exact and
// cuts nothing; at the ends of the range t' 2^k overflows or rounds to 0, and a shape found
// there would be refused on the way back, leaving no answer: a search for any hit, stopped at
// it, would miss a nearer shape that blocks the ray, and the nearest hit one farther. So each
// end is cut where t' 2^k crosses it (CutAt), then checked against ScaleBack's own rounding and
// moved one step where it falls on the wrong side (a tie rounds to even). ScaleByPowerOfTwo
// rounds monotonically, so every t' between the two ends comes back inside, and none outside
// them would. (Cold: only a direction outside the window comes here, and inlined it made
// ScaleRay too large to be inlined into every search: 3% more instructions for the assignment.)
RT_COLD static void ScaledInterval(real tMin, real tMax, int k, real *lo, real *hi) {
    real first = CutAt(tMin, NextAfter(tMin, true), k); // the least t' above tMin
    if (!(ScaleByPowerOfTwo(first, k) > tMin))
        first = NextAfter(first, true);
    real last = CutAt(tMax, NextAfter(tMax, false), k); // the largest t' below tMax
    if (!(ScaleByPowerOfTwo(last, k) < tMax))
        last = NextAfter(last, false);
    *lo = NextAfter(first, false), *hi = NextAfter(last, true); // (both ends open)
}

static bool ScaleRay(const Ray *ray, real tMin, real tMax, ScaledRay *s) {
    if (SearchedAsIs(ray->dir)) { // s->ray is not needed
        s->k = 0, s->tMin = tMin, s->tMax = tMax;
        return true;
    }
    s->k = UnitExponent(ray->dir);
    s->ray = {ray->origin, ScaleByPowerOfTwo(ray->dir, s->k)};
    ScaledInterval(tMin, tMax, s->k, &s->tMin, &s->tMax);
    return MaxComponent(s->ray.dir) >= 1 && IsFinite(s->ray.dir);
}

// The hit's t in units of the original direction; false if that leaves (tMin, tMax) by
// overflowing or underflowing.
static bool ScaleBack(const ScaledRay *s, real tMin, real tMax, RayHit *hit) {
    if (s->k == 0)
        return true;
    hit->t = ScaleByPowerOfTwo(hit->t, s->k);
    return hit->t > tMin && hit->t < tMax;
}

bool IntersectTriangle(const Triangle *tri, const Ray *ray, real tMin, real tMax, RayHit *hit) {
    ScaledRay s;
    RayShear shear;
    RayHit found;
    if (!ScaleRay(ray, tMin, tMax, &s))
        return false;
    if (s.k == 0)
        s.ray = *ray;
    ShearRay(&s.ray, &shear);
    if (!IntersectWatertight(tri, nullptr, &s.ray, &shear, s.tMin, s.tMax, &found) ||
        !ScaleBack(&s, tMin, tMax, &found))
        return false;
    *hit = found;
    return true;
}

// Trusted only when a r^2 is a normal number: a square that overflowed (inf - inf is NaN, not
// < 0) or fell below the normal range goes on to IntersectSphere, which rescales.
static inline bool LineMissesSphere(const Sphere *s, const Ray *ray) {
    vec3 d = ray->dir;
    real a = Dot(d, d), r2 = s->radius * s->radius;
    return SphereDiscriminant(ray->origin - s->center, d, a, r2) < 0 &&
           a * r2 >= std::numeric_limits<real>::min();
}

// One sphere, by the chosen method. The stable test's first step is inlined here: most spheres
// a ray meets end at it.
static inline bool HitSphere(Methods methods, const Sphere *s, const Ray *ray, real tMin, real tMax,
                             RayHit *hit) {
    if (methods.sphere == SPHERE_TEXTBOOK)
        return IntersectSphereTextbook(s, ray, tMin, tMax, hit);
    return !LineMissesSphere(s, ray) && IntersectSphere(s, ray, tMin, tMax, hit);
}

// One triangle by a handout method (the watertight method has its own loop, in watertight.cpp).
static inline bool HitTriangle(Methods methods, const Triangle *tri, const Ray *ray, real tMin,
                               real tMax, RayHit *hit) {
    if (methods.triangle == TRIANGLE_CRAMER)
        return IntersectTriangleCramer(tri, ray, tMin, tMax, hit);
    return IntersectTrianglePlane(tri, ray, tMin, tMax, hit);
}

// The spheres one by one, in scene order, the reference for the kernel's sphere blocks
// (HitCommittedSpheres): each hit lowers *tMax, so a later sphere only counts if it is nearer,
// and a tie keeps the earlier one. With anyHit the first hit ends the search.
static bool HitSpheres(const Scene *scene, Methods methods, int skip, const Ray *ray, real tMin,
                       real *tMax, bool anyHit, RayHit *hit) {
    bool found = false;
    for (int i = 0, n = (int)scene->spheres.size(); i < n; i++) {
        if (i == skip || !HitSphere(methods, &scene->spheres[i], ray, tMin, *tMax, hit))
            continue; // (the skip first: a test that hits writes *hit)
        hit->index = i;
        *tMax = hit->t;
        found = true;
        if (anyHit)
            return true;
    }
    return found;
}

// The second handout's nearest hit over the list of shapes: every hit shrinks tMax, so each
// later shape only counts if it is nearer, and a tie keeps the earlier shape. With anyHit, the
// first hit found ends the search (a shadow ray needs no more). The shape `start` names is passed
// over: under --self-hit skip the one the ray leaves; under the default bound, the triangle it
// leaves where the ray plainly goes away from it (StartLeaving, robust.h), and none otherwise.
static bool HitShapes(const Scene *scene, Methods methods, const Ray *given, const RayStart *start,
                      real tMax, bool anyHit, RayHit *hit) {
    ScaledRay s;
    if (!ScaleRay(given, start->tMin, tMax, &s))
        return false;
    const Ray *ray = s.k == 0 ? given : &s.ray;
    int skipSphere = start->shape == SHAPE_SPHERE ? start->index : -1;
    int skipTriangle = start->shape == SHAPE_TRIANGLE ? start->index : -1;
    // The sphere blocks only in AVX2 vectors: lane by lane (or in SSE2 pairs) they cost more than
    // HitSpheres (the assignment at 128 x 128, 16 spp: 498 and 518 against 482 M instructions)
    bool blocks = SpheresAreCurrent(scene) && scene->layout.wide;
    bool found = methods.sphere != SPHERE_TEXTBOOK && blocks
                     ? HitCommittedSpheres(scene, skipSphere, ray, s.tMin, &s.tMax, anyHit, hit)
                     : HitSpheres(scene, methods, skipSphere, ray, s.tMin, &s.tMax, anyHit, hit);
    if (found && anyHit)
        return ScaleBack(&s, start->tMin, tMax, hit);
    if (methods.triangle == TRIANGLE_WATERTIGHT) {
        if (LayoutIsCurrent(scene)) { // the same answers, faster (kernel.cpp)
            found = HitCommittedTriangles(scene, skipTriangle, ray, s.tMin, s.tMax, anyHit, hit) ||
                    found;
        } else {
            RayShear shear; // the per-ray half of the test, once for all the triangles
            ShearRay(ray, &shear);
            found =
                HitWatertightTriangles(scene->triangles.data(), (int)scene->triangles.size(),
                                       skipTriangle, ray, &shear, s.tMin, s.tMax, anyHit, hit) ||
                found;
        }
        return found && ScaleBack(&s, start->tMin, tMax, hit);
    }
    for (int i = 0, n = (int)scene->triangles.size(); i < n; i++) {
        if (i == skipTriangle ||
            !HitTriangle(methods, &scene->triangles[i], ray, s.tMin, s.tMax, hit))
            continue;
        hit->index = i;
        s.tMax = hit->t;
        found = true;
        if (anyHit)
            break;
    }
    return found && ScaleBack(&s, start->tMin, tMax, hit);
}

bool FindNearestHit(const Scene *scene, Methods methods, const Ray *ray, real tMin, real tMax,
                    RayHit *hit) {
    RayStart start = {tMin, SHAPE_SPHERE, -1};
    return HitShapes(scene, methods, ray, &start, tMax, false, hit);
}

bool AnyHit(const Scene *scene, Methods methods, const Ray *ray, real tMin, real tMax) {
    RayStart start = {tMin, SHAPE_SPHERE, -1};
    RayHit scratch;
    return HitShapes(scene, methods, ray, &start, tMax, true, &scratch);
}

bool FindNearestHitFrom(const Scene *scene, Methods methods, const Ray *ray, const RayStart *start,
                        real tMax, RayHit *hit) {
    return HitShapes(scene, methods, ray, start, tMax, false, hit);
}

bool AnyHitFrom(const Scene *scene, Methods methods, const Ray *ray, const RayStart *start,
                real tMax) {
    RayHit scratch;
    return HitShapes(scene, methods, ray, start, tMax, true, &scratch);
}

void LeaveSurface(const RayHit *hit, vec3 dir, const Methods *methods, Ray *ray, RayStart *start) {
    *start = kFromTheEye;
    ray->dir = dir;
    ray->origin = hit->point;
    if (methods->selfHit == SELF_HIT_BOUND) { // handout: skip the shape left, or t_min = 0.001
        ray->origin = OffsetRayOrigin(hit, dir);
        *start = StartLeaving(hit, dir, dir);
    } else if (methods->selfHit == SELF_HIT_EPSILON) {
        start->tMin = methods->epsilon / SafeLength(dir); // epsilon world units along the ray
    } else {
        start->shape = hit->shape;
        start->index = hit->index;
    }
}

// The shadow ray: leaves the surface as LeaveSurface says, toward the light, with dir = light -
// origin, so t = 1 is the light itself and the open interval (tMin, 1) holds every possible
// blocker, however far away the light is. Under the bound, the origin moves to the light's side
// and the pass-over is judged for the final direction.
bool ShadowRay(const RayHit *hit, vec3 lightPosition, const Methods *methods, Ray *ray,
               RayStart *start) {
    vec3 side = lightPosition - hit->point;
    if (methods->selfHit == SELF_HIT_BOUND) {
        ray->origin = OffsetRayOrigin(hit, side);
        ray->dir = lightPosition - ray->origin;
        *start = StartLeaving(hit, side, ray->dir);
    } else {
        LeaveSurface(hit, side, methods, ray, start);
        ray->dir = lightPosition - ray->origin;
        if (methods->selfHit == SELF_HIT_EPSILON)
            start->tMin = methods->epsilon / SafeLength(ray->dir);
    }
    return ray->dir.x != 0 || ray->dir.y != 0 || ray->dir.z != 0;
}
