// geometry.cpp -- where rays meet shapes, and how a ray leaves one.
//
// Read top to bottom: the slide's sphere; Cramer's rule with the slide's A..M and the second
// handout's plane test; the one loop over the list of shapes, for the nearest hit and a shadow
// ray's any hit; then how a ray leaves a surface. The handouts' methods are what a careful
// student writes, o + t d included; all they gain is an honest bound on that point's error, and
// no hit where it is not a number. Compiled with -ffp-contract=off: see the Makefile.
#include "ray.h"
#include "robust/robust.h" // robust/: the watertight test, rescaling, leaving a surface

#include <algorithm>

// ---- spheres -------------------------------------------------------------------------------

// The hit record of a handout sphere test at ray parameter t: the point o + t d, as a student
// computes it, the normal (p - c) / r turned toward the ray, and the point's honest error bound,
// measured, not assumed: how far o + t d is from the sphere. False (and *hit untouched) for a
// point beyond the range of numbers, where the quadratic has no answer.
static bool SetHandoutSphereHit(const Sphere *s, const Ray *ray, real t, RayHit *hit) {
    vec3 point = ray->origin + t * ray->dir, local = point - s->center;
    vec3 normal = (1 / s->radius) * local;
    real offSphere = std::fabs(SafeLength(local) - s->radius) + Gamma(4) * SafeLength(local);
    if (!IsFinite(point) || !IsFinite(normal) || !std::isfinite(offSphere))
        return false; // beyond the range of numbers: the quadratic has no answer there
    hit->t = t;
    hit->point = point;
    hit->pointError = offSphere * Abs(normal) + Gamma(2) * Abs(point);
    SetFaceNormal(ray, SafeNormalize(normal), hit);
    hit->material = s->material;
    hit->shape = SHAPE_SPHERE;
    hit->awayShare = 0; // never passed over
    return true;
}

// The assignment handout's sphere test, as the slide writes it: A t^2 + B t + C = 0 with
// A = d.d, B = 2 d.(o - c), C = (o - c).(o - c) - r^2; no hit if B^2 - 4AC < 0; else the least root
// above tMin (the second handout: the least non-negative one), and the point o + t d. It loses a
// small sphere far away (C swallows r^2) and the near root of a big one (-B + sqrt cancels).
// SetHandoutSphereHit writes the hit record.
// Checked by TestSphere (tests/test_handout.cpp).
bool IntersectSphereTextbook(const Sphere *s, const Ray *ray, real tMin, real tMax, RayHit *hit) {
    vec3 d = ray->dir, oc = ray->origin - s->center;
    real A = Dot(d, d);
    real B = 2 * Dot(d, oc);
    real C = Dot(oc, oc) - s->radius * s->radius;
    real discriminant = B * B - 4 * A * C;
    if (!(discriminant >= 0) || !(A > 0))
        return false;
    real t = (-B - std::sqrt(discriminant)) / (2 * A);
    if (!(t > tMin))
        t = (-B + std::sqrt(discriminant)) / (2 * A);
    if (!(t > tMin && t < tMax))
        return false;
    return SetHandoutSphereHit(s, ray, t, hit);
}

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
// passes f, d and r inside numbers.h's windows, as they are or rescaled (IntersectSphere,
// IntersectSphereRescaled), so that no square over- or underflows.
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

// The discriminant's test, taken first, where most spheres a ray meets end: the line passes the
// centre farther than the radius. Trusted only when A r^2 is a normal number: a square that
// overflowed (inf - inf is NaN, not < 0) or fell below the normal range goes on to the full
// test. (fast/ takes this step for several spheres at once, with the same rounding.)
static inline bool LineMissesSphere(const Sphere *s, const Ray *ray) {
    vec3 d = ray->dir;
    real a = Dot(d, d), r2 = s->radius * s->radius;
    return SphereDiscriminant(ray->origin - s->center, d, a, r2) < 0 &&
           a * r2 >= std::numeric_limits<real>::min();
}

