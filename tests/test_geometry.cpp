// tests/test_geometry.cpp -- ray/sphere hits predicted by hand, and the intersect contract.
//
// The handout's advice: a scene, a ray, the hit you predicted. Each row is worked out on paper
// from |o + t d - c| = r; the Ray Tracer Challenge's canonical cases are among them.
#include "../robust/robust.h"
#include "hard_cases.h"
#include "test.h"

#include <cstring>

struct SphereCase {
    const char *name;
    Ray ray;
    Sphere sphere;
    real tMax;
    bool expectHit;
    real t;
    vec3 normal; // facing the ray
    bool frontFace;
};

// clang-format off: one case a line (name, ray, sphere, tMax, hit?, t, normal, front face)
static const SphereCase kSphereCases[] = {
    // A unit sphere 5 ahead: the ray meets its near pole at t = 4, normal back toward the eye
    {"through the centre", {{0, 0, 0}, {0, 0, -1}}, {{0, 0, -5}, 1, 0}, kInfinity, true, 4, {0, 0, 1}, true},
    // Off axis at height 0.6: (z + 5)^2 = 1 - 0.36 = 0.64, so z = -4.2, normal (0, 0.6, 0.8)
    {"off-axis at y = 0.6", {{0, 0.6, 0}, {0, 0, -1}}, {{0, 0, -5}, 1, 0}, kInfinity, true, 4.2, {0, 0.6, 0.8}, true},
    // Off axis in x and y: x^2 + y^2 = 0.36 + 0.28 = 0.64, (z + 5)^2 = 0.36, z = -4.4
    {"off-axis in x and y", {{0.6, std::sqrt(real(0.28)), 0}, {0, 0, -1}}, {{0, 0, -5}, 1, 0}, kInfinity, true, 4.4, {0.6, std::sqrt(real(0.28)), 0.6}, true},
    // RTC "a ray intersects a sphere at a tangent": both roots are 5
    {"tangent at y = 1", {{0, 1, -5}, {0, 0, 1}}, {{0, 0, 0}, 1, 0}, kInfinity, true, 5, {0, 1, 0}, true},
    // RTC: a ray passing above the sphere misses
    {"miss above", {{0, 2, -5}, {0, 0, 1}}, {{0, 0, 0}, 1, 0}, kInfinity, false, 0, {0, 0, 0}, false},
    // RTC "a ray originates inside a sphere": roots -1 and 1; the hit is the far wall at t = 1,
    // seen from inside, so the normal is flipped toward the ray and frontFace is false
    {"origin inside", {{0, 0, 0}, {0, 0, 1}}, {{0, 0, 0}, 1, 0}, kInfinity, true, 1, {0, 0, -1}, false},
    // RTC "a sphere is behind a ray": roots -6 and -4, nothing at t > 0
    {"sphere behind", {{0, 0, 5}, {0, 0, 1}}, {{0, 0, 0}, 1, 0}, kInfinity, false, 0, {0, 0, 0}, false},
    // RTC: roots 4 and 6, the nearer wins
    {"nearer of two roots", {{0, 0, -5}, {0, 0, 1}}, {{0, 0, 0}, 1, 0}, kInfinity, true, 4, {0, 0, -1}, true},
    // t scales with 1/|d|: |d| = 1e-3 reaches the near pole (distance 4) at t = 4000
    {"short direction", {{0, 0, 0}, {0, 0, real(-1e-3)}}, {{0, 0, -5}, 1, 0}, kInfinity, true, 4000, {0, 0, 1}, true},
    // |d| = 1e3: t = 4e-3
    {"long direction", {{0, 0, 0}, {0, 0, real(-1e3)}}, {{0, 0, -5}, 1, 0}, kInfinity, true, real(4e-3), {0, 0, 1}, true},
    // Open interval: tMax = 4 exactly excludes the near root at 4, and the far one at 6
    {"tMax excludes the hit", {{0, 0, 0}, {0, 0, -1}}, {{0, 0, -5}, 1, 0}, 4, false, 0, {0, 0, 0}, false},
    // A big sphere far away, radius 100 at distance 1e4: near pole at 1e4 - 100 = 9900
    {"big and far", {{0, 0, 0}, {1, 0, 0}}, {{10000, 0, 0}, 100, 0}, kInfinity, true, 9900, {-1, 0, 0}, true},
};
// clang-format on

