// tools/grade/set.cpp -- grade-set: writes a reference set (grade.h) for the grader, in rt only.
//
//   grade-set DIR [--seed N] [--steps "get-ray sphere ..."] [--tiny PROGRAM]
//
// For each grading scene (scenes.cpp) of the seed: the scene file; rt's image of it under the
// handouts' methods, drawn by the same code as `ray SCENE --methods handout`; the shape each
// pixel's eye ray meets; and the image the tiny tracer (tests/grade/tiny.cpp) draws with each
// of the scene's bugs. --steps are the steps handed out (stubs.list): the second handout's
// (plane, phong) are graded only when they are among them.
#include "grade.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sys/stat.h>
#include <unistd.h>

// What each known bug is and what to do about it, as the handouts put it, and the step
// (stubs.list's name) whose code holds it. A bug of an optional step is named only when that
// step is handed out.
static const struct {
    const char *name, *steps, *advice;
} kBugs[] = {
    {"upside-down", "get-ray", "the screen is upside down: pixel rows go down the image, the screen's y goes up (y = (H/2 - (j + 0.5)) times the pixel's size)"},
    {"mirrored", "get-ray", "the screen is mirrored left to right: the screen's x grows with the column (x = (i + 0.5 - W/2) times the pixel's size)"},
    {"aspect", "get-ray", "pixels are not square: a pixel's height on the screen is the screen's width over the image's width, as its width is, not over the image's height"},
    {"far-root", "sphere", "the sphere takes the far root of the quadratic: take the least root above tMin"},
    {"sphere-tmin", "sphere", "the sphere test ignores tMin: a ray that leaves a sphere finds it again at t near 0 (acne on spheres); accept a root only if tMin < t < tMax"},
    {"edges", "cramer", "rays slip through the edges triangles share: accept beta >= 0, gamma >= 0 and beta + gamma <= 1, the edges included"},
    {"inside-gamma", "cramer", "the triangle's inside test bounds gamma by 1 - gamma: the bound is beta <= 1 - gamma (beta + gamma <= 1)"},
    {"inside-beta", "cramer", "the triangle's inside test bounds beta by 1 alone: with gamma >= 0, beta <= 1 - gamma"},
    {"cramer-sign", "cramer", "a sign in Cramer's rule: M, t, beta or gamma has a term of the wrong sign; check A..L and each product against the slides"},
    {"t-sign", "cramer plane", "the triangle's t has the wrong sign (a triangle behind the eye is drawn, those before it are not): Cramer's t = -(F (AK - JB) + E (JC - AL) + D (BL - KC)) / M; the plane's t = N.(a - o) / N.d"},
    {"triangle-tmin", "cramer plane", "the triangle test ignores tMin: a ray that leaves a triangle finds it again at t near 0 (acne on triangles); accept t only if tMin < t < tMax"},
    {"plane-axis", "plane", "the plane test always drops z: drop the normal's largest coordinate (y for a floor)"},
    {"plane-order", "plane", "one edge of the plane test is taken the wrong way round: (b - a) x (p - a), (c - b) x (p - b) and (a - c) x (p - c), each against N"},
    {"first-hit", "nearest-hit", "the search keeps the first hit it finds: keep the nearest, passing the nearest t so far as tMax"},
    {"acne", "shadow", "shadow acne: a shadow ray hits the surface it starts on (start it 1e-4 along, or skip that shape)"},
    {"beyond", "shadow", "a shadow ray counts a blocker beyond the light (with D = light - P, only 0 < t < 1 blocks)"},
    {"nl-clamp", "floor", "a light behind the surface takes light away: skip a light with N.L <= 0 (or clamp N.L at 0)"},
    {"l-length", "floor", "L is not of unit length: N.L needs L = (light - P) / |light - P|"},
    {"reflect", "reflect", "the reflection has the wrong sign (R = D - 2 (D.N) N)"},
    {"no-limit", "depth", "no limit on the chain of rays (at most 10 rays in a chain, the 11th black)"},
    {"depth-9", "depth", "the chain of rays ends one ray early: at most depth rays in a chain, the eye's ray the first"},
    {"depth-11", "depth", "the chain of rays goes one ray too far: at most depth rays in a chain, the eye's ray the first"},
    {"phong-view", "phong", "V points the wrong way: it goes from the point toward the eye (V = -D)"},
    {"phong-shadow", "phong", "the highlight shows where the light is hidden: a hidden light adds neither diffuse nor specular"},
    {"phong-tint", "phong", "the highlight takes the surface's colour: ks (R.V)^n is white, added to each channel alike"},
    {"normals", "normals", "normals not turned toward the viewer: a light behind a surface lights its front (if N.D > 0, N = -N)"},
    {"clamp", "clamp", "colours above 1 wrap around: clamp each channel to [0, 1] before it becomes a byte"},
};

