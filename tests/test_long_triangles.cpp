// tests/test_long_triangles.cpp -- long triangles keep their hits: closed boxes never leak.
//
// A corridor 1e8 units long is two triangles per wall, each 1e8 long and a few units wide. The
// watertight test's own t loses about u L^2 / w there, more than the way to the floor; rt takes
// t from the plane (plane.cpp). Every check below runs in double and in float, each over the
// lengths that precision holds (docs/bench/robustness.md has the measured table), axis-aligned and
// rotated (corners rounded after an exact rotation, so the walls are no longer on the grid).
#include "../robust/robust.h"
#include "robust_scenes.h"
#include "test.h"

#include <cstdio>

static const bool kDouble = sizeof(real) == sizeof(double);

// The ray that first showed the leak: from (1, 1.5, 0) down and along the box, the floor at
// t = 1.5 exactly.
static void TestCorridorFloor() {
    double length = kDouble ? 1e8 : 1e3;
    Scene box = BoxScene(length, false);
    Ray ray = {{1, real(1.5), 0}, {0, -1, 1}};
    RayHit hit;
    bool found = FindNearestHit(&box, kRobustMethods, &ray, 0, kInfinity, &hit);
    CHECK(found && hit.t == real(3) && hit.point.y == real(-1.5) && hit.point.z == 3,
          "a ray from (1, 1.5, 0) along (0, -1, 1) in a 4 x 3 x " + std::to_string(length) +
              " box meets the floor at t = 3, point (1, -1.5, 3)");
    ray = {{1, 0, 0}, {0, -1, 1}};
    found = FindNearestHit(&box, kRobustMethods, &ray, 0, kInfinity, &hit);
    CHECK(found && hit.t == real(1.5) && hit.point.z == real(1.5),
          "from (1, 0, 0) the same ray meets the floor at t = 1.5, far from any edge");
}

// Random rays from inside closed boxes: each meets a wall, and its mirror ray from there meets
// another face (never the same one: the box is convex), so nothing leaks and nothing re-hits.
static void TestClosedBoxesHoldEveryRay() {
    const double lengths[] = {1e2, 1e4, 1e8, 1e12};
    const double floatLengths[] = {1e2, 1e3, 3e3, 1e4};
    for (int turn = 0; turn < 2; turn++) {
        for (int k = 0; k < 4; k++) {
            double length = kDouble ? lengths[k] : floatLengths[k];
            BoxLeaks leaks = CountBoxLeaks(length, turn, 500, 2024 + 7 * k + turn);
            char what[160];
            snprintf(
                what, sizeof what,
                "%s box 4 x 3 x %g: 500 rays from inside, %d escape, %d mirror rays escape, %d "
                "re-hit their wall",
                turn ? "rotated" : "axis-aligned", length, leaks.escapes, leaks.mirrorEscapes,
                leaks.reHits);
            CHECK(leaks.escapes == 0 && leaks.mirrorEscapes == 0 && leaks.reHits == 0, what);
        }
    }
}

// Arithmetic with at least 113 bits, for reference values: products of two doubles are exact in
// it, so the plane's normal and n.(a - o) carry only a rounding or two of 2^-113.
#if defined(__SIZEOF_FLOAT128__)
typedef __float128 Quad;
#else
typedef long double Quad; // 113 bits where the platform has no __float128 (e.g. AArch64)
#endif

// The t at which a ray meets the plane through a, b, c, from the rounded inputs.
static double ExactPlaneT(vec3 a, vec3 b, vec3 c, const Ray *ray) {
    Quad e1[3] = {(Quad)b.x - a.x, (Quad)b.y - a.y, (Quad)b.z - a.z};
    Quad e2[3] = {(Quad)c.x - a.x, (Quad)c.y - a.y, (Quad)c.z - a.z};
    Quad n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                 e1[0] * e2[1] - e1[1] * e2[0]};
    Quad toA[3] = {(Quad)a.x - ray->origin.x, (Quad)a.y - ray->origin.y, (Quad)a.z - ray->origin.z};
    Quad d[3] = {ray->dir.x, ray->dir.y, ray->dir.z};
    return (double)((n[0] * toA[0] + n[1] * toA[1] + n[2] * toA[2]) /
                    (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]));
}

