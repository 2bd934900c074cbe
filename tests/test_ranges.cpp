// tests/test_ranges.cpp -- sizes at the ends of the number range: no input aborts, no square
// over- or underflows, and the picture is the same at every scale the documentation claims.
//
// Directions of 1e-310 and 1e300, spheres of radius 1e-200, a light 1e153 away, the assignment
// scene scaled from 1e-300 to 1e300 (float: 1e-37 to 1e36) with each of the three cameras, and
// glass of index 1 at grazing incidence. Each runs in double and in float, over that precision's
// range.
#include "../app/app.h"
#include "robust_scenes.h"
#include "test.h"

#include <cstdio>

static const bool kDouble = sizeof(real) == sizeof(double);

static bool RenderText(const std::string &text, Image *image) {
    Scene scene;
    std::string error;
    if (!ParseSceneText(text, "range.scene", &scene, &error))
        return false;
    RenderSettings settings = TestSettings(&scene);
    RayStats stats = {};
    Render(&scene, &settings, image, &stats);
    return true;
}

// The same picture at every scale and with each camera: 99.8% of pixels within 2/255 of the
// picture at scale 1, and glass too.
static void TestEveryScale() {
    const double scales[] = {1e-300, 1e-150, 1e-100, 1e100, 1e200, 1e300};
    const double floatScales[] = {1e-37, 1e-30, 1e-20, 1e20, 1e30, 1e36};
    for (const char *camera : {"perspective", "screen", "lookat"}) {
        for (bool glass : {false, true}) {
            Image original, scaled;
            RenderText(AssignmentText(1, 0, camera, glass), &original);
            for (int k = 0; k < 6; k++) {
                double scale = kDouble ? scales[k] : floatScales[k];
                bool read = RenderText(AssignmentText(scale, 0, camera, glass), &scaled);
                double share = read ? ShareAlike(original, scaled) : 0;
                char what[160];
                snprintf(what, sizeof what,
                         "%s scene scaled by %g, %s camera: %.2f%% of pixels alike",
                         glass ? "glass" : "assignment", scale, camera, 100 * share);
                CHECK(share >= 0.998, what);
            }
        }
    }
}

// Far from the origin every camera builds its rays from the eye outward, so the picture holds
// until the scene's own coordinates round (double 1e13, float 1e4: a double's spacing at 1e15 is
// 0.125, a float's at 1e6 is 0.06, both near the size of the scene's details).
static void TestFarFromTheOrigin() {
    double shift = kDouble ? 1e13 : 1e4;
    for (const char *camera : {"perspective", "screen", "lookat"}) {
        Image original, moved;
        RenderText(AssignmentText(1, 0, camera, false), &original);
        bool read = RenderText(AssignmentText(1, shift, camera, false), &moved);
        double share = read ? ShareAlike(original, moved) : 0;
        char what[160];
        snprintf(what, sizeof what, "assignment scene moved %g from the origin, %s camera: %.2f%%",
                 shift, camera, 100 * share);
        CHECK(share >= 0.998, what);
    }
}

// A camera whose screen is 1e155 wide (double; 1e30 in float) sees what a screen 1 wide sees:
// its rays are the same up to length, and glass normalises them without overflowing.
static void TestHugeCamera() {
    std::string text = AssignmentText(1, 0, "perspective", true);
    std::string huge = text, size = kDouble ? "1e155" : "1e30";
    size_t at = huge.find("camera perspective");
    huge.replace(at, huge.find('\n', at) - at, "camera perspective 0 0 0 " + size + " " + size);
    std::string one = text;
    at = one.find("camera perspective");
    one.replace(at, one.find('\n', at) - at, "camera perspective 0 0 0 1 1");
    Image a, b;
    bool read = RenderText(huge, &a) && RenderText(one, &b);
    CHECK(read && a.pixels == b.pixels,
          "glass seen by `camera perspective 0 0 0 " + size + " " + size +
              "` renders the bytes of `camera perspective 0 0 0 1 1`");
}

