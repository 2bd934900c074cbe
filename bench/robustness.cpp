// bench/robustness.cpp -- `rtbench robustness`: the measured tables of docs/bench/robustness.md.
//
// Where the claims of rt's robustness hold, in this build's precision: long triangles (closed
// boxes, big floors, slivers, axis-aligned and turned), the assignment scene at every scale and
// distance from the origin with each camera, and spheres and triangles of every size. Prints
// Markdown; the tests (tests/test_long_triangles.cpp, test_ranges.cpp) assert the documented
// parts of it.
#include "../app/app.h"
#include "../tests/robust_scenes.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <random>

static const bool kDouble = sizeof(real) == sizeof(double);
static const char *kPrecision = sizeof(real) == sizeof(double) ? "double" : "float";

// 2000 rays from random points inside the box (CountBoxLeaks): lost, mirror rays lost, mirror
// rays that meet the wall they left.
static std::string BoxCell(double length, bool turn, std::mt19937_64 *rng) {
    BoxLeaks leaks = CountBoxLeaks(length, turn, 2000, (*rng)());
    char cell[64];
    snprintf(cell, sizeof cell, "%d / %d / %d", leaks.escapes, leaks.mirrorEscapes, leaks.reHits);
    return cell;
}

// 2000 rays 25 degrees below the horizon from heights 1e-4..100 onto a floor: how many are lost.
static std::string FloorCell(double half, bool turn, std::mt19937_64 *rng) {
    std::uniform_real_distribution<double> u(0, 1);
    vec3 corners[4];
    Scene floor = FloorScene((real)half, turn, corners);
    double slope = std::sin(25 * 3.14159265358979 / 180),
           flat = std::cos(25 * 3.14159265358979 / 180);
    int lost = 0;
    for (double height : {1e-4, 1e-3, 1e-2, 1.0, 100.0}) {
        for (int i = 0; i < 400; i++) {
            double phi = 6.283185307179586 * u(*rng);
            vec3 o = {(real)(10 * u(*rng) - 5), (real)height, (real)(10 * u(*rng) - 5)};
            vec3 d = {(real)(flat * std::cos(phi)), (real)-slope, (real)(flat * std::sin(phi))};
            Ray ray = {Turn(o, turn), Turn(d, turn)};
            RayHit hit;
            lost += !FindNearestHit(&floor, kRobustMethods, &ray, 0, kInfinity, &hit);
        }
    }
    return std::to_string(lost);
}

// 1000 rays straight down at interior points of a needle (0,0,0) (L,0,0) (0,0,1) or a cap
// (0,0,0) (L,0,0) (L/2,0,1): how many miss.
static std::string SliverCell(double length, bool cap, bool turn, std::mt19937_64 *rng) {
    std::uniform_real_distribution<double> u(0, 1);
    vec3 apex = cap ? vec3{(real)(length / 2), 0, 1} : vec3{0, 0, 1};
    Scene s = WallScene();
    s.triangles = {{Turn({0, 0, 0}, turn), Turn({(real)length, 0, 0}, turn), Turn(apex, turn), 0}};
    int misses = 0;
    for (int i = 0; i < 1000; i++) {
        double a = 0.05 + 0.9 * u(*rng), b = (0.05 + 0.9 * u(*rng)) * (1 - a);
        vec3 q = {(real)(a * length + b * apex.x), 1, (real)(b * apex.z)};
        Ray ray = {Turn(q, turn), Turn({0, -1, 0}, turn)};
        RayHit hit;
        misses += !FindNearestHit(&s, kRobustMethods, &ray, 0, kInfinity, &hit);
    }
    return std::to_string(misses);
}

