// app/modes.cpp -- the program's modes besides a render (--compare, --ray and --rays, --pixel),
// what it checks of a screen camera's size, and what it reports (--stats, warnings).
#include "app.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

void Complain(const std::string &message) {
    fprintf(stderr, "ray: %s\n", PrintableLine(message).c_str());
}

int CompareMode(const Options *opt) {
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
    if (!d.worst.empty())
        printf("worst pixels (x y: first image, second image):\n");
    for (const PixelDifference &p : d.worst)
        printf("  %d %d: %d %d %d, %d %d %d\n", p.x, p.y, p.a[0], p.a[1], p.a[2], p.b[0], p.b[1],
               p.b[2]);
    if (!opt->output.empty() && !WriteImage(opt->output.c_str(), &heat, &error)) {
        Complain(error);
        return 3;
    }
    return d.pixelsOver > 0 ? 1 : 0;
}

int ProbeMode(const Options *opt, const Scene *scene, const RenderSettings *settings) {
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
    // From a pipe or a terminal, each answer goes out as its line is read: the program at the
    // other end may wait for it before it writes the next line. From a file, they are buffered.
    bool answerEachLine = fstat(fileno(file), &info) != 0 || !S_ISREG(info.st_mode);
    int status = 0;
    std::string line, error;
    for (int lineNumber = 1;; lineNumber++) {
        LineStatus read = ReadTextLine(file, lineNumber, &line, &error);
        if (read == LINE_END)
            break;
        if (read == LINE_BAD || lineNumber == INT_MAX) { // not text (no line after this one can
            // be trusted either), or line numbers past what an int holds: an endless file
            Complain(opt->raysFile + ":" + std::to_string(lineNumber) + ": " +
                     (read == LINE_BAD ? error : "too many lines"));
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
        if (answerEachLine)
            fflush(stdout);
        if (ferror(stdout)) { // no one reads the answers any more, or the disk is full
            Complain(std::string("standard output: ") + strerror(errno));
            return 3;
        }
    }
    if (!fromStdin)
        fclose(file);
    return status;
}

int PixelTreeMode(const Options *opt, const Scene *scene, const RenderSettings *settings) {
    if (opt->pixelX >= settings->width || opt->pixelY >= settings->height) {
        fprintf(stderr, "ray: --pixel: (%d, %d) is outside the %dx%d image\n", opt->pixelX,
                opt->pixelY, settings->width, settings->height);
        return 2;
    }
    printf("%s\n", PixelTreeJson(scene, settings, opt->pixelX, opt->pixelY).c_str());
    return 0;
}

// --size refused (false, *error), or the scene's own size warned of (true, *warning), when the
// pixels of a screen camera would not be square; the message names a size that fits. Where none
// does (a screen 2 units wide and 1e-6 high), --size is only warned of too: refusing every size
// would leave no way to render the scene at another one. A screen whose edges are not at right
// angles (ScreenIsSheared) has parallelograms for pixels, whose
// sides the size can still make equal. A probe of single rays (--ray, --rays) draws no image:
// nothing to check.
bool CheckScreenCameraSize(const Options *opt, const Scene *scene, std::string *error,
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

std::string OneColourWarning(const Scene *scene) {
    if (scene->spheres.empty() && scene->triangles.empty())
        return "the scene has no shapes: every pixel is the background colour";
    color b = scene->background;
    bool anyEmit = false; // (a material that emits, whether or not a shape uses it)
    for (const Material &m : scene->materials)
        anyEmit = anyEmit || Emits(&m);
    bool unlit = scene->shading == SHADING_PATH ? !anyEmit : scene->ambientLight == 0;
    bool shines = false; // (a light of intensity 0 0 0 lights nothing)
    for (const Light &light : scene->lights)
        shines = shines || Shines(&light);
    if (!shines && unlit && b.x == 0 && b.y == 0 && b.z == 0)
        return scene->shading == SHADING_PATH
                   ? "nothing gives off light (no light that shines, no material that emits, a "
                     "black background): every pixel is black"
                   : "no light that shines, ambient 0 and a black background: every pixel is "
                     "black";
    return "";
}

void PrintMeshes(const Scene *scene) {
    for (const MeshRange &m : scene->meshes) {
        vec3 lo = {kInfinity, kInfinity, kInfinity}, hi = -lo;
        bool smooth = false;
        for (size_t t = m.first; t < m.first + m.count; t++) {
            const Triangle *tri = &scene->triangles[t];
            for (vec3 p : {tri->a, tri->b, tri->c})
                lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)},
                hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
            smooth = smooth || (t < scene->cornerNormals.size() &&
                                MaxComponent(scene->cornerNormals[t].a) > 0);
        }
        vec3 size = hi - lo;
        fprintf(stderr,
                "mesh %s: %zu triangles%s, box (%.6g %.6g %.6g) to (%.6g %.6g %.6g), size %.6g x "
                "%.6g x %.6g\n",
                m.path.c_str(), m.count, smooth ? ", smooth" : "", (double)lo.x, (double)lo.y,
                (double)lo.z, (double)hi.x, (double)hi.y, (double)hi.z, (double)size.x,
                (double)size.y, (double)size.z);
    }
}

void PrintStats(const RayStats *s, const RenderSettings *settings, int threads,
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
    const char *names[] = {" shadows",  " reflection",   " refraction", " specular",
                           " indirect", " antialiasing", " defocus",    " fuzz"};
    bool used[] = {s->shadow > 0,
                   s->reflection > 0,
                   s->refraction > 0,
                   s->specularTerms > 0,
                   s->diffuse > 0,
                   settings->samplesPerPixel > 1,
                   settings->effects.defocus && s->primary > 0, // (every eye ray, on the lens)
                   settings->effects.fuzz && s->reflection > 0};
    for (int k = 0; k < 8; k++)
        if (used[k])
            effects += names[k];
    fprintf(stderr, "effects: %s\n", effects.empty() ? "none" : effects.c_str() + 1);
}