// Zero and not-finite directions have no answer (and abort nothing); directions of 1e-310 and
// 1e300 (float: 1e-40, a subnormal, and 1e30) hit a sphere and a triangle at t in units of the
// direction given (t = 5e306 for the shortest).
static void TestDirectionSizes() {
    Sphere sphere = {{real(1e-3), 0, 0}, real(5e-4), 0};
    real x = real(5e-4);
    Triangle tri = {{x, -1, -1}, {x, 1, -1}, {x, 0, 2}, 0};
    RayHit hit;
    real nan = std::numeric_limits<real>::quiet_NaN();
    for (vec3 d : {vec3{0, 0, 0}, vec3{nan, 0, 1}, vec3{kInfinity, 0, 0}}) {
        Ray ray = {{0, 0, 0}, d};
        Scene scene;
        InitScene(&scene);
        scene.materials.push_back(Matte("m", {1, 1, 1}));
        scene.spheres.push_back(sphere);
        scene.triangles.push_back(tri);
        CHECK(!IntersectSphere(&sphere, &ray, 0, kInfinity, &hit) &&
                  !IntersectTriangle(&tri, &ray, 0, kInfinity, &hit) &&
                  !FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &hit) &&
                  !AnyHit(&scene, kRobustMethods, &ray, 0, kInfinity),
              "a zero, NaN or infinite direction has no hit");
    }
    const real sizes[] = {kDouble ? real(1e-310) : real(1e-40), kDouble ? real(1e300) : real(1e30)};
    for (real size : sizes) {
        Ray ray = {{0, 0, 0}, {size, 0, 0}};
        bool found = IntersectSphere(&sphere, &ray, 0, kInfinity, &hit);
        char what[96];
        snprintf(what, sizeof what, "a ray along x of length %g hits the sphere", (double)size);
        CHECK(found, what);
        if (found)
            CHECK_NEAR(hit.t, 5e-4 / (double)size, 4 * kRelTol * (5e-4 / (double)size),
                       "t in units of the direction as given, t = 5e-4 / |d|");
        found = IntersectTriangle(&tri, &ray, 0, kInfinity, &hit);
        if (found)
            CHECK_NEAR(hit.t, 5e-4 / (double)size, 4 * kRelTol * (5e-4 / (double)size),
                       "the triangle at x = 5e-4, t = 5e-4 / |d|");
        snprintf(what, sizeof what, "a ray along x of length %g hits the triangle", (double)size);
        CHECK(found, what);
    }
}

// A direction the search rescales, with a shape whose t leaves the range of numbers on the way
// back. A tiny direction, 2^-70 (float: 2^-12): a triangle at z = 1e300 (float: 3e38), first in
// the scene, lies at a t beyond the largest number, and one at z = 1 at t = 2^70; a search for
// any hit must find the second, which blocks the ray. A huge direction, 1e300 (float: 1e30): a
// triangle at z = 1e-320 (float: 1e-44) lies at a t that rounds to 0, no hit (t > 0), and the
// nearest hit is the one at z = 1, t = 1e-300 (float: 1e-30); one at a t of 0.8 of the smallest
// number is hit, at that number.
static void TestRescaledSearchRange() {
    auto square = [](real z) { return Triangle{{-1, -1, z}, {3, -1, z}, {-1, 3, z}, 0}; };
    Scene scene;
    InitScene(&scene);
    scene.materials.push_back(Matte("m", {1, 1, 1}));
    real tiny = kDouble ? real(0x1p-70) : real(0x1p-12);
    scene.triangles = {square(kDouble ? real(1e300) : real(3e38)), square(1)};
    Ray ray = {{0, 0, 0}, {0, 0, tiny}};
    RayHit hit;
    CHECK(AnyHit(&scene, kRobustMethods, &ray, 0, kInfinity),
          "any hit: the triangle at z = 1 blocks a ray of length 2^-70 (float: 2^-12) whose first "
          "shape lies beyond the range of t");
    bool found = FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &hit);
    CHECK(found && hit.index == 1 && hit.t == 1 / tiny, "nearest hit: z = 1, at t = 1 / |d|");
    real huge = kDouble ? real(1e300) : real(1e30);
    scene.triangles = {square(kDouble ? real(1e-320) : real(1e-44)), square(1)};
    ray = {{0, 0, 0}, {0, 0, huge}};
    found = FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &hit);
    CHECK(found && hit.index == 1,
          "nearest hit past a shape whose t rounds to 0: the triangle at z = 1");
    if (found)
        CHECK_NEAR(hit.t, 1 / (double)huge, kRelTol / (double)huge, "at t = 1 / |d|");
    CHECK(AnyHit(&scene, kRobustMethods, &ray, 0, kInfinity), "any hit: the same ray is blocked");
    // A triangle at a t of 0.8 of the smallest number rounds up to it: a hit, at that t.
    real smallest = std::numeric_limits<real>::denorm_min();
    scene.triangles = {square(real((double)smallest * (double)huge * 0.8)), square(1)};
    found = FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &hit);
    CHECK(found && hit.index == 0 && hit.t == smallest,
          "nearest hit at t = 0.8 of the smallest number: the first triangle, t rounded up to it");
}

