// render.cpp -- the render loop: samples in each pixel, and every pixel on every core.
//
// One ray per pixel through its centre (the handout's method), or N samples per pixel: on a
// regular grid, jittered in its cells, or adaptively (by the colours and shapes the first five
// meet, or, for `shading path`, by the pixel's own Monte Carlo error); the cameras' rays come
// from camera.cpp.
// Each pixel is computed the same way whichever thread takes it, so the image never depends on
// the thread count; threads take whole rows from a shared counter, so no core waits while work
// remains. Also here: PlanRender, what a render decides once before its first pixel.
#include "render.h"
#include "ray.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <cstdio>
#include <system_error>
#include <thread>

// Rounding half away from zero, as std::lround does, without the library call (three of them a
// pixel): v - whole is exact (whole is v with its fraction cut off, so the difference is that
// fraction), where the shortcut (int)(v + 0.5) is not: v + 0.5 can round up to the next integer,
// as it does for the largest float below 0.5, which c * 255 reaches in the float build.
// Checked by TestClamp (tests/test_handout_light.cpp).
uint8_t ToByte(real c) {
    if (!(c > 0))
        return 0;
    if (c >= 1)
        return 255;
    real v = c * 255;
    int whole = (int)v;
    return (uint8_t)(whole + (v - (real)whole >= real(0.5)));
}

// The sRGB transfer curve (IEC 61966-2-1): linear light in [0, 1] to the encoded value a display
// expects, linear near black and a 1/2.4 power above.
real SrgbEncode(real linear) {
    if (!(linear > real(0.0031308)))
        return real(12.92) * std::max(real(0), linear);
    return real(1.055) * std::pow(std::min(real(1), linear), real(1) / real(2.4)) - real(0.055);
}

static void AddStats(const RayStats *part, RayStats *total) {
    total->primary += part->primary;
    total->shadow += part->shadow;
    total->reflection += part->reflection;
    total->refraction += part->refraction;
    total->specularTerms += part->specularTerms;
    total->diffuse += part->diffuse;
    total->primaryHits += part->primaryHits;
}

// Cell s of n inside the unit pixel, on a regular grid that holds exactly n cells: `rows` =
// floor(sqrt(n)) rows, each with n / rows cells (the first rows take one fewer when n is not a
// multiple). `inCell` places the sample in its cell: (0.5, 0.5) is the centre. n = 1 is the
// pixel centre (the handout's method), n = k * k the usual k x k grid.
struct GridCell {
    int rows, row;    // the grid's rows, and the cell's
    int first, count; // the row holds cells [first, first + count)
};
static GridCell FindCell(int s, int n) {
    assert(n >= 1 && n <= 65536 && s >= 0 && s < n);
    if (n == 1) // (one sample a pixel: its one cell is the pixel, found without a square root)
        return {1, 0, 0, 1};
    int rows = (int)std::sqrt((double)n);
    while ((rows + 1) * (rows + 1) <= n) // guard sqrt rounding for large perfect squares
        rows++;
    // Row r holds the cells [n r / rows, n (r + 1) / rows); start from the estimate s rows / n.
    // n <= 65536 and rows <= 256 keep every product below 2^31
    int row = s * rows / n;
    while (row > 0 && n * row / rows > s)
        row--;
    while (n * (row + 1) / rows <= s)
        row++;
    int first = n * row / rows;
    return {rows, row, first, n * (row + 1) / rows - first};
}
// The cell of sample s, from the cell of sample s - 1: the grid walked row by row, the same row
// until it is full, then the next, which starts where that one ended (every row holds at least
// one cell: n / rows >= rows). A pixel's samples, taken in order, need no FindCell of their own.
static GridCell NextCell(const GridCell *previous, int s, int n) {
    int first = previous->first + previous->count, row = previous->row + 1;
    if (s < first)
        return *previous;
    return {previous->rows, row, first, n * (row + 1) / previous->rows - first};
}
static vec2 CellPosition(const GridCell *cell, int s, vec2 inCell) {
    return {(real(s - cell->first) + inCell.x) / cell->count,
            (real(cell->row) + inCell.y) / cell->rows};
}

// Sample s of pixel (i, j) at the centre of its cell.
static vec2 GridPosition(int i, int j, const GridCell *cell, int s) {
    vec2 p = CellPosition(cell, s, {real(0.5), real(0.5)});
    return {i + p.x, j + p.y};
}
vec2 SamplePosition(int i, int j, int s, int n) {
    GridCell cell = FindCell(s, n);
    return GridPosition(i, j, &cell, s);
}