// The hit record of rt's sphere test: SolveSphere's root t and its point `local`, relative to the
// centre in units of 2^-kr (r: the radius in those units). A point at the very centre has no
// normal to give, so it is no hit: f = o - c rounded so far (an origin some 1e178 radii away,
// float 1e30) that the ray seemed to pass through the centre.
static bool SetSphereHit(const Sphere *s, const Ray *ray, real t, vec3 local, real r, int kr,
                         RayHit *hit) {
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

// robust: the sphere test where a square could leave the range of numbers (a light 1e153 away, a
// sphere of radius 1e-200), in rescaled units: d times 2^kd (largest component in [1, 2)) and
// every length in units of about the radius (times 2^kr, r in [1, 2)). Each root is then
// t' = t 2^(kr - kd). Powers of two are exact, so where nothing over- or underflowed this gives
// the very bits of the unscaled arithmetic.
static bool IntersectSphereRescaled(const Sphere *s, const Ray *ray, real tMin, real tMax,
                                    RayHit *hit) {
    int kd = UnitExponent(ray->dir), kr = -BinaryExponent(s->radius);
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
    return SetSphereHit(s, ray, t, local, r, kr, hit);
}

// The sphere test for a ray and sphere of any size: SolveSphere on the lengths as they are where
// no square over- or underflows (inside numbers.h's windows: almost every test), else rescaled.
// No root is discarded as "too close to 0": a ray that leaves this sphere starts outside its
// rounding error (OffsetRayOrigin), so C has the right sign and the root it would re-hit is
// negative; a probe that starts a hair outside the sphere still sees it (a hit at t = 3e-11).
bool IntersectSphere(const Sphere *s, const Ray *ray, real tMin, real tMax, RayHit *hit) {
    // No hit if the line passes farther from the centre than the radius: most spheres end here
    if (LineMissesSphere(s, ray) || !(s->radius > 0) || !std::isfinite(s->radius))
        return false;
    real t;
    vec3 local;
    if (SearchedAsIs(ray->dir) && WithinWindow(s->radius, kLengthWindow) &&
        MaxComponent(ray->origin - s->center) <= PowerOfTwo(kLengthWindow))
        return SolveSphere(ray->origin - s->center, ray->dir, s->radius, tMin, tMax, &t, &local) &&
               SetSphereHit(s, ray, t, local, s->radius, 0, hit);
    return IntersectSphereRescaled(s, ray, tMin, tMax, hit); // robust: lengths rescaled
}

// ---- triangles: the handouts' forms ---------------------------------------------------------

// The hit record of a handout triangle test at ray parameter t: the point o + t d, as a student
// computes it, and its honest error bound, measured: how far that point is from the triangle's
// plane, plus its own rounding. False (and *hit untouched) for a triangle with no area, or a
// point that is not a number.
static bool SetHandoutTriangleHit(const Triangle *tri, const Ray *ray, real t, RayHit *hit) {
    vec3 unit = SafeNormalize(Cross(tri->b - tri->a, tri->c - tri->a));
    vec3 p = ray->origin + t * ray->dir;
    real offPlane =
        std::fabs(Dot(unit, p - tri->a)) + Gamma(4) * (SafeLength(p) + SafeLength(tri->a));
    if (!(MaxComponent(unit) > 0) || !IsFinite(unit) || !IsFinite(p) || !std::isfinite(offPlane))
        return false;
    hit->t = t;
    hit->point = p;
    hit->pointError = offPlane * Abs(unit) + Gamma(2) * Abs(p);
    SetFaceNormal(ray, unit, hit);
    hit->material = tri->material;
    hit->shape = SHAPE_TRIANGLE;
    hit->awayShare = 0; // never passed over: a handout method's hit has no such bound
    return true;
}

// The handout's triangle test: solve a + beta (b - a) + gamma (c - a) = e + t d by Cramer's
// rule, with the variables A..M of the slide (Shirley & Marschner, Fundamentals of Computer
// Graphics, §4.4.2). Not watertight: each triangle rounds its shared edges differently, so rays
// through an edge can slip between two triangles (docs/robustness.md). rt's IntersectTriangle
// (robust/watertight.cpp) is.
// Checked by TestCramer (tests/test_handout.cpp).
bool IntersectTriangleCramer(const Triangle *tri, const Ray *ray, real tMin, real tMax,
                             RayHit *hit) {
    vec3 a = tri->a, b = tri->b, c = tri->c, e = ray->origin, d = ray->dir;
    real A = a.x - b.x, B = a.y - b.y, C = a.z - b.z;
    real D = a.x - c.x, E = a.y - c.y, F = a.z - c.z;
    real G = d.x, H = d.y, I = d.z;
    real J = a.x - e.x, K = a.y - e.y, L = a.z - e.z;

    // M is the determinant; 0 means the ray is parallel to the plane (or the triangle is flat)
    real EIHF = E * I - H * F, GFDI = G * F - D * I, DHEG = D * H - E * G;
    real M = A * EIHF + B * GFDI + C * DHEG;
    if (M == 0 || !std::isfinite(M))
        return false;

    // Compute t, then reject early, as the handout does: t, then gamma, then beta
    real AKJB = A * K - J * B, JCAL = J * C - A * L, BLKC = B * L - K * C;
    real t = -(F * AKJB + E * JCAL + D * BLKC) / M;
    if (!(t > tMin && t < tMax))
        return false;
    real gamma = (I * AKJB + H * JCAL + G * BLKC) / M;
    if (gamma < 0 || gamma > 1)
        return false;
    real beta = (J * EIHF + K * GFDI + L * DHEG) / M;
    if (beta < 0 || beta > 1 - gamma)
        return false;

    return SetHandoutTriangleHit(tri, ray, t, hit);
}

// The second handout's triangle test, in two steps. First the plane: n = (b - a) x (c - a) and
// t = n.(a - o) / n.d (no hit if the ray is parallel, n.d = 0). Then inside or outside: the hit
// point p is inside if the cross products (b - a) x (p - a), (c - b) x (p - b) and
// (a - c) x (p - c) all point the way n does, compared on the coordinate where n is largest
// (the other two can be 0 for a triangle seen edge-on). The handout dots each with n instead;
// for p on the plane each cross product is parallel to n, so the sign is the same up to
// rounding, from three products instead of nine. Not watertight: p is rounded, and each
// triangle rounds its shared edge its own way. Its point's error bound is measured: how far
// o + t d is from the plane, plus its own rounding.
// Checked by TestPlane (tests/test_handout.cpp).
bool IntersectTrianglePlane(const Triangle *tri, const Ray *ray, real tMin, real tMax,
                            RayHit *hit) {
    vec3 a = tri->a, b = tri->b, c = tri->c;
    vec3 n = Cross(b - a, c - a);
    real nDotD = Dot(n, ray->dir);
    if (nDotD == 0 || !std::isfinite(nDotD))
        return false;
    real t = Dot(n, a - ray->origin) / nDotD;
    if (!(t > tMin && t < tMax))
        return false;
    vec3 p = ray->origin + t * ray->dir;
    vec3 size = Abs(n);
    int k = size.x > size.y ? (size.x > size.z ? 0 : 2) : (size.y > size.z ? 1 : 2);
    real nk = Component(n, k);
    // handout: Dot(Cross(b - a, p - a), n) < 0 || ... for the three edges
    if (Component(Cross(b - a, p - a), k) * nk < 0 || Component(Cross(c - b, p - b), k) * nk < 0 ||
        Component(Cross(a - c, p - c), k) * nk < 0)
        return false;
    return SetHandoutTriangleHit(tri, ray, t, hit);
}

// ---- the nearest hit over the list of shapes ----------------------------------------------

// One sphere, and one triangle, by the chosen method.
static bool HitSphere(Methods methods, const Sphere *s, const Ray *ray, real tMin, real tMax,
                      RayHit *hit) {
    if (methods.sphere == SPHERE_TEXTBOOK)
        return IntersectSphereTextbook(s, ray, tMin, tMax, hit);
    return IntersectSphere(s, ray, tMin, tMax, hit);
}

static bool HitTriangle(Methods methods, const Triangle *tri, const Ray *ray, real tMin, real tMax,
                        RayHit *hit) {
    if (methods.triangle == TRIANGLE_CRAMER)
        return IntersectTriangleCramer(tri, ray, tMin, tMax, hit);
    if (methods.triangle == TRIANGLE_PLANE)
        return IntersectTrianglePlane(tri, ray, tMin, tMax, hit);
    return IntersectTriangle(tri, ray, tMin, tMax, hit); // robust/: rt's own, watertight
}

// The second handout's nearest hit over the list of shapes: every hit shrinks tMax, so each
// later shape only counts if it is nearer, and a tie keeps the earlier shape. With anyHit, the
// first hit ends the search (a shadow ray needs no more). The shape the ray leaves, if `from`
// names one, is passed over (the second handout's rule). The skip comes before the test,
// because a test that hits writes *hit.
// Checked by TestNearestHit (tests/test_handout.cpp).
static bool HitList(const Scene *scene, Methods methods, const Ray *ray, const SelfHit *from,
                    real tMin, real tMax, bool anyHit, RayHit *hit) {
    bool found = false;
    for (int i = 0; i < (int)scene->spheres.size(); i++) {
        if ((from->shape == SHAPE_SPHERE && i == from->index) ||
            !HitSphere(methods, &scene->spheres[i], ray, tMin, tMax, hit))
            continue;
        hit->index = i;
        tMax = hit->t;
        found = true;
        if (anyHit)
            return true;
    }
    for (int i = 0; i < (int)scene->triangles.size(); i++) {
        if ((from->shape == SHAPE_TRIANGLE && i == from->index) ||
            !HitTriangle(methods, &scene->triangles[i], ray, tMin, tMax, hit))
            continue;
        hit->index = i;
        tMax = hit->t;
        found = true;
        if (anyHit)
            return true;
    }
    return found;
}

bool SearchList(const Scene *scene, Methods methods, const Ray *ray, const SelfHit *from, real tMax,
                bool anyHit, RayHit *hit) {
    if (SearchedAsIs(ray->dir)) // almost every ray
        return HitList(scene, methods, ray, from, from->tMin, tMax, anyHit, hit);
    ScaledRay s; // robust: a direction of 1e-200 or 1e200 rescaled, so that no test squares it
    if (!ScaleRay(ray, from->tMin, tMax, &s))
        return false;
    bool found = HitList(scene, methods, SearchedRay(&s, ray), from, s.tMin, s.tMax, anyHit, hit);
    return found && ScaleBack(&s, from->tMin, tMax, hit);
}

// Every search: the list above.
static inline bool Search(const Scene *scene, Methods methods, const Ray *ray, const SelfHit *from,
                          real tMax, bool anyHit, RayHit *hit) {
    if (const Accelerator *fast = scene->accelerator) // fast/: SearchList's very answer, faster
        return fast->search(fast, scene, methods, ray, from, tMax, anyHit, hit);
    return SearchList(scene, methods, ray, from, tMax, anyHit, hit);
}

bool FindNearestHit(const Scene *scene, Methods methods, const Ray *ray, real tMin, real tMax,
                    RayHit *hit) {
    SelfHit from = {tMin, SHAPE_SPHERE, -1};
    return Search(scene, methods, ray, &from, tMax, false, hit);
}

bool AnyHit(const Scene *scene, Methods methods, const Ray *ray, real tMin, real tMax) {
    SelfHit from = {tMin, SHAPE_SPHERE, -1};
    RayHit scratch;
    return Search(scene, methods, ray, &from, tMax, true, &scratch);
}

bool FindNearestHitFrom(const Scene *scene, Methods methods, const Ray *ray, const SelfHit *from,
                        real tMax, RayHit *hit) {
    return Search(scene, methods, ray, from, tMax, false, hit);
}

bool AnyHitFrom(const Scene *scene, Methods methods, const Ray *ray, const SelfHit *from,
                real tMax) {
    RayHit scratch;
    return Search(scene, methods, ray, from, tMax, true, &scratch);
}

void FindEyeRayHits(const Scene *scene, Methods methods, const Ray *rays, int count, RayHit *hits,
                    bool *found) {
    if (const Accelerator *fast = scene->accelerator) // fast/: packets and a BVH, the same answers
        return fast->eyeRays(fast, scene, methods, rays, count, hits, found);
    for (int k = 0; k < count; k++)
        found[k] = SearchList(scene, methods, &rays[k], &kNoSelfHit, kInfinity, false, &hits[k]);
}

// ---- leaving a surface ---------------------------------------------------------------------

// Leaving a surface (SelfHitMethod), the handouts' ways: start at the hit point and ignore hits
// closer than an epsilon (the journal's t_min = 0.001), or ignore the shape left (the second
// handout's shadow rays).
void LeaveSurface(const Scene *scene, Methods methods, const RayHit *hit, vec3 dir, Ray *ray,
                  SelfHit *from) {
    *from = kNoSelfHit;
    ray->dir = dir;
    ray->origin = hit->point;
    if (methods.selfHit == SELF_HIT_BOUND) { // robust/: rt's way, the bound; the handouts' below
        // Start where no rounding can put the ray behind the surface: the hit point moved off by
        // its own error bound (no epsilon at any scale), and for a hit near a triangle's edge in
        // from the edge first, so the ray starts inside a closed mesh (LeavingPoint; off a smooth
        // mesh, out at the curved surface where the way is free: DeparturePoint). A triangle the
        // ray plainly goes away from is then passed over, which changes no answer and saves its
        // test (StartLeaving).
        ray->origin = DeparturePoint(scene, methods, hit, dir, dir);
        *from = StartLeaving(scene, hit, dir, dir);
        return;
    }
    if (methods.selfHit == SELF_HIT_EPSILON) {
        from->tMin = methods.epsilon / SafeLength(dir); // epsilon world units along the ray
    } else {
        from->shape = hit->shape;
        from->index = hit->index;
    }
}

// The shadow ray: leaves the surface as LeaveSurface says, toward the light, with dir = light -
// origin, so t = 1 is the light itself and the open interval (tMin, 1) holds every possible
// blocker, however far away the light is.
bool ShadowRay(const Scene *scene, Methods methods, const RayHit *hit, vec3 lightPosition, Ray *ray,
               SelfHit *from) {
    vec3 side = lightPosition - hit->point;
    if (methods.selfHit == SELF_HIT_BOUND) { // robust/: rt's way, as in LeaveSurface
        // The origin on the light's side (off a smooth mesh, the side the hit was seen from: the
        // light may lie behind the flat triangle); the pass-over judged for the final direction.
        ray->origin = DeparturePoint(scene, methods, hit, side, hit->normal);
        ray->dir = lightPosition - ray->origin;
        *from = StartLeaving(scene, hit, side, ray->dir);
        return ray->dir.x != 0 || ray->dir.y != 0 || ray->dir.z != 0;
    }
    LeaveSurface(scene, methods, hit, side, ray, from);
    ray->dir = lightPosition - ray->origin;
    if (methods.selfHit == SELF_HIT_EPSILON)
        from->tMin = methods.epsilon / SafeLength(ray->dir);
    return ray->dir.x != 0 || ray->dir.y != 0 || ray->dir.z != 0;
}

// The handouts' hard shadow: a light is visible from a hit when nothing lies between them, that
// is, when the shadow ray (t = 1 at the light) meets no shape at t < 1.
// Checked by TestShadow (tests/test_handout_light.cpp).
bool LightVisible(const Scene *scene, Methods methods, const RayHit *hit, vec3 lightPosition) {
    Ray shadow;
    SelfHit from;
    if (!ShadowRay(scene, methods, hit, lightPosition, &shadow, &from))
        return true; // the light is where the ray starts: nothing can be in between
    return !AnyHitFrom(scene, methods, &shadow, &from, 1);
}
