// ray.cpp -- the program: reads the command line, loads the scene, and renders it, probes it or
// compares two images.
//
// `ray [SCENE] [options]`, as the README describes it. Errors are values until they reach
// main, which prints one line `ray: MESSAGE` and exits with 2 (bad usage or input) or 3 (I/O).
#include "options.h"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <new>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

// The scenes built in C++ (the scene_*.cpp files, which the Makefile compiles, all of them), by
// the name the command line gives them, and the image each writes by default. A scene of your
// own: a builder in scene_NAME.cpp, its declaration in ray.h, and a line here.
static const struct {
    const char *name, *output;
    void (*build)(Scene *scene);
} kBuiltInScenes[] = {
    {"default", "reference.png", BuildDefaultScene},
    {"test", "test.png", BuildTestScene},
};

static bool IsBuiltIn(const std::string &name) {
    for (const auto &b : kBuiltInScenes)
        if (name == b.name)
            return true;
    return false;
}

// Loads the named built-in scene or a scene file, and picks the default output name.
static bool LoadScene(const std::string &name, Scene *scene, std::string *defaultOutput,
                      std::string *error) {
    for (const auto &b : kBuiltInScenes)
        if (name == b.name) {
            b.build(scene);
            *defaultOutput = b.output;
            return true;
        }
    std::string base = name.substr(name.find_last_of('/') + 1); // NAME.png for path/NAME.scene
    size_t dot = base.find_last_of('.');
    *defaultOutput = (dot == std::string::npos || dot == 0 ? base : base.substr(0, dot)) + ".png";
    if (ReadSceneFile(name.c_str(), scene, error))
        return true;
    // A bare word that names no file may be a built-in scene misremembered
    struct stat info;
    if (name.find_first_of("/.") == std::string::npos && stat(name.c_str(), &info) != 0 &&
        errno == ENOENT) {
        size_t n = sizeof kBuiltInScenes / sizeof kBuiltInScenes[0];
        std::string names;
        for (size_t k = 0; k < n; k++)
            names += (k == 0       ? ""
                      : k + 1 == n ? " and "
                                   : ", ") +
                     std::string(kBuiltInScenes[k].name);
        *error += " (nor is it a built-in scene: those are " + names + ")";
    }
    return false;
}

// The line of --stats that says how the triangles were searched.
static void PrintLayout(const Scene *scene, double commitSeconds) {
    const SceneLayout *layout = &scene->layout;
    if (scene->triangles.empty()) { // (--layout bvh too: there is nothing to build a tree over)
        fprintf(stderr, "triangles: none\n");
        return;
    }
    if (!LayoutIsCurrent(scene)) {
        fprintf(stderr, "triangles: %zu, tested one by one (the chosen method)\n",
                scene->triangles.size());
        return;
    }
    fprintf(stderr, "triangles: %zu in %zu blocks of %d, ", scene->triangles.size(),
            layout->blocks.size(), kLanes);
    if (layout->nodes.empty())
        fprintf(stderr, "one list");
    else
        fprintf(stderr, "a BVH of %zu nodes of %d", layout->nodes.size(), kWidth);
    fprintf(stderr, " (built in %.3g ms), %s\n", commitSeconds * 1e3,
            layout->wide ? "blocks tested in AVX2 vectors" : "blocks tested lane by lane");
}

// (`threads`: the threads the render ran on, which may be fewer than --threads asked for.)
static void PrintStats(const RayStats *s, const RenderSettings *settings, int threads,
                       double renderSeconds, double totalSeconds) {
    uint64_t total = s->primary + s->shadow + s->reflection + s->refraction + s->diffuse;
    fprintf(stderr, "image: %dx%d, %d spp, depth %d, %d thread%s\n", settings->width,
            settings->height, settings->samplesPerPixel, settings->depth, threads,
            threads == 1 ? "" : "s");
    fprintf(stderr, "time: render %.4f s, whole process %.4f s\n", renderSeconds, totalSeconds);
    fprintf(stderr,
            "rays: primary=%llu shadow=%llu reflection=%llu refraction=%llu diffuse=%llu "
            "total=%llu\n",
            (unsigned long long)s->primary, (unsigned long long)s->shadow,
            (unsigned long long)s->reflection, (unsigned long long)s->refraction,
            (unsigned long long)s->diffuse, (unsigned long long)total);
    fprintf(stderr, "speed: %.3g Mrays/s\n", total / renderSeconds / 1e6);
    std::string effects;
    const char *names[] = {" shadows",  " reflection", " refraction",
                           " specular", " indirect",   " antialiasing"};
    bool used[] = {s->shadow > 0,        s->reflection > 0, s->refraction > 0,
                   s->specularTerms > 0, s->diffuse > 0,    settings->samplesPerPixel > 1};
    for (int k = 0; k < 6; k++)
        if (used[k])
            effects += names[k];
    fprintf(stderr, "effects: %s\n", effects.empty() ? "none" : effects.c_str() + 1);
}

