// geometry.cpp -- where rays meet shapes, and nothing else.
//
// The assignment handout's sphere (a quadratic) and triangle (Cramer's rule, variables A..M),
// the second handout's nearest hit over a list of shapes, and a safe origin for rays that leave
// a surface. The defaults are the numerically robust forms (Ray Tracing Gems ch. 7 for spheres,
// Woop, Benthin & Wald 2013 for triangles, pbrt-v4 §6.8 for error bounds); the handout's Cramer
// form stays selectable for teaching. Compiled with -ffp-contract=off: see the Makefile.
#include "ray.h"

#include <algorithm>

// Writes the fields every shape fills the same way; `outwardNormal` must be unit length.
// The normal is turned to face the incoming ray, and frontFace records which side it came from;
// a ray that grazes the surface (d.N = 0, a tangent) counts as arriving from outside.
static void SetFaceNormal(const Ray *ray, vec3 outwardNormal, RayHit *hit) {
    hit->frontFace = !(Dot(ray->dir, outwardNormal) > 0);
    hit->normal = hit->frontFace ? outwardNormal : -outwardNormal;
}

// The quadratic's discriminant b^2 - a c0 in the form a r^2 - |f x d|^2 (see IntersectSphere):
// |f x d| / |d| is how far the ray's line passes from the centre, so it is negative exactly
// when the line misses the sphere.
static inline real SphereDiscriminant(vec3 f, vec3 d, real a, real r2) {
    vec3 fxd = Cross(f, d);
    return a * r2 - Dot(fxd, fxd);
}

// Solve |f + t d|^2 = r^2 for f = o - c, the ray origin relative to the centre. Expanded, this
// is a t^2 + 2 b t + c0 = 0 with a = d.d, b = f.d, c0 = f.f - r^2 (RTIOW v4 §6.2 uses the same
// half-b form; the handout's A, B, C are a, 2b, c0).
// Two fixes from Ray Tracing Gems ch. 7 (Haines et al. 2019), because the textbook form fails
// for small spheres far away and for the near root:
//   discriminant b^2 - a c0 = a r^2 - |f x d|^2 = a (r^2 - |f - (b/a) d|^2): measure how far the
//     line passes from the centre instead of subtracting two huge nearly equal numbers (Hearn &
//     Baker; the cross product gives the same distance without a division);
//   roots q = -(b + sign(b) sqrt(disc)), t0 = c0 / q, t1 = q / a: never subtract nearly equal
//     numbers (Press et al., Numerical Recipes §5.6).
// Writes the nearest root in (tMin, tMax) and the hit point relative to the centre. The caller
// has scaled f, d and r so that no square over- or underflows (IntersectSphere).
static bool SolveSphere(vec3 f, vec3 d, real r, real tMin, real tMax, real *tHit, vec3 *local) {
    real a = Dot(d, d);
    real b = Dot(f, d);
    real r2 = r * r;

    // Reject a sphere behind the ray: origin outside (c0 > 0) and moving away (b > 0) means both
    // roots are negative (their product c0/a > 0, their sum -2b/a < 0)
    real c0 = Dot(f, f) - r2;
    if (b > 0 && c0 > 0 && tMin >= 0)
        return false;

    // Reject if the line passes farther from the centre than the radius (NaN input lands here too)
    real disc = SphereDiscriminant(f, d, a, r2);
    if (!(disc >= 0))
        return false;

    // Both roots without cancellation
    real sqrtDisc = std::sqrt(disc);
    real q = -(b + std::copysign(sqrtDisc, b));
    if (q == 0) // the ray starts on the surface and is tangent to it
        return false;
    real t0 = c0 / q, t1 = q / a;
    if (t0 > t1)
        std::swap(t0, t1);

    // Pick the nearest root inside (tMin, tMax)
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
    // chord back (near root) or on (far root), t = -b/a -+ sqrt(disc)/a. Unlike f + t d, this
    // never subtracts nearly equal numbers, so it stays right when the sphere is tiny and far
    // away. Then put it back on the sphere (pbrt-v4 §6.8.5): what error remains lies along the
    // surface, not across it, a few roundings of the coordinates.
    vec3 offLine = f - (b / a) * d;
    vec3 p = offLine + ((nearRoot ? -sqrtDisc : sqrtDisc) / a) * d;
    *local = (r / Length(p)) * p;
    *tHit = t;
    return true;
}

