// bench/bench.cpp -- what accuracy costs in time (`make bench`).
//
//   bench rows DIR      renders every row this build can (double: references, anti-aliasing,
//                       triangle and sphere methods, depth; both builds: precision) and prints
//                       one CSV line per row; references are DIR/ref_SCENE.png, made by the
//                       double build and read by the float build
//   bench report DIR    reads DIR/results.csv, writes DIR/results.md and DIR/accuracy_vs_time.svg
//   bench raw PNG RGB   the pixels of a PNG as a raw RGB file
//   bench pngfloor RGB PNG   writes the raw 512 x 512 RGB file as a PNG, nothing else: the floor
//                       for the whole-process time of `ray`
//   bench robustness    prints the measured tables of docs/bench/robustness.md (robustness.cpp)
//   bench methods [DIR] what each numerical method costs and buys (methods.cpp); with DIR, also
//                       the pictures of a fixed epsilon at the wrong scale
//   bench layout DIR    render time against mesh size, list against BVH (layout.cpp):
//                       DIR/layout.md and DIR/layout.svg
//   bench path DIR      a path tracer's error against time, per method (path.cpp): DIR/path.md
//                       (path_float.md from the float build), DIR/path_*.svg
//   bench time PROGRAM ARGS...   runs PROGRAM once (its standard output thrown away, its
//                       standard error passed on) and prints its whole-process wall time in ms:
//                       from fork to the end of waitpid, so the clock includes starting and
//                       loading the program and nothing of the shell
//   bench timemem PROGRAM ARGS...   the same, and the program's peak resident memory in MB
//
// Every time is the median of at least kRuns renders in this process, and of as many as fit in
// kMinSeconds (render only, all threads), with the fastest and the slowest of them beside it
// (the CSV's last columns, seconds_min and seconds_max); errors are against a converged
// reference: double, 256 samples per pixel on a grid.
#include "../app/app.h"
#include "../fast/fast.h"
#include "../ray.h"
#include "../tests/hard_cases.h"
#include "svg.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

static const int kRuns = 5;
static const double kMinSeconds = 1;
static const int kReferenceSpp = 256;
static const char *kPrecision = sizeof(real) == sizeof(double) ? "double" : "float";

struct BenchScene {
    const char *name;
    int size; // the test scene's 139 triangles make it ~10x slower: it runs at 256 x 256
    void (*build)(Scene *);
};
static const BenchScene kScenes[] = {{"assignment", 512, BuildDefaultScene},
                                     {"test", 256, BuildTestScene}};

static RenderSettings Settings(const BenchScene &b, int spp, SampleMethod sampling) {
    unsigned hardware = std::thread::hardware_concurrency();
    RenderSettings s = {b.size,         b.size,  spp, sampling, 10, hardware ? (int)hardware : 1,
                        kRobustMethods, nullptr, {},  {},       {}};
    return s;
}

// Renders at least kRuns times and for at least kMinSeconds (a 20 ms render needs more runs for
// a steady median); returns the seconds' median, min and max, the last image and its rays.
static Spread TimeRender(const Scene *scene, const RenderSettings *s, Image *image,
                         uint64_t *rays) {
    std::vector<double> times;
    double total = 0;
    while ((int)times.size() < kRuns || total < kMinSeconds) {
        RayStats stats = {};
        auto start = std::chrono::steady_clock::now();
        Render(scene, s, image, &stats);
        times.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        total += times.back();
        *rays = stats.primary + stats.shadow + stats.reflection + stats.refraction;
    }
    return SpreadOf(times);
}

// RMSE and PSNR over channels, and the share of pixels off by more than 1/255 and 8/255.
static void ErrorOf(const Image *image, const Image *reference, double *rmse, double *psnr,
                    double *off1, double *off8) {
    ImageDifference d1, d8;
    Image heat;
    CompareImages(image, reference, 1, &d1, &heat);
    CompareImages(image, reference, 8, &d8, &heat);
    double pixels = (double)image->width * image->height;
    *rmse = d1.rmse;
    *psnr = d1.psnr;
    *off1 = d1.pixelsOver / pixels;
    *off8 = d8.pixelsOver / pixels;
}