// A random point in [0, 1)^2 that depends only on the pixel, the sample and a stream number, so
// every thread draws the same one: SplitMix64's finaliser (Steele, Lea & Flood, "Fast Splittable
// Pseudorandom Number Generators", OOPSLA 2014) applied to the four numbers in turn.
static vec2 HashPoint(int i, int j, int s, int stream) {
    uint64_t z = 0;
    for (uint64_t word : {(uint64_t)i, (uint64_t)j, (uint64_t)s, (uint64_t)stream})
        z = MixWord(z, word);
    return {real((z >> 40) * (1.0 / 16777216.0)),
            real(((z >> 16) & 0xffffff) * (1.0 / 16777216.0))};
}

// Sample s of n of pixel (i, j), jittered: a random point in its grid cell (stratified).
static vec2 JitterPosition(int i, int j, const GridCell *cell, int s, int stream) {
    vec2 p = CellPosition(cell, s, HashPoint(i, j, s, stream));
    return {i + p.x, j + p.y};
}

void TraceEyeRays(const Scene *scene, const RenderSettings *settings, const Ray *rays, int count,
                  int i, int j, int s, TraceLog *log, color *colours) {
    RayHit hits[kEyeRaysTogether];
    bool found[kEyeRaysTogether];
    FindEyeRayHits(scene, settings->methods, rays, count, hits, found);
    for (int k = 0; k < count; k++)
        colours[k] =
            scene->shading == SHADING_PATH
                ? TracePath(scene, settings, &rays[k], found[k], &hits[k], i, j, s + k, log)
                : ShadeFound(scene, settings, RAY_PRIMARY, &rays[k], RayChain{1, 1}, found[k],
                             &hits[k], log);
}

// Sample s of pixel (i, j), alone: the camera ray through `position`, and its colour.
static color SampleColor(const Scene *scene, const RenderSettings *settings, vec2 position, int i,
                         int j, int s, TraceLog *log) {
    Ray ray;
    color c;
    GetCameraRay(&settings->camera, settings->width, settings->height, position, &ray);
    TraceEyeRays(scene, settings, &ray, 1, i, j, s, log, &c);
    return c;
}

