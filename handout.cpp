// handout.cpp -- the course's own ray/shape methods, as the handouts write them.
//
// The assignment slides' sphere (the quadratic with A, B, C) and triangle (Cramer's rule with
// the variables A..M), and the second handout's triangle (the plane's t, then the signs of three
// cross products). Chosen by `--methods handout`, `--sphere textbook`, `--triangle cramer|plane`;
// rt's defaults are the robust forms (geometry.cpp, watertight.cpp, plane.cpp), and the README's
// "Differences from the handouts" says what each buys. Each method is what a careful student
// writes, its hit point o + t d included. What is added is only what every method needs to be
// used at all: an honest bound on its hit point's error, measured, for rays that leave it, and
// no hit where the point is not a number.
#include "ray.h"

// The assignment handout's sphere test, as the slide writes it: A t^2 + B t + C = 0 with
// A = d.d, B = 2 d.(o - c), C = (o - c).(o - c) - r^2; no hit if B^2 - 4AC < 0; else the least root
// above tMin (the second handout: the least non-negative one), and the point o + t d. It loses a
// small sphere far away (C swallows r^2) and the near root of a big one (-B + sqrt cancels).
// Its point's honest error bound is measured, not assumed: how far o + t d is from the sphere.
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
    vec3 point = ray->origin + t * d, local = point - s->center;
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
// Graphics, §4.4.2). Kept for teaching and for the benchmark: it is not watertight, because each
// triangle rounds its shared edges differently, so rays through an edge can slip between two
// triangles (see docs/robustness.md).
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