static double SecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// An error or warning, as one line `ray: MESSAGE` on standard error, whatever it quotes: a
// control character (a newline in a file's name) is written as an escape (PrintableLine).
static void Complain(const std::string &message) {
    fprintf(stderr, "ray: %s\n", PrintableLine(message).c_str());
}

// --compare: prints the difference, writes the heat map if -o was given. Returns the exit code.
static int Compare(const Options *opt) {
    Image a, b, heat;
    std::string error;
    int status;
    if (!opt->output.empty() &&
        !CheckOutputPath(opt->output, {opt->compareA, opt->compareB}, &status, &error)) {
        Complain(error);
        return status;
    }
    if (!ReadImage(opt->compareA.c_str(), &a, &error) ||
        !ReadImage(opt->compareB.c_str(), &b, &error)) {
        Complain(error);
        return 2;
    }
    ImageDifference d;
    if (!CompareImages(&a, &b, (int)opt->tolerance, &d, &heat)) {
        printf("sizes differ: %dx%d and %dx%d\n", a.width, a.height, b.width, b.height);
        return 1;
    }
    printf("rmse: %.6f\npsnr: %.2f dB\nlargest difference: %d\npixels over tolerance %g: %ld of "
           "%ld\n",
           d.rmse, d.psnr, d.largest, opt->tolerance, d.pixelsOver, (long)a.width * a.height);
    if (!opt->output.empty() && !WriteImage(opt->output.c_str(), &heat, &error)) {
        Complain(error);
        return 3;
    }
    return d.pixelsOver > 0 ? 1 : 0;
}