// The sphere test for a ray and sphere of any size. SolveSphere squares lengths (d.d, r^2,
// |f x d|^2), which overflow for a light 1e153 away and underflow for a sphere of radius
// 1e-200. So outside the windows of ray.h it runs in rescaled units: d times 2^kd (largest
// component in [1, 2)) and every length in units of about the radius (times 2^kr, r in [1, 2)).
// Each root is then t' = t 2^(kr - kd). Powers of two are exact, so where nothing over- or
// underflowed this gives the very bits of the unscaled arithmetic. No root is discarded as "too
// close to 0": a ray that leaves this sphere starts outside its rounding error (OffsetRayOrigin),
// so c0 has the right sign and the root it would re-hit is negative; a probe that starts a hair
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
    hit->t = t;
    vec3 world = ScaleByPowerOfTwo(local, -kr);
    hit->point = s->center + world;
    hit->pointError = Gamma(5) * Abs(world) + Gamma(1) * Abs(hit->point);
    SetFaceNormal(ray, (1 / r) * local, hit);
    hit->material = s->material;
    hit->shape = SHAPE_SPHERE;
    return true;
}

// The textbook sphere test, kept only so `make bench` can show what the stable form buys:
// t = (-b -+ sqrt(b^2 - a c0)) / a with c0 = f.f - r^2 and the hit point o + t d. It loses a
// small sphere far away (c0 swallows r^2) and the near root of a big one (-b + sqrt cancels).
bool IntersectSphereTextbook(const Sphere *s, const Ray *ray, real tMin, real tMax, RayHit *hit) {
    vec3 d = ray->dir, f = ray->origin - s->center;
    real a = Dot(d, d), b = Dot(f, d), c0 = Dot(f, f) - s->radius * s->radius;
    real disc = b * b - a * c0;
    if (!(disc >= 0) || !(a > 0))
        return false;
    real t = (-b - std::sqrt(disc)) / a;
    if (!(t > tMin))
        t = (-b + std::sqrt(disc)) / a;
    if (!(t > tMin && t < tMax))
        return false;
    vec3 local = f + t * d;
    hit->t = t;
    hit->point = ray->origin + t * d;
    hit->pointError = Gamma(5) * Abs(local) + Gamma(1) * Abs(hit->point);
    SetFaceNormal(ray, (1 / s->radius) * local, hit);
    hit->material = s->material;
    hit->shape = SHAPE_SPHERE;
    return true;
}

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

// Fills the hit record of a triangle hit at ray parameter t with barycentric coordinates
// (b0, b1, b2) of the corners a, b, c; false (and *hit untouched) for a zero-area triangle. The
// point is the barycentric combination, not o + t d: it lies on the triangle within
// gamma(7) sum |b_i p_i| per axis (pbrt-v4 §6.8.5).
static bool SetTriangleHit(const Triangle *tri, const Ray *ray, real t, real b0, real b1, real b2,
                           RayHit *hit) {
    // Return no intersection if the triangle is degenerate (zero area): it has no normal
    vec3 n = SafeNormalize(Cross(tri->b - tri->a, tri->c - tri->a));
    if (!(MaxComponent(n) > 0) || !IsFinite(n))
        return false;
    vec3 p0 = b0 * tri->a, p1 = b1 * tri->b, p2 = b2 * tri->c;
    hit->t = t;
    hit->point = p0 + p1 + p2;
    hit->pointError = Gamma(7) * (Abs(p0) + Abs(p1) + Abs(p2));
    SetFaceNormal(ray, n, hit);
    hit->material = tri->material;
    hit->shape = SHAPE_TRIANGLE;
    return true;
}

// The per-ray half of the watertight test, shared by every triangle the ray meets: the ray in
// the renamed axes (see RenameAxes) and the shear that turns it into the +z axis.
struct RayShear {
    int kz;      // the axis renamed z: the largest |d| component
    vec3 origin; // the ray origin, axes renamed
    real sx, sy; // d[kx]/d[kz] and d[ky]/d[kz]
};

// v with its axes renamed (kx, ky, kz) = (kz + 1, kz + 2, kz) mod 3. A rotation keeps the
// triangles' winding, whatever kz is. kz is a compile-time constant, so every component below is
// a plain field, not an indexed load: the triangle loop is compiled once per axis (HitShapes).
template <int kz> static inline vec3 RenameAxes(vec3 v) {
    if constexpr (kz == 0)
        return {v.y, v.z, v.x};
    else if constexpr (kz == 1)
        return {v.z, v.x, v.y};
    else
        return v;
}

// The per-ray half of the watertight test (Woop, Benthin & Wald 2013, §3): kz is the largest
// |d| component, and the shear turns the ray into the +z axis. It depends on the ray only, so
// the shape loop computes it once for all the triangles. (The paper also swaps kx and ky when
// d[kz] < 0, to keep the winding for back-face culling. That negates u, v and w together, which
// changes nothing for a two-sided test, so it is left out.)
template <int kz> static void ShearRayAxes(const Ray *ray, RayShear *shear) {
    vec3 d = RenameAxes<kz>(ray->dir);
    *shear = {kz, RenameAxes<kz>(ray->origin), d.x / d.z, d.y / d.z};
}

