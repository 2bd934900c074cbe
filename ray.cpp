// ray.cpp -- the program: reads the command line, builds the scene, renders, writes the PNG.
//
// `ray [SCENE] [options]`, as pinned in SPEC.md section 2. Errors are values until they reach
// main, which prints one line `ray: MESSAGE` and exits with 2 (bad usage or input) or 3 (I/O).
#include "ray.h"

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>

static const char *kVersion = "rt 0.1.0";

static const char *kUsage =
    "usage: ray [SCENE] [options]\n"
    "\n"
    "SCENE is `default` (the assignment scene, also when omitted) or `test` (rt's own scene).\n"
    "\n"
    "options:\n"
    "  -o FILE                  output PNG (default: reference.png for default, test.png for "
    "test)\n"
    "  --size W[xH]             image size in pixels, 1..16384 (H defaults to W)\n"
    "  --spp N                  samples per pixel on a regular grid, 1..65536 (default 1)\n"
    "  --depth N                most rays in one chain, primary included, 1..1000 (default 10)\n"
    "  --threads N              worker threads, 1..1024 (default: all hardware threads)\n"
    "  --triangle watertight|cramer\n"
    "                           ray/triangle method: Woop-Benthin-Wald (default) or the\n"
    "                           handout's Cramer's rule\n"
    "  --stats                  print time, rays by kind, Mrays/s and the effects used to stderr\n"
    "  --help, --version        this text; the version\n";

// What the command line asks for; zero means "not given, use the scene's or the default".
struct Options {
    const char *scene = "default";
    const char *output = nullptr;
    int width = 0, height = 0, spp = 1, depth = 0, threads = 0;
    TriangleMethod triangleMethod = TRIANGLE_WATERTIGHT;
    bool stats = false, help = false, version = false;
};

// Reads a whole decimal integer in [lo, hi]; anything else is an error naming the option.
static bool ParseInt(const char *text, int lo, int hi, const char *what, int *value,
                     std::string *error) {
    char *end = nullptr;
    errno = 0;
    long v = strtol(text, &end, 10);
    bool whole = end != text && *end == 0 && (*text == '-' || *text == '+' || isdigit(*text));
    if (!whole || errno == ERANGE) {
        *error = std::string(what) + ": not an integer: '" + text + "'";
        return false;
    }
    if (v < lo || v > hi) {
        *error = std::string(what) + " must be between " + std::to_string(lo) + " and " +
                 std::to_string(hi) + ", not " + text;
        return false;
    }
    *value = (int)v;
    return true;
}

// --size W or WxH
static bool ParseSize(const char *text, Options *opt, std::string *error) {
    std::string s = text;
    size_t x = s.find('x');
    std::string w = s.substr(0, x), h = x == std::string::npos ? w : s.substr(x + 1);
    return ParseInt(w.c_str(), 1, 16384, "--size width", &opt->width, error) &&
           ParseInt(h.c_str(), 1, 16384, "--size height", &opt->height, error);
}

static bool ParseOptions(int argc, char **argv, Options *opt, std::string *error) {
    bool sceneGiven = false;
    for (int k = 1; k < argc; k++) {
        std::string a = argv[k];
        // Options that take one value
        const char *needsValue[] = {"-o", "--size", "--spp", "--depth", "--threads", "--triangle"};
        bool takesValue = false;
        for (const char *name : needsValue)
            takesValue = takesValue || a == name;
        if (takesValue && k + 1 >= argc) {
            *error = a + " needs a value";
            return false;
        }
        bool ok = true;
        if (a == "-o")
            opt->output = argv[++k];
        else if (a == "--size")
            ok = ParseSize(argv[++k], opt, error);
        else if (a == "--spp")
            ok = ParseInt(argv[++k], 1, 65536, "--spp", &opt->spp, error);
        else if (a == "--depth")
            ok = ParseInt(argv[++k], 1, 1000, "--depth", &opt->depth, error);
        else if (a == "--threads")
            ok = ParseInt(argv[++k], 1, 1024, "--threads", &opt->threads, error);
        else if (a == "--triangle") {
            std::string m = argv[++k];
            ok = m == "watertight" || m == "cramer";
            opt->triangleMethod = m == "cramer" ? TRIANGLE_CRAMER : TRIANGLE_WATERTIGHT;
            if (!ok)
                *error = "--triangle must be watertight or cramer, not '" + m + "'";
        } else if (a == "--stats")
            opt->stats = true;
        else if (a == "--help" || a == "-h")
            opt->help = true;
        else if (a == "--version")
            opt->version = true;
        else if (a.size() > 1 && a[0] == '-') {
            *error = "unknown option '" + a + "' (see ray --help)";
            return false;
        } else if (sceneGiven) {
            *error = "more than one scene given: '" + std::string(opt->scene) + "' and '" + a + "'";
            return false;
        } else {
            opt->scene = argv[k];
            sceneGiven = true;
        }
        if (!ok)
            return false;
    }
    return true;
}

