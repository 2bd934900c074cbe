// tests/test_main.cpp -- the harness: counts checks, prints failures, runs every group.
#include "../render.h"
#include "test.h"

#include <cstring>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

static int passedChecks = 0, failedChecks = 0; // the harness's own tally, not the renderer's

void TestCheck(bool ok, const char *file, int line, const std::string &why,
               const std::string &detail) {
    if (ok) {
        passedChecks++;
        return;
    }
    failedChecks++;
    printf("%s:%d: FAILED %s (%s)\n", file, line, why.c_str(), detail.c_str());
}

void TestAdvice(bool ok, const char *file, int line, const std::string &should,
                const std::string &got, const std::string &cause) {
    TestCheck(ok, file, line, should + "; " + got + (cause.empty() ? "" : ": " + cause), "handout");
}

std::string DescribeNear(double actual, double expected, double tolerance) {
    char text[160];
    snprintf(text, sizeof text, "got %.17g, expected %.17g within %.3g", actual, expected,
             tolerance);
    return text;
}

std::string MakeTestDir(const char *name) {
    std::string pattern = std::string("/tmp/rt-") + name + "-XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back(0);
    const char *dir = mkdtemp(buffer.data());
    CHECK(dir != nullptr, std::string("a temporary directory for the ") + name + " tests");
    return dir ? dir : "";
}

void RemoveTestDir(const std::string &dir) {
    CHECK(system(("rm -rf '" + dir + "'").c_str()) == 0, "temporary directory removed");
}

RenderSettings TestSettings(const Scene *scene) {
    RenderSettings s;
    s.width = scene->width;
    s.height = scene->height;
    s.samplesPerPixel = 1;
    s.sampling = SAMPLES_GRID;
    s.depth = scene->depth;
    s.threads = 1;
    s.methods = kRobustMethods;
    s.progress = nullptr;
    s.path = {}; // the path tracer's defaults (cosine sampling, MIS, roulette, seed 0)
    PlanRender(scene, &s);
    return s;
}

bool SameBits(real a, real b) { return memcmp(&a, &b, sizeof a) == 0; }
bool SameBits(vec3 a, vec3 b) {
    return SameBits(a.x, b.x) && SameBits(a.y, b.y) && SameBits(a.z, b.z);
}
bool SameHit(const RayHit &a, const RayHit &b) {
    return SameBits(a.t, b.t) && SameBits(a.point, b.point) && SameBits(a.normal, b.normal) &&
           a.frontFace == b.frontFace && a.material == b.material && a.shape == b.shape &&
           a.index == b.index && SameBits(a.pointError, b.pointError) &&
           SameBits(a.awayShare, b.awayShare);
}

// The share of pixels whose channels all lie within 2/255 of the other image's.
double ShareAlike(const Image &a, const Image &b) {
    long alike = 0, pixels = (long)a.width * a.height;
    for (long p = 0; p < pixels; p++) {
        int largest = 0;
        for (int c = 0; c < 3; c++)
            largest = std::max(largest, std::abs(a.pixels[3 * p + c] - b.pixels[3 * p + c]));
        alike += largest <= 2;
    }
    return (double)alike / pixels;
}

std::string RayProgram() {
    const char *fromEnvironment = getenv("RAY");
    if (fromEnvironment && *fromEnvironment)
        return fromEnvironment;
#ifdef RT_FLOAT
    return "./ray_float";
#else
    return "./ray";
#endif
}

// Every group of checks, by the name `run_tests NAME...` runs it under.
static const struct {
    const char *name;
    void (*run)();
} kGroups[] = {
    {"geometry", TestGeometry},
    {"triangles", TestTriangles},
    {"shading", TestShading},
    {"camera", TestCamera},
    {"assignment_image", TestAssignmentImage},
    {"effects", TestEffects},
    {"hard_cases", TestHardCases},
    {"stability", TestStability},
    {"long_triangles", TestLongTriangles},
    {"ranges", TestRanges},
    {"files", TestFiles},
    {"methods", TestMethods},
    {"layout", TestLayout},
    {"wide", TestWide},
    {"spheres", TestSpheres},
    {"packet", TestPacket},
    {"path", TestPath},
    {"scene_files", TestSceneFiles},
    {"text", TestText},
    {"mesh", TestMesh},
    {"mesh_rays", TestMeshRays},
    {"smooth", TestSmooth},
    {"smooth_walls", TestSmoothWalls},
    {"leaks", TestLeaks},
    {"handout", TestHandout},
    {"lens", TestLens},
    {"fuzz", TestFuzz},
    {"probes", TestProbes},
    {"program", TestProgram},
    {"corpus", TestCorpus},
};

// True if this process is the first to claim the group in dir: it creates the file dir/name,
// which exists only once however many processes try.
static bool Claim(const char *dir, const char *name) {
    std::string path = std::string(dir) + "/" + name;
    int fd = open(path.c_str(), O_CREAT | O_EXCL | O_WRONLY, 0600);
    if (fd < 0)
        return false;
    close(fd);
    return true;
}

// run_tests: every group; run_tests NAME...: only those (a teacher's or a student's quicker loop);
// run_tests --claim DIR: every group no other process has claimed in DIR (an empty folder), so
// that processes started together with one DIR run every group once between them, each taking
// the next group as it finishes one (`make sanitize` runs one a core).
int main(int argc, char **argv) {
    const char *claims = nullptr;
    int first = 1;
    if (argc == 3 && strcmp(argv[1], "--claim") == 0)
        claims = argv[2], first = argc;
    if (claims && access(claims, W_OK | X_OK) != 0) { // (else every claim fails and nothing runs)
        fprintf(stderr, "run_tests: --claim needs a folder to write in: %s\n", claims);
        return 2;
    }
    for (int k = first; k < argc; k++) {
        bool known = false;
        for (const auto &g : kGroups)
            known = known || strcmp(argv[k], g.name) == 0;
        if (!known) {
            fprintf(stderr, "run_tests: no group '%s'; the groups:", argv[k]);
            for (const auto &g : kGroups)
                fprintf(stderr, " %s", g.name);
            fprintf(stderr, "\n");
            return 2;
        }
    }
    for (const auto &g : kGroups) {
        bool chosen = first == argc && (!claims || Claim(claims, g.name));
        for (int k = first; k < argc; k++)
            chosen = chosen || strcmp(argv[k], g.name) == 0;
        if (chosen)
            g.run();
    }
    printf("%d passed, %d failed\n", passedChecks, failedChecks);
    return failedChecks == 0 ? 0 : 1;
}
