// tests/test_leaks.cpp -- the leak detector: no ray gets out of a closed mesh.
//
// A camera inside a closed mesh whose walls let no light in (white diffuse walls and no lamp under
// `shading path`, or perfect mirrors under `shading floor`) and a green background: every pixel
// must be black, and a pixel with any green in it is a ray that got out (LeakScene). Boxes
// 4 x 3 x L (the robustness tables' lengths), 10 x 3 x 4 boxes far from the origin and long
// prisms with a sharp edge, turned by the `mesh` statement's own rotate words at random angles,
// seen from near their middle in a random direction, a chain of 100 rays a pixel (at reflectance
// 1 roulette ends no path). A glass ball inside sends refracted rays to the walls too. And smooth
// meshes, whose rays start where their curved surface would be, near and touching the walls.
// docs/robustness.md gives the ranges, and `make bench` a larger sweep with rates.
#include "robust_scenes.h"
#include "test.h"

#include <string>

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

// The cube [-1, 1]^3 as OBJ quads wound outward (`smooth` gives it normals), and with normals of
// its own that lean every way, from the test's generator.
static const char *kCube = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\n"
                           "v 1 1 1\nv -1 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\n"
                           "f 1 5 8 4\nf 2 3 7 6\n";
static std::string RandomNormalsCube(TestRng *rng) {
    std::string text = kCube;
    text = text.substr(0, text.find("f "));
    char line[128];
    for (int k = 0; k < 8; k++) {
        vec3 n = UnitDirection(Uniform(rng), Uniform(rng));
        snprintf(line, sizeof line, "vn %.9g %.9g %.9g\n", (double)n.x, (double)n.y, (double)n.z);
        text += line;
    }
    return text + "f 1//1 4//4 3//3 2//2\nf 5//5 6//6 7//7 8//8\nf 1//1 2//2 6//6 5//5\n"
                  "f 4//4 8//8 7//7 3//3\nf 1//1 5//5 8//8 4//4\nf 2//2 3//3 7//7 6//6\n";
}

// Smooth meshes inside the 4 x 3 x 4 box, near and touching its walls, turned with it: an
// icosphere of 80 faces with the true sphere's normals resting on the floor, a `smooth` cube
// 0.05 below the ceiling, a cube with random normals against a side wall, and a `smooth` cube
// with a face wound the other way in a corner. A ray leaving a smooth mesh starts where the
// curved surface would be, up to a quarter of the cube's side off its faces: never past a wall.
static void TestSmoothMeshesAtWalls() {
    std::string dir = MakeTestDir("leaks");
    if (dir.empty())
        return;
    std::string flipped = kCube;
    flipped.replace(flipped.find("f 5 6 7 8"), 9, "f 8 7 6 5");
    TestRng rng = {4404};
    int leaks = 0, pixels = 0;
    for (int turn = 0; turn < 3; turn++) {
        std::string words = RandomTurn(&rng), error;
        vec3 view = UnitDirection(Uniform(&rng), Uniform(&rng));
        std::string random = RandomNormalsCube(&rng);
        for (bool mirror : {false, true}) {
            Scene scene = LeakScene(mirror, {0, 0, 0}, view, 32);
            bool made = AddMeshBox(&scene, 4, 3, 4, words) &&
                        AddMeshText(&scene, dir, IcosphereObj(1),
                                    "scale 0.6 translate -1 -0.9 0.5 " + words, &error) &&
                        AddMeshText(&scene, dir, kCube,
                                    "smooth scale 0.5 translate 1 0.95 -0.5 " + words, &error) &&
                        AddMeshText(&scene, dir, random, "scale 0.5 translate 1.5 -0.5 1 " + words,
                                    &error) &&
                        AddMeshText(&scene, dir, flipped,
                                    "smooth scale 0.4 translate -1.6 1.1 -1.6 " + words, &error);
            CHECK(made, "the box and the smooth meshes in it: " + error);
            leaks += made ? PixelsThatSeeOut(&scene, turn) : 0, pixels += 32 * 32;
        }
    }
    char what[200];
    snprintf(what, sizeof what,
             "smooth meshes touching and near the walls of a closed box, three turns, diffuse and "
             "mirror walls: %d of %d pixels see out",
             leaks, pixels);
    CHECK(leaks == 0, what);
    RemoveTestDir(dir);
}

void TestLeaks() {
    TestReportedLeak();
    TestTurnedBoxes();
    TestBoxesFarAway();
    TestWedges();
    TestSmoothMeshesAtWalls();
}