// A Markdown table's header: the first columns' names, then `unit value` for each value.
static void Header(const char *first, int firstColumns, const char *unit,
                   const std::vector<double> &values) {
    printf("| %s | ", first);
    for (double v : values)
        printf("%s %g | ", unit, v);
    printf("\n|");
    for (int k = 0; k < firstColumns; k++)
        printf(" --- |");
    for (size_t k = 0; k < values.size(); k++)
        printf(" ---: |");
    printf("\n");
}

// A table: one row per shape and orientation, one column per size.
static void Table(const char *title, const char *unit, const std::vector<double> &sizes,
                  const char *rowNames[2],
                  std::string (*cell)(double size, int row, bool turn, std::mt19937_64 *rng),
                  int rows, std::mt19937_64 *rng) {
    printf("%s, %s\n\n", title, kPrecision);
    Header("shape", 1, unit, sizes);
    for (int row = 0; row < rows; row++) {
        for (int turn = 0; turn < 2; turn++) {
            printf("| %s, %s |", rowNames[row], turn ? "turned" : "axis-aligned");
            for (double size : sizes)
                printf(" %s |", cell(size, row, turn, rng).c_str());
            printf("\n");
        }
    }
    printf("\n");
}

static std::string BoxTableCell(double size, int, bool turn, std::mt19937_64 *rng) {
    return BoxCell(size, turn, rng);
}
static std::string FloorTableCell(double size, int, bool turn, std::mt19937_64 *rng) {
    return FloorCell(size, turn, rng);
}
static std::string SliverTableCell(double size, int row, bool turn, std::mt19937_64 *rng) {
    return SliverCell(size, row == 1, turn, rng);
}

static void LongTriangles() {
    std::mt19937_64 rng(2026);
    const char *box[2] = {"box 4 x 3 x L", ""}, *floor[2] = {"floor", ""};
    const char *slivers[2] = {"needle", "cap"};
    Table("### Closed boxes: of 2000 rays from inside, lost / mirror rays lost / mirror rays that "
          "re-hit their wall",
          "L",
          kDouble ? std::vector<double>{1e2, 1e4, 1e6, 1e8, 1e10, 1e12, 1e15}
                  : std::vector<double>{1e2, 1e3, 3e3, 1e4, 1e5, 1e6},
          box, BoxTableCell, 1, &rng);
    Table("### Floors: of 2000 rays 25 degrees down from heights 1e-4..100, lost", "half-size",
          kDouble ? std::vector<double>{1e3, 1e6, 1e9, 1e12, 1e15}
                  : std::vector<double>{1e3, 1e4, 1e5, 1e6},
          floor, FloorTableCell, 1, &rng);
    Table("### Slivers: of 1000 rays down at interior points, lost", "aspect",
          kDouble ? std::vector<double>{1e4, 1e8, 1e12, 1e14}
                  : std::vector<double>{1e2, 1e4, 1e5, 1e6},
          slivers, SliverTableCell, 2, &rng);
}

// The share of pixels of the 64 x 64 assignment scene (scaled, moved, with glass or not) within
// 2/255 of the same scene at scale 1; -1 if the scene file was refused.
static double Alike(double scale, double shift, const char *camera, bool glass) {
    Image images[2];
    for (int k = 0; k < 2; k++) {
        Scene scene;
        std::string error;
        std::string text =
            k ? AssignmentText(scale, shift, camera, glass) : AssignmentText(1, 0, camera, glass);
        if (!ParseSceneText(text, "r.scene", &scene, &error))
            return -1;
        RenderSettings settings = {64, 64, 1, SAMPLES_GRID, 10, 1, kRobustMethods, nullptr,
                                   {}, {}, {}};
        RayStats stats = {};
        Render(&scene, &settings, &images[k], &stats);
    }
    long alike = 0;
    for (size_t p = 0; p < images[0].pixels.size(); p += 3) {
        int largest = 0;
        for (int c = 0; c < 3; c++)
            largest =
                std::max(largest, std::abs(images[0].pixels[p + c] - images[1].pixels[p + c]));
        alike += largest <= 2;
    }
    return (double)alike / (64 * 64);
}