// A two-triangle floor of half-size L and rays 25 degrees below the horizon from heights 1e-4 to
// 100: each meets the floor, at the t of the plane through its rounded corners (to 64 u).
static void TestBigFloors() {
    const double sizes[] = {1e3, 1e9, 1e15};
    const double floatSizes[] = {1e3, 1e4, 1e6};
    TestRng rng = {77};
    real slope = std::sin(real(25 * 3.14159265358979 / 180)),
         flat = std::cos(real(25 * 3.14159265358979 / 180));
    for (int turn = 0; turn < 2; turn++) {
        for (int k = 0; k < 3; k++) {
            real half = (real)(kDouble ? sizes[k] : floatSizes[k]);
            vec3 corner[4];
            Scene s = FloorScene(half, turn, corner);
            vec3 a = corner[0], b = corner[1], c = corner[2];
            // t is within a few u of itself, plus a few u^2 (of double: both tiers compute in
            // double) of the floor's size over the height, 1e-4 at least (the double-double
            // tier, for a ray that starts 1e-4 above a floor 1e15 wide); the reference within
            // 2^-113 of the same ratio
            double ud = std::ldexp(1.0, -53), uQuad = std::ldexp(1.0, -113);
            double tolerance =
                64 * (double)kUnitRoundoff + (1e3 * ud * ud + 16 * uQuad) * (double)half / 1e-4;
            int lost = 0, off = 0;
            for (real height : {real(1e-4), real(1e-2), real(1), real(100)}) {
                for (int i = 0; i < 100; i++) {
                    real phi = real(6.283185307179586) * Uniform(&rng);
                    vec3 o = {10 * Uniform(&rng) - 5, height, 10 * Uniform(&rng) - 5};
                    Ray ray = {Turn(o, turn),
                               Turn({flat * std::cos(phi), -slope, flat * std::sin(phi)}, turn)};
                    RayHit hit;
                    if (!FindNearestHit(&s, kRobustMethods, &ray, 0, kInfinity, &hit))
                        lost++;
                    else if (std::fabs(hit.t - ExactPlaneT(a, c, b, &ray)) > tolerance * hit.t)
                        off++;
                }
            }
            char what[256];
            snprintf(
                what, sizeof what,
                "%s floor of half-size %g: 400 rays 25 degrees down from heights 1e-4..100, %d "
                "lost, %d with t off by more than %.2g of t",
                turn ? "rotated" : "axis-aligned", (double)half, lost, off, tolerance);
            CHECK(lost == 0 && off == 0, what);
        }
    }
}

// Slivers: a needle (0,0,0) (L,0,0) (0,0,1) and a cap (0,0,0) (L,0,0) (L/2,0,1), rays straight
// down at interior points (barycentric coordinates at least 0.05 from every edge's share).
static void TestSlivers() {
    const double aspects[] = {1e4, 1e8, 1e12};
    const double floatAspects[] = {1e2, 1e3, 1e4};
    TestRng rng = {5};
    for (int turn = 0; turn < 2; turn++) {
        for (int k = 0; k < 3; k++) {
            for (int cap = 0; cap < 2; cap++) {
                real length = (real)(kDouble ? aspects[k] : floatAspects[k]);
                vec3 apex = cap ? vec3{length / 2, 0, 1} : vec3{0, 0, 1};
                Scene s = WallScene();
                s.triangles = {
                    {Turn({0, 0, 0}, turn), Turn({length, 0, 0}, turn), Turn(apex, turn), 0}};
                int misses = 0;
                for (int i = 0; i < 200; i++) {
                    real u = real(0.05) + real(0.9) * Uniform(&rng);
                    real v = (real(0.05) + real(0.9) * Uniform(&rng)) * (1 - u);
                    vec3 q = {u * length + v * apex.x, 1, v * apex.z};
                    Ray ray = {Turn(q, turn), Turn({0, -1, 0}, turn)};
                    RayHit hit;
                    misses += !FindNearestHit(&s, kRobustMethods, &ray, 0, kInfinity, &hit);
                }
                char what[160];
                snprintf(what, sizeof what,
                         "%s %s sliver of aspect %g: %d of 200 interior rays miss",
                         turn ? "rotated" : "axis-aligned", cap ? "cap" : "needle", (double)length,
                         misses);
                CHECK(misses == 0, what);
            }
        }
    }
}

