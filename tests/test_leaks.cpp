// tests/test_leaks.cpp -- the leak detector: no ray gets out of a closed mesh.
//
// A camera inside a closed mesh whose walls let no light in (white diffuse walls and no lamp under
// `shading path`, or perfect mirrors under `shading floor`) and a green background: every pixel
// must be black, and a pixel with any green in it is a ray that got out (LeakScene). Boxes
// 4 x 3 x L (the robustness tables' lengths), 10 x 3 x 4 boxes far from the origin and long
// prisms with a sharp edge, turned by the `mesh` statement's own rotate words at random angles,
// seen from near their middle in a random direction, a chain of 100 rays a pixel (at reflectance
// 1 roulette ends no path). A glass ball inside sends refracted rays to the walls too.
// docs/robustness.md gives the ranges, and `make bench` a larger sweep with rates.
#include "robust_scenes.h"
#include "test.h"

#include <cstdio>

static const bool kDouble = sizeof(real) == sizeof(double);

// Random rotate words, from the test's generator.
static std::string RandomTurn(TestRng *rng) {
    double x = 360 * (double)Uniform(rng), y = 360 * (double)Uniform(rng);
    return TurnWords(x, y, 360 * (double)Uniform(rng));
}

// The box that leaked: 10 x 3 x 4 at the origin, turned as the report turned it; in float, at
// 48 x 48, sample 0 of pixel (25, 12) with seed 68 went out near an edge on its 62nd ray.
static void TestReportedLeak() {
    Scene scene = LeakScene(
        false, {0, 0, 0},
        {real(-0.3334740585882376), real(0.7059279025963143), real(0.4740857132903602)}, 48);
    CHECK(AddMeshBox(&scene, 10, 3, 4,
                     "scale 1.0 rotate x 184.28711005505 rotate y 226.7577792780487 rotate z "
                     "285.47167410718293 translate 0.0 -0.0 0.0"),
          "the reported box's transform words");
    RenderSettings settings = TestSettings(&scene);
    settings.path.seed = 68;
    RayStats stats = {};
    color c = RenderPixel(&scene, &settings, 25, 12, &stats);
    CHECK(c.y == 0, "the reported box, pixel (25, 12), seed 68: no path gets out (green " +
                        std::to_string((double)c.y) + ")");
    CHECK(PixelsThatSeeOut(&scene, 68) == 0, "... and no pixel of its 48 x 48 image");
}

// Boxes of every claimed length, turned three ways each, with diffuse walls (path tracing) and
// mirror walls (the ray chain), a glass ball inside.
static void TestTurnedBoxes() {
    const double lengths[] = {10, 1e2, 1e4, 1e8, 1e12};
    const double floatLengths[] = {10, 1e2, 1e3, 1e4};
    TestRng rng = {2026};
    for (int k = 0; k < (kDouble ? 5 : 4); k++) {
        double length = kDouble ? lengths[k] : floatLengths[k];
        int leaks = 0, pixels = 0;
        for (int turn = 0; turn < 3; turn++) {
            std::string words = RandomTurn(&rng);
            vec3 view = UnitDirection(Uniform(&rng), Uniform(&rng));
            for (bool mirror : {false, true}) {
                Scene scene = LeakScene(mirror, {0, 0, 0}, view, 16);
                CHECK(AddMeshBox(&scene, 4, 3, length, words), words);
                scene.spheres.push_back({{real(0.4), real(-0.3), real(0.2)}, real(0.5), 1});
                leaks += PixelsThatSeeOut(&scene, turn), pixels += 16 * 16;
            }
        }
        char what[160];
        snprintf(what, sizeof what,
                 "closed 4 x 3 x %g boxes, three turns, diffuse and mirror walls: %d of %d pixels "
                 "see out",
                 length, leaks, pixels);
        CHECK(leaks == 0, what);
    }
}

// The 10 x 3 x 4 box moved away from the origin along (1, -1, 1): the hit points' rounding grows
// with the distance, and the edges' margin with it. 48 x 48 with mirror walls at the farthest.
static void TestBoxesFarAway() {
    const double shifts[] = {1e3, 1e9, 1e12};
    const double floatShifts[] = {10, 1e2, 1e3};
    TestRng rng = {77};
    for (int k = 0; k < 3; k++) {
        double s = kDouble ? shifts[k] : floatShifts[k];
        int size = k == 2 ? 48 : 16, leaks = 0;
        for (int turn = 0; turn < 2; turn++) {
            char words[240];
            snprintf(words, sizeof words, "%s translate %.17g %.17g %.17g",
                     RandomTurn(&rng).c_str(), s, -s, s);
            Scene scene = LeakScene(k == 2, {(real)s, (real)-s, (real)s},
                                    UnitDirection(Uniform(&rng), Uniform(&rng)), size);
            CHECK(AddMeshBox(&scene, 10, 3, 4, words), words);
            leaks += PixelsThatSeeOut(&scene, turn);
        }
        char what[120];
        snprintf(what, sizeof what,
                 "a 10 x 3 x 4 box %g from the origin, turned: %d pixels see out", s, leaks);
        CHECK(leaks == 0, what);
    }
}

// Long prisms with an edge of the narrowest angle the margin is claimed for, and a wider one.
static void TestWedges() {
    double length = kDouble ? 1e6 : 1e3;
    TestRng rng = {16};
    for (double degrees : {16.0, 45.0}) {
        int leaks = 0;
        for (int turn = 0; turn < 3; turn++) {
            std::string words = RandomTurn(&rng);
            Scene scene =
                LeakScene(false, {0, 0, 0}, UnitDirection(Uniform(&rng), Uniform(&rng)), 16);
            CHECK(AddPrism(&scene, degrees, length, words), words);
            leaks += PixelsThatSeeOut(&scene, turn);
        }
        char what[120];
        snprintf(what, sizeof what, "a prism %g long with an edge of %g degrees: %d pixels see out",
                 length, degrees, leaks);
        CHECK(leaks == 0, what);
    }
}

void TestLeaks() {
    TestReportedLeak();
    TestTurnedBoxes();
    TestBoxesFarAway();
    TestWedges();
}