static void ShearRay(const Ray *ray, RayShear *shear) {
    vec3 ad = Abs(ray->dir);
    int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
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

// The signs of the three edge functions of the sheared triangle (IntersectShearedTriangle), exact.
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

// The 2D edge functions U, V, W of the sheared corners (see IntersectShearedTriangle), rounded.
// True if two have strictly opposite signs: the ray passes outside an edge. Rounding is
// monotonic (x >= y gives fl(x) >= fl(y)), so a rounded a b - c d has the sign of the exact one
// or is 0. A true here is therefore never wrong, and a 0 is left to the exact recomputation.
// Two that disagree end the test before the third is computed.
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
static bool IntersectShearedTriangle(const Triangle *tri, const Ray *ray, const RayShear *k,
                                     real tMin, real tMax, RayHit *hit) {
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
    return HitTrianglePlane(tri, ray, tMin, tMax, hit);
}

// The first step of IntersectShearedTriangle, small enough to sit inside the shape loop: true if
// the ray passes outside an edge by the rounded edge functions alone. Most triangles a ray meets
// end here, and only the rest pay for the whole test (which repeats these few operations).
template <int kz> static inline bool PassesOutside(const Triangle *tri, const RayShear *k) {
    ShearedTriangle s = ShearCorners<kz>(tri, k);
    real u, v, w;
    return EdgesDisagree(&s, &u, &v, &w);
}

// A ray's direction rescaled to a largest component in [1, 2) when it lies outside
// kDirectionWindow (ray.h), and its interval with it, so that no shape test squares or divides a
// direction of 1e-200 or 1e200 out of range. Scaling d by 2^k scales every t by 2^-k exactly;
// ScaleBack undoes it. False for a direction that is zero (or not finite): such a ray has no
// answer.
struct ScaledRay {
    Ray ray;
    int k;
    real tMin, tMax;
};

static bool ScaleRay(const Ray *ray, real tMin, real tMax, ScaledRay *s) {
    if (WithinWindow(MaxComponent(ray->dir), kDirectionWindow)) { // s->ray is not needed
        s->k = 0, s->tMin = tMin, s->tMax = tMax;
        return true;
    }
    s->k = UnitExponent(ray->dir);
    s->ray = {ray->origin, ScaleByPowerOfTwo(ray->dir, s->k)};
    s->tMin = ScaleByPowerOfTwo(tMin, -s->k);
    s->tMax = ScaleByPowerOfTwo(tMax, -s->k);
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
    bool hits =
        shear.kz == 0   ? IntersectShearedTriangle<0>(tri, &s.ray, &shear, s.tMin, s.tMax, &found)
        : shear.kz == 1 ? IntersectShearedTriangle<1>(tri, &s.ray, &shear, s.tMin, s.tMax, &found)
                        : IntersectShearedTriangle<2>(tri, &s.ray, &shear, s.tMin, s.tMax, &found);
    if (!hits || !ScaleBack(&s, tMin, tMax, &found))
        return false;
    *hit = found;
    return true;
}

// The handout's triangle test: solve a + beta (b - a) + gamma (c - a) = e + t d by Cramer's
// rule, with the variables A..M of the slide (Shirley & Marschner, Fundamentals of Computer
// Graphics, §4.4.2). Kept for teaching and for the benchmark: it is not watertight, because each
// triangle rounds its shared edges differently, so rays through an edge can slip between two
// triangles (see the README's robustness section).
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

    return SetTriangleHit(tri, ray, t, 1 - beta - gamma, beta, gamma, hit);
}

// The first step of IntersectSphere, small enough to sit inside the shape loop: true if the
// ray's line misses the sphere. It is the same expression IntersectSphere rejects on (there
// rescaled by powers of two, which changes no sign), so the two agree, and most spheres a ray
// meets end here.
// Trusted only when a r^2 is a normal number: a square that overflowed (inf - inf is NaN, not
// < 0) or fell below the normal range goes on to IntersectSphere, which rescales.
static inline bool LineMissesSphere(const Sphere *s, const Ray *ray) {
    vec3 d = ray->dir;
    real a = Dot(d, d), r2 = s->radius * s->radius;
    return SphereDiscriminant(ray->origin - s->center, d, a, r2) < 0 &&
           a * r2 >= std::numeric_limits<real>::min();
}

static bool HitSphere(Methods methods, const Sphere *s, const Ray *ray, real tMin, real tMax,
                      RayHit *hit) {
    return methods.sphere == SPHERE_TEXTBOOK
               ? IntersectSphereTextbook(s, ray, tMin, tMax, hit)
               : !LineMissesSphere(s, ray) && IntersectSphere(s, ray, tMin, tMax, hit);
}