// Every row through both sphere methods: these cases are the ordinary ones, where the
// handout's quadratic is right too (its failures are the hard-case suite's).
static void TestSphereTable(SphereRoutine intersect, const char *method) {
    for (const SphereCase &c : kSphereCases) {
        RayHit hit;
        memset(&hit, 0, sizeof hit);
        bool got = intersect(&c.sphere, &c.ray, 0, c.tMax, &hit);
        std::string name = std::string(method) + " sphere, " + c.name;
        CHECK(got == c.expectHit, name + ": hit or miss");
        if (!got || !c.expectHit)
            continue;
        CHECK_NEAR(hit.t, c.t, kRelTol * c.t, name + ": t");
        CHECK(std::fabs(hit.normal.x - c.normal.x) < 16 * kRelTol &&
                  std::fabs(hit.normal.y - c.normal.y) < 16 * kRelTol &&
                  std::fabs(hit.normal.z - c.normal.z) < 16 * kRelTol,
              name + ": unit normal facing the ray");
        CHECK(hit.frontFace == c.frontFace, name + ": front face");
    }
}

// The contract of every intersect function: a miss leaves *hit exactly as it was.
static void TestMissLeavesHitAlone() {
    Sphere s = {{0, 0, -5}, 1, 7};
    Ray ray = {{0, 3, 0}, {0, 0, -1}};
    RayHit hit, before;
    memset(&hit, 0xAB, sizeof hit);
    memcpy(&before, &hit, sizeof hit);
    IntersectSphere(&s, &ray, 0, kInfinity, &hit);
    CHECK(memcmp(&hit, &before, sizeof hit) == 0, "sphere miss: the hit record is not written");

    Triangle tri = {{0, 1, -5}, {-1, 0, -5}, {1, 0, -5}, 7};
    IntersectTriangle(&tri, &ray, 0, kInfinity, &hit);
    IntersectTriangleCramer(&tri, &ray, 0, kInfinity, &hit);
    CHECK(memcmp(&hit, &before, sizeof hit) == 0, "triangle miss: the hit record is not written");
}

// A hit reports which shape and material it found; the hit point lies on the sphere.
static void TestSphereHitRecord() {
    Scene scene;
    scene.spheres = {{{0, 0, -10}, 1, 3}, {{0, 0, -5}, 1, 2}};
    Ray ray = {{0, 0, 0}, {0, 0, -1}};
    RayHit hit;
    bool got = FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &hit);
    CHECK(got && hit.shape == SHAPE_SPHERE && hit.index == 1 && hit.material == 2,
          "nearest of two spheres in a row is the second in the list, at t = 4");
    CHECK_NEAR(hit.t, 4, 4 * kRelTol, "nearest of two spheres: t = 4");
    CHECK_NEAR(hit.point.z, -4, 4 * kRelTol, "hit point on the near pole, z = -4");
    CHECK(AnyHit(&scene, kRobustMethods, &ray, 0, 5) && !AnyHit(&scene, kRobustMethods, &ray, 0, 4),
          "any hit: a blocker at t = 4 counts for tMax = 5, not for the open bound tMax = 4");
}

// A ray leaving a sphere from its own hit point must not hit the sphere again, at any scale.
static void TestSphereSpawnedRaysDoNotReHit() {
    int reHits = 0, rays = 0;
    for (real scale : {real(1e-4), real(1), real(1e4)}) {
        Sphere s = {{3 * scale, -2 * scale, -20 * scale}, 1.5f * scale, 0};
        for (int k = 0; k < 200; k++) {
            real u = real(k) / 200 - real(0.5), v = real((k * 37) % 200) / 200 - real(0.5);
            Ray ray = {{0, 0, 0},
                       {s.center.x + u * s.radius * 2, s.center.y + v * s.radius * 2, s.center.z}};
            RayHit hit;
            if (!IntersectSphere(&s, &ray, 0, kInfinity, &hit))
                continue;
            // Reflect away from the surface, and also aim at a light high above
            vec3 dirs[2] = {ray.dir - (2 * Dot(ray.dir, hit.normal)) * hit.normal,
                            vec3{0, 100 * scale, 0} - hit.point};
            for (vec3 dir : dirs) {
                if (Dot(dir, hit.normal) <= 0)
                    continue;
                Ray spawned = {OffsetRayOrigin(&hit, dir), dir};
                RayHit again;
                rays++;
                reHits += IntersectSphere(&s, &spawned, 0, kInfinity, &again);
            }
        }
    }
    CHECK(rays > 500 && reHits == 0,
          "rays leaving a sphere at scales 1e-4, 1, 1e4 never re-hit it (" +
              std::to_string(reHits) + " of " + std::to_string(rays) + ")");
}

