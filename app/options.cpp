// app/options.cpp -- the command line: `ray [SCENE] [options]`, as the README describes it.
//
// A table of the options and how many values each takes, a parser per value kind, and the
// checks of what goes together. Nothing here prints; main does (ray.cpp).
#include "app.h"

#include <cstring>
#include <vector>

const char *kVersion = "rt 0.2.0";

// --help's text, in three parts: the options before the numerical methods', theirs (a starter
// kit has the handouts' alone), and the options after.
static const char *kUsageStart =
    "usage: ray [SCENE] [options]\n"
    "\n"
    "SCENE is `default` (the assignment scene, also when omitted), `test` (rt's own scene)\n"
    "or the path of a scene file (README.md and docs/scene-format.md give the format).\n"
    "\n"
    "rendering:\n"
    "  -o FILE                  output image, .png or .ppm (default: reference.png for\n"
    "                           default, test.png for test, NAME.png for a file NAME.scene)\n"
    "  --size W[xH]             image size in pixels, 1..16384 (H defaults to W)\n"
    "  --spp N                  samples per pixel, 1..65536 (default 1: the pixel centre)\n"
    "  --aa grid|jitter|adaptive\n"
    "                           where the samples go: a regular grid (default), one random\n"
    "                           point per grid cell, or 5 first (centre and corners) and N\n"
    "                           only where those differ (N > 5; up to 5 it is jitter; with\n"
    "                           shading path, 16 random pilots, then up to N: path-tracing.md)\n"
    "  --depth N                most rays in one chain, primary included, 1..1000 (default 10)\n"
    "  --threads N              worker threads, 1..1024 (default: all hardware threads)\n";

static const char *kMethodsUsage =
    "  --methods robust|handout the numerical methods: rt's robust ones (default), or what a\n"
    "                           student following the course documents writes (the slides'\n"
    "                           GetRay, textbook sphere, Cramer, --self-hit epsilon, Schlick);\n"
    "                           the options below override one part of either set\n"
    "  --sphere stable|textbook ray/sphere: Ray Tracing Gems ch. 7, or the slide's A, B, C\n"
    "  --triangle watertight|cramer|plane\n"
    "                           ray/triangle: Woop-Benthin-Wald with the plane's t, the\n"
    "                           assignment's Cramer's rule, or the second handout's test\n"
    "  --self-hit bound|epsilon[=E]|skip\n"
    "                           rays leaving a surface: start off it by the hit point's error\n"
    "                           bound, ignore hits closer than E (1e-4), or skip the shape\n"
    "  --camera-ray eye|slides  primary rays from the eye, or from the screen with unit length\n"
    "  --fresnel exact|schlick  how much glass reflects\n"
    "  --layout auto|list|bvh|plain\n"
    "                           how the robust tests search the shapes: blocks, with a BVH\n"
    "                           from 32 triangles on (auto, default), one list of blocks, a\n"
    "                           BVH, or the plain loop over the shapes; the answers are the same\n";

static const char *kUsageEnd =
    "  --estimator full|journal `shading path`: rt's estimator (default: the options below), or\n"
    "                           the journal's, as Ray Tracing in One Weekend writes it\n"
    "  --scatter cosine|uniform `shading path`: diffuse directions drawn by cos(theta) (default)\n"
    "                           or uniformly over the hemisphere\n"
    "  --lights mis|nee|none    `shading path`: how emitting shapes are found: sampled and\n"
    "                           combined with scattered rays by MIS (default), sampled only, or\n"
    "                           only hit by chance (point lights are always sampled)\n"
    "  --roulette on|off        `shading path`: Russian roulette ends dim paths (default, "
    "unbiased)\n"
    "                           or only --depth does (biased)\n"
    "  --sphere-lamps cone|area `shading path`: points on a glowing sphere drawn in the cone it\n"
    "                           is seen in (default), or uniformly over its area\n"
    "  --seed N                 another seed draws other random numbers (0): `shading path`,\n"
    "                           a lens's points, fuzzy mirrors' directions\n"
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
    "  --compare A.png B.png    RMSE, PSNR, largest difference, pixels over the tolerance\n"
    "                           (PNG or PPM images); -o FILE writes a heat map; exit 0 within\n"
    "                           tolerance, 1 outside\n"
    "  --tolerance T            largest channel difference (0..255) still counted equal (0)\n"
    "\n"
    "  --help, --version        this text; the version\n";