// Builds the named built-in scene and its default output name.
static bool LoadScene(const char *name, Scene *scene, const char **defaultOutput,
                      std::string *error) {
    if (strcmp(name, "default") == 0) {
        BuildDefaultScene(scene);
        *defaultOutput = "reference.png";
        return true;
    }
    if (strcmp(name, "test") == 0) {
        BuildTestScene(scene);
        *defaultOutput = "test.png";
        return true;
    }
    *error = std::string("unknown scene '") + name + "': this version knows `default` and `test`";
    return false;
}

static void PrintStats(const RayStats *s, const RenderSettings *settings, double renderSeconds,
                       double totalSeconds) {
    uint64_t total = s->primary + s->shadow + s->reflection + s->refraction;
    fprintf(stderr, "image: %dx%d, %d spp, depth %d, %d threads\n", settings->width,
            settings->height, settings->samplesPerPixel, settings->depth, settings->threads);
    fprintf(stderr, "time: render %.4f s, whole process %.4f s\n", renderSeconds, totalSeconds);
    fprintf(stderr, "rays: primary=%llu shadow=%llu reflection=%llu refraction=%llu total=%llu\n",
            (unsigned long long)s->primary, (unsigned long long)s->shadow,
            (unsigned long long)s->reflection, (unsigned long long)s->refraction,
            (unsigned long long)total);
    fprintf(stderr, "speed: %.2f Mrays/s\n", total / renderSeconds / 1e6);
    std::string effects;
    if (s->shadow > 0)
        effects += " shadows";
    if (s->reflection > 0)
        effects += " reflection";
    if (s->refraction > 0)
        effects += " refraction";
    if (settings->samplesPerPixel > 1)
        effects += " antialiasing";
    fprintf(stderr, "effects: %s\n", effects.empty() ? "none" : effects.c_str() + 1);
}

static double SecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int main(int argc, char **argv) {
    auto start = std::chrono::steady_clock::now();
    Options opt;
    std::string error;
    if (!ParseOptions(argc, argv, &opt, &error)) {
        fprintf(stderr, "ray: %s\n", error.c_str());
        return 2;
    }
    if (opt.help || opt.version) {
        fputs(opt.help ? kUsage : kVersion, stdout);
        if (!opt.help)
            fputc('\n', stdout);
        return 0;
    }

    Scene scene;
    const char *defaultOutput = nullptr;
    if (!LoadScene(opt.scene, &scene, &defaultOutput, &error)) {
        fprintf(stderr, "ray: %s\n", error.c_str());
        return 2;
    }
    RenderSettings settings;
    settings.width = opt.width ? opt.width : scene.camera.widthPixels;
    settings.height = opt.height ? opt.height : scene.camera.heightPixels;
    settings.samplesPerPixel = opt.spp;
    settings.depth = opt.depth ? opt.depth : scene.depth;
    unsigned hardware = std::thread::hardware_concurrency();
    settings.threads = opt.threads ? opt.threads : (hardware ? (int)hardware : 1);
    settings.triangleMethod = opt.triangleMethod;
    settings.showProgress = true;

    Image image;
    RayStats stats = {0, 0, 0, 0};
    auto renderStart = std::chrono::steady_clock::now();
    Render(&scene, &settings, &image, &stats);
    double renderSeconds = SecondsSince(renderStart);

    const char *output = opt.output ? opt.output : defaultOutput;
    if (!WritePng(output, &image, &error)) {
        fprintf(stderr, "ray: %s\n", error.c_str());
        return 3;
    }
    if (opt.stats)
        PrintStats(&stats, &settings, renderSeconds, SecondsSince(start));
    return 0;
}
