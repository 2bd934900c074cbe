// ray.cpp -- the program: reads the command line, loads the scene, and renders it, probes it or
// compares two images.
//
// `ray [SCENE] [options]`, as pinned in SPEC.md section 2. Errors are values until they reach
// main, which prints one line `ray: MESSAGE` and exits with 2 (bad usage or input) or 3 (I/O).
#include "ray.h"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <new>
#include <sys/stat.h>
#include <thread>

static const char *kVersion = "rt 0.2.0";

static const char *kUsage =
    "usage: ray [SCENE] [options]\n"
    "\n"
    "SCENE is `default` (the assignment scene, also when omitted), `test` (rt's own scene)\n"
    "or the path of a scene file (see the README for the format).\n"
    "\n"
    "rendering:\n"
    "  -o FILE                  output image, .png or .ppm (default: reference.png for default, "
    "test.png for\n"
    "                           test, NAME.png for a file NAME.scene)\n"
    "  --size W[xH]             image size in pixels, 1..16384 (H defaults to W)\n"
    "  --spp N                  samples per pixel, 1..65536 (default 1: the pixel centre)\n"
    "  --aa grid|jitter|adaptive\n"
    "                           where the samples go: a regular grid (default), one random\n"
    "                           point per grid cell, or 5 first (centre and corners) and N\n"
    "                           only where those differ (N > 5; up to 5 it is jitter)\n"
    "  --depth N                most rays in one chain, primary included, 1..1000 (default 10)\n"
    "  --threads N              worker threads, 1..1024 (default: all hardware threads)\n"
    "  --triangle watertight|cramer\n"
    "                           ray/triangle method: Woop-Benthin-Wald (default) or the\n"
    "                           handout's Cramer's rule\n"
    "  --sphere stable|textbook ray/sphere method: Ray Tracing Gems ch. 7 (default) or the\n"
    "                           textbook quadratic, kept only to show what it gets wrong\n"
    "  --view normal|depth|id|cost|shadow\n"
    "                           draw a debug view instead of the lit image (default output:\n"
    "                           the image's name with _VIEW added, e.g. reference_normal.png)\n"
    "  --stats                  print time, rays by kind, Mrays/s and the effects used to stderr\n"
    "\n"
    "probing (prints JSON, renders nothing):\n"
    "  --ray OX OY OZ DX DY DZ  the nearest hit of one ray\n"
    "  --rays FILE              the nearest hit of every line `OX OY OZ DX DY DZ` (- = stdin)\n"
    "  --pixel X Y              the tree of rays behind pixel (X, Y)\n"
    "\n"
    "comparing:\n"
    "  --compare A.png B.png    RMSE, PSNR, largest difference, pixels over the tolerance;\n"
    "                           -o FILE writes a heat map; exit 0 within tolerance, 1 outside\n"
    "  --tolerance T            largest channel difference (0..255) still counted equal (0)\n"
    "\n"
    "  --help, --version        this text; the version\n";

// What the command line asks for; zero or empty means "not given".
struct Options {
    std::string scene = "default", output;
    int width = 0, height = 0, spp = 1, depth = 0, threads = 0;
    int sampling = 0;  // --aa: grid, jitter, adaptive, in SampleMethod's order
    int methodSet = 0; // --methods: robust, handout
    int sphere = -1, triangle = -1, selfHit = -1, cameraRay = -1, fresnel = -1; // -1: from the set
    real epsilon = 0; // --self-hit epsilon=E
    bool stats = false, help = false, version = false;
    bool probeRay = false, pixel = false, view = false, compare = false;
    real probe[6];
    int pixelX = 0, pixelY = 0;
    ViewKind viewKind = VIEW_NORMAL;
    std::string raysFile, compareA, compareB;
    double tolerance = 0;
};

// Reads a whole number in [lo, hi] (ParseWholeNumber); an error names the option.
static bool ParseInt(const char *text, int lo, int hi, const char *what, int *value,
                     std::string *error) {
    if (ParseWholeNumber(text, lo, hi, value, error))
        return true;
    *error = std::string(what) + ": " + *error;
    return false;
}

// --size W or WxH
static bool ParseSize(const char *text, Options *opt, std::string *error) {
    std::string s = text;
    size_t x = s.find('x');
    std::string w = s.substr(0, x), h = x == std::string::npos ? w : s.substr(x + 1);
    return ParseInt(w.c_str(), 1, 16384, "--size width", &opt->width, error) &&
           ParseInt(h.c_str(), 1, 16384, "--size height", &opt->height, error);
}