// The steps only some courses hand out; the others are graded always.
static bool Optional(const std::string &step) { return step == "plane" || step == "phong"; }

// Whether bug k may be named, with these steps handed out: one of its steps is always graded,
// or handed out.
static bool Offered(int k, const std::string &steps) {
    std::string handedOut = " " + steps + " ", list = kBugs[k].steps;
    for (size_t at = 0; at <= list.size();) {
        size_t end = std::min(list.find(' ', at), list.size());
        std::string step = list.substr(at, end - at);
        if (!Optional(step) || handedOut.find(" " + step + " ") != std::string::npos)
            return true;
        at = end + 1;
    }
    return false;
}

// rt's image of the scene file at path, as `ray PATH --methods handout` draws it, and the shape
// each pixel's eye ray meets (by its line in `text`). False with *error.
static bool DrawReference(const std::string &path, const std::string &text, Image *image,
                          Image *shapes, std::string *error) {
    const char *args[] = {"ray", path.c_str(), "--methods", "handout", "--threads", "1"};
    Options opt;
    Scene scene;
    if (!ParseOptions(6, (char **)args, &opt, error) || !ReadSceneFile(path.c_str(), &scene, error))
        return false;
    RenderSettings settings = ChosenSettings(&opt, &scene);
    settings.progress = nullptr;
    RayStats stats = {};
    Render(&scene, &settings, image, &stats);
    std::vector<int> lines[2]; // the lines of the sphere and triangle statements, in order
    int number = 0;
    for (size_t at = 0; at < text.size(); at = text.find('\n', at) + 1) {
        number++;
        if (text.compare(at, 7, "sphere ") == 0)
            lines[0].push_back(number);
        if (text.compare(at, 9, "triangle ") == 0)
            lines[1].push_back(number);
        if (text.find('\n', at) == std::string::npos)
            break;
    }
    int w = settings.width, h = settings.height;
    *shapes = {w, h, std::vector<uint8_t>((size_t)3 * w * h, 0)};
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            Ray ray;
            RayHit hit;
            GetCameraRay(&settings.camera, w, h, SamplePosition(i, j, 0, 1), &ray);
            if (!FindNearestHit(&scene, settings.methods, &ray, 0, kInfinity, &hit))
                continue;
            const std::vector<int> &of = lines[hit.shape == SHAPE_SPHERE ? 0 : 1];
            int line = hit.index < (int)of.size() ? of[hit.index] : 0;
            uint8_t *p = &shapes->pixels[3 * ((size_t)j * w + i)];
            p[0] = (uint8_t)(line & 255), p[1] = (uint8_t)(line >> 8);
        }
    return true;
}

// Whether the scene's `# reveals:` line names bug k.
static bool Reveals(const std::string &text, int k) {
    std::string first = text.substr(0, text.find('\n')) + " ";
    return first.find(std::string(" ") + kBugs[k].name + " ") != std::string::npos;
}

const int kBugCount = (int)(sizeof kBugs / sizeof kBugs[0]);

// The image the tiny tracer draws of the scene at base.scene with bug k, into base.bug.NAME.png.
static bool DrawBug(const std::string &dir, const std::string &base, int k, const std::string &tiny,
                    Image *image, std::string *error) {
    std::string out = base + ".bug." + kBugs[k].name + ".png";
    RunResult run;
    Limits limits = {60, 1L << 26, 0};
    RunLimited({tiny, "--bug", kBugs[k].name, base + ".scene", "-o", out}, dir, &limits, &run);
    if (run.end == RUN_EXITED && run.status == 0 && ReadImage(out.c_str(), image, error))
        return true;
    *error = tiny + " --bug " + kBugs[k].name + " did not draw " + base + ".scene: " +
             (run.end == RUN_NOT_STARTED ? run.why : run.output);
    return false;
}