// A heat map of |image - reference| scaled so that 32/255 is white: small errors stay visible.
static void WriteHeatMap(const char *path, const Image *image, const Image *reference) {
    Image heat = *image;
    for (size_t k = 0; k + 2 < heat.pixels.size(); k += 3) {
        int largest = 0;
        for (int c = 0; c < 3; c++)
            largest = std::max(largest, std::abs(image->pixels[k + c] - reference->pixels[k + c]));
        color h = HeatColor(std::min(real(1), real(largest) / 32));
        heat.pixels[k] = ToByte(h.x), heat.pixels[k + 1] = ToByte(h.y),
        heat.pixels[k + 2] = ToByte(h.z);
    }
    std::string error;
    WriteImage(path, &heat, &error);
}

static void PrintRow(const BenchScene &b, const char *knob, const std::string &setting, int spp,
                     const Spread &seconds, uint64_t rays, const Image *image,
                     const Image *against) {
    double rmse, psnr, off1, off8;
    ErrorOf(image, against, &rmse, &psnr, &off1, &off8);
    printf("%s,%s,%s,%d,%.5f,%llu,%.6f,%.3f,%.6f,%.6f,%.5f,%.5f\n", b.name, knob, setting.c_str(),
           spp, seconds.median, (unsigned long long)rays, rmse, psnr, off1, off8, seconds.min,
           seconds.max);
    fflush(stdout);
    fprintf(stderr, "bench: %-10s %-10s %-28s %4d spp %s s  rmse %.4f\n", b.name, knob,
            setting.c_str(), spp, SpreadText(seconds, "%.3f").c_str(), rmse);
}

// One row: render, time, compare with the reference, print the CSV line and a progress line.
// With `base` (the double, robust, 1-spp image), a second row `difference` compares with it:
// what this knob alone changes, apart from the aliasing every 1-spp image has.
static void Row(const std::string &dir, const BenchScene &b, const Scene *scene, const char *knob,
                const std::string &setting, const RenderSettings *s, const Image *reference,
                const char *heatMap, const Image *base = nullptr) {
    Image image;
    uint64_t rays = 0;
    Spread seconds = TimeRender(scene, s, &image, &rays);
    PrintRow(b, knob, setting, s->samplesPerPixel, seconds, rays, &image, reference);
    if (base)
        PrintRow(b, "difference", setting, s->samplesPerPixel, seconds, rays, &image, base);
    if (heatMap)
        WriteHeatMap((dir + "/" + heatMap).c_str(), &image, base ? base : reference);
}

// The double build's robust 1-spp image, which the float build and the other methods are
// compared with (written by the double build, read by the float build).
static bool BaseImage(const std::string &dir, const BenchScene &b, const Scene *scene,
                      Image *base) {
    std::string path = dir + "/base_" + b.name + ".png", error;
    if (sizeof(real) != sizeof(double))
        return ReadImage(path.c_str(), base, &error);
    RenderSettings s = Settings(b, 1, SAMPLES_GRID);
    RayStats stats = {};
    Render(scene, &s, base, &stats);
    return WriteImage(path.c_str(), base, &error);
}

static bool Reference(const std::string &dir, const BenchScene &b, const Scene *scene,
                      Image *reference) {
    std::string path = dir + "/ref_" + b.name + ".png", error;
    if (sizeof(real) != sizeof(double)) // the float build reads the double build's reference
        return ReadImage(path.c_str(), reference, &error);
    RenderSettings s = Settings(b, kReferenceSpp, SAMPLES_GRID);
    RayStats stats = {};
    fprintf(stderr, "bench: %-10s reference, %d spp grid, double...\n", b.name, kReferenceSpp);
    Render(scene, &s, reference, &stats);
    return WriteImage(path.c_str(), reference, &error);
}