// One option with its values v[0..]; false with *error if a value is bad.
// One word of a list: *index is its position. "--sphere must be stable or textbook, not 'x'".
static bool ParseChoice(const std::string &option, const std::string &word,
                        std::initializer_list<const char *> words, int *index, std::string *error) {
    int k = 0;
    std::string list;
    for (const char *w : words) {
        if (word == w) {
            *index = k;
            return true;
        }
        list += (k == 0 ? "" : k + 1 == (int)words.size() ? " or " : ", ") + std::string(w);
        k++;
    }
    *error = option + " must be " + list + ", not '" + word + "'";
    return false;
}

// `--self-hit bound|epsilon[=E]|skip`; E is a distance in world units, > 0 (default 1e-4).
static bool ParseSelfHit(const std::string &word, Options *opt, std::string *error) {
    size_t equals = word.find('=');
    std::string name = word.substr(0, equals);
    if (!ParseChoice("--self-hit", name, {"bound", "epsilon", "skip"}, &opt->selfHit, error))
        return false;
    if (equals == std::string::npos)
        return true;
    real e;
    if (name != "epsilon" || !ParseReal(word.substr(equals + 1), &e, error) || !(e > 0)) {
        *error =
            "--self-hit: only epsilon takes a value, a distance > 0, as in epsilon=1e-3 (not '" +
            word + "')";
        return false;
    }
    opt->epsilon = e;
    return true;
}

// The methods the options choose: the set (--methods), then each single-method option given.
static Methods ChosenMethods(const Options *opt) {
    Methods m = opt->methodSet == 1 ? kHandoutMethods : kRobustMethods;
    if (opt->sphere >= 0)
        m.sphere = (SphereMethod)opt->sphere;
    if (opt->triangle >= 0)
        m.triangle = (TriangleMethod)opt->triangle;
    if (opt->selfHit >= 0)
        m.selfHit = (SelfHitMethod)opt->selfHit;
    if (opt->epsilon > 0)
        m.epsilon = opt->epsilon;
    if (opt->cameraRay >= 0)
        m.cameraRay = (CameraRayMethod)opt->cameraRay;
    if (opt->fresnel >= 0)
        m.fresnel = (FresnelMethod)opt->fresnel;
    return m;
}

static bool ParseOption(const std::string &a, char **v, Options *opt, std::string *error) {
    if (a == "-o")
        opt->output = v[0];
    else if (a == "--size")
        return ParseSize(v[0], opt, error);
    else if (a == "--spp")
        return ParseInt(v[0], 1, 65536, "--spp", &opt->spp, error);
    else if (a == "--depth")
        return ParseInt(v[0], 1, 1000, "--depth", &opt->depth, error);
    else if (a == "--threads")
        return ParseInt(v[0], 1, 1024, "--threads", &opt->threads, error);
    else if (a == "--aa")
        return ParseChoice(a, v[0], {"grid", "jitter", "adaptive"}, &opt->sampling, error);
    else if (a == "--methods")
        return ParseChoice(a, v[0], {"robust", "handout"}, &opt->methodSet, error);
    else if (a == "--sphere")
        return ParseChoice(a, v[0], {"stable", "textbook"}, &opt->sphere, error);
    else if (a == "--triangle")
        return ParseChoice(a, v[0], {"watertight", "cramer", "plane"}, &opt->triangle, error);
    else if (a == "--camera-ray")
        return ParseChoice(a, v[0], {"eye", "slides"}, &opt->cameraRay, error);
    else if (a == "--fresnel")
        return ParseChoice(a, v[0], {"exact", "schlick"}, &opt->fresnel, error);
    else if (a == "--self-hit")
        return ParseSelfHit(v[0], opt, error);
    else if (a == "--view") {
        opt->view = FindView(v[0], &opt->viewKind);
        if (!opt->view) {
            *error =
                std::string("--view must be normal, depth, id, cost or shadow, not '") + v[0] + "'";
            return false;
        }
    } else if (a == "--ray") {
        opt->probeRay = true;
        for (int k = 0; k < 6; k++)
            if (!ParseReal(v[k], &opt->probe[k], error)) {
                *error = "--ray: " + *error;
                return false;
            }
        if (opt->probe[3] == 0 && opt->probe[4] == 0 && opt->probe[5] == 0) {
            *error = "--ray: direction is zero";
            return false;
        }
    } else if (a == "--rays")
        opt->raysFile = v[0];
    else if (a == "--pixel") {
        opt->pixel = true;
        return ParseInt(v[0], 0, 16383, "--pixel X", &opt->pixelX, error) &&
               ParseInt(v[1], 0, 16383, "--pixel Y", &opt->pixelY, error);
    } else if (a == "--compare") {
        opt->compare = true;
        opt->compareA = v[0];
        opt->compareB = v[1];
    } else if (a == "--tolerance") {
        real t;
        if (!ParseReal(v[0], &t, error) || !(t >= 0 && t <= 255)) {
            *error = std::string("--tolerance must be a number from 0 to 255, not '") + v[0] + "'";
            return false;
        }
        opt->tolerance = t;
    }
    return true;
}

