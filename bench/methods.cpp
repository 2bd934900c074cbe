// bench/methods.cpp -- `rtbench methods`: what each numerical method costs and what it buys.
//
// For every sphere, triangle and self-hit method, in this build's precision: the time of one
// intersection test (a fixed set of rays, hits and misses timed apart), the hard-case rows it
// passes, and the pixels of the test scene that differ from the robust image (by more than
// 2/255) at scales 1e-4, 1, 1e4 and 1e6 and moved far from the origin, where a method's failures
// show as acne, lost shadows and cracks (and, at any scale, as ties: a ray exactly through a
// shared edge may take either triangle, both right). Prints Markdown.
#include "../app/app.h"
#include "../fast/fast.h"
#include "../tests/hard_cases.h"
#include "../tests/robust_scenes.h"
#include "svg.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

static const bool kDouble = sizeof(real) == sizeof(double);

// Nanoseconds per call of test(ray k) over the rays, in 5 rounds of at least 20 ms each.
template <typename Test> static Spread NanosecondsPerCall(const std::vector<Ray> &rays, Test test) {
    std::vector<double> rounds;
    for (int round = 0; round < 5; round++) {
        long calls = 0;
        int sink = 0;
        auto start = std::chrono::steady_clock::now();
        double seconds = 0;
        while (seconds < 0.02) {
            for (const Ray &ray : rays)
                sink += test(&ray);
            calls += (long)rays.size();
            seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        rounds.push_back(seconds * 1e9 / calls + sink * 1e-300);
    }
    return SpreadOf(rounds);
}

// Rays from around the origin toward random points of a box that holds the shape: about half hit.
static std::vector<Ray> RaySet(uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.2, 1.2);
    std::vector<Ray> rays;
    for (int k = 0; k < 4096; k++) {
        vec3 o = {(real)(0.1 * u(rng)), (real)(0.1 * u(rng)), (real)(0.1 * u(rng))};
        vec3 target = {(real)u(rng), (real)u(rng), -5};
        rays.push_back({o, target - o});
    }
    return rays;
}

// Splits the ray set by whether the robust routine hits, and times `routine` on each part.
template <typename Routine, typename Robust>
static void TimeRoutine(const char *name, Routine routine, Robust robust) {
    std::vector<Ray> all = RaySet(7), hits, misses;
    RayHit hit;
    for (const Ray &ray : all)
        (robust(&ray, &hit) ? hits : misses).push_back(ray);
    Spread h = NanosecondsPerCall(hits, [&](const Ray *r) { return (int)routine(r, &hit); });
    Spread m = NanosecondsPerCall(misses, [&](const Ray *r) { return (int)routine(r, &hit); });
    printf("| %s | %s | %s |", name, SpreadText(h, "%.1f").c_str(), SpreadText(m, "%.1f").c_str());
}

static Image RenderWith(const Scene *scene, Methods methods) {
    RenderSettings settings = {128, 128, 1, SAMPLES_GRID, scene->depth, 2, methods, nullptr,
                               {},  {},  {}};
    Image image;
    RayStats stats = {};
    Render(scene, &settings, &image, &stats);
    return image;
}

// The pixels (as indices y * 128 + x) where two images differ by more than 2/255.
static std::vector<int> PixelsOff(const Image &a, const Image &b) {
    std::vector<int> off;
    for (size_t p = 0; p < a.pixels.size(); p += 3) {
        int largest = 0;
        for (int c = 0; c < 3; c++)
            largest = std::max(largest, std::abs(a.pixels[p + c] - b.pixels[p + c]));
        if (largest > 2)
            off.push_back((int)(p / 3));
    }
    return off;
}

// What a pixel off the robust image is, from the trees of the pixel's centre ray under both
// methods, compared node by node to the first difference: a shadow ray blocked only under the
// method (acne), or only under the robust one (a lost shadow); a ray that meets a different
// surface elsewhere (a crack, or a false hit); the same point on a different triangle (a tie: a
// ray exactly through a shared edge, either answer right); or no difference in the trees
// (another: a different shading term, such as Schlick's). Counted over all placements.
struct Kinds {
    long acne, lostShadows, wrongSurface, ties, other;
};

static std::vector<RayNode> CentreTree(const Scene *scene, Methods methods, int i, int j) {
    RenderSettings settings = {128, 128, 1, SAMPLES_GRID, scene->depth, 1, methods, nullptr,
                               {},  {},  {}};
    PlanRender(scene, &settings);
    std::vector<RayNode> tree;
    TraceLog log = {RayStats{}, &tree, -1, 0};
    Ray ray;
    GetCameraRay(&settings.camera, 128, 128, SamplePosition(i, j, 0, 1), &ray);
    TraceRay(scene, &settings, RAY_PRIMARY, &ray, &kNoSelfHit, RayChain{1, 1}, &log);
    return tree;
}

