// tests/test_triangles.cpp -- ray/triangle hits predicted by hand, for both methods.
//
// The triangle a = (0, 1, -2), b = (-1, 0, -2), c = (1, 0, -2) stands in the plane z = -2;
// (b - a) x (c - a) = (-1, -1, 0) x (1, -1, 0) = (0, 0, 2): its outward side faces +z, the eye.
#include "../robust/robust.h"
#include "test.h"

#include <cstring>

static const Triangle kTri = {{0, 1, -2}, {-1, 0, -2}, {1, 0, -2}, 0};
static const Triangle kTriFlipped = {{0, 1, -2}, {1, 0, -2}, {-1, 0, -2}, 0}; // other winding

struct TriangleCase {
    const char *name;
    Ray ray;
    const Triangle *tri;
    bool expectHit;
    real t;
    bool frontFace;
};

// clang-format off: one case a line (name, ray, triangle, hit?, t, front face)
static const TriangleCase kTriangleCases[] = {
    // From the eye straight at (0, 0.5, -2): inside, t = 2, seen from the outward side
    {"inside", {{0, 0.5, 0}, {0, 0, -1}}, &kTri, true, 2, true},
    // The same point with |d| = 4: t = 0.5
    {"inside, long direction", {{0, 0.5, 0}, {0, 0, -4}}, &kTri, true, 0.5, true},
    // |d| = 1e-8 and 1e8: t = 2e8 and 2e-8 (a regression: the conservative-t bound once mixed
    // z before and after scaling by 1 / d.z, and rejected every hit of a short direction)
    {"inside, direction of length 1e-8", {{0, 0.5, 0}, {0, 0, real(-1e-8)}}, &kTri, true, real(2e8), true},
    {"inside, direction of length 1e8", {{0, 0.5, 0}, {0, 0, real(-1e8)}}, &kTri, true, real(2e-8), true},
    // Slanted: d = (0.125, 0.125, -1) reaches z = -2 at t = 2, at (0.25, 0.25), inside
    {"inside, slanted", {{0, 0, 0}, {0.125, 0.125, -1}}, &kTri, true, 2, true},
    // Outside past edge a-c (x + y = 1): the point (0.6, 0.6)
    {"outside past edge a-c", {{0.6, 0.6, 0}, {0, 0, -1}}, &kTri, false, 0, false},
    // Outside past edge a-b (y - x = 1): the point (-0.6, 0.6)
    {"outside past edge a-b", {{-0.6, 0.6, 0}, {0, 0, -1}}, &kTri, false, 0, false},
    // Outside past edge b-c (y = 0): the point (0, -0.1)
    {"outside past edge b-c", {{0, -0.1, 0}, {0, 0, -1}}, &kTri, false, 0, false},
    // The other winding: same hit, but the ray now arrives on the inward side
    {"other winding", {{0, 0.5, 0}, {0, 0, -1}}, &kTriFlipped, true, 2, false},
    // From behind the triangle: arrives on the inward side at t = 2
    {"from behind", {{0, 0.5, -4}, {0, 0, 1}}, &kTri, true, 2, false},
    // Parallel to the plane (d.z = 0): never meets it
    {"parallel to the plane", {{0, -1, -2.5}, {0, 1, 0}}, &kTri, false, 0, false},
    // The triangle is behind the ray (t = -2)
    {"triangle behind the ray", {{0, 0.5, 0}, {0, 0, 1}}, &kTri, false, 0, false},
};
// clang-format on

typedef bool (*IntersectFn)(const Triangle *, const Ray *, real, real, RayHit *);

static void TestTriangleTable(IntersectFn intersect, const char *method) {
    for (const TriangleCase &c : kTriangleCases) {
        RayHit hit;
        bool got = intersect(c.tri, &c.ray, 0, kInfinity, &hit);
        std::string name = std::string(method) + " triangle, " + c.name;
        CHECK(got == c.expectHit, name + ": hit or miss");
        if (!got || !c.expectHit)
            continue;
        CHECK_NEAR(hit.t, c.t, kRelTol * c.t, name + ": t");
        CHECK(hit.frontFace == c.frontFace && Dot(hit.normal, c.ray.dir) < 0 &&
                  std::fabs(std::fabs(hit.normal.z) - 1) < kRelTol,
              name + ": unit normal along z, facing the ray");
    }
}