static bool ParseOptions(int argc, char **argv, Options *opt, std::string *error) {
    static const struct {
        const char *name;
        int values;
    } kOptions[] = {{"-o", 1},        {"--size", 1},      {"--spp", 1},        {"--depth", 1},
                    {"--threads", 1}, {"--aa", 1},        {"--triangle", 1},   {"--sphere", 1},
                    {"--methods", 1}, {"--self-hit", 1},  {"--camera-ray", 1}, {"--fresnel", 1},
                    {"--view", 1},    {"--ray", 6},       {"--rays", 1},       {"--pixel", 2},
                    {"--compare", 2}, {"--tolerance", 1}, {"--stats", 0},      {"--help", 0},
                    {"-h", 0},        {"--version", 0}};
    bool sceneGiven = false;
    std::string seen; // the options given so far, each between spaces
    for (int k = 1; k < argc; k++) {
        std::string a = argv[k];
        int values = -1;
        for (const auto &o : kOptions)
            if (a == o.name)
                values = o.values;
        if (values < 0 && a.size() > 1 && a[0] == '-') {
            *error = "unknown option '" + a + "' (see ray --help)";
            return false;
        }
        if (values < 0) { // the scene
            if (sceneGiven) {
                *error = "more than one scene given: '" + opt->scene + "' and '" + a + "'";
                return false;
            }
            opt->scene = a;
            sceneGiven = true;
            continue;
        }
        if (seen.find(" " + a + " ") != std::string::npos) {
            *error = a + " given twice";
            return false;
        }
        seen += " " + a + " ";
        if (k + values >= argc) {
            *error = a + " needs " + std::to_string(values) + " value" + (values > 1 ? "s" : "");
            return false;
        }
        opt->stats = opt->stats || a == "--stats";
        opt->help = opt->help || a == "--help" || a == "-h";
        opt->version = opt->version || a == "--version";
        if (!ParseOption(a, argv + k + 1, opt, error))
            return false;
        k += values;
    }
    if (seen.find(" --tolerance ") != std::string::npos && !opt->compare) {
        *error = "--tolerance goes with --compare";
        return false;
    }
    int modes = opt->probeRay + !opt->raysFile.empty() + opt->pixel + opt->compare + opt->view;
    if (modes > 1) {
        *error = "choose one of --ray, --rays, --pixel, --view and --compare";
        return false;
    }
    if (!opt->output.empty() && (opt->probeRay || opt->pixel || !opt->raysFile.empty())) {
        *error = "-o goes with a render, --view or --compare; probes print to standard output";
        return false;
    }
    return true;
}

// Loads the named built-in scene or a scene file, and picks the default output name.
static bool LoadScene(const std::string &name, Scene *scene, std::string *defaultOutput,
                      std::string *error) {
    if (name == "default") {
        BuildDefaultScene(scene);
        *defaultOutput = "reference.png";
        return true;
    }
    if (name == "test") {
        BuildTestScene(scene);
        *defaultOutput = "test.png";
        return true;
    }
    std::string base = name.substr(name.find_last_of('/') + 1); // NAME.png for path/NAME.scene
    size_t dot = base.find_last_of('.');
    *defaultOutput = (dot == std::string::npos || dot == 0 ? base : base.substr(0, dot)) + ".png";
    return ReadSceneFile(name.c_str(), scene, error);
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
    const char *names[] = {" shadows", " reflection", " refraction", " specular", " antialiasing"};
    bool used[] = {s->shadow > 0, s->reflection > 0, s->refraction > 0, s->specularTerms > 0,
                   settings->samplesPerPixel > 1};
    for (int k = 0; k < 5; k++)
        if (used[k])
            effects += names[k];
    fprintf(stderr, "effects: %s\n", effects.empty() ? "none" : effects.c_str() + 1);
}

