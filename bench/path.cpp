// bench/path.cpp -- what a path tracer's accuracy costs in time (`rtbench path DIR`, part of
// `make bench`).
//
// The Cornell box and the path-traced assignment scene at 96 x 96, each method at 1 to 256
// samples a pixel, against a reference of 4,096 samples (cosine sampling with MIS, another seed):
// RMSE in 8-bit levels of the sRGB image against render time (all threads). Writes DIR/path.md
// (the table and sentences worded from it) and DIR/path.svg (error against time, log-log).
#include "ray.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

static const int kSize = 96, kReferenceSpp = 4096;

struct PathRow {
    std::string scene, method;
    int spp;
    double ms, rmse;
};

struct PathMethod {
    const char *name;
    PathMethods path;
    SampleMethod sampling;
    int depth; // 0: the scene's
};

static const PathMethod kMethods[] = {
    {"cosine + MIS", {SCATTER_COSINE, LIGHTS_MIS, false, 0}, SAMPLES_JITTER, 0},
    {"uniform + MIS", {SCATTER_UNIFORM, LIGHTS_MIS, false, 0}, SAMPLES_JITTER, 0},
    {"cosine + NEE only", {SCATTER_COSINE, LIGHTS_NEE, false, 0}, SAMPLES_JITTER, 0},
    {"cosine, no NEE", {SCATTER_COSINE, LIGHTS_NONE, false, 0}, SAMPLES_JITTER, 0},
    {"fixed cap of 3 rays", {SCATTER_COSINE, LIGHTS_MIS, true, 0}, SAMPLES_JITTER, 3},
    {"fixed cap of 10 rays", {SCATTER_COSINE, LIGHTS_MIS, true, 0}, SAMPLES_JITTER, 10},
    {"adaptive (at most N)", {SCATTER_COSINE, LIGHTS_MIS, false, 0}, SAMPLES_ADAPTIVE, 0},
};

