// bench/path.cpp -- what a path tracer's accuracy costs in time (`rtbench path DIR`, part of
// `make bench`).
//
// The Cornell box and the path-traced assignment scene at 96 x 96, each method at 1 to 256
// samples a pixel, against a reference of 4,096 samples (cosine sampling with MIS, another seed;
// rendered by the double build into DIR/ref_path_SCENE.png, which the float build reads):
// RMSE in 8-bit levels of the sRGB image against render time (all threads). Every row is
// rendered kRounds times, a round being one render of every row, so all rows see the same
// machine load; its time is the median, min and max. Writes DIR/path.md (the table and
// sentences worded from it; two times whose ranges overlap are the same within noise) and
// DIR/path_SCENE.svg (error against time, log-log).
#include "../app/app.h"
#include "../ray.h"
#include "svg.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

static const int kSize = 96, kReferenceSpp = 4096, kRounds = 3;

struct PathRow {
    std::string scene, method;
    int spp;
    std::vector<double> times; // ms, one a round
    Spread ms;
    double rmse;
};

struct PathMethod {
    const char *name;
    PathMethods path;
    SampleMethod sampling;
    int depth; // 0: the scene's
};

static const PathMethod kMethods[] = {
    {"cosine + MIS",
     {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_MIS, false, 0, SPHERES_CONE},
     SAMPLES_JITTER,
     0},
    {"uniform + MIS",
     {ESTIMATOR_FULL, SCATTER_UNIFORM, LIGHTS_MIS, false, 0, SPHERES_CONE},
     SAMPLES_JITTER,
     0},
    {"cosine + NEE only",
     {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_NEE, false, 0, SPHERES_CONE},
     SAMPLES_JITTER,
     0},
    {"cosine, no NEE",
     {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_NONE, false, 0, SPHERES_CONE},
     SAMPLES_JITTER,
     0},
    {"fixed cap of 3 rays",
     {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_MIS, true, 0, SPHERES_CONE},
     SAMPLES_JITTER,
     3},
    {"fixed cap of 10 rays",
     {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_MIS, true, 0, SPHERES_CONE},
     SAMPLES_JITTER,
     10},
    {"adaptive (at most N)",
     {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_MIS, false, 0, SPHERES_CONE},
     SAMPLES_ADAPTIVE,
     0},
    {"the journal's estimator",
     {ESTIMATOR_JOURNAL, SCATTER_COSINE, LIGHTS_MIS, true, 0, SPHERES_CONE},
     SAMPLES_JITTER,
     0},
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
                        nullptr,
                        {},
                        {},
                        path};
    RayStats stats = {};
    auto start = std::chrono::steady_clock::now();
    ::Render(scene, &s, image, &stats);
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

// The reference: rendered and written by the double build, read by the float build (rendered
// if it cannot be read).
static void Reference(const Scene *scene, const char *folder, const char *name, Image *image) {
    std::string path = std::string(folder) + "/ref_path_" + name + ".png", error;
    if (sizeof(real) != sizeof(double) && ReadImage(path.c_str(), image, &error))
        return;
    Render(scene, {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_MIS, false, 99, SPHERES_CONE},
           SAMPLES_JITTER, kReferenceSpp, 0, image);
    if (sizeof(real) == sizeof(double) && !WriteImage(path.c_str(), image, &error))
        fprintf(stderr, "bench: %s\n", error.c_str());
}