static double SecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// --compare: prints the difference, writes the heat map if -o was given. Returns the exit code.
static int Compare(const Options *opt) {
    Image a, b, heat;
    std::string error;
    int status;
    if (!opt->output.empty() &&
        !CheckOutputPath(opt->output, {opt->compareA, opt->compareB}, &status, &error)) {
        fprintf(stderr, "ray: %s\n", error.c_str());
        return status;
    }
    if (!ReadPng(opt->compareA.c_str(), &a, &error) ||
        !ReadPng(opt->compareB.c_str(), &b, &error)) {
        fprintf(stderr, "ray: %s\n", error.c_str());
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
        fprintf(stderr, "ray: %s\n", error.c_str());
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
        fprintf(stderr, "ray: %s: is a directory, not a file of rays\n", opt->raysFile.c_str());
        return 2;
    }
    FILE *file = fromStdin ? stdin : fopen(opt->raysFile.c_str(), "rb");
    if (!file) {
        fprintf(stderr, "ray: %s: %s\n", opt->raysFile.c_str(), strerror(errno));
        return 2;
    }
    int status = 0;
    std::string line, error;
    for (int lineNumber = 1;; lineNumber++) {
        LineStatus read = ReadTextLine(file, lineNumber, &line, &error);
        if (read == LINE_END)
            break;
        if (read == LINE_BAD) { // not text: no line after this one can be trusted either
            fprintf(stderr, "ray: %s:%d: %s\n", opt->raysFile.c_str(), lineNumber, error.c_str());
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
    }
    if (!fromStdin)
        fclose(file);
    return status;
}

static int Run(int argc, char **argv) {
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
    if (opt.compare)
        return Compare(&opt);

    Scene scene;
    std::string defaultOutput;
    if (!LoadScene(opt.scene, &scene, &defaultOutput, &error)) {
        fprintf(stderr, "ray: %s\n", error.c_str());
        return 2;
    }
    RenderSettings settings;
    settings.width = opt.width ? opt.width : scene.width;
    settings.height = opt.height ? opt.height : scene.height;
    settings.samplesPerPixel = opt.spp;
    settings.sampling = (SampleMethod)opt.sampling;
    settings.depth = opt.depth ? opt.depth : scene.depth;
    unsigned hardware = std::thread::hardware_concurrency();
    settings.threads = opt.threads ? opt.threads : (hardware ? (int)hardware : 1);
    settings.methods = ChosenMethods(&opt);
    settings.showProgress = true;
    PlanRender(&scene, &settings);

    if (opt.probeRay || !opt.raysFile.empty())
        return Probe(&opt, &scene, &settings);
    if (opt.pixel) {
        if (opt.pixelX >= settings.width || opt.pixelY >= settings.height) {
            fprintf(stderr, "ray: --pixel: (%d, %d) is outside the %dx%d image\n", opt.pixelX,
                    opt.pixelY, settings.width, settings.height);
            return 2;
        }
        printf("%s\n", PixelTreeJson(&scene, &settings, opt.pixelX, opt.pixelY).c_str());
        return 0;
    }

    // The output is checked before the render, so a mistake in it costs no time. A debug view is
    // written beside the image, not over it: reference_normal.png
    if (opt.view && opt.output.empty())
        defaultOutput = defaultOutput.substr(0, defaultOutput.size() - 4) + "_" +
                        ViewName(opt.viewKind) + ".png";
    std::string output = opt.output.empty() ? defaultOutput : opt.output;
    std::vector<std::string> inputs;
    if (opt.scene != "default" && opt.scene != "test")
        inputs.push_back(opt.scene);
    int status;
    if (!CheckOutputPath(output, inputs, &status, &error)) {
        fprintf(stderr, "ray: %s\n", error.c_str());
        return status;
    }

    Image image;
    RayStats stats = {0, 0, 0, 0, 0};
    auto renderStart = std::chrono::steady_clock::now();
    if (opt.view)
        RenderView(&scene, &settings, opt.viewKind, &image);
    else
        Render(&scene, &settings, &image, &stats);
    double renderSeconds = SecondsSince(renderStart);

    if (!WriteImage(output.c_str(), &image, &error)) {
        fprintf(stderr, "ray: %s\n", error.c_str());
        return 3;
    }
    if (opt.stats)
        PrintStats(&stats, &settings, renderSeconds, SecondsSince(start));
    return 0;
}

// An allocation that fails (a scene of millions of shapes under a memory limit, an image of
// 16384 x 16384 on a small machine) is an error message and exit 2, never an abort.
int main(int argc, char **argv) {
    try {
        return Run(argc, argv);
    } catch (const std::bad_alloc &) {
        fprintf(stderr, "ray: out of memory\n");
        return 2;
    }
}
