// ray.cpp -- the program: `ray [SCENE] [options]`, as the README describes it.
//
// main reads the command line, loads the scene, installs the speed machinery (fast/: the scene
// committed into blocks and a BVH, searched behind the core's one seam), and renders the scene
// into a file, or runs one of the other modes (app/): probe single rays, print a pixel's ray
// tree, compare two images. Errors are values until they reach main, which prints one line
// `ray: MESSAGE` and exits with 2 (bad usage or input) or 3 (I/O).
#include "app/app.h"
#include "fast/fast.h" // fast/: the scene committed into blocks and a BVH, searched faster

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <new>
#include <sys/stat.h>

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

static double SecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// What an image of shapes that no eye ray met is: the background alone, and what may be wrong.
static const char *kNoHitWarning =
    "warning: no eye ray met a shape: the image is the background alone (is the camera turned "
    "away, or the scene far larger or smaller than it sees? --stats gives each mesh's bounding "
    "box)";

// A render (or --view) to the output file, which is checked before the render, so a mistake in it
// costs no time. Returns the exit code.
static int RenderToFile(const Options *opt, const Scene *scene, const RenderSettings *settings,
                        const std::string &defaultOutput, const std::string &layoutText,
                        std::chrono::steady_clock::time_point start) {
    std::string output, error;
    int status;
    if (!ChooseOutput(opt, scene, !IsBuiltIn(opt->scene), defaultOutput, &output, &status))
        return status;
    WarnOfRender(opt, scene, settings);
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
    bool shapes = !scene->spheres.empty() || !scene->triangles.empty(); // (else said before)
    if (!opt->view && stats.primary > 0 && stats.primaryHits == 0 && shapes)
        Complain(kNoHitWarning);
    if (opt->stats) {
        fprintf(stderr, "%s\n", layoutText.c_str());
        PrintMeshes(scene);
        PrintStats(&stats, settings, threads, renderSeconds, SecondsSince(start));
    }
    return 0;
}

// The scene the command line names, read and checked against the options, its warnings said.
// False: it cannot be drawn, and the reason is said.
static bool LoadCheckedScene(Options *opt, Scene *scene, std::string *defaultOutput) {
    std::string error, warning;
    if (!LoadScene(opt->scene, scene, defaultOutput, &error)) {
        Complain(error);
        return false;
    }
    for (const std::string &w : scene->warnings)
        Complain(w);
    if (!CheckScreenCameraSize(opt, scene, &error, &warning)) {
        Complain(error);
        return false;
    }
    if (!warning.empty())
        Complain(warning);
    return true;
}

// --version: rt's, and which form of fast/'s search (its kernels) this build and processor run.
static void PrintVersion() { printf("%s\nkernels: %s\n", kVersion, KernelName()); }

// The speed machinery, for the robust tests only (the handouts' methods are the plain loop, as
// written): the scene committed, its BVH built on as many threads as the render runs on (two at
// most), and its accelerator installed in the scene, *layout holding them for as long as the
// scene is searched. Returns what it is, for --stats.
static std::string CommitFast(const Options *opt, const RenderSettings *settings, Scene *scene,
                              SceneLayout *layout) {
    static_assert(LAYOUT_PLAIN == kPlainLayout, "--layout's words in LayoutChoice's order");
    auto commitStart = std::chrono::steady_clock::now();
    if (settings->methods.triangle == TRIANGLE_WATERTIGHT &&
        settings->methods.sphere == SPHERE_STABLE)
        CommitScene(scene, (LayoutChoice)opt->layout, settings->threads, layout);
    return DescribeLayout(scene, layout, SecondsSince(commitStart));
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
        if (opt.help)
            fputs(UsageText().c_str(), stdout);
        else
            PrintVersion();
        return 0;
    }
    if (opt.compare)
        return CompareMode(&opt);
    Scene scene;
    if (!LoadCheckedScene(&opt, &scene, &defaultOutput))
        return 2;
    RenderSettings settings = ChosenSettings(&opt, &scene);
    SceneLayout layout;                                                    // fast/: blocks, a BVH
    std::string layoutText = CommitFast(&opt, &settings, &scene, &layout); // fast/: built here
    if (opt.probeRay || !opt.raysFile.empty())
        return ProbeMode(&opt, &scene, &settings);
    if (opt.pixel)
        return PixelTreeMode(&opt, &scene, &settings);
    return RenderToFile(&opt, &scene, &settings, defaultOutput, layoutText, start);
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