// Spheres of radius 1e-200 and 1e200 (float: 1e-30 and 1e30), seen from 10 radii: a ray 3 degrees
// off the line to the centre hits (the sphere spans 5.7 degrees), on the sphere with a unit
// normal; 31 degrees off misses.
static void TestSphereSizes() {
    for (real r : {kDouble ? real(1e-200) : real(1e-30), kDouble ? real(1e200) : real(1e30)}) {
        Sphere s = {{0, 0, 0}, r, 0};
        for (real degrees : {real(3), real(31)}) {
            real a = degrees * real(3.14159265358979 / 180);
            Ray ray = {{0, 0, 10 * r}, {std::sin(a), 0, -std::cos(a)}};
            RayHit hit;
            bool found = IntersectSphere(&s, &ray, 0, kInfinity, &hit);
            if (degrees > 10) {
                CHECK(!found, "31 degrees off the axis misses a sphere of radius " +
                                  std::to_string((double)r));
                continue;
            }
            CHECK(found && IsFinite(hit.point) &&
                      std::fabs(SafeLength(hit.point) - r) <= 8 * kRelTol * r &&
                      std::fabs(Length(hit.normal) - 1) <= 8 * kRelTol,
                  "3 degrees off the axis hits a sphere of radius " + std::to_string((double)r) +
                      " on its surface, with a unit normal");
        }
    }
}

// A light 1e153 above a sphere of radius 100 (float: 1e30): the floor under the sphere is in
// its shadow (ambient only) and the floor beside it is lit, as the probe of the same shadow
// ray says.
static void TestFarLight() {
    std::string text = std::string("size 8 8\nmaterial white diffuse 1 1 1\nlight 0 ") +
                       (kDouble ? "1e153" : "1e30") +
                       " 0\nsphere 0 300 0 100 white\n"
                       "triangle -1000 0 -1000  1000 0 1000  1000 0 -1000 white\n"
                       "triangle -1000 0 -1000  -1000 0 1000  1000 0 1000 white\n";
    Scene scene;
    std::string error;
    bool read = ParseSceneText(text, "sun.scene", &scene, &error);
    RenderSettings settings = TestSettings(&scene);
    real shadow = -1, lit = -1;
    for (real x : {real(0), real(500)}) {
        TraceLog log = {RayStats{}, nullptr, -1, 0};
        Ray ray = {{x, 50, 30}, {0, -50, -30}};
        color c =
            read ? TraceRay(&scene, &settings, RAY_PRIMARY, &ray, &kNoSelfHit, RayChain{1, 1}, &log)
                 : color{-1, -1, -1};
        (x == 0 ? shadow : lit) = c.x;
    }
    CHECK(read && std::fabs(shadow - real(0.2)) <= real(1e-6) && lit > real(0.99),
          "a light 1e153 away: the floor under the sphere shows the ambient 0.2 (" +
              std::to_string((double)shadow) + "), beside it full light (" +
              std::to_string((double)lit) + ")");
}