std::string UsageText() { return std::string(kUsageStart) + kMethodsUsage + kUsageEnd; }

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

// One word of a list: *index is its position. "--sphere must be stable or textbook, not 'x'".
static bool ParseChoice(const std::string &option, const std::string &word,
                        const std::vector<const char *> &words, int *index, std::string *error) {
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
    if (name != "epsilon") {
        *error = "--self-hit: only epsilon takes a value, as in epsilon=1e-3 (not '" + word + "')";
        return false;
    }
    real e;
    if (!ParseReal(word.substr(equals + 1), &e, error) || !(e > 0)) {
        *error = "--self-hit epsilon=E: E must be a distance > 0 that a number of this build can "
                 "hold, as in epsilon=1e-3 (not '" +
                 word.substr(equals + 1) + "')";
        return false;
    }
    opt->epsilon = e;
    return true;
}

Methods ChosenMethods(const Options *opt) {
    Methods m = opt->methodSet == 1 ? kHandoutMethods : kRobustMethods; // robust/: the default
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

// --ray OX OY OZ DX DY DZ: six finite numbers, the direction not zero.
static bool ParseProbe(char **v, Options *opt, std::string *error) {
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
    return true;
}

// --tolerance T: a number from 0 to 255. One too small to be anything but 0 (1e-400) is 0:
// channel differences are whole numbers, so it counts the same pixels as 0 does.
static bool ParseTolerance(const char *text, Options *opt, std::string *error) {
    real t = 0;
    if (!TooSmallForNumber(text) && (!ParseReal(text, &t, error) || !(t >= 0 && t <= 255))) {
        *error = std::string("--tolerance must be a number from 0 to 255, not '") + text + "'";
        return false;
    }
    opt->tolerance = t;
    return true;
}

// The options that choose one word of a list, and where the choice goes.
struct ChoiceOption {
    const char *name;
    std::vector<const char *> words;
    int Options::*field;
};
static const ChoiceOption kChoices[] = {
    {"--aa", {"grid", "jitter", "adaptive"}, &Options::sampling},
    {"--methods", {"robust", "handout"}, &Options::methodSet},
    {"--layout", {"auto", "list", "bvh", "plain"}, &Options::layout},
    {"--estimator", {"full", "journal"}, &Options::estimator},
    {"--scatter", {"cosine", "uniform"}, &Options::scatter},
    {"--lights", {"mis", "nee", "none"}, &Options::lights},
    {"--roulette", {"on", "off"}, &Options::roulette},
    {"--sphere-lamps", {"cone", "area"}, &Options::sphereLamps},
    {"--sphere", {"stable", "textbook"}, &Options::sphere},
    {"--triangle", {"watertight", "cramer", "plane"}, &Options::triangle},
    {"--camera-ray", {"eye", "slides"}, &Options::cameraRay},
    {"--fresnel", {"exact", "schlick"}, &Options::fresnel}};

// One option with its values v[0..]; false with *error if a value is bad.
static bool ParseOption(const std::string &a, char **v, Options *opt, std::string *error) {
    for (const ChoiceOption &c : kChoices)
        if (a == c.name)
            return ParseChoice(a, v[0], c.words, &(opt->*c.field), error);
    if (a == "-o") {
        opt->output = v[0];
        if (opt->output.empty()) { // (an empty output is how "no -o" is kept)
            *error = "-o needs a file name, .png or .ppm";
            return false;
        }
    } else if (a == "--size")
        return ParseSize(v[0], opt, error);
    else if (a == "--spp")
        return ParseInt(v[0], 1, 65536, "--spp", &opt->spp, error);
    else if (a == "--depth")
        return ParseInt(v[0], 1, 1000, "--depth", &opt->depth, error);
    else if (a == "--seed")
        return ParseInt(v[0], 0, 1000000000, "--seed", &opt->seed, error);
    else if (a == "--threads")
        return ParseInt(v[0], 1, 1024, "--threads", &opt->threads, error);
    else if (a == "--self-hit")
        return ParseSelfHit(v[0], opt, error);
    else if (a == "--view" && !(opt->view = FindView(v[0], &opt->viewKind))) {
        *error =
            std::string("--view must be normal, depth, id, cost or shadow, not '") + v[0] + "'";
        return false;
    } else if (a == "--ray")
        return ParseProbe(v, opt, error);
    else if (a == "--rays")
        opt->raysFile = v[0];
    else if (a == "--pixel") {
        opt->pixel = true;
        return ParseInt(v[0], 0, 16383, "--pixel X", &opt->pixelX, error) &&
               ParseInt(v[1], 0, 16383, "--pixel Y", &opt->pixelY, error);
    } else if (a == "--compare") {
        opt->compare = true;
        opt->compareA = v[0];
        opt->compareB = v[1];
    } else if (a == "--tolerance")
        return ParseTolerance(v[0], opt, error);
    return true;
}

// Every option and how many values follow it.
static const struct {
    const char *name;
    int values;
} kOptions[] = {{"-o", 1},          {"--size", 1},        {"--spp", 1},
                {"--depth", 1},     {"--threads", 1},     {"--aa", 1},
                {"--triangle", 1},  {"--sphere", 1},      {"--methods", 1},
                {"--self-hit", 1},  {"--camera-ray", 1},  {"--fresnel", 1},
                {"--view", 1},      {"--ray", 6},         {"--rays", 1},
                {"--pixel", 2},     {"--compare", 2},     {"--tolerance", 1},
                {"--stats", 0},     {"--help", 0},        {"-h", 0},
                {"--version", 0},   {"--layout", 1},      {"--scatter", 1},
                {"--lights", 1},    {"--roulette", 1},    {"--seed", 1},
                {"--estimator", 1}, {"--sphere-lamps", 1}};

// Options that would change nothing in the mode chosen are errors, not silently ignored: a probe
// asks about one given ray (no image, no samples, no threads, no camera, nothing it leads to);
// --pixel shows the centre ray's tree (the image's size and the depth matter, the samples do not);
// --compare reads two images; and where the samples go (--aa) only matters when there are several
// (--spp N, N > 1).
static bool CheckUnused(const Options *opt, const std::string &seen, std::string *error) {
    struct Rule {
        bool mode;
        const char *name;
        std::vector<const char *> unused;
    };
    const Rule rules[] = {
        {opt->probeRay || !opt->raysFile.empty(),
         opt->probeRay ? "--ray" : "--rays",
         {"--size", "--spp", "--aa", "--threads", "--depth", "--view", "--stats", "--seed",
          "--scatter", "--lights", "--roulette", "--estimator", "--sphere-lamps", "--self-hit",
          "--camera-ray", "--fresnel"}},
        {opt->pixel, "--pixel", {"--spp", "--aa", "--threads", "--stats"}},
        {opt->view, // one ray through each pixel's centre, on one thread
         "--view",
         {"--spp", "--aa", "--threads", "--seed", "--scatter", "--lights", "--roulette",
          "--estimator", "--sphere-lamps"}},
        // what the eye ray found: no ray leaves a surface, no glass is shaded, no chain follows
        {opt->view && opt->viewKind != VIEW_COST && opt->viewKind != VIEW_SHADOW,
         "--view normal, depth or id",
         {"--self-hit", "--fresnel", "--depth"}},
        {opt->view && opt->viewKind == VIEW_SHADOW, "--view shadow", {"--fresnel", "--depth"}},
        {opt->compare,
         "--compare",
         {"--size", "--spp", "--aa", "--threads", "--depth", "--methods", "--sphere", "--triangle",
          "--self-hit", "--camera-ray", "--fresnel", "--layout", "--stats", "--seed", "--scatter",
          "--lights", "--roulette", "--estimator", "--sphere-lamps"}},
        {opt->spp == 1, "one sample a pixel", {"--aa"}},
    };
    for (const Rule &r : rules) {
        if (!r.mode)
            continue;
        for (const char *option : r.unused)
            if (seen.find(std::string(" ") + option + " ") != std::string::npos) {
                *error = std::string(option) + " changes nothing with " + r.name +
                         (r.mode && r.name[0] == 'o' ? " (give --spp N, N > 1)" : "");
                return false;
            }
    }
    return true;
}

// Whether the methods chosen go with the options given (`seen`, each between spaces): --layout's
// search is for the robust tests; the handouts' run in the plain loop, as written.
static bool CheckMethods(const Options *opt, const std::string &seen, std::string *error) {
    Methods methods = ChosenMethods(opt);
    if (seen.find(" --layout ") != std::string::npos && opt->layout != kPlainLayout &&
        (methods.triangle != TRIANGLE_WATERTIGHT || methods.sphere != SPHERE_STABLE)) {
        *error = "--layout auto, list and bvh go with the robust sphere and triangle tests: the "
                 "handouts' tests run in the plain loop, as written";
        return false;
    }
    return true;
}

// What must not be given together: `seen` lists the options given, each between spaces.
static bool CheckCombinations(const Options *opt, const std::string &seen, std::string *error) {
    if (seen.find(" --tolerance ") != std::string::npos && !opt->compare) {
        *error = "--tolerance goes with --compare";
        return false;
    }
    int modes = opt->probeRay + !opt->raysFile.empty() + opt->pixel + opt->compare + opt->view;
    if (modes > 1) {
        *error = "choose one of --ray, --rays, --pixel, --view and --compare";
        return false;
    }
    if (!CheckMethods(opt, seen, error))
        return false;
    if (!opt->output.empty() && (opt->probeRay || opt->pixel || !opt->raysFile.empty())) {
        *error = "-o goes with a render, --view or --compare; probes print to standard output";
        return false;
    }
    return CheckUnused(opt, seen, error);
}

// The message for an option rt does not know. `--size=64`, the GNU way, is told how rt writes it,
// and a slip of the keyboard the option it may be: the same letters with other dashes, or
// letters a slip away (NearWord).
static std::string UnknownOption(const std::string &a) {
    size_t equals = a.find('=');
    std::string name = a.substr(0, equals);
    for (const auto &o : kOptions)
        if (equals != std::string::npos && name == o.name)
            return "unknown option '" + a + "': write " +
                   (o.values == 0 ? "'" + name + "' alone: it takes no value"
                    : o.values == 1 && equals + 1 < a.size()
                        ? "'" + name + " " + a.substr(equals + 1) + "'"
                        : "'" + name + "' and then " +
                              (o.values > 1 ? "its values, each" : "its value,") +
                              " a word of its own") +
                   " (see ray --help)";
    std::vector<const char *> bare; // the names without their dashes
    for (const auto &o : kOptions)
        bare.push_back(o.name + strspn(o.name, "-"));
    bare.push_back(nullptr);
    size_t dashes = strspn(name.c_str(), "-");
    int near = -1; // the option with these letters and other dashes (-size), or a slip away
    for (int k = 0; bare[k] && dashes > 0; k++)
        near = name.substr(dashes) == bare[k] ? k : near;
    if (near < 0 && dashes > 0)
        near = NearWord(name.substr(dashes), bare.data());
    return "unknown option '" + a + "'" +
           (near < 0 ? "" : ": did you mean '" + std::string(kOptions[near].name) + "'?") +
           " (see ray --help)";
}

bool ParseOptions(int argc, char **argv, Options *opt, std::string *error) {
    bool sceneGiven = false;
    std::string seen; // the options given so far, each between spaces
    for (int k = 1; k < argc; k++) {
        std::string a = argv[k];
        int values = -1;
        for (const auto &o : kOptions)
            if (a == o.name)
                values = o.values;
        if (values < 0 && a.size() > 1 && a[0] == '-') {
            *error = UnknownOption(a);
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
    if (sceneGiven && opt->compare) {
        *error =
            "a scene ('" + opt->scene + "') changes nothing with --compare, which reads two images";
        return false;
    }
    return CheckCombinations(opt, seen, error);
}