// Whether two images of a scene look alike to the grader (as a pass would count them).
static bool Alike(const Image *a, const Image *b) {
    ImageDifference d;
    Image heat;
    return CompareImages(a, b, kTolerance, &d, &heat) &&
           d.pixelsOver <= (long)a->width * a->height / kPassRatio;
}

// One scene of the set: its file, rt's image and shapes, and the images of the bugs it reveals;
// *line is its scenes.txt line, `NAME BUG BUG=OTHER,OTHER ...`: each bug the scene is made to
// show, with the other known bugs that draw this scene alike (so the grader names them too).
static bool WriteScene(const std::string &dir, const GradingScene *g, const std::string &steps,
                       const std::string &tiny, std::string *line, std::string *error) {
    std::string base = dir + "/" + g->name;
    Image reference, shapes, images[kBugCount];
    if (!WriteTextFile(base + ".scene", g->text, error) ||
        !DrawReference(base + ".scene", g->text, &reference, &shapes, error) ||
        !WriteImage((base + ".png").c_str(), &reference, error) ||
        !WriteImage((base + ".shapes.png").c_str(), &shapes, error))
        return false;
    *line = g->name;
    for (int k = 0; k < kBugCount; k++)
        if (Offered(k, steps) && !DrawBug(dir, base, k, tiny, &images[k], error))
            return false;
    for (int k = 0; k < kBugCount; k++) {
        if (!Offered(k, steps) || !Reveals(g->text, k)) {
            unlink((base + ".bug." + kBugs[k].name + ".png").c_str());
            continue;
        }
        *line += std::string(" ") + kBugs[k].name;
        char separator = '=';
        for (int other = 0; other < kBugCount; other++)
            if (other != k && Offered(other, steps) && Alike(&images[k], &images[other]))
                *line += separator + std::string(kBugs[other].name), separator = ',';
    }
    return true;
}

// *path made absolute (it must exist). False with errno.
static bool Absolute(std::string *path) {
    char resolved[PATH_MAX];
    if (!realpath(path->c_str(), resolved))
        return false;
    *path = resolved;
    return true;
}

static int Usage() {
    fputs("usage: grade-set DIR [--seed N] [--steps \"STEP ...\"] [--tiny PROGRAM]\n", stderr);
    return 2;
}

int main(int argc, char **argv) {
    if (argc < 2)
        return Usage();
    std::string dir = argv[1], steps, tiny = "build/tiny", error;
    unsigned long seed = 0;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--seed") == 0)
            seed = strtoul(argv[i + 1], nullptr, 10);
        else if (strcmp(argv[i], "--steps") == 0)
            steps = argv[i + 1];
        else if (strcmp(argv[i], "--tiny") == 0)
            tiny = argv[i + 1];
        else
            return Usage();
    }
    if (argc % 2 != 0)
        return Usage();
    mkdir(dir.c_str(), 0777);
    if (!Absolute(&dir) || !Absolute(&tiny)) { // (the tiny tracer runs in the set's folder)
        fprintf(stderr, "grade-set: %s: %s\n", dir.c_str(), strerror(errno));
        return 2;
    }
    std::string scenesTxt, bugsTxt;
    for (const GradingScene &g : MakeGradingScenes(seed)) {
        bool offered = false;
        for (int k = 0; k < kBugCount; k++)
            offered = offered || (Reveals(g.text, k) && Offered(k, steps));
        if (!offered)
            continue; // (a scene of an optional step not handed out)
        std::string line;
        if (!WriteScene(dir, &g, steps, tiny, &line, &error)) {
            fprintf(stderr, "grade-set: %s\n", error.c_str());
            return 2;
        }
        scenesTxt += line + "\n";
    }
    for (const auto &b : kBugs)
        bugsTxt += std::string(b.name) + " " + b.advice + "\n";
    if (!WriteTextFile(dir + "/scenes.txt", scenesTxt, &error) ||
        !WriteTextFile(dir + "/bugs.txt", bugsTxt, &error)) {
        fprintf(stderr, "grade-set: %s\n", error.c_str());
        return 3;
    }
    return 0;
}