static void ScaleRow(const char *label, const std::vector<double> &values, bool shift) {
    for (const char *camera : {"perspective", "screen", "lookat"}) {
        for (bool glass : {false, true}) {
            printf("| %s | %s%s |", label, camera, glass ? ", glass" : "");
            for (double v : values) {
                double share = shift ? Alike(1, v, camera, glass) : Alike(v, 0, camera, glass);
                if (share < 0)
                    printf(" refused |");
                else
                    printf(" %.4g%% |", 100 * share);
            }
            printf("\n");
        }
    }
}

static void Scales() {
    std::vector<double> scales =
        kDouble ? std::vector<double>{1e-300, 1e-200, 1e-100, 1e-30, 1e30, 1e100, 1e200, 1e300}
                : std::vector<double>{1e-37, 1e-30, 1e-20, 1e-10, 1e10, 1e20, 1e30, 1e36};
    std::vector<double> shifts = kDouble ? std::vector<double>{1e6, 1e10, 1e12, 1e13, 1e14, 1e15}
                                         : std::vector<double>{1e3, 1e4, 1e5, 1e6, 1e7};
    printf("### The assignment scene scaled, %s: pixels within 2/255 of scale 1\n\n", kPrecision);
    Header("build | camera", 2, "scale", scales);
    ScaleRow(kPrecision, scales, false);
    printf("\n### The assignment scene moved from the origin along (1, -1, 1), %s\n\n", kPrecision);
    Header("build | camera", 2, "moved", shifts);
    ScaleRow(kPrecision, shifts, true);
    printf("\n");
}

// Spheres and triangles of size s, seen from 10 s away: whether the hit is found and how far
// the hit point is from the surface, in units of s.
static void Sizes() {
    std::vector<double> sizes =
        kDouble ? std::vector<double>{1e-306, 1e-300, 1e-200, 1e-100, 1e100, 1e200, 1e300, 1e304}
                : std::vector<double>{1e-37, 1e-30, 1e-20, 1e20, 1e30, 1e36};
    printf("### Shapes of every size, %s: seen from 10 sizes away, 3 degrees off the centre\n\n",
           kPrecision);
    printf("| size | sphere hit | its distance from the surface / r | triangle hit | relative "
           "error of "
           "t |\n| ---: | --- | ---: | --- | ---: |\n");
    for (double size : sizes) {
        real r = (real)size, a = real(3 * 3.14159265358979 / 180);
        Sphere sphere = {{0, 0, 0}, r, 0};
        Ray ray = {{0, 0, 10 * r}, {std::sin(a), 0, -std::cos(a)}};
        RayHit hit;
        bool sphereHit = IntersectSphere(&sphere, &ray, 0, kInfinity, &hit);
        double surface = sphereHit ? std::fabs((double)SafeLength(hit.point) / size - 1) : 0;
        Triangle tri = {{-2 * r, -2 * r, 0}, {2 * r, -2 * r, 0}, {0, 2 * r, 0}, 0};
        bool triangleHit = IntersectTriangle(&tri, &ray, 0, kInfinity, &hit);
        double exact = 10 * size / std::cos((double)a);
        double error = triangleHit ? std::fabs((double)hit.t - exact) / exact : 0;
        printf("| %g | %s | %.2g | %s | %.2g |\n", size, sphereHit ? "yes" : "no", surface,
               triangleHit ? "yes" : "no", error);
    }
    printf("\n");
}

// ---- the leak detector's sweep: closed meshes seen from inside, every ray chain 100 long -----