// On ordinary rays (aimed at points clearly inside or clearly outside) the handout's Cramer form
// and the watertight default agree: same verdict, same t.
static void TestMethodsAgree() {
    TestRng rng = {42};
    int disagree = 0, hits = 0;
    for (int k = 0; k < 2000; k++) {
        Triangle tri = {{Uniform(&rng) * 4 - 2, Uniform(&rng) * 4 - 2, -5 - Uniform(&rng) * 5},
                        {Uniform(&rng) * 4 - 2, Uniform(&rng) * 4 - 2, -5 - Uniform(&rng) * 5},
                        {Uniform(&rng) * 4 - 2, Uniform(&rng) * 4 - 2, -5 - Uniform(&rng) * 5},
                        0};
        // Barycentrics spread from -0.5 to 1.5, kept 1% away from every edge
        real b1 = Uniform(&rng) * 2 - real(0.5), b2 = Uniform(&rng) * 2 - real(0.5);
        real b0 = 1 - b1 - b2;
        if (std::fabs(b0) < 0.01 || std::fabs(b1) < 0.01 || std::fabs(b2) < 0.01)
            continue;
        vec3 target = b0 * tri.a + b1 * tri.b + b2 * tri.c;
        Ray ray = {{Uniform(&rng) - real(0.5), Uniform(&rng) - real(0.5), 1}, {}};
        ray.dir = target - ray.origin;
        RayHit h1, h2;
        bool w = IntersectTriangle(&tri, &ray, 0, kInfinity, &h1);
        bool c = IntersectTriangleCramer(&tri, &ray, 0, kInfinity, &h2);
        hits += w;
        disagree += w != c || (w && std::fabs(h1.t - h2.t) > 1e-3);
    }
    CHECK(hits > 100 && disagree == 0, "Cramer and watertight agree on 2000 ordinary rays (" +
                                           std::to_string(disagree) + " disagree, " +
                                           std::to_string(hits) + " hits)");
}

// Watertightness: a fan of 7 triangles around a shared vertex, in a tilted plane (so there is no
// silhouette a ray could legitimately pass), and rays aimed exactly at the shared vertex and at
// points of the shared edges. Every one must find a triangle.
static vec3 FanPoint(vec3 center, real angle) {
    real x = std::cos(angle), y = std::sin(angle);
    return {center.x + x, center.y + y, center.z + real(0.3) * x - real(0.45) * y};
}

static void TestFanIsWatertight() {
    const int n = 7;
    vec3 center = {real(0.1), real(0.2), real(-3.3)};
    Scene fan;
    for (int k = 0; k < n; k++) {
        vec3 p0 = FanPoint(center, real(2 * M_PI * k / n));
        vec3 p1 = FanPoint(center, real(2 * M_PI * ((k + 1) % n) / n)); // closes exactly
        fan.triangles.push_back({center, p0, p1, 0});
    }
    TestRng rng = {7};
    int missesVertex = 0, missesEdge = 0;
    for (int k = 0; k < 2000; k++) {
        Ray ray = {{Uniform(&rng) * 2 - 1, Uniform(&rng) * 2 - 1, 1}, {}};
        ray.dir = center - ray.origin; // through the shared vertex
        RayHit hit;
        missesVertex += !FindNearestHit(&fan, kRobustMethods, &ray, 0, kInfinity, &hit);
        const Triangle &t = fan.triangles[k % n];
        ray.dir = (t.a + Uniform(&rng) * (t.b - t.a)) - ray.origin; // through a shared edge
        missesEdge += !FindNearestHit(&fan, kRobustMethods, &ray, 0, kInfinity, &hit);
    }
    CHECK(missesVertex == 0, "2000 rays through a fan's shared vertex all hit (" +
                                 std::to_string(missesVertex) + " slipped through)");
    CHECK(missesEdge == 0, "2000 rays through shared edges all hit (" + std::to_string(missesEdge) +
                               " slipped through)");
}

// A triangle with zero area has no normal: it is never hit, and nothing becomes NaN.
static void TestDegenerateTriangle() {
    Triangle line = {{0, 0, -2}, {1, 1, -2}, {2, 2, -2}, 0}; // three points on a line
    Triangle point = {{1, 1, -2}, {1, 1, -2}, {1, 1, -2}, 0};
    Ray ray = {{1, 1, 0}, {0, 0, -1}};
    RayHit hit;
    CHECK(!IntersectTriangle(&line, &ray, 0, kInfinity, &hit) &&
              !IntersectTriangle(&point, &ray, 0, kInfinity, &hit),
          "degenerate triangles (collinear, a point) are not hit by the watertight test");
    CHECK(!IntersectTriangleCramer(&line, &ray, 0, kInfinity, &hit) &&
              !IntersectTriangleCramer(&point, &ray, 0, kInfinity, &hit),
          "degenerate triangles are not hit by Cramer's rule");
}

