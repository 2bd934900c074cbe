// bench/layout.cpp -- what the committed layout buys: render time against mesh size, one list
// of blocks against the BVH (`rtbench layout DIR`, part of `make bench`).
//
// The mesh is a closed sphere of 8 * 4^level triangles (a subdivided octahedron), lit by one
// point light and seen whole, 256 x 256, one sample a pixel, one thread: primary and shadow
// rays. Each time is the median of kRounds renders, the list and the BVH taken in turn so both
// see the same machine load; min and max are printed beside it. Beside the build's time: the
// committed layout's size, and what its memory costs to touch for the first time on this machine
// (a floor under any build that writes it). Writes DIR/layout.md (the table) and DIR/layout.svg
// (the log-log plot).
#include "../fast/fast.h"
#include "../render.h"
#include "svg.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

static const int kRounds = 5;
static const int kLevels[] = {1, 2, 3, 4, 5, 6, 7, 8}; // 32 to 524,288 triangles
static const size_t kMostForList = 8192; // beyond this the list takes minutes: not timed

static vec3 Unit(vec3 v) { return (1 / Length(v)) * v; }

// The sphere mesh of radius 2 at (0, -0.5, -8), with the scene around it.
static Scene SphereMesh(int level) {
    Scene scene;
    InitScene(&scene);
    scene.width = scene.height = 256;
    scene.materials = {
        {"white", {real(0.9), real(0.9), real(0.9)}, {1, 1, 1}, 0, 1, 0, 0, {0, 0, 0}}};
    scene.lights = {{{3, 5, 0}, {1, 1, 1}}};
    vec3 p[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    int f[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    std::vector<Triangle> faces;
    for (auto &t : f)
        faces.push_back({p[t[0]], p[t[1]], p[t[2]], 0});
    for (int k = 0; k < level; k++) {
        std::vector<Triangle> finer;
        for (const Triangle &t : faces) {
            vec3 ab = Unit(t.a + t.b), bc = Unit(t.b + t.c), ca = Unit(t.c + t.a);
            finer.push_back({t.a, ab, ca, 0}), finer.push_back({ab, t.b, bc, 0});
            finer.push_back({ca, bc, t.c, 0}), finer.push_back({ab, bc, ca, 0});
        }
        faces.swap(finer);
    }
    vec3 centre = {0, real(-0.5), -8};
    for (const Triangle &t : faces)
        scene.triangles.push_back({centre + 2 * t.a, centre + 2 * t.b, centre + 2 * t.c, 0});
    return scene;
}

struct Timing {
    std::vector<double> ms;
    uint64_t rays;
    double Median() const {
        std::vector<double> v = ms;
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    }
    double Min() const { return *std::min_element(ms.begin(), ms.end()); }
    double Max() const { return *std::max_element(ms.begin(), ms.end()); }
};

static void TimeRender(const Scene *scene, Timing *timing) {
    RenderSettings settings = {};
    settings.width = scene->width, settings.height = scene->height;
    settings.samplesPerPixel = 1, settings.sampling = SAMPLES_GRID, settings.depth = scene->depth;
    settings.threads = 1, settings.methods = kRobustMethods, settings.progress = nullptr;
    PlanRender(scene, &settings);
    Image image;
    RayStats stats = {};
    auto start = std::chrono::steady_clock::now();
    Render(scene, &settings, &image, &stats);
    std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - start;
    timing->ms.push_back(ms.count());
    timing->rays = stats.primary + stats.shadow;
}

// One row: the mesh at `level`, its commit time, the list's and the BVH's render times.
struct Row {
    size_t triangles;
    Timing commit, list, tree; // the BVH build; the two renders
    size_t layoutBytes;        // the BVH layout's arrays: blocks, nodes, set-ups, sphere blocks
};

// What this machine takes to give a process a fresh 4 KB page, in microseconds: a 64 MB buffer,
// new each pass, written a byte a page; the median of 5 passes. Measured before anything large
// has been freed: glibc's malloc takes a buffer this size from the system (mmap) and gives it
// back when freed, so every pass gets pages the process never had, unless a free piece of its
// heap is as large. (The writes are volatile, so the compiler cannot drop them.) A build writes
// its layout into such pages.
static double FreshPageMicroseconds() {
    const size_t kBytes = (size_t)64 << 20, kPage = 4096;
    std::vector<double> us;
    for (int pass = 0; pass < 5; pass++) {
        std::unique_ptr<char[]> buffer(new char[kBytes]);
        volatile char *bytes = buffer.get();
        auto start = std::chrono::steady_clock::now();
        for (size_t i = 0; i < kBytes; i += kPage)
            bytes[i] = 1;
        std::chrono::duration<double, std::micro> t = std::chrono::steady_clock::now() - start;
        us.push_back(t.count() / (double)(kBytes / kPage));
    }
    std::sort(us.begin(), us.end());
    return us[us.size() / 2];
}

static Row MeasureRow(int level) {
    Row row;
    Scene list = SphereMesh(level), tree = list;
    SceneLayout listLayout, treeLayout;
    row.triangles = list.triangles.size();
    for (int round = 0; round < kRounds; round++) { // each build into a fresh layout
        SceneLayout fresh;
        auto start = std::chrono::steady_clock::now();
        CommitScene(&tree, LAYOUT_BVH, 2, &fresh);
        std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - start;
        row.commit.ms.push_back(ms.count());
    }
    CommitScene(&tree, LAYOUT_BVH, 2, &treeLayout);
    row.layoutBytes = LayoutBytes(&treeLayout);
    CommitScene(&list, LAYOUT_LIST, 2, &listLayout);
    for (int round = 0; round < kRounds; round++) { // in turn: the same load for both
        if (row.triangles <= kMostForList)
            TimeRender(&list, &row.list);
        TimeRender(&tree, &row.tree);
    }
    return row;
}

static std::string Cell(const Timing &t) {
    if (t.ms.empty())
        return "(not timed)";
    char text[96];
    snprintf(text, sizeof text, "%.1f (%.1f-%.1f)", t.Median(), t.Min(), t.Max());
    return text;
}

// One line of the plot: its points (median, a whisker from min to max) and, by its last point,
// its name.
static std::string PlotLine(const std::vector<Row> &rows, bool tree, const SvgAxis &x,
                            const SvgAxis &y, SvgLabels *labels) {
    const char *colour = tree ? "steelblue" : "crimson";
    std::string points, marks;
    double lastX = -1, lastY = -1;
    for (const Row &r : rows) {
        const Timing &t = tree ? r.tree : r.list;
        if (t.ms.empty())
            continue;
        double px = AxisPixel(x, (double)r.triangles), py = AxisPixel(y, t.Median());
        double lo = AxisPixel(y, t.Min()), hi = AxisPixel(y, t.Max());
        points += Format("%.1f,%.1f ", px, py);
        marks += Format("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s'/>\n<circle "
                        "cx='%.1f' cy='%.1f' r='3' fill='%s'/>\n",
                        px, lo, px, hi, colour, px, py, colour);
        AddMarker(labels, px, py, 3), AddLine(labels, px, lo, px, hi, true);
        if (lastX >= 0)
            AddLine(labels, lastX, lastY, px, py, false);
        lastX = px, lastY = py;
    }
    return Format("<polyline points='%s' fill='none' stroke='%s' stroke-width='2'/>\n%s",
                  points.c_str(), colour, marks.c_str());
}

// The log-log plot: render time (256 x 256, one thread) against triangles, the list and the BVH.
static void WritePlot(const std::vector<Row> &rows, const std::string &path) {
    FILE *svg = fopen(path.c_str(), "w");
    if (!svg)
        return;
    double fewest = 1e30, most = 0, fast = 1e30, slow = 0;
    for (const Row &r : rows)
        for (const Timing *t : {&r.list, &r.tree})
            if (!t->ms.empty())
                fewest = std::min(fewest, (double)r.triangles),
                most = std::max(most, (double)r.triangles), fast = std::min(fast, t->Min()),
                slow = std::max(slow, t->Max());
    if (most <= 0) {
        fclose(svg);
        return;
    }
    SvgAxis x = FitAxis(fewest, most, true, 80, 620), y = FitAxis(fast, slow, true, 330, 20);
    SvgLabels labels = {FrameBox(x, y), {}, {}, {}, {}, {}, {}};
    std::string lines = PlotLine(rows, false, x, y, &labels) + PlotLine(rows, true, x, y, &labels);
    for (bool tree : {false, true})
        for (auto r = rows.rbegin(); r != rows.rend(); ++r) { // the line's name by its last point
            const Timing &t = tree ? r->tree : r->list;
            if (t.ms.empty())
                continue;
            lines +=
                PlaceLabel(&labels, AxisPixel(x, (double)r->triangles), AxisPixel(y, t.Median()), 3,
                           tree ? "BVH (binned SAH)" : "one list of blocks",
                           tree ? "steelblue" : "crimson", 12);
            break;
        }
    int height = 384 + 16 * (int)labels.legend.size();
    fprintf(svg,
            "<svg xmlns='http://www.w3.org/2000/svg' width='640' height='%d' "
            "font-family='sans-serif' font-size='12'>\n<rect width='640' height='%d' "
            "fill='white'/>\n%s%s%s</svg>\n",
            height, height,
            SvgFrame(x, y, "triangles (log)", "render ms (log; median, min to max)").c_str(),
            lines.c_str(), SvgLegend(labels, 80, 388, 16).c_str());
    fclose(svg);
}

int LayoutTable(const char *folder) {
    double pageUs = FreshPageMicroseconds(); // (first: later, freed layouts may serve the buffer)
    std::vector<Row> rows;
    for (int level : kLevels)
        rows.push_back(MeasureRow(level));
    std::string path = std::string(folder) + "/layout.md";
    FILE *md = fopen(path.c_str(), "w");
    if (!md)
        return 3;
    fprintf(md, "| triangles | BVH build ms | layout MB | its first touch, ms | list render ms "
                "| BVH render ms | rays | BVH Mrays/s |\n"
                "|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Row &r : rows)
        fprintf(md, "| %zu | %s | %.1f | %.1f | %s | %s | %llu | %.2f |\n", r.triangles,
                Cell(r.commit).c_str(), r.layoutBytes / 1e6, r.layoutBytes / 4096.0 * pageUs / 1e3,
                Cell(r.list).c_str(), Cell(r.tree).c_str(), (unsigned long long)r.tree.rays,
                r.tree.rays / r.tree.Median() / 1e3);
    fprintf(md,
            "\nA fresh 4 KB page costs this machine %.2f us (a new 64 MB buffer written a byte a "
            "page on one thread, wall time, median of 5): \"its first touch\" is the layout's "
            "pages at that price, the time one thread would spend; a build that writes the layout "
            "on two threads spends it on both, in about half the time at best.\n",
            pageUs);
    fclose(md);
    WritePlot(rows, std::string(folder) + "/layout.svg");
    return 0;
}