static double Render(const Scene *scene, PathMethods path, SampleMethod sampling, int spp,
                     int depth, Image *image) {
    unsigned hardware = std::thread::hardware_concurrency();
    RenderSettings s = {kSize,
                        kSize,
                        spp,
                        sampling,
                        depth ? depth : scene->depth,
                        hardware ? (int)hardware : 1,
                        kRobustMethods,
                        false,
                        {},
                        {},
                        path};
    RayStats stats = {};
    auto start = std::chrono::steady_clock::now();
    ::Render(scene, &s, image, &stats);
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

static void SceneRows(const char *file, const char *name, std::vector<PathRow> *rows) {
    Scene scene;
    std::string error;
    if (!ReadSceneFile(file, &scene, &error)) {
        fprintf(stderr, "bench: %s\n", error.c_str());
        return;
    }
    Image reference, image;
    Render(&scene, {SCATTER_COSINE, LIGHTS_MIS, false, 99}, SAMPLES_JITTER, kReferenceSpp, 0,
           &reference);
    for (const PathMethod &m : kMethods)
        for (int spp = 1; spp <= 256; spp *= 4) {
            double ms = Render(&scene, m.path, m.sampling, spp, m.depth, &image);
            ImageDifference d;
            Image heat;
            CompareImages(&reference, &image, 0, &d, &heat);
            rows->push_back({name, m.name, spp, ms, d.rmse});
            fprintf(stderr, "bench: path %-10s %-22s %4d spp %8.1f ms rmse %.3f\n", name, m.name,
                    spp, ms, d.rmse);
        }
}

static const PathRow *Find(const std::vector<PathRow> &rows, const std::string &scene,
                           const std::string &method, int spp) {
    for (const PathRow &r : rows)
        if (r.scene == scene && r.method == method && r.spp == spp)
            return &r;
    return nullptr;
}

// The time at which `method` reaches RMSE `target` on `scene`, by log-log interpolation between
// its measured sample counts; -1 if it never gets there.
static double TimeToReach(const std::vector<PathRow> &rows, const std::string &scene,
                          const std::string &method, double target) {
    for (int spp = 1; spp < 256; spp *= 4) {
        const PathRow *a = Find(rows, scene, method, spp), *b = Find(rows, scene, method, spp * 4);
        if (!a || !b || !(a->rmse >= target && b->rmse <= target))
            continue;
        double f = std::log(a->rmse / target) / std::log(a->rmse / b->rmse);
        return std::exp(std::log(a->ms) + f * std::log(b->ms / a->ms));
    }
    return -1;
}

// "X reaches Y's error (at 256 samples) in P% of its time", or that it does not.
static void Compare(FILE *md, const std::vector<PathRow> &rows, const std::string &scene,
                    const char *x, const char *y) {
    const PathRow *base = Find(rows, scene, y, 256);
    if (!base)
        return;
    double t = TimeToReach(rows, scene, x, base->rmse);
    if (t < 0)
        fprintf(md, "- %s: %s does not reach %s's RMSE at 256 spp (%.2f) within 256 spp.\n",
                scene.c_str(), x, y, base->rmse);
    else
        fprintf(md, "- %s: %s reaches %s's RMSE at 256 spp (%.2f) in %.0f%% of its time.\n",
                scene.c_str(), x, y, base->rmse, 100 * t / base->ms);
}

static void WritePathPlot(const std::vector<PathRow> &rows, const std::string &scene,
                          const std::string &path) {
    FILE *svg = fopen(path.c_str(), "w");
    if (!svg)
        return;
    double lo = 1e9, hi = 0, elo = 1e9, ehi = 0;
    for (const PathRow &r : rows)
        if (r.scene == scene)
            lo = std::min(lo, r.ms), hi = std::max(hi, r.ms), elo = std::min(elo, r.rmse),
            ehi = std::max(ehi, r.rmse);
    auto x = [&](double ms) { return 70 + 500 * std::log(ms / lo) / std::log(hi / lo); };
    auto y = [&](double e) { return 30 + 300 * std::log(ehi / e) / std::log(ehi / elo); };
    fprintf(svg,
            "<svg xmlns='http://www.w3.org/2000/svg' width='780' height='380' "
            "font-family='sans-serif' font-size='12'>\n<rect width='780' height='380' "
            "fill='white'/>\n<text x='320' y='370' text-anchor='middle'>render time, ms (log, "
            "%.0f to %.0f)</text>\n<text x='16' y='180' transform='rotate(-90 16 180)' "
            "text-anchor='middle'>RMSE, 8-bit levels (log, %.1f to %.1f)</text>\n",
            lo, hi, elo, ehi);
    const char *colours[] = {"black",     "crimson",   "darkorange", "seagreen",
                             "steelblue", "slateblue", "orchid"};
    int k = 0;
    for (const PathMethod &m : kMethods) {
        std::string points;
        for (const PathRow &r : rows)
            if (r.scene == scene && r.method == m.name)
                points += std::to_string(x(r.ms)) + "," + std::to_string(y(r.rmse)) + " ";
        fprintf(svg, "<polyline points='%s' fill='none' stroke='%s' stroke-width='2'/>\n",
                points.c_str(), colours[k]);
        fprintf(svg, "<text x='600' y='%d' fill='%s'>%s</text>\n", 40 + 18 * k, colours[k], m.name);
        k++;
    }
    fprintf(svg, "</svg>\n");
    fclose(svg);
}

int PathTable(const char *folder) {
    std::vector<PathRow> rows;
    SceneRows("scenes/cornell.scene", "cornell", &rows);
    SceneRows("scenes/assignment_path.scene", "assignment", &rows);
    bool isDouble = sizeof(real) == sizeof(double);
    std::string base = std::string(folder) + (isDouble ? "/path" : "/path_float");
    FILE *md = fopen((base + ".md").c_str(), "w");
    if (!md)
        return 3;
    fprintf(md, "| scene | method | spp | ms | RMSE |\n|---|---|---:|---:|---:|\n");
    for (const PathRow &r : rows)
        fprintf(md, "| %s | %s | %d | %.1f | %.3f |\n", r.scene.c_str(), r.method.c_str(), r.spp,
                r.ms, r.rmse);
    fprintf(md, "\n");
    for (const char *scene : {"cornell", "assignment"}) {
        Compare(md, rows, scene, "cosine + MIS", "uniform + MIS");
        Compare(md, rows, scene, "cosine + MIS", "cosine, no NEE");
        Compare(md, rows, scene, "cosine + MIS", "cosine + NEE only");
        Compare(md, rows, scene, "adaptive (at most N)", "cosine + MIS");
        Compare(md, rows, scene, "cosine + MIS", "fixed cap of 3 rays");
    }
    fclose(md);
    if (isDouble) {
        WritePathPlot(rows, "cornell", std::string(folder) + "/path_cornell.svg");
        WritePathPlot(rows, "assignment", std::string(folder) + "/path_assignment.svg");
    }
    return 0;
}