// ---- a screen camera's shape ----------------------------------------------------------------

bool ScreenCameraIsValid(const Camera *c, std::string *error) {
    vec3 h = SafeNormalize(c->horizontal), v = SafeNormalize(c->vertical), hxv = Cross(h, v);
    // |h x v| of the unit edges is the sine of their angle, known only to a few roundings: each
    // unit vector's components are within about 2 u of the exact ones (4 u for the two), and
    // the products and the subtraction add 3 u: 7 u, taken as 8. Below that the edges may as
    // well be parallel (their screen has no height that rounding can tell from none: every row
    // of pixels would be the same)
    vec3 normal = SafeNormalize(hxv);
    if (!(Length(hxv) > 8 * kUnitRoundoff) || !IsFinite(normal)) {
        *error = "the edges h and v must be non-zero and not parallel";
        return false;
    }
    vec3 toCorner = c->lowerLeft - c->eye;
    if (!IsFinite(Abs(toCorner) + Abs(c->horizontal) + Abs(c->vertical))) {
        *error = "the screen is so large that a pixel's direction would overflow";
        return false;
    }
    if (!(std::fabs(Dot(normal, SafeNormalize(toCorner))) > 0)) {
        *error = "the eye lies on the screen's plane (or is too far from it to subtract), so no "
                 "ray can pass through the screen";
        return false;
    }
    return true;
}

// A screen camera's edges fix its shape, so the image must keep it, or the pixels would not be
// square and spheres would come out as eggs: W : H must be |h| : |v| to within 1 part in 256
// (less than a pixel's width across 256 pixels). A perspective or lookat camera adapts its
// screen to the image instead.
bool SquarePixels(double W, double H, double h, double v) {
    double longer = std::max(h, v); // (edges of 1e308 rescaled first: W v would overflow)
    if (longer > 0 && std::isfinite(longer))
        h /= longer, v /= longer;
    return std::fabs(W * v - H * h) <= (W * v + H * h) / 512;
}

// A size that keeps the screen's pixels square: `width` wide, or, when no whole height fits that
// width (a 3 x 1 screen 100 pixels wide would need 33.3 rows), the nearest width that has one
// (99, with 33 rows; 33 x 24 asked of a 4 x 3 screen gives 32 x 24). A width's height is the
// nearest whole one, or the limit where that is beyond it (within 1 part in 256, the limit
// itself may fit). False when no size within the limit (16384) fits.
bool SquareSize(int width, double h, double v, int *W, int *H) {
    const int kMaxSide = 16384; // as --size and `size` allow
    for (int away = 0; away < kMaxSide; away++)
        for (int w : {width - away, width + away}) { // (the narrower first)
            double exact = w * (v / h); // (v / h first: w v may overflow where v / h does not)
            int height = exact >= kMaxSide ? kMaxSide : std::max(1, (int)std::lround(exact));
            if (w >= 1 && w <= kMaxSide && SquarePixels(w, height, h, v)) {
                *W = w, *H = height;
                return true;
            }
        }
    return false;
}

// The cosine of the edges' angle above 1/256, the tolerance SquarePixels allows the proportions:
// a pixel's corner more than about a quarter of a degree from a right angle. (SafeNormalize:
// edges of 1e-310 or 1e300 have the angle they have at 1.)
bool ScreenIsSheared(const Camera *camera) {
    vec3 h = SafeNormalize(camera->horizontal), v = SafeNormalize(camera->vertical);
    return std::fabs(Dot(h, v)) > real(1) / 256;
}

// ---- a render's output and warnings ---------------------------------------------------------

bool ChooseOutput(const Options *opt, const Scene *scene, bool sceneIsFile,
                  const std::string &defaultOutput, std::string *output, int *status) {
    *output = opt->output.empty() ? defaultOutput : opt->output;
    if (opt->view && opt->output.empty()) // beside the image, not over it
        *output = defaultOutput.substr(0, defaultOutput.size() - 4) + "_" +
                  ViewName(opt->viewKind) + ".png";
    std::vector<std::string> inputs;
    if (sceneIsFile)
        inputs.push_back(opt->scene);
    inputs.insert(inputs.end(), scene->meshFiles.begin(), scene->meshFiles.end());
    std::string error;
    if (CheckOutputPath(*output, inputs, status, &error))
        return true;
    Complain(error);
    return false;
}

void WarnOfRender(const Options *opt, const Scene *scene, const RenderSettings *settings) {
    if (opt->view) // a debug view shows what the rays found, lit or not
        return;
    std::string flat = OneColourWarning(scene);
    if (!flat.empty())
        Complain("warning: " + flat);
    Ray centre; // where the eye rays start: the eye, or under the slides' rays the screen
    GetCameraRay(&settings->camera, settings->width, settings->height,
                 {real(0.5) * settings->width, real(0.5) * settings->height}, &centre);
    for (const std::string &inside : InsideWarnings(scene, centre.origin))
        Complain("warning: " + inside);
}

// ---- the render's settings -------------------------------------------------------------

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

RenderSettings ChosenSettings(const Options *opt, const Scene *scene) {
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
    settings.path = {(Estimator)opt->estimator,
                     (ScatterMethod)opt->scatter,
                     (LightMethod)opt->lights,
                     opt->roulette == 1,
                     opt->seed,
                     (SphereSampling)opt->sphereLamps};
    settings.progress = isatty(2) ? ShowProgress : nullptr; // (a line drawn in place: a terminal's)
    PlanRender(scene, &settings);
    return settings;
}