static void Classify(const Scene *scene, Methods methods, int i, int j, Kinds *kinds) {
    std::vector<RayNode> a = CentreTree(scene, kRobustMethods, i, j);
    std::vector<RayNode> b = CentreTree(scene, methods, i, j);
    for (size_t k = 0; k < a.size() && k < b.size() && a[k].kind == b[k].kind; k++) {
        const RayNode &x = a[k], &y = b[k];
        if (x.kind == RAY_SHADOW && x.found != y.found) {
            (y.found ? kinds->acne : kinds->lostShadows)++;
            return;
        }
        if (x.kind == RAY_SHADOW ||
            (x.found == y.found &&
             (!x.found || (x.record.shape == y.record.shape && x.record.index == y.record.index))))
            continue;
        vec3 gap = x.record.point - y.record.point;
        bool samePoint = x.found && y.found &&
                         SafeLength(gap) <= real(1e-6) * (SafeLength(x.record.point) + 1e-30);
        (samePoint ? kinds->ties : kinds->wrongSurface)++;
        return;
    }
    kinds->other++;
}

// The artefact columns: pixels off the robust image of the same scene, per placement.
// The test scene twice: committed as ./ray commits it (the accelerator serves the robust sphere
// and triangle tests; the handouts' run the plain loop), and with no accelerator (every method in
// the same plain loop: --layout plain), where their times compare fairly.
struct TestScenes {
    const Scene *committed, *plain;
};

// One point of the plot: a method's render time and the pixels it gets wrong, over all scales.
struct PlotPoint {
    std::string name;
    Spread milliseconds;
    long pixelsOff;
};