// --ray or --rays: one JSON line per ray. Returns the exit code.
static int Probe(const Options *opt, const Scene *scene, const RenderSettings *settings) {
    if (opt->probeRay) {
        Ray ray = {{opt->probe[0], opt->probe[1], opt->probe[2]},
                   {opt->probe[3], opt->probe[4], opt->probe[5]}};
        printf("%s\n", ProbeRayJson(scene, settings, &ray).c_str());
        return 0;
    }
    bool fromStdin = opt->raysFile == "-";
    struct stat info;
    if (!fromStdin && stat(opt->raysFile.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) {
        Complain(opt->raysFile + ": is a directory, not a file of rays");
        return 2;
    }
    FILE *file = fromStdin ? stdin : fopen(opt->raysFile.c_str(), "rb");
    if (!file) {
        Complain(opt->raysFile + ": " + strerror(errno));
        return 2;
    }
    int status = 0;
    std::string line, error;
    for (int lineNumber = 1;; lineNumber++) {
        LineStatus read = ReadTextLine(file, lineNumber, &line, &error);
        if (read == LINE_END)
            break;
        if (read == LINE_BAD) { // not text: no line after this one can be trusted either
            Complain(opt->raysFile + ":" + std::to_string(lineNumber) + ": " + error);
            status = 2;
            break;
        }
        Ray ray;
        bool blank;
        if (read == LINE_TOO_LONG || !ParseProbeLine(line, &ray, &blank, &error)) {
            printf("%s\n",
                   ProbeErrorJson("line " + std::to_string(lineNumber) + ": " + error).c_str());
            status = 2;
        } else if (!blank) {
            printf("%s\n", ProbeRayJson(scene, settings, &ray).c_str());
        }
        if (ferror(stdout)) { // no one reads the answers any more, or the disk is full
            Complain(std::string("standard output: ") + strerror(errno));
            return 3;
        }
    }
    if (!fromStdin)
        fclose(file);
    return status;
}

// --size refused (false, *error), or the scene's own size warned of (true, *warning), when the
// pixels of a screen camera would not be square; the message names a size that fits. Where none
// does (a screen 2 units wide and 1e-6 high), --size is only warned of too: refusing every size
// would leave no way to render the scene at another one. A screen whose edges are not at right
// angles (ScreenIsSheared) has parallelograms for pixels, whose
// sides the size can still make equal. A probe of single rays (--ray, --rays) draws no image:
// nothing to check.
static bool CheckScreenCameraSize(const Options *opt, const Scene *scene, std::string *error,
                                  std::string *warning) {
    if (scene->camera.kind != CAMERA_SCREEN || opt->probeRay || !opt->raysFile.empty())
        return true;
    double h = SafeLength(scene->camera.horizontal), v = SafeLength(scene->camera.vertical);
    int width = opt->width ? opt->width : scene->width;
    int height = opt->width ? (opt->height ? opt->height : opt->width) : scene->height;
    if (SquarePixels(width, height, h, v))
        return true;
    bool skew = ScreenIsSheared(&scene->camera);
    const char *shape = skew ? "equal-sided" : "square";
    const char *sheared = skew ? " (the screen is sheared: they are parallelograms)" : "";
    int W, H;
    bool fits = SquareSize(width, h, v, &W, &H);
    char size[96];
    snprintf(size, sizeof size, "no size up to 16384 x 16384 keeps them %s", shape);
    if (fits)
        snprintf(size, sizeof size,
                 opt->width ? "--size %dx%d keeps them %s" : "`size %d %d` keeps them %s", W, H,
                 shape);
    char text[400];
    if (opt->width)
        snprintf(text, sizeof text,
                 "%s--size %dx%d: the scene's screen camera is %g x %g, so its pixels would not be "
                 "%s%s; %s",
                 fits ? "" : "warning: ", width, height, h, v, shape, sheared, size);
    else
        snprintf(text, sizeof text,
                 "warning: the scene's screen camera is %g x %g and its image %d x %d, so its "
                 "pixels are not %s%s; %s",
                 h, v, width, height, shape, sheared, size);
    (opt->width && fits ? *error : *warning) = text;
    return !(opt->width && fits);
}

// The progress line on standard error: percentage, rays per second (every kind), time left,
// redrawn in place, and cleared at the end.
static void ShowProgress(const RenderProgress *p) {
    if (p->finished)
        fprintf(stderr, "\r%*s\r", 45, "");
    else
        fprintf(stderr, "\r%5.1f%%  %7.2f Mrays/s  %5.1f s left ", 100 * p->done,
                p->raysPerSecond / 1e6, p->secondsLeft);
    fflush(stderr);
}

// The render settings the scene and the options choose.
static RenderSettings ChosenSettings(const Options *opt, const Scene *scene) {
    RenderSettings settings;
    settings.width = opt->width ? opt->width : scene->width;
    settings.height = opt->height ? opt->height : scene->height;
    settings.samplesPerPixel = opt->spp;
    settings.sampling = (SampleMethod)opt->sampling;
    settings.depth = opt->depth ? opt->depth : scene->depth;
    unsigned hardware = std::thread::hardware_concurrency();
    settings.threads = opt->threads ? opt->threads : (hardware ? (int)hardware : 1);
    if (opt->view)
        settings.threads = 1; // (RenderView draws on one thread)
    settings.methods = ChosenMethods(opt);
    settings.path = {(ScatterMethod)opt->scatter, (LightMethod)opt->lights, opt->roulette == 1,
                     opt->seed};
    settings.progress = isatty(2) ? ShowProgress : nullptr; // (a line drawn in place: a terminal's)
    PlanRender(scene, &settings);
    return settings;
}

// --pixel X Y: the pixel's ray tree as JSON. Returns the exit code.
static int PixelTree(const Options *opt, const Scene *scene, const RenderSettings *settings) {
    if (opt->pixelX >= settings->width || opt->pixelY >= settings->height) {
        fprintf(stderr, "ray: --pixel: (%d, %d) is outside the %dx%d image\n", opt->pixelX,
                opt->pixelY, settings->width, settings->height);
        return 2;
    }
    printf("%s\n", PixelTreeJson(scene, settings, opt->pixelX, opt->pixelY).c_str());
    return 0;
}

// A render (or --view) to the output file. The output is checked before the render, so a
// mistake in it costs no time; a debug view is written beside the image, not over it
// (reference_normal.png). Returns the exit code.
static int RenderToFile(const Options *opt, const Scene *scene, const RenderSettings *settings,
                        std::string defaultOutput, std::chrono::steady_clock::time_point start,
                        double commitSeconds) {
    if (opt->view && opt->output.empty())
        defaultOutput = defaultOutput.substr(0, defaultOutput.size() - 4) + "_" +
                        ViewName(opt->viewKind) + ".png";
    std::string output = opt->output.empty() ? defaultOutput : opt->output, error;
    std::vector<std::string> inputs;
    if (!IsBuiltIn(opt->scene))
        inputs.push_back(opt->scene);
    inputs.insert(inputs.end(), scene->meshFiles.begin(), scene->meshFiles.end());
    int status;
    if (!CheckOutputPath(output, inputs, &status, &error)) {
        Complain(error);
        return status;
    }
    std::string flat = opt->view ? "" : OneColourWarning(scene);
    if (!flat.empty())
        Complain("warning: " + flat);
    Ray centre; // where the eye rays start: the eye, or under the slides' rays the screen
    GetCameraRay(&settings->camera, settings->width, settings->height,
                 {real(0.5) * settings->width, real(0.5) * settings->height}, &centre);
    for (const std::string &inside :
         opt->view ? std::vector<std::string>() : InsideWarnings(scene, centre.origin))
        Complain("warning: " + inside);
    Image image;
    RayStats stats = {};
    auto renderStart = std::chrono::steady_clock::now();
    int threads = 1; // (RenderView draws on one thread)
    if (opt->view)
        RenderView(scene, settings, opt->viewKind, &image, &stats);
    else
        threads = Render(scene, settings, &image, &stats);
    double renderSeconds = SecondsSince(renderStart);
    if (!WriteImage(output.c_str(), &image, &error)) {
        Complain(error);
        return 3;
    }
    if (opt->stats) {
        PrintLayout(scene, commitSeconds);
        PrintStats(&stats, settings, threads, renderSeconds, SecondsSince(start));
    }
    return 0;
}

// The program: one mode per run (help, compare, probe, pixel tree, render or view).
static int Run(int argc, char **argv) {
    auto start = std::chrono::steady_clock::now();
    Options opt;
    std::string error, defaultOutput;
    if (!ParseOptions(argc, argv, &opt, &error)) {
        Complain(error);
        return 2;
    }
    if (opt.help || opt.version) {
        fputs(opt.help ? kUsage : kVersion, stdout);
        if (!opt.help)
            fputc('\n', stdout);
        return 0;
    }
    if (opt.compare)
        return Compare(&opt);
    Scene scene;
    if (!LoadScene(opt.scene, &scene, &defaultOutput, &error)) {
        Complain(error);
        return 2;
    }
    for (const std::string &warning : scene.warnings)
        Complain(warning);
    std::string warning;
    if (!CheckScreenCameraSize(&opt, &scene, &error, &warning)) {
        Complain(error);
        return 2;
    }
    if (!warning.empty())
        Complain(warning);
    RenderSettings settings = ChosenSettings(&opt, &scene);
    // The scene's commit: only the robust triangle test has a fast layout, and the sphere blocks
    // come with it (the handouts' methods are the plain loop, as written). The BVH is built on
    // as many threads as the render runs on (two at most).
    auto commitStart = std::chrono::steady_clock::now();
    if (settings.methods.triangle == TRIANGLE_WATERTIGHT)
        CommitScene(&scene, (LayoutChoice)opt.layout, settings.threads);
    double commitSeconds = SecondsSince(commitStart);
    if (opt.probeRay || !opt.raysFile.empty())
        return Probe(&opt, &scene, &settings);
    if (opt.pixel)
        return PixelTree(&opt, &scene, &settings);
    return RenderToFile(&opt, &scene, &settings, defaultOutput, start, commitSeconds);
}

// Whether all that was printed reached standard output; false with *why where some could not
// be written (a pipe whose reader has gone, a full disk).
static bool OutputWritten(std::string *why) {
    errno = 0;
    if (fflush(stdout) == 0 && !ferror(stdout))
        return true;
    *why = errno != 0 ? strerror(errno) : "write error";
    return false;
}

// An allocation that fails (a scene of millions of shapes under a memory limit, an image of
// 16384 x 16384 on a small machine) is an error message and exit 2, never an abort.
int main(int argc, char **argv) {
    // A reader that goes away (`ray --rays - | head -1`) is an error to report, not a signal
    // that ends the program: with SIGPIPE ignored, a write to the closed pipe fails instead
    // (EPIPE), and the run ends with exit 3.
    std::signal(SIGPIPE, SIG_IGN);
    int status;
    try {
        status = Run(argc, argv);
    } catch (const std::bad_alloc &) {
        Complain("out of memory");
        return 2;
    }
    std::string why;
    if (status != 3 && !OutputWritten(&why)) { // (3: an output error, said already)
        Complain("standard output: " + why);
        return 3;
    }
    return status;
}