// Rays leaving a triangle from its hit point never hit it again, at any scale or distance.
static void TestTriangleSpawnedRaysDoNotReHit() {
    int reHits = 0, rays = 0;
    for (real scale : {real(1e-4), real(1), real(1e4)}) {
        for (real far : {real(0), real(1e3)}) {
            vec3 shift = {far * scale, far * scale * real(0.5), far * scale * real(0.7)};
            Triangle tri = {shift + scale * vec3{-3, -1, -5}, shift + scale * vec3{4, -1.2f, -9},
                            shift + scale * vec3{0, 3, -7}, 0};
            TestRng rng = {99};
            for (int k = 0; k < 300; k++) {
                real b1 = Uniform(&rng), b2 = Uniform(&rng) * (1 - b1);
                vec3 target = (1 - b1 - b2) * tri.a + b1 * tri.b + b2 * tri.c;
                Ray ray = {shift, target - shift};
                RayHit hit;
                if (!IntersectTriangle(&tri, &ray, 0, kInfinity, &hit))
                    continue;
                vec3 toLight = (shift + scale * vec3{1, 10, 2}) - hit.point;
                Ray spawned = {OffsetRayOrigin(&hit, toLight), toLight};
                RayHit again;
                rays++;
                reHits += IntersectTriangle(&tri, &spawned, 0, 1, &again);
            }
        }
    }
    CHECK(rays > 1500 && reHits == 0,
          "shadow rays leaving a triangle (scales 1e-4..1e4, near and far) never re-hit it (" +
              std::to_string(reHits) + " of " + std::to_string(rays) + ")");
}

// The shape loop rejects most triangles by the rounded edge functions alone, before the whole
// test (PassesOutside in geometry.cpp); that quick reject must never change an answer. Integer
// corners, rays aimed at corners and at quarter points of edges, directions with a main axis
// of length 8 and sides of whole numbers: every step of the shear is exact, so the edge functions
// there are exactly 0, the case the quick reject must leave to the whole test. Along each main
// axis (the loop is compiled once per axis), FindNearestHit on a one-triangle scene must give
// exactly what IntersectTriangle, which has no quick reject, gives.
static void TestQuickRejectChangesNothing() {
    TestRng rng = {2024};
    int differ = 0, hits = 0;
    auto whole = [&rng](int lo, int hi) { return real(lo + (int)(Uniform(&rng) * (hi - lo + 1))); };
    for (int k = 0; k < 3000; k++) {
        vec3 p[3];
        for (vec3 &corner : p)
            corner = {whole(-4, 4), whole(-4, 4), whole(-4, 4)};
        Scene one;
        one.triangles.push_back({p[0], p[1], p[2], 0});
        real along = whole(0, 3) / 4;
        vec3 target = p[k % 3] + along * (p[(k + 1) % 3] - p[k % 3]);
        int axis = (k / 3) % 3;
        vec3 dir = {whole(-2, 2), whole(-2, 2), whole(-2, 2)};
        real main = k % 2 ? 8 : -8;
        dir = {axis == 0 ? main : dir.x, axis == 1 ? main : dir.y, axis == 2 ? main : dir.z};
        Ray ray = {target - dir, dir};
        RayHit direct, looped;
        bool a = IntersectTriangle(&one.triangles[0], &ray, 0, kInfinity, &direct);
        bool b = FindNearestHit(&one, kRobustMethods, &ray, 0, kInfinity, &looped);
        hits += a;
        differ += a != b || (a && (direct.t != looped.t || direct.point.x != looped.point.x));
    }
    CHECK(differ == 0 && hits > 1000,
          "the shape loop's quick reject changes no answer for 3000 rays through edges and "
          "corners (" +
              std::to_string(differ) + " differ, " + std::to_string(hits) + " hits)");
}

void TestTriangles() {
    TestTriangleTable(IntersectTriangle, "watertight");
    TestTriangleTable(IntersectTriangleCramer, "Cramer");
    TestTriangleTable(IntersectTrianglePlane, "plane");
    TestMethodsAgree();
    TestFanIsWatertight();
    TestDegenerateTriangle();
    TestTriangleSpawnedRaysDoNotReHit();
    TestQuickRejectChangesNothing();
}