// A mirror ball of radius 0.01 resting on a floor of half-size 1e12 (1e4 in float): every ray
// leaving the ball's lower half downward meets the floor (the ball reflects floor, not sky).
static void TestBallOnBigFloor() {
    real half = kDouble ? real(1e12) : real(1e4), r = real(0.01);
    Scene s = WallScene();
    s.triangles = {{{-half, 0, -half}, {half, 0, half}, {half, 0, -half}, 0},
                   {{-half, 0, -half}, {-half, 0, half}, {half, 0, half}, 0}};
    Sphere ball = {{0, r, 0}, r, 0};
    TestRng rng = {11};
    int lost = 0;
    for (int i = 0; i < 400; i++) {
        vec3 d = UnitDirection(Uniform(&rng), Uniform(&rng));
        if (d.y > 0)
            d.y = -d.y;
        // a point on the ball's lower half, hit from inside along -d... found by a probe from the
        // centre, so it carries the sphere's own hit record and error bound
        Ray fromCentre = {ball.center, d};
        RayHit onBall, floor;
        if (!IntersectSphere(&ball, &fromCentre, 0, kInfinity, &onBall))
            continue;
        vec3 down = {d.x, -std::fabs(d.y) - real(0.05), d.z};
        Ray leaving = {OffsetRayOrigin(&onBall, down), down};
        lost += !FindNearestHit(&s, kRobustMethods, &leaving, 0, kInfinity, &floor);
    }
    CHECK(lost == 0,
          "rays leaving a ball of radius 0.01 downward all meet the floor of half-size " +
              std::to_string(half) + " (" + std::to_string(lost) + " lost)");
}

// A sheet just behind a turned floor of half-size 1e13 (float: 1e5), listed before it: rays from
// 1 above the floor, 25 degrees down, must meet the floor, not the sheet behind it. The floor's
// plain-double t is off by more than the gap there; only its accurate t may be compared.
static void TestFloorBeforeWhatIsBehindIt() {
    real half = kDouble ? real(1e13) : real(1e5), gap = kDouble ? real(2e-3) : real(5e-2);
    vec3 corner[4];
    Scene s = FloorScene(half, true, corner);
    Triangle sheet = {Turn({-20, -gap, -20}, true), Turn({20, -gap, 20}, true),
                      Turn({20, -gap, -20}, true), 0};
    s.triangles.insert(s.triangles.begin(), sheet);
    TestRng rng = {31};
    real slope = std::sin(real(25 * 3.14159265358979 / 180)),
         flat = std::cos(real(25 * 3.14159265358979 / 180));
    int wrong = 0;
    for (int i = 0; i < 200; i++) {
        real phi = real(6.283185307179586) * Uniform(&rng);
        vec3 o = {10 * Uniform(&rng) - 5, 1, 10 * Uniform(&rng) - 5};
        Ray ray = {Turn(o, true), Turn({flat * std::cos(phi), -slope, flat * std::sin(phi)}, true)};
        RayHit hit;
        wrong += !FindNearestHit(&s, kRobustMethods, &ray, 0, kInfinity, &hit) || hit.index == 0;
    }
    char what[160];
    snprintf(what, sizeof what,
             "a sheet %g behind a turned floor of half-size %g, listed first: %d of 200 rays "
             "meet it instead of the floor",
             (double)gap, (double)half, wrong);
    CHECK(wrong == 0, what);
}

void TestLongTriangles() {
    TestFloorBeforeWhatIsBehindIt();
    TestCorridorFloor();
    TestClosedBoxesHoldEveryRay();
    TestBigFloors();
    TestSlivers();
    TestBallOnBigFloor();
}