// The triangle half of the shape loop (HitShapes), for a ray whose main axis is kz.
template <int kz>
static bool HitTriangles(const Scene *scene, Methods methods, const Ray *ray, const RayShear *shear,
                         real tMin, real tMax, bool anyHit, RayHit *hit) {
    bool found = false;
    const Triangle *triangles = scene->triangles.data();
    for (size_t i = 0, n = scene->triangles.size(); i < n; i++) {
        const Triangle *tri = &triangles[i];
        if (methods.triangle == TRIANGLE_CRAMER
                ? IntersectTriangleCramer(tri, ray, tMin, tMax, hit)
                : !PassesOutside<kz>(tri, shear) &&
                      IntersectShearedTriangle<kz>(tri, ray, shear, tMin, tMax, hit)) {
            hit->index = (int)i;
            tMax = hit->t;
            found = true;
            if (anyHit)
                break;
        }
    }
    return found;
}

// The second handout's nearest hit over the list of shapes: every hit shrinks tMax, so each
// later shape only counts if it is nearer, and a tie keeps the earlier shape. With anyHit, the
// first hit found ends the search (a shadow ray needs no more).
static bool HitShapes(const Scene *scene, Methods methods, const Ray *given, real tMin, real tMax,
                      bool anyHit, RayHit *hit) {
    ScaledRay s;
    if (!ScaleRay(given, tMin, tMax, &s))
        return false;
    const Ray *ray = s.k == 0 ? given : &s.ray;
    bool found = false;
    const Sphere *spheres = scene->spheres.data();
    for (size_t i = 0, n = scene->spheres.size(); i < n && !(found && anyHit); i++) {
        if (HitSphere(methods, &spheres[i], ray, s.tMin, s.tMax, hit)) {
            hit->index = (int)i;
            s.tMax = hit->t;
            found = true;
        }
    }
    if (!(found && anyHit)) {
        RayShear shear;
        ShearRay(ray, &shear);
        if (shear.kz == 0)
            found =
                HitTriangles<0>(scene, methods, ray, &shear, s.tMin, s.tMax, anyHit, hit) || found;
        else if (shear.kz == 1)
            found =
                HitTriangles<1>(scene, methods, ray, &shear, s.tMin, s.tMax, anyHit, hit) || found;
        else
            found =
                HitTriangles<2>(scene, methods, ray, &shear, s.tMin, s.tMax, anyHit, hit) || found;
    }
    return found && ScaleBack(&s, tMin, tMax, hit);
}

bool FindNearestHit(const Scene *scene, Methods methods, const Ray *ray, real tMin, real tMax,
                    RayHit *hit) {
    return HitShapes(scene, methods, ray, tMin, tMax, false, hit);
}

bool AnyHit(const Scene *scene, Methods methods, const Ray *ray, real tMin, real tMax) {
    RayHit scratch;
    return HitShapes(scene, methods, ray, tMin, tMax, true, &scratch);
}

// The shadow ray from a hit toward a light: from the safe origin, with dir = light - origin, so
// t = 1 is the light itself and the open interval (0, 1) holds every possible blocker, however
// far away the light is. Returns false (and casts nothing) if the light sits within rounding
// distance of the surface, where dir would be zero and nothing can be in between.
bool ShadowRay(const RayHit *hit, vec3 lightPosition, Ray *ray) {
    ray->origin = OffsetRayOrigin(hit, lightPosition - hit->point);
    ray->dir = lightPosition - ray->origin;
    return ray->dir.x != 0 || ray->dir.y != 0 || ray->dir.z != 0;
}

// Self-intersection ("shadow acne") is prevented by one method for every ray that leaves a
// surface (pbrt-v4 §6.8.6): the hit point is within pointError of the true surface, so moving
// it along the normal by the error box's extent in that direction, sum |n_i| pointError_i, puts
// it on the side the new ray goes to, whatever the scene's scale. Rounding the moved point
// outward (nextafter) keeps the addition itself from undoing the move. The new ray then uses
// tMin = 0, and the intersectors' own "t above its rounding error" tests do the rest.
vec3 OffsetRayOrigin(const RayHit *hit, vec3 dir) {
    real distance = Dot(Abs(hit->normal), hit->pointError);
    vec3 offset = distance * hit->normal;
    if (Dot(dir, hit->normal) < 0)
        offset = -offset;
    vec3 moved = hit->point + offset;
    real *coord[3] = {&moved.x, &moved.y, &moved.z};
    real push[3] = {offset.x, offset.y, offset.z};
    for (int i = 0; i < 3; i++) {
        if (push[i] > 0)
            *coord[i] = std::nextafter(*coord[i], kInfinity);
        else if (push[i] < 0)
            *coord[i] = std::nextafter(*coord[i], -kInfinity);
    }
    return moved;
}