// The shape loop skips a sphere when the ray's line misses it (LineMissesSphere in geometry.cpp)
// before the whole test; that must never change an answer. Rays aimed at the silhouette, where
// the discriminant is 0 or within rounding of it, and just inside and outside it: FindNearestHit
// on a one-sphere scene must give exactly what IntersectSphere, which has no quick reject, gives.
static void TestSphereQuickRejectChangesNothing() {
    TestRng rng = {77};
    int differ = 0, hits = 0;
    for (int k = 0; k < 3000; k++) {
        Scene one;
        one.spheres.push_back(
            {{Uniform(&rng), Uniform(&rng), -5 - Uniform(&rng)}, real(0.5) + Uniform(&rng), 0});
        const Sphere &s = one.spheres[0];
        // A line passing r (1 + e) from the centre, e = 0 or up to 1e-6 either way: through a
        // point `side` of the centre, along w perpendicular to side, from 6 units back
        vec3 w = Normalize({Uniform(&rng) - real(0.5), Uniform(&rng) - real(0.5), -1});
        vec3 side = Normalize(Cross(w, vec3{Uniform(&rng), 1, Uniform(&rng)}));
        real r = s.radius * (1 + (Uniform(&rng) * 2 - 1) * real(1e-6) * (k % 3));
        vec3 target = s.center + r * side;
        if (k % 2)
            target.y = std::nextafter(target.y, k % 4 == 1 ? kInfinity : -kInfinity);
        Ray ray = {target - 6 * w, 6 * w};
        RayHit direct, looped;
        bool a = IntersectSphere(&s, &ray, 0, kInfinity, &direct);
        bool b = FindNearestHit(&one, kRobustMethods, &ray, 0, kInfinity, &looped);
        hits += a;
        differ += a != b || (a && (direct.t != looped.t || direct.point.x != looped.point.x));
    }
    CHECK(differ == 0 && hits > 300 && hits < 2700,
          "the shape loop's sphere quick reject changes no answer for 3000 silhouette rays (" +
              std::to_string(differ) + " differ, " + std::to_string(hits) + " hits)");
}

// NextAfter, the inline step to the neighbouring number that OffsetRayOrigin and the shape loop
// use, is the library's nextafter bit for bit: at 0 and -0, the subnormals, the largest
// numbers, the infinities, NaN, and random bit patterns of every exponent.
static void TestNextAfterIsTheLibrarys() {
    typedef std::numeric_limits<real> L;
    std::vector<real> xs = {0,         -real(0), L::denorm_min(), -L::denorm_min(), L::min(),
                            -L::min(), L::max(), -L::max(),       kInfinity,        -kInfinity,
                            1,         -1,       real(0.1)};
    TestRng rng = {7};
    for (int k = 0; k < 20000; k++) {
        uint64_t wide = rng.state = rng.state * 6364136223846793005ULL + 1442695040888963407ULL;
        real x;
        if (sizeof x == 4) {
            uint32_t bits = (uint32_t)(wide >> 32);
            memcpy(&x, &bits, sizeof x);
        } else {
            memcpy(&x, &wide, sizeof x);
        }
        xs.push_back(x);
    }
    int differ = 0;
    for (real x : xs)
        for (bool up : {true, false}) {
            real mine = NextAfter(x, up), theirs = std::nextafter(x, up ? kInfinity : -kInfinity);
            differ +=
                memcmp(&mine, &theirs, sizeof mine) != 0 && !(mine != mine && theirs != theirs);
        }
    CHECK(differ == 0, "NextAfter is nextafter, bit for bit, both ways for " +
                           std::to_string(xs.size()) + " numbers (" + std::to_string(differ) +
                           " differ)");
}

void TestGeometry() {
    TestSphereTable(IntersectSphere, "stable");
    TestSphereTable(IntersectSphereTextbook, "textbook");
    TestMissLeavesHitAlone();
    TestSphereHitRecord();
    TestSphereSpawnedRaysDoNotReHit();
    TestSphereQuickRejectChangesNothing();
    TestNextAfterIsTheLibrarys();
}