// Pixels that see out of `turns` turned renders, 48 x 48, of the mesh `add` makes (diffuse walls
// under `shading path`, or mirror walls): "N of M", and where N > 0, per render: how many renders
// let any out, and the most one did.
static std::string LeakCell(bool mirror, vec3 eye, int turns, std::mt19937_64 *rng,
                            const std::function<bool(Scene *, const std::string &)> &add) {
    std::uniform_real_distribution<double> angle(0, 360), unit(0, 1);
    int leaks = 0, renders = 0, most = 0;
    for (int turn = 0; turn < turns; turn++) {
        std::string words = TurnWords(angle(*rng), angle(*rng), angle(*rng));
        vec3 view = UnitDirection((real)unit(*rng), (real)unit(*rng));
        Scene scene = LeakScene(mirror, eye, view, 48);
        if (!add(&scene, words))
            return "refused";
        int out = PixelsThatSeeOut(&scene, turn);
        leaks += out, renders += out > 0, most = std::max(most, out);
    }
    std::string cell = std::to_string(leaks) + " of " + std::to_string(turns * 48 * 48);
    if (leaks > 0)
        cell += " (" + std::to_string(renders) + " of " + std::to_string(turns) +
                " renders, at most " + std::to_string(most) + " in one)";
    return cell;
}

static void LeakRows(const char *name, const std::vector<double> &values, int turns,
                     std::mt19937_64 *rng,
                     const std::function<bool(Scene *, double, const std::string &)> &add,
                     const std::function<vec3(double)> &eye) {
    for (bool mirror : {false, true}) {
        printf("| %s, %s walls |", name, mirror ? "mirror" : "diffuse");
        for (double v : values) {
            auto addThis = [&](Scene *scene, const std::string &words) {
                return add(scene, v, words);
            };
            printf(" %s |", LeakCell(mirror, eye(v), turns, rng, addThis).c_str());
        }
        printf("\n");
    }
}

static void Leaks() {
    std::mt19937_64 rng(68);
    const int turns = 10;
    auto origin = [](double) { return vec3{0, 0, 0}; };
    printf("### Closed meshes seen from inside: pixels that see out, %s (%d turns, 48 x 48, "
           "chains of 100 rays)\n\n",
           kPrecision, turns);
    std::vector<double> lengths = kDouble ? std::vector<double>{10, 1e4, 1e8, 1e12, 1e13, 1e14}
                                          : std::vector<double>{10, 1e2, 1e3, 1e4, 1e5, 1e6};
    Header("box 4 x 3 x L", 1, "L", lengths);
    LeakRows(
        "box", lengths, turns, &rng,
        [](Scene *s, double l, const std::string &w) { return AddMeshBox(s, 4, 3, l, w); }, origin);
    std::vector<double> shifts = kDouble ? std::vector<double>{1e3, 1e9, 1e12, 1e13}
                                         : std::vector<double>{10, 1e3, 1e4, 1e5};
    printf("\n");
    Header("box 10 x 3 x 4, moved by s along (1, -1, 1)", 1, "s", shifts);
    LeakRows(
        "box", shifts, turns, &rng,
        [](Scene *s, double v, const std::string &w) {
            char move[120];
            snprintf(move, sizeof move, " translate %.17g %.17g %.17g", v, -v, v);
            return AddMeshBox(s, 10, 3, 4, w + move);
        },
        [](double v) {
            return vec3{(real)v, (real)-v, (real)v};
        });
    // (The prisms' sharp edges let a few rays out in some renders and none in others: ten
    // times as many renders, so that a row says how often)
    std::vector<double> angles = {5, 10, 16, 45};
    printf("\n");
    Header(kDouble ? "prism 1e6 long, an edge of A degrees (100 turns)"
                   : "prism 1e3 long, an edge of A degrees (100 turns)",
           1, "A", angles);
    LeakRows(
        "prism", angles, 10 * turns, &rng,
        [](Scene *s, double a, const std::string &w) {
            return AddPrism(s, a, kDouble ? 1e6 : 1e3, w);
        },
        origin);
    printf("\n");
}

int RobustnessTables() {
    LongTriangles();
    Leaks();
    Scales();
    Sizes();
    return 0;
}