static void SceneRows(const std::string &dir, const BenchScene &b) {
    Scene scene;
    b.build(&scene);
    SceneLayout layout;
    CommitScene(&scene, LAYOUT_AUTO, 1, &layout); // as ./ray commits it: every time the program's
    Image reference;
    if (!Reference(dir, b, &scene, &reference)) {
        fprintf(stderr, "bench: no reference image for %s in %s\n", b.name, dir.c_str());
        return;
    }
    Image base;
    if (!BaseImage(dir, b, &scene, &base)) {
        fprintf(stderr, "bench: no 1-spp double image for %s in %s\n", b.name, dir.c_str());
        return;
    }
    bool isFloat = sizeof(real) != sizeof(double);
    for (int spp : {1, 16}) { // precision: both builds; float is also compared with double
        RenderSettings s = Settings(b, spp, SAMPLES_GRID);
        std::string heat = b.name + std::string("_float_vs_double.png");
        bool compare = isFloat && spp == 1;
        Row(dir, b, &scene, "precision", kPrecision, &s, &reference,
            compare ? heat.c_str() : nullptr, compare ? &base : nullptr);
    }
    if (isFloat)
        return;
    const char *names[] = {"grid", "jitter", "adaptive"};
    for (int spp : {4, 16, 64})
        for (int m = 0; m < 3; m++) {
            RenderSettings s = Settings(b, spp, (SampleMethod)m);
            std::string heat = b.name + std::string("_") + names[m] + "16.png";
            Row(dir, b, &scene, "aa", names[m], &s, &reference, spp == 16 ? heat.c_str() : nullptr);
        }
    // The methods are compared in the same plain loop (--layout plain): the accelerator serves the
    // robust tests only, and with it the comparison would be of loops, not of methods
    Scene plain = scene;
    plain.accelerator = nullptr;
    RenderSettings s = Settings(b, 1, SAMPLES_GRID);
    s.methods.triangle = TRIANGLE_CRAMER;
    Row(dir, b, &plain, "triangle", "cramer", &s, &reference, nullptr, &base);
    s = Settings(b, 1, SAMPLES_GRID);
    Row(dir, b, &plain, "triangle", "watertight", &s, &reference, nullptr);
    s.methods.sphere = SPHERE_TEXTBOOK;
    std::string textbookHeat = b.name + std::string("_textbook_sphere.png");
    Row(dir, b, &plain, "sphere", "textbook", &s, &reference, textbookHeat.c_str(), &base);
    s = Settings(b, 1, SAMPLES_GRID);
    Row(dir, b, &plain, "sphere", "stable", &s, &reference, nullptr);
    for (int depth : {1, 2, 3, 5, 10}) {
        s = Settings(b, 1, SAMPLES_GRID);
        s.depth = depth;
        Row(dir, b, &scene, "depth", std::to_string(depth), &s, &reference, nullptr);
    }
}