// Glass of index 1 bends nothing and reflects nothing, at any angle, down to grazing rays with
// cos(i) = 1e-300 (float: 1e-37); Snell's law without cancellation (RefractedCosine).
static void TestGlassOfIndexOne() {
    const real cosines[] = {real(0.5), real(1e-3), real(1e-9), real(1e-12),
                            kDouble ? real(1e-300) : real(1e-37)};
    vec3 n = {0, 1, 0};
    for (real c : cosines) {
        vec3 d = {std::sqrt((1 - c) * (1 + c)), -c, 0};
        vec3 t;
        bool refracted = Refract(d, n, 1, &t);
        CHECK(refracted && t.x == d.x && t.y == d.y && t.z == d.z && FresnelReflectance(c, 1) == 0,
              "glass of index 1 passes a ray with cos(i) = " + std::to_string((double)c) +
                  " straight through, reflecting none of it");
    }
    // eta = 1.5 (leaving glass): total internal reflection just above the critical angle only
    real critical = std::sqrt(1 - 1 / real(2.25));
    vec3 t;
    vec3 in = {std::sqrt(1 - critical * critical * real(1.01)), -critical * real(1.01), 0};
    vec3 out = {std::sqrt(1 - critical * critical * real(0.99)), -critical * real(0.99), 0};
    CHECK(Refract(SafeNormalize(in), n, real(1.5), &t) &&
              !Refract(SafeNormalize(out), n, real(1.5), &t) &&
              FresnelReflectance(critical * real(0.99), real(1.5)) == 1,
          "leaving glass of index 1.5: refraction above the critical cosine, total internal "
          "reflection below it");
}

// Probe numbers are the shortest that read back exactly, and finite: the ray trees of every
// pixel of the glass scene at the ends of the range contain no nan or inf.
static void TestProbeNumbers() {
    Scene scene;
    InitScene(&scene);
    scene.materials.push_back(Matte("m", {1, 1, 1}));
    scene.triangles.push_back({{-1, -1, real(-4.2)}, {1, -1, real(-4.2)}, {0, 1, real(-4.2)}, 0});
    RenderSettings settings = TestSettings(&scene);
    Ray ray = {{0, 0, 0}, {0, 0, -1}};
    std::string json = ProbeRayJson(&scene, &settings, &ray);
    CHECK(json.find("\"t\":4.2,") != std::string::npos &&
              json.find("\"point\":[0,0,-4.2]") != std::string::npos,
          "a hit at t = 4.2 prints as 4.2, not 4.2000000000000002: " + json);
    int bad = 0;
    for (double scale : {kDouble ? 1e-300 : 1e-37, kDouble ? 1e300 : 1e36}) {
        Scene s;
        std::string error;
        ParseSceneText(AssignmentText(scale, 0, "lookat", true), "g.scene", &s, &error);
        RenderSettings st = TestSettings(&s);
        for (int y = 0; y < 64; y += 3)
            for (int x = 0; x < 64; x += 3) {
                std::string tree = PixelTreeJson(&s, &st, x, y);
                bad +=
                    tree.find("nan") != std::string::npos || tree.find("inf") != std::string::npos;
            }
    }
    CHECK(bad == 0, "ray trees of the glass scene at scales 1e+-300 (float 1e-37, 1e36) hold only "
                    "finite numbers (" +
                        std::to_string(bad) + " trees with nan or inf)");
}

// A screen so large that a pixel's direction would overflow is refused when read.
static void TestOverflowingScreen() {
    Scene scene;
    std::string error, big = kDouble ? "1e308" : "3e38", half = kDouble ? "0.5e308" : "1.5e38";
    std::string text = "camera screen 0 0 0  -" + half + " -" + half + " -1.5" + big.substr(1) +
                       "  " + big + " 0 0  0 " + big + " -" + big + "\n";
    CHECK(!ParseSceneText(text, "s.scene", &scene, &error) &&
              error.find("so large that a pixel's direction would overflow") != std::string::npos,
          "a screen whose pixel directions overflow is refused (" + error + ")");
}

void TestRanges() {
    TestOverflowingScreen();
    TestProbeNumbers();
    TestEveryScale();
    TestFarFromTheOrigin();
    TestHugeCamera();
    TestDirectionSizes();
    TestRescaledSearchRange();
    TestSphereSizes();
    TestFarLight();
    TestGlassOfIndexOne();
}
