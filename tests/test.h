// tests/test.h -- rt's own small test harness (no framework: the design card allows none).
//
// CHECK(cond, why) and CHECK_NEAR(actual, expected, tolerance, why) count a pass or print the
// failure with its file and line; `why` says what was predicted and how. main (test_main.cpp)
// runs every test group and ends with the line `N passed, M failed`.
#ifndef RT_TEST_H
#define RT_TEST_H

#include "../render.h"

#include <string>

// Records one check; prints `file:line: FAILED why (detail)` when it fails.
void TestCheck(bool ok, const char *file, int line, const std::string &why,
               const std::string &detail);
std::string DescribeNear(double actual, double expected, double tolerance);

#define CHECK(cond, why) TestCheck((cond), __FILE__, __LINE__, (why), #cond)
#define CHECK_NEAR(actual, expected, tolerance, why)                                               \
    do {                                                                                           \
        double a_ = (actual), e_ = (expected), t_ = (tolerance);                                   \
        TestCheck(std::fabs(a_ - e_) <= t_, __FILE__, __LINE__, (why), DescribeNear(a_, e_, t_));  \
    } while (0)

// Relative tolerance for values computed in `real` by a few operations: 64 ulps of the build's
// precision, so the same predictions hold in the double and the float test program.
const double kRelTol = 64 * std::numeric_limits<real>::epsilon();

// Tiny deterministic generator for the randomised checks (tests own their state).
struct TestRng {
    uint64_t state;
};
inline real Uniform(TestRng *rng) { // in [0, 1)
    rng->state = rng->state * 6364136223846793005ULL + 1442695040888963407ULL;
    return real((rng->state >> 40) * (1.0 / 16777216.0));
}

// A default render configuration for tests: the scene's size, 1 spp, its depth, one thread, the
// path tracer's defaults.
RenderSettings TestSettings(const Scene *scene);

// A matte material of colour kd, and a mirror reflecting the fraction k (test_shade.cpp).
Material Matte(const char *name, color kd);
Material Mirror(const char *name, real k);

// Two numbers, or two vectors, bit for bit; and every field of two hit records, bit for bit (the
// struct has padding, so not memcmp).
bool SameBits(real a, real b);
bool SameBits(vec3 a, vec3 b);
bool SameHit(const RayHit &a, const RayHit &b);

// The share of pixels whose channels all lie within 2/255 of the other image's (same size).
double ShareAlike(const Image &a, const Image &b);

// The program under test for command-line checks: $RAY, or ./ray (./ray_float in the float build).
// RayPath: the same as an absolute path, for commands run in another directory.
std::string RayProgram();
std::string RayPath();

// A fresh directory /tmp/rt-NAME-XXXXXX for a group's program tests, checked; "" if none could be
// made (the group then returns). RemoveTestDir deletes it with its contents, checked.
std::string MakeTestDir(const char *name);
void RemoveTestDir(const std::string &dir);

// A whole file's bytes ("" if it cannot be read).
std::string ReadFile(const std::string &path);

// Runs `RayProgram() ARGS` in directory dir, standard output to dir/out.txt, standard error
// returned in *stderrText; returns the exit status (-1 if it did not exit normally).
int RunRay(const std::string &dir, const std::string &args, std::string *stderrText);

// RunRay after a command that pipes into it: `PIPE ray ARGS` (PIPE: nothing, or a command and
// `|`).
int RunRayAfter(const std::string &dir, const std::string &pipe, const std::string &args,
                std::string *stderrText);

// Whether a file exists and can be read; what the last RunRay wrote to standard output.
bool FileExists(const std::string &path);
std::string ReadOutput(const std::string &dir);

// `ray --compare`, in the test directory TestProgram makes (test_compare.cpp).
void TestCompare(const std::string &dir);

// The test groups, one per file.
void TestGeometry();
void TestTriangles();
void TestShading();
void TestCamera();
void TestAssignmentImage();
void TestSceneFiles();
void TestText();
void TestProbes();
void TestProgram();
void TestCorpus();
void TestEffects();
void TestHardCases();
void TestStability();
void TestLongTriangles();
void TestRanges();
void TestFiles();
void TestMethods();
void TestLayout();
void TestWide();
void TestSmooth();
void TestSmoothWalls();
void TestSpheres();
void TestPacket();
void TestPath();
void TestMesh();
void TestMeshRays();
void TestLeaks();
void TestHandout();
void TestLens();
void TestFuzz();

// The handouts' steps checked as their debugging advice puts it (test_handout.cpp), a group a
// step, named as a starter kit's stubs.list names the function a student writes; `needs`, the
// earlier steps its checks go through (space-separated).
struct HandoutGroup {
    const char *name;
    void (*run)();
    const char *needs;
};

// One check of a handout step: the prediction, what came out, the likely cause. rt's harness
// (test_main.cpp) prints the three; a kit's (kit_main.cpp) blames an earlier step that fails.
void TestAdvice(bool ok, const char *file, int line, const std::string &should,
                const std::string &got, const std::string &cause);
extern const HandoutGroup kHandoutGroups[];
extern const int kHandoutGroupCount;

#endif