// The hard-case suite with each pair of routines: its pass count goes in the `setting` column.
static void HardCaseRows() {
    struct {
        const char *name;
        SphereRoutine sphere;
        TriangleRoutine triangle;
    } pairs[] = {{"stable+watertight", IntersectSphere, IntersectTriangle},
                 {"stable+cramer", IntersectSphere, IntersectTriangleCramer},
                 {"textbook+watertight", IntersectSphereTextbook, IntersectTriangle},
                 {"textbook+cramer", IntersectSphereTextbook, IntersectTriangleCramer}};
    for (const auto &p : pairs) {
        std::vector<HardCaseResult> results;
        std::vector<double> times;
        for (int run = 0; run < kRuns; run++) {
            results.clear();
            auto start = std::chrono::steady_clock::now();
            RunHardCases(p.sphere, p.triangle, &results);
            times.push_back(
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
        Spread seconds = SpreadOf(times);
        int passed = 0;
        for (const HardCaseResult &r : results)
            passed += r.passed;
        printf("hard_cases,suite,%s %s %d/%d,0,%.5f,0,,,,,%.5f,%.5f\n", p.name, kPrecision, passed,
               (int)results.size(), seconds.median, seconds.min, seconds.max);
        fprintf(stderr, "bench: hard cases %-20s %-6s %d of %d rows pass\n", p.name, kPrecision,
                passed, (int)results.size());
    }
}

// The pixels of a PNG as a raw RGB file, for PngFloor.
static int RawPixels(const char *png, const char *rgb) {
    Image image;
    std::string error;
    FILE *out = nullptr;
    if (!ReadImage(png, &image, &error) || !(out = fopen(rgb, "wb")))
        return 2;
    bool ok = fwrite(image.pixels.data(), 1, image.pixels.size(), out) == image.pixels.size();
    return fclose(out) == 0 && ok ? 0 : 3;
}

static int PngFloor(const char *rgb, const char *png) {
    Image image = {512, 512, std::vector<uint8_t>(512 * 512 * 3)};
    FILE *in = fopen(rgb, "rb");
    if (!in || fread(image.pixels.data(), 1, image.pixels.size(), in) != image.pixels.size())
        return 2;
    fclose(in);
    std::string error;
    return WriteImage(png, &image, &error) ? 0 : 3;
}

static int TimeProcess(char **command, bool memory) {
    auto start = std::chrono::steady_clock::now();
    pid_t child = fork();
    if (child == 0) {
        int null = open("/dev/null", O_WRONLY);
        dup2(null, 1);
        execv(command[0], command);
        _exit(127);
    }
    int status = 0;
    struct rusage usage;
    if (child < 0 || wait4(child, &status, 0, &usage) != child)
        return 3;
    std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - start;
    if (memory) // the child's peak resident memory, in MB
        printf("%.3f %.1f\n", ms.count(), usage.ru_maxrss / 1024.0);
    else
        printf("%.3f\n", ms.count());
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : 1;
}

int ReportMain(const std::string &dir);                          // report.cpp
int RobustnessTables();                                          // robustness.cpp
int MethodsTable(const char *folder);                            // methods.cpp
int LayoutTable(const char *folder);                             // layout.cpp
int PathTable(const char *folder);                               // path.cpp
int NoiseMain(char **argv);                                      // peers.cpp
int TerminatorTable(const char *folder, char **objs, int count); // terminator.cpp

int main(int argc, char **argv) {
    std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "pngfloor" && argc == 4)
        return PngFloor(argv[2], argv[3]);
    if (mode == "raw" && argc == 4)
        return RawPixels(argv[2], argv[3]);
    if (mode == "report" && argc == 3)
        return ReportMain(argv[2]);
    if (mode == "time" && argc >= 3)
        return TimeProcess(argv + 2, false);
    if (mode == "timemem" && argc >= 3)
        return TimeProcess(argv + 2, true);
    if (mode == "robustness" && argc == 2)
        return RobustnessTables();
    if (mode == "methods" && (argc == 2 || argc == 3))
        return MethodsTable(argc == 3 ? argv[2] : nullptr);
    if (mode == "layout" && argc == 3)
        return LayoutTable(argv[2]);
    if (mode == "path" && argc == 3)
        return PathTable(argv[2]);
    if (mode == "noise" && argc == 8)
        return NoiseMain(argv + 2);
    if (mode == "terminator" && argc >= 4)
        return TerminatorTable(argv[2], argv + 3, argc - 3);
    if (mode != "rows" || argc != 3) {
        fprintf(stderr, "usage: bench rows DIR | bench report DIR | bench pngfloor RGB PNG | "
                        "bench time PROGRAM ARGS... | bench robustness | bench methods [DIR] | "
                        "bench layout DIR | bench path DIR | bench noise IMAGE CURVE N REF CURVE R "
                        "| bench terminator DIR OBJ...\n");
        return 2;
    }
    for (const BenchScene &b : kScenes)
        SceneRows(argv[2], b);
    HardCaseRows();
    return 0;
}