static void SceneRows(const char *file, const char *name, const char *folder,
                      std::vector<PathRow> *rows) {
    Scene scene;
    std::string error;
    if (!ReadSceneFile(file, &scene, &error)) {
        fprintf(stderr, "bench: %s\n", error.c_str());
        return;
    }
    Image reference, image;
    Reference(&scene, folder, name, &reference);
    size_t first = rows->size();
    for (int round = 0; round < kRounds; round++) {
        size_t row = first;
        for (const PathMethod &m : kMethods)
            for (int spp = 1; spp <= 256; spp *= 4, row++) {
                double ms = Render(&scene, m.path, m.sampling, spp, m.depth, &image);
                if (round == 0) { // the same image every round: its error once
                    ImageDifference d;
                    Image heat;
                    CompareImages(&reference, &image, 0, &d, &heat);
                    rows->push_back({name, m.name, spp, {}, {}, d.rmse});
                }
                PathRow &r = (*rows)[row];
                r.times.push_back(ms);
                r.ms = SpreadOf(r.times);
                fprintf(stderr, "bench: path %-10s %-22s %4d spp %8.1f ms rmse %.3f (round %d)\n",
                        name, m.name, spp, ms, r.rmse, round + 1);
            }
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
// its measured sample counts: the medians' time, and the mins' and the maxes' as its range;
// false if it never gets there.
static bool TimeToReach(const std::vector<PathRow> &rows, const std::string &scene,
                        const std::string &method, double target, Spread *t) {
    for (int spp = 1; spp < 256; spp *= 4) {
        const PathRow *a = Find(rows, scene, method, spp), *b = Find(rows, scene, method, spp * 4);
        if (!a || !b || !(a->rmse >= target && b->rmse <= target))
            continue;
        double f = std::log(a->rmse / target) / std::log(a->rmse / b->rmse);
        auto at = [f](double ta, double tb) {
            return std::exp(std::log(ta) + f * std::log(tb / ta));
        };
        *t = {at(a->ms.median, b->ms.median), at(a->ms.min, b->ms.min), at(a->ms.max, b->ms.max)};
        return true;
    }
    return false;
}

// "X reaches Y's error (at 256 samples) in P% of its time", or in the same time within noise
// when the two ranges overlap, or that it is below it from the first sample, or never gets there.
static void Compare(FILE *md, const std::vector<PathRow> &rows, const std::string &scene,
                    const char *x, const char *y) {
    const PathRow *base = Find(rows, scene, y, 256);
    Spread t;
    if (!base)
        return;
    fprintf(md, "- %s: %s ", scene.c_str(), x);
    const PathRow *first = Find(rows, scene, x, 1);
    if (first && first->rmse <= base->rmse) {
        fprintf(md, "is already below %s's RMSE at 256 spp (%.2f) at 1 spp (%.2f, %s ms).\n", y,
                base->rmse, first->rmse, SpreadText(first->ms, "%.0f").c_str());
        return;
    }
    if (!TimeToReach(rows, scene, x, base->rmse, &t)) {
        fprintf(md, "does not reach %s's RMSE at 256 spp (%.2f) within 256 spp.\n", y, base->rmse);
        return;
    }
    std::string times =
        SpreadText(t, "%.0f") + " ms against " + SpreadText(base->ms, "%.0f") + " ms";
    if (WithinNoise(t, base->ms))
        fprintf(md,
                "reaches %s's RMSE at 256 spp (%.2f) in the same time within noise (ratio of "
                "medians %.2f; %s).\n",
                y, base->rmse, t.median / base->ms.median, times.c_str());
    else
        fprintf(md, "reaches %s's RMSE at 256 spp (%.2f) in %.0f%% of its time (%s).\n", y,
                base->rmse, 100 * t.median / base->ms.median, times.c_str());
}

static const char *kColours[] = {"black",     "crimson",   "darkorange", "seagreen",
                                 "steelblue", "slateblue", "orchid",     "saddlebrown"};
static_assert(sizeof kColours / sizeof kColours[0] >= sizeof kMethods / sizeof kMethods[0],
              "a colour for each method");

// One method's line: a point a sample count (its median time, a whisker from min to max), and
// the sample counts written by the points of the first method's line.
static std::string MethodLine(const std::vector<PathRow> &rows, const std::string &scene, int k,
                              const SvgAxis &x, const SvgAxis &y, SvgLabels *labels,
                              std::vector<SvgMark> *names) {
    std::string points, marks;
    double lastX = -1, lastY = -1;
    for (const PathRow &r : rows) {
        if (r.scene != scene || r.method != kMethods[k].name)
            continue;
        double px = AxisPixel(x, r.ms.median), py = AxisPixel(y, r.rmse);
        double lo = AxisPixel(x, r.ms.min), hi = AxisPixel(x, r.ms.max);
        points += Format("%.1f,%.1f ", px, py);
        marks += Format("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s'/>\n<circle "
                        "cx='%.1f' cy='%.1f' r='2.5' fill='%s'/>\n",
                        lo, py, hi, py, kColours[k], px, py, kColours[k]);
        AddMarker(labels, px, py, 2.5), AddLine(labels, lo, py, hi, py, true);
        if (lastX >= 0)
            AddLine(labels, lastX, lastY, px, py, false);
        lastX = px, lastY = py;
        if (k == 0)
            names->push_back({px, py, 2.5, std::to_string(r.spp), "black", 11});
    }
    return Format("<polyline points='%s' fill='none' stroke='%s' stroke-width='2'/>\n%s",
                  points.c_str(), kColours[k], marks.c_str());
}

static void WritePathPlot(const std::vector<PathRow> &rows, const std::string &scene,
                          const std::string &path) {
    double lo = 1e30, hi = 0, elo = 1e30, ehi = 0;
    for (const PathRow &r : rows)
        if (r.scene == scene)
            lo = std::min(lo, r.ms.min), hi = std::max(hi, r.ms.max), elo = std::min(elo, r.rmse),
            ehi = std::max(ehi, r.rmse);
    FILE *svg = hi > 0 ? fopen(path.c_str(), "w") : nullptr;
    if (!svg)
        return;
    SvgAxis x = FitAxis(lo, hi, true, 80, 560), y = FitAxis(elo, ehi, true, 330, 20);
    SvgLabels labels = {FrameBox(x, y), {}, {}, {}, {}, {}, {}};
    std::vector<SvgMark> names;
    std::string lines;
    for (int k = 0; k < (int)(sizeof kMethods / sizeof kMethods[0]); k++) {
        lines += MethodLine(rows, scene, k, x, y, &labels, &names);
        lines += Format("<line x1='580' y1='%d' x2='600' y2='%d' stroke='%s' stroke-width='2'/>"
                        "<text x='606' y='%d' fill='%s'>%s</text>\n",
                        36 + 18 * k, 36 + 18 * k, kColours[k], 40 + 18 * k, kColours[k],
                        kMethods[k].name);
    }
    lines += PlaceLabels(&labels, names);
    int height = 384 + 16 * (int)labels.legend.size();
    fprintf(svg,
            "<svg xmlns='http://www.w3.org/2000/svg' width='780' height='%d' "
            "font-family='sans-serif' font-size='12'>\n<rect width='780' height='%d' "
            "fill='white'/>\n%s%s<text x='580' y='%d'>numbers: spp of %s</text>\n%s</svg>\n",
            height, height,
            SvgFrame(x, y, "render time, ms (log; median, line from min to max)",
                     "RMSE, 8-bit levels (log)")
                .c_str(),
            lines.c_str(), 54 + 18 * (int)(sizeof kMethods / sizeof kMethods[0]), kMethods[0].name,
            SvgLegend(labels, 80, 388, 16).c_str());
    fclose(svg);
}

int PathTable(const char *folder) {
    std::vector<PathRow> rows;
    SceneRows("scenes/cornell.scene", "cornell", folder, &rows);
    SceneRows("scenes/assignment_path.scene", "assignment", folder, &rows);
    bool isDouble = sizeof(real) == sizeof(double);
    std::string base = std::string(folder) + (isDouble ? "/path" : "/path_float");
    FILE *md = fopen((base + ".md").c_str(), "w");
    if (!md)
        return 3;
    fprintf(md,
            "Render ms: median (min-max) of %d rounds.\n\n| scene | method | spp | ms | RMSE "
            "|\n|---|---|---:|---:|---:|\n",
            kRounds);
    for (const PathRow &r : rows)
        fprintf(md, "| %s | %s | %d | %s | %.3f |\n", r.scene.c_str(), r.method.c_str(), r.spp,
                SpreadText(r.ms, "%.1f").c_str(), r.rmse);
    fprintf(md, "\n");
    for (const char *scene : {"cornell", "assignment"}) {
        Compare(md, rows, scene, "cosine + MIS", "uniform + MIS");
        Compare(md, rows, scene, "cosine + MIS", "cosine, no NEE");
        Compare(md, rows, scene, "cosine + MIS", "cosine + NEE only");
        Compare(md, rows, scene, "adaptive (at most N)", "cosine + MIS");
        Compare(md, rows, scene, "cosine + MIS", "fixed cap of 3 rays");
        Compare(md, rows, scene, "cosine + MIS", "the journal's estimator");
    }
    fclose(md);
    if (isDouble) {
        WritePathPlot(rows, "cornell", std::string(folder) + "/path_cornell.svg");
        WritePathPlot(rows, "assignment", std::string(folder) + "/path_assignment.svg");
    }
    return 0;
}