// The render time of the 128 x 128 test scene with `methods`, one thread, 3 renders (ms).
static Spread RenderMilliseconds(const Scene &test, Methods methods) {
    std::vector<double> times(3);
    for (double &t : times) {
        RenderSettings settings = {128,     128,     1,  SAMPLES_GRID, test.depth, 1,
                                   methods, nullptr, {}, {},           {}};
        Image image;
        RayStats stats = {};
        auto start = std::chrono::steady_clock::now();
        Render(&test, &settings, &image, &stats);
        t = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return SpreadOf(times);
}

// The render-time cells (as ./ray runs it, and in the plain loop) and the artefact cells: pixels
// off the robust image of the same scene, per placement. Adds the method's point to *plot, at its
// time in the plain loop.
static void ArtefactCells(const TestScenes *scenes, Methods methods, const char *name,
                          std::vector<PlotPoint> *plot) {
    const Scene &test = *scenes->plain;
    const real placements[][2] = {{real(1e-4), 0},
                                  {1, 0},
                                  {real(1e4), 0},
                                  {real(1e6), 0},
                                  {1, kDouble ? real(1e9) : real(1e3)}};
    Spread fast = RenderMilliseconds(*scenes->committed, methods);
    Spread ms = RenderMilliseconds(test, methods);
    printf(" %s | %s |", SpreadText(fast, "%.0f").c_str(), SpreadText(ms, "%.0f").c_str());
    long total = 0;
    Kinds kinds = {0, 0, 0, 0, 0};
    for (const auto &p : placements) {
        Scene scene = TransformedScene(test, p[0], {p[1], -p[1], p[1]});
        std::vector<int> off =
            PixelsOff(RenderWith(&scene, kRobustMethods), RenderWith(&scene, methods));
        printf(" %zu |", off.size());
        total += (long)off.size();
        for (int pixel : off)
            Classify(&scene, methods, pixel % 128, pixel / 128, &kinds);
    }
    printf(" %ld / %ld / %ld / %ld / %ld |", kinds.acne, kinds.lostShadows, kinds.wrongSurface,
           kinds.ties, kinds.other);
    plot->push_back({name, ms, total});
}

// The points (median time, a whisker from min to max) and their names.
static std::string PlotMarks(const std::vector<PlotPoint> &plot, const SvgAxis &x, const SvgAxis &y,
                             SvgLabels *labels) {
    std::vector<SvgMark> names;
    std::string marks;
    for (const PlotPoint &p : plot) {
        double px = AxisPixel(x, p.milliseconds.median), py = AxisPixel(y, 1.0 + p.pixelsOff);
        double lo = AxisPixel(x, p.milliseconds.min), hi = AxisPixel(x, p.milliseconds.max);
        const char *fill = p.name.find("handout") != std::string::npos ? "crimson" : "steelblue";
        marks += Format("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s'/>\n"
                        "<circle cx='%.1f' cy='%.1f' r='4' fill='%s'/>\n",
                        lo, py, hi, py, fill, px, py, fill);
        AddMarker(labels, px, py, 4);
        AddLine(labels, lo, py, hi, py, true);
        names.push_back({px, py, 4, p.name, "black", 12});
    }
    return marks + PlaceLabels(labels, names);
}

// The plot: pixels off (all placements together, on a log scale from 1) against render time
// (median, whiskers from min to max), one labelled point per method, as an SVG file.
static void WritePlot(const std::vector<PlotPoint> &plot, const std::string &path) {
    FILE *svg = fopen(path.c_str(), "w");
    if (!svg)
        return;
    double fast = 1e30, slow = 0, most = 1;
    for (const PlotPoint &p : plot)
        fast = std::min(fast, p.milliseconds.min), slow = std::max(slow, p.milliseconds.max),
        most = std::max(most, 1.0 + p.pixelsOff);
    SvgAxis x = FitAxis(fast, slow, false, 80, 780), y = FitAxis(1, most, true, 330, 20);
    SvgLabels labels = {FrameBox(x, y), {}, {}, {}, {}, {}, {}};
    std::string marks = PlotMarks(plot, x, y, &labels);
    int height = 404 + 16 * (int)labels.legend.size();
    std::string xTitle = Format("render time of the test scene in the plain loop, ms (%s, one "
                                "thread; median, line from min to max of 3)",
                                kDouble ? "double" : "float");
    fprintf(svg,
            "<svg xmlns='http://www.w3.org/2000/svg' width='800' height='%d' "
            "font-family='sans-serif' font-size='12'>\n<rect width='800' height='%d' "
            "fill='white'/>\n",
            height, height);
    fprintf(
        svg, "%s%s",
        SvgFrame(x, y, xTitle.c_str(), "1 + pixels off the robust image, all scales (log)").c_str(),
        marks.c_str());
    fprintf(svg,
            "<circle cx='84' cy='384' r='4' fill='crimson'/><text x='92' y='388'>a handout's "
            "method</text>\n<circle cx='234' cy='384' r='4' fill='steelblue'/><text x='242' "
            "y='388'>rt's methods</text>\n%s</svg>\n",
            SvgLegend(labels, 80, 406, 16).c_str());
    fclose(svg);
}

static int HardCasesPassed(SphereRoutine sphere, TriangleRoutine triangle, int *rows) {
    std::vector<HardCaseResult> results;
    RunHardCases(sphere, triangle, &results);
    int passed = 0;
    for (const HardCaseResult &r : results)
        passed += r.passed;
    *rows = (int)results.size();
    return passed;
}

// The sphere rows: each method's time, hard cases (with watertight triangles) and artefacts.
static void SphereRows(const TestScenes *test, std::vector<PlotPoint> *plot) {
    Sphere sphere = {{0, 0, -5}, 1, 0};
    auto stable = [&](const Ray *r, RayHit *h) {
        return IntersectSphere(&sphere, r, 0, kInfinity, h);
    };
    struct {
        const char *name;
        SphereRoutine routine;
        SphereMethod method;
    } rows[] = {{"sphere: stable", IntersectSphere, SPHERE_STABLE},
                {"sphere: textbook (handout)", IntersectSphereTextbook, SPHERE_TEXTBOOK}};
    for (const auto &row : rows) {
        TimeRoutine(
            row.name,
            [&](const Ray *r, RayHit *h) { return row.routine(&sphere, r, 0, kInfinity, h); },
            stable);
        int cases, passed = HardCasesPassed(row.routine, IntersectTriangle, &cases);
        printf(" %d of %d |", passed, cases);
        Methods m = kRobustMethods;
        m.sphere = row.method;
        ArtefactCells(test, m, row.name, plot);
        printf("\n");
    }
}

// The triangle rows, likewise (hard cases with the stable sphere).
static void TriangleRows(const TestScenes *test, std::vector<PlotPoint> *plot) {
    Triangle tri = {{-1, -1, -5}, {1, -1, -5}, {0, 1, -5}, 0};
    auto watertight = [&](const Ray *r, RayHit *h) {
        return IntersectTriangle(&tri, r, 0, kInfinity, h);
    };
    struct {
        const char *name;
        TriangleRoutine routine;
        TriangleMethod method;
    } rows[] = {{"triangle: watertight", IntersectTriangle, TRIANGLE_WATERTIGHT},
                {"triangle: Cramer (handout)", IntersectTriangleCramer, TRIANGLE_CRAMER},
                {"triangle: plane (2nd handout)", IntersectTrianglePlane, TRIANGLE_PLANE}};
    for (const auto &row : rows) {
        TimeRoutine(
            row.name,
            [&](const Ray *r, RayHit *h) { return row.routine(&tri, r, 0, kInfinity, h); },
            watertight);
        int cases, passed = HardCasesPassed(IntersectSphere, row.routine, &cases);
        printf(" %d of %d |", passed, cases);
        Methods m = kRobustMethods;
        m.triangle = row.method;
        ArtefactCells(test, m, row.name, plot);
        printf("\n");
    }
}

// Two renders side by side, a white gap between: what the robust offset draws and what a fixed
// epsilon draws, the test scene at `scale`, 256 x 256 each, written to path.
static void EpsilonPicture(const Scene &test, real scale, const std::string &path) {
    Scene scene = TransformedScene(test, scale, {0, 0, 0});
    Methods epsilon = kRobustMethods;
    epsilon.selfHit = SELF_HIT_EPSILON;
    Image sides[2];
    for (int k = 0; k < 2; k++) {
        RenderSettings settings = {
            256, 256, 1, SAMPLES_GRID, scene.depth, 2, k ? epsilon : kRobustMethods, nullptr,
            {},  {},  {}};
        RayStats stats = {};
        Render(&scene, &settings, &sides[k], &stats);
    }
    Image both = {2 * 256 + 4, 256, {}};
    for (int y = 0; y < 256; y++) {
        const uint8_t *left = &sides[0].pixels[3 * 256 * y], *right = &sides[1].pixels[3 * 256 * y];
        both.pixels.insert(both.pixels.end(), left, left + 3 * 256);
        both.pixels.insert(both.pixels.end(), 12, 255);
        both.pixels.insert(both.pixels.end(), right, right + 3 * 256);
    }
    std::string error;
    if (!WriteImage(path.c_str(), &both, &error))
        fprintf(stderr, "bench: %s\n", error.c_str());
}

// The table, and with a folder, the pictures of what a fixed epsilon does at the wrong scale:
// contact shadows lost at scale 1e-4 (double), acne at 1e4 (float).
int MethodsTable(const char *folder) {
    if (folder) {
        Scene test;
        BuildTestScene(&test);
        EpsilonPicture(test, kDouble ? real(1e-4) : real(1e4),
                       std::string(folder) +
                           (kDouble ? "/epsilon_at_1e-4.png" : "/epsilon_at_1e4_float.png"));
    }
    printf("### What each method costs and buys, %s\n\nTimes are median (min-max): ns of 5 rounds "
           "of at least 20 ms, render ms of 3 renders (128 x 128, one thread), as ./ray runs the "
           "method and in the plain loop (--layout plain), where every method runs alike.\n\n",
           kDouble ? "double" : "float");
    printf("| method | ns, hit | ns, miss | hard cases | render ms | render ms, plain loop | off "
           "at 1e-4 | off at 1 | off at 1e4 | off at 1e6 | off far away | acne / lost shadows / "
           "wrong surface / ties / other |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: "
           "| ---: | ---: | ---: | ---: |\n");
    Scene plain, committed;
    BuildTestScene(&plain);
    committed = plain;
    SceneLayout layout;
    CommitScene(&committed, LAYOUT_AUTO, 1, &layout);
    TestScenes scenes = {&committed, &plain};
    const TestScenes *test = &scenes;
    std::vector<PlotPoint> plot;
    SphereRows(test, &plot);
    TriangleRows(test, &plot);
    const char *selfHits[] = {"self-hit: bound", "self-hit: epsilon 1e-4 (a usual student fix)",
                              "self-hit: skip (2nd handout)"};
    for (int k = 0; k < 3; k++) {
        printf("| %s | | | |", selfHits[k]);
        Methods m = kRobustMethods;
        m.selfHit = (SelfHitMethod)k;
        ArtefactCells(test, m, selfHits[k], &plot);
        printf("\n");
    }
    printf("| the whole handout set | | | |");
    ArtefactCells(test, kHandoutMethods, "the whole handout set", &plot);
    printf("\n\n");
    if (folder)
        WritePlot(plot, std::string(folder) + (kDouble ? "/methods.svg" : "/methods_float.svg"));
    return 0;
}