// Whether samples differ, in any channel clamped to [0, 1], by more than kAdaptiveContrast.
static bool Disagree(const color *c, int count) {
    for (int channel = 0; channel < 3; channel++) {
        real lo = 1, hi = 0;
        for (int k = 0; k < count; k++) {
            real v = std::min(real(1), std::max(real(0), Component(c[k], channel)));
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
        if (hi - lo > kAdaptiveContrast)
            return true;
    }
    return false;
}

// Adaptive sampling with n samples: first the pixel's centre and its four corners, which decide.
// An edge, a shadow border or a reflected detail that crosses the pixel separates at least one
// corner from the rest, in colour or in the shapes its rays met (a mirror corridor's sub-pixel
// detail can agree in colour by chance, never in shapes). Where all five agree, the weighted
// average (centre 1/2, corners 1/8 each) is the pixel. Where they do not, the pixel is the average
// of its centre and n - 1 stratified jittered samples inside it: the corners, on the pixel's
// border, only decide (averaged in, they would blur the edge into the neighbours). Such a pixel
// costs n + 4 rays, a flat one 5.
static color AdaptivePixel(const Scene *scene, const RenderSettings *settings, int i, int j,
                           TraceLog *log) {
    int n = settings->samplesPerPixel;
    const vec2 firstPositions[5] = {{0.5, 0.5}, {0, 0}, {1, 0}, {0, 1}, {1, 1}};
    color first[5], corners = {0, 0, 0};
    bool sameSurfaces = true;
    uint64_t centre = 0;
    for (int s = 0; s < 5; s++) {
        vec2 p = firstPositions[s];
        log->surfaces = 0;
        first[s] = SampleColor(scene, settings, {i + p.x, j + p.y}, i, j, s, log);
        centre = s == 0 ? log->surfaces : centre;
        sameSurfaces = sameSurfaces && log->surfaces == centre;
        if (s > 0)
            corners = corners + first[s];
    }
    if (sameSurfaces && !Disagree(first, 5))
        return real(0.5) * first[0] + real(0.125) * corners;
    color sum = first[0];
    GridCell cell = FindCell(0, n - 1);
    for (int s = 0; s < n - 1; s++) {
        cell = NextCell(&cell, s, n - 1);
        vec2 p = JitterPosition(i, j, &cell, s, 1);
        sum = sum + SampleColor(scene, settings, p, i, j, 5 + s, log);
    }
    return (real(1) / n) * sum;
}

// Adaptive sampling for `shading path`, in two stages so that it stays unbiased: kPathFirst
// pilot samples, each at a random point of the pixel, estimate the spread of the pixel's
// samples; from it follows how many samples bring the error of the mean, as the sRGB curve will
// show it, below kPathTolerance, two 8-bit steps (at least kPathFirst, at most samplesPerPixel);
// then that many fresh samples make the pixel. The pilots are not averaged in: a count chosen
// from the very samples it averages leans toward those that happened to agree (16 black pilots
// of a lamp found only by chance would stop a pixel at black). A pixel whose paths agree (the
// background, a surface lit straight on) costs 2 x kPathFirst; a noisy one all its samples.
// 16 pilots estimate a pixel's spread to within about a fifth (the relative error of a sample
// deviation from n samples is about 1 / sqrt(2 (n - 1))), which the count's square law turns into
// some 40%: coarse, but it only sets how many fresh samples to take, never what they average to.
// The tolerance is the choice of what noise a viewer may still see; docs/path-tracing.md measures
// what it buys.
const int kPathFirst = 16;
const double kPathTolerance = 2.0 / 255;

// How much the sRGB curve magnifies a small change of linear light m.
static double SrgbSlope(double m) {
    if (m <= 0.0031308)
        return 12.92;
    return 1.055 / 2.4 * std::pow(std::min(m, 1.0), 1 / 2.4 - 1);
}

static color AdaptivePathPixel(const Scene *scene, const RenderSettings *settings, int i, int j,
                               TraceLog *log) {
    int most = settings->samplesPerPixel;
    double brightness = 0, squares = 0;
    for (int s = 0; s < kPathFirst; s++) { // the pilots: sample numbers past the pixel's own
        vec2 u = HashPoint(i, j, most + s, 2);
        color c = SampleColor(scene, settings, {i + u.x, j + u.y}, i, j, most + s, log);
        double y = ((double)c.x + c.y + c.z) / 3;
        brightness += y, squares += y * y;
    }
    double mean = brightness / kPathFirst;
    double variance =
        std::max(0.0, squares / kPathFirst - mean * mean) * kPathFirst / (kPathFirst - 1);
    double slope = SrgbSlope(mean),
           wanted = variance * slope * slope / (kPathTolerance * kPathTolerance);
    int n = (int)std::min((double)most, std::max((double)kPathFirst, std::ceil(wanted)));
    color sum = {0, 0, 0};
    for (int s = 0; s < n; s++) {
        vec2 u = HashPoint(i, j, s, 2);
        sum = sum + SampleColor(scene, settings, {i + u.x, j + u.y}, i, j, s, log);
    }
    return (real(1) / n) * sum;
}

// Sample s of n of pixel (i, j): for n = 1 the pixel's centre, the handout's ray; else a point of
// its cell of the grid (*cell, the cell of sample s - 1 moved on), jittered where asked.
static vec2 SamplePoint(int i, int j, int s, int n, bool jitter, GridCell *cell) {
    if (n == 1)
        return {i + real(0.5), j + real(0.5)};
    *cell = s == 0 ? FindCell(0, n) : NextCell(cell, s, n);
    return jitter ? JitterPosition(i, j, cell, s, 0) : GridPosition(i, j, cell, s);
}

// n samples of pixel (i, j) on the grid (jittered in their cells but for n = 1, whose one sample
// is the pixel's centre: the handout's ray), a few at a time, their rays traced together.
static color SampledPixel(const Scene *scene, const RenderSettings *settings, int i, int j,
                          TraceLog *log) {
    int n = settings->samplesPerPixel;
    bool jitter = settings->sampling != SAMPLES_GRID && n > 1;
    GridCell cell = {};
    color sum = {0, 0, 0};
    for (int first = 0; first < n; first += kEyeRaysTogether) {
        int count = std::min(kEyeRaysTogether, n - first);
        Ray rays[kEyeRaysTogether];
        color colours[kEyeRaysTogether];
        for (int s = first; s < first + count; s++) {
            vec2 p = SamplePoint(i, j, s, n, jitter, &cell);
            GetCameraRay(&settings->camera, settings->width, settings->height, p, &rays[s - first]);
        }
        TraceEyeRays(scene, settings, rays, count, i, j, first, log, colours);
        for (int k = 0; k < count; k++)
            sum = sum + colours[k];
    }
    return (real(1) / n) * sum;
}

color RenderPixel(const Scene *scene, const RenderSettings *settings, int i, int j,
                  RayStats *stats) {
    TraceLog log = {RayStats{}, nullptr, -1, 0};
    color result;
    if (settings->sampling == SAMPLES_ADAPTIVE && scene->shading == SHADING_PATH)
        result = AdaptivePathPixel(scene, settings, i, j, &log);
    else if (settings->sampling == SAMPLES_ADAPTIVE && settings->samplesPerPixel > 5)
        result = AdaptivePixel(scene, settings, i, j, &log);
    else
        result = SampledPixel(scene, settings, i, j, &log);
    AddStats(&log.stats, stats);
    return result;
}

void PlanRender(const Scene *scene, RenderSettings *settings) {
    PlanEffects(scene, settings, &settings->effects);
    settings->camera = scene->camera;
    settings->camera.perspective.widthPixels = settings->width;
    settings->camera.perspective.heightPixels = settings->height;
    settings->camera.toCorner = scene->camera.lowerLeft - scene->camera.eye;
    std::string unused;
    if (scene->camera.kind == CAMERA_LOOKAT) // checked when the scene was read
        LookAtToScreen(&scene->camera, settings->width, settings->height, &settings->camera,
                       &unused);
    settings->camera.fromScreen = settings->methods.cameraRay == CAMERA_RAY_SLIDES;
    settings->camera.seed = settings->path.seed;
}

static void RenderRow(const Scene *scene, const RenderSettings *settings, int j, Image *image,
                      RayStats *stats) {
    uint8_t *out = &image->pixels[(size_t)j * settings->width * 3];
    for (int i = 0; i < settings->width; i++) {
        color c = RenderPixel(scene, settings, i, j, stats);
        if (scene->shading == SHADING_PATH) // light, not a colour: encode it for the screen
            c = {SrgbEncode(c.x), SrgbEncode(c.y), SrgbEncode(c.z)};
        out[3 * i + 0] = ToByte(c.x);
        out[3 * i + 1] = ToByte(c.y);
        out[3 * i + 2] = ToByte(c.z);
    }
}

// Shared by the workers of one render: the next row to take, and how many are finished.
struct RowQueue {
    std::atomic<int> nextRow{0};
    std::atomic<int> rowsDone{0};
    std::atomic<uint64_t> raysCast{0}; // for the progress line only
};

// Takes the next row from the queue and renders it; false when no rows are left. The row counts
// its rays in a local RayStats, added to the thread's once per row: counters that two threads
// write on every ray would share a cache line and slow both down.
static bool TakeRow(const Scene *scene, const RenderSettings *settings, RowQueue *queue,
                    Image *image, RayStats *stats) {
    int j = queue->nextRow.fetch_add(1);
    if (j >= settings->height)
        return false;
    RayStats row = {};
    RenderRow(scene, settings, j, image, &row);
    AddStats(&row, stats);
    queue->raysCast.fetch_add(row.primary + row.shadow + row.reflection + row.refraction +
                              row.diffuse);
    queue->rowsDone.fetch_add(1);
    return true;
}

static void RenderWorker(const Scene *scene, const RenderSettings *settings, RowQueue *queue,
                         Image *image, RayStats *stats) {
    while (TakeRow(scene, settings, queue, image, stats)) {
    }
}

// How far the render has come after `seconds`, for the progress report.
static RenderProgress Progress(const RowQueue *queue, int height, double seconds) {
    double rays = (double)queue->raysCast.load();
    double done = (double)queue->rowsDone.load() / height;
    double left = done > 0 ? seconds * (1 - done) / done : 0;
    return {done, rays / seconds, left, false};
}

// The calling thread renders too; with a progress report it renders one row at a time and
// reports every half second once the render has run that long. True if it reported.
static bool RenderOwnRows(const Scene *scene, const RenderSettings *settings, RowQueue *queue,
                          Image *image, RayStats *stats) {
    auto start = std::chrono::steady_clock::now();
    double lastShown = 0;
    while (TakeRow(scene, settings, queue, image, stats)) {
        if (!settings->progress)
            continue;
        auto elapsed = std::chrono::steady_clock::now() - start;
        double seconds = std::chrono::duration<double>(elapsed).count();
        if (seconds - lastShown >= 0.5) {
            RenderProgress now = Progress(queue, settings->height, seconds);
            settings->progress(&now);
            lastShown = seconds;
        }
    }
    return lastShown > 0;
}

int Render(const Scene *scene, const RenderSettings *requested, Image *image, RayStats *stats) {
    // Plan a copy for this scene, so settings planned for another scene can do no harm
    RenderSettings planned = *requested;
    PlanRender(scene, &planned);
    const RenderSettings *settings = &planned;
    image->width = settings->width;
    image->height = settings->height;
    image->pixels.assign((size_t)settings->width * settings->height * 3, 0);
    int threads = std::max(1, std::min(settings->threads, settings->height));
    std::vector<RayStats> perThread(threads, RayStats{});
    RowQueue queue;
    std::vector<std::thread> workers;
    workers.reserve(threads - 1);
    for (int k = 1; k < threads; k++) {
        try {
            workers.emplace_back(RenderWorker, scene, settings, &queue, image, &perThread[k]);
        } catch (const std::exception &) { // the system gives no more threads (a limit on
            break; // threads or on memory): the rows are shared, so fewer render the same bytes
        }
    }

    bool shown = RenderOwnRows(scene, settings, &queue, image, &perThread[0]);
    for (std::thread &w : workers)
        w.join();
    if (shown) {
        RenderProgress end = {1, 0, 0, true};
        settings->progress(&end);
    }

    for (const RayStats &s : perThread)
        AddStats(&s, stats);
    return 1 + (int)workers.size();
}
