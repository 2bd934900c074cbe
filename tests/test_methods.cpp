// tests/test_methods.cpp -- the course's own methods, beside the robust ones.
//
// `--methods handout` is what a careful student writes from the course documents: the textbook
// sphere quadratic, Cramer's rule, a fixed epsilon against self-hits, the slides' GetRay,
// Schlick's Fresnel. At scale 1 it must draw essentially rt's image; where it fails, the failure
// must be the method's own (which hard cases it gets wrong, acne far from the origin, lost
// contact shadows at small scale, glass under the skip rule), and these tests hold each to it.
#include "../app/app.h"
#include "../render.h"
#include "hard_cases.h"
#include "robust_scenes.h"
#include "test.h"

#include <algorithm>
#include <cstdio>

static const bool kDouble = sizeof(real) == sizeof(double);

static Image RenderWith(const Scene *scene, Methods methods, int size) {
    RenderSettings settings = TestSettings(scene);
    settings.width = settings.height = size;
    settings.methods = methods;
    PlanRender(scene, &settings);
    Image image;
    RayStats stats = {};
    Render(scene, &settings, &image, &stats);
    return image;
}

// Which hard-case rows each handout pair fails, asserted, so that a change in either is noticed:
// the far small spheres and the near root of a big one (the quadratic), shared edges and vertices
// (Cramer's rule and the plane test round each triangle's edges their own way), and with Cramer
// also the tiny far triangle (its determinant) and a vertex fan.
static void TestHandoutHardCases() {
    struct {
        const char *name;
        TriangleRoutine triangle;
        const char *fails;
    } pairs[] = {{"textbook + Cramer", IntersectTriangleCramer,
                  kDouble ? "SPH-1 SPH-2 SPH-3 SPH-4 SPH-5 TRI-6 TRI-8 TRI-9 TRI-11"
                          : "SPH-3 TRI-7 TRI-8 TRI-10 TRI-11"},
                 {"textbook + plane", IntersectTrianglePlane,
                  kDouble ? "SPH-1 SPH-2 SPH-3 SPH-4 SPH-5 TRI-6 TRI-11" : "SPH-3 TRI-7 TRI-11"}};
    for (const auto &pair : pairs) {
        std::vector<HardCaseResult> results;
        RunHardCases(IntersectSphereTextbook, pair.triangle, &results);
        std::string failed;
        for (const HardCaseResult &r : results)
            if (!r.passed)
                failed += (failed.empty() ? "" : " ") + r.id;
        CHECK(failed == pair.fails,
              std::string(pair.name) + " fails exactly " + pair.fails + " (got: " + failed + ")");
    }
}

// The handout set at scale 1 on the three bundled scenes: the assignment image alike in every
// pixel (double; float but for one or two); the test scene but for a few dozen pixels where rays
// meet shared edges (cracks); the effects gallery but for its glass, where Schlick's approximation
// is not the exact Fresnel term (3% of the pixels; with the exact term, alike there too).
static void TestHandoutSetAtScaleOne() {
    Scene scenes[3];
    BuildDefaultScene(&scenes[0]);
    BuildTestScene(&scenes[1]);
    std::string error;
    bool read = ReadSceneFile("scenes/effects.scene", &scenes[2], &error);
    const char *names[] = {"assignment", "test", "effects"};
    const double needed[] = {0.9995, 0.999, 0.97};
    Methods exactFresnel = kHandoutMethods;
    exactFresnel.fresnel = FRESNEL_EXACT;
    for (int k = 0; k < (read ? 3 : 2); k++) {
        Image robust = RenderWith(&scenes[k], kRobustMethods, 256);
        double share = ShareAlike(robust, RenderWith(&scenes[k], kHandoutMethods, 256));
        char what[160];
        snprintf(what, sizeof what, "the handout set on the %s scene at 256 x 256: %.3f%% alike",
                 names[k], 100 * share);
        CHECK(share >= needed[k], what);
        if (k == 2) {
            share = ShareAlike(robust, RenderWith(&scenes[k], exactFresnel, 256));
            snprintf(what, sizeof what, "... with the exact Fresnel term: %.3f%% alike",
                     100 * share);
            CHECK(share >= 0.999, what);
        }
    }
    CHECK(read, "scenes/effects.scene reads");
}

// The test scene 1e13 from the origin (float: 1e4). There the hit points' own rounding (a
// double's spacing at 1e13 is 0.002) is larger than a fixed epsilon of 1e-4: shadow and
// reflection rays re-hit the spheres and the triangles beside the one they leave, and pixels go
// dark (acne). The error-bound offset draws the scene as it is at the origin.
static void TestEpsilonAcneFarAway() {
    real shift = kDouble ? real(1e13) : real(1e4);
    Scene test, far;
    BuildTestScene(&test);
    test.width = test.height = 64;
    far = TransformedScene(test, 1, {shift, -shift, shift});
    Methods epsilon = kRobustMethods;
    epsilon.selfHit = SELF_HIT_EPSILON;
    Image reference = RenderWith(&test, kRobustMethods, 64);
    double bound = ShareAlike(reference, RenderWith(&far, kRobustMethods, 64));
    double fixed = ShareAlike(reference, RenderWith(&far, epsilon, 64));
    char what[200];
    snprintf(what, sizeof what,
             "the test scene %g from the origin: the bound offset draws %.1f%% of it as at the "
             "origin, epsilon 1e-4 only %.1f%% (acne)",
             (double)shift, 100 * bound, 100 * fixed);
    CHECK(bound >= 0.99 && fixed < bound - 0.01, what);
}

// A ball of radius 3e-5 resting on a floor, the light straight above: the floor beside the
// contact point, under the ball's side, is in its shadow. A fixed epsilon of 1e-4 is more than
// the ball's whole size: shadow rays start past it and the shadow is lost. The bound offset
// keeps it.
static void TestEpsilonLosesSmallShadows() {
    real r = real(3e-5);
    Scene s = WallScene();
    s.lights.push_back({{0, 1, 0}, {1, 1, 1}});
    s.spheres.push_back({{0, r, 0}, r, 0});
    s.triangles = {{{-1, 0, -1}, {1, 0, 1}, {1, 0, -1}, 0},
                   {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, 0}};
    Methods epsilon = kRobustMethods;
    epsilon.selfHit = SELF_HIT_EPSILON;
    bool shadowed[2];
    for (int k = 0; k < 2; k++) {
        RenderSettings settings = TestSettings(&s);
        settings.methods = k ? epsilon : kRobustMethods;
        PlanRender(&s, &settings);
        TraceLog log = {RayStats{}, nullptr, -1, 0};
        // from the side, low, onto the floor at x = 0.9 r, under the ball's flank
        vec3 target = {real(0.9) * r, 0, 0}, from = {1, real(0.1) * r, 0};
        Ray ray = {from, target - from};
        color c = TraceRay(&s, &settings, RAY_PRIMARY, &ray, &kNoSelfHit, RayChain{1, 1}, &log);
        shadowed[k] = std::fabs(c.x - s.ambientLight) < real(1e-3);
    }
    CHECK(shadowed[0] && !shadowed[1],
          "beside a ball of radius 3e-5: the bound offset keeps its shadow, epsilon 1e-4 loses it");
}

// The second handout's rule, skip the shape the ray leaves, cannot see glass from inside: the ray
// refracted into a sphere must meet the same sphere to leave it.
static void TestSkipCannotSeeGlassFromInside() {
    Scene s = WallScene();
    Material glass = s.materials[0];
    glass.name = "glass";
    glass.ior = real(1.5);
    s.materials.push_back(glass);
    s.spheres.push_back({{0, 0, -5}, 1, 1});
    for (int k = 0; k < 2; k++) {
        RenderSettings settings = TestSettings(&s);
        settings.methods.selfHit = k ? SELF_HIT_SKIP : SELF_HIT_BOUND;
        PlanRender(&s, &settings);
        std::vector<RayNode> tree;
        TraceLog log = {RayStats{}, &tree, -1, 0};
        Ray ray = {{0, real(0.3), 0}, {0, 0, -1}};
        TraceRay(&s, &settings, RAY_PRIMARY, &ray, &kNoSelfHit, RayChain{1, 1}, &log);
        bool leavesFromInside = false;
        for (const RayNode &n : tree)
            leavesFromInside =
                leavesFromInside || (n.kind == RAY_REFRACTION && n.found &&
                                     n.record.shape == SHAPE_SPHERE && !n.record.frontFace);
        CHECK(
            leavesFromInside == (k == 0),
            k ? "under --self-hit skip the refracted ray never meets the sphere it is inside"
              : "under --self-hit bound the refracted ray meets the sphere's far side from inside");
    }
}

// Under skip, the shape the ray leaves is passed over, and only it: a ray that enters sphere 1
// toward sphere 0 finds sphere 0, its record intact, although sphere 1's far side, later in the
// list, is nearer; likewise a ray leaving triangle 1 finds triangle 0.
static void TestSkipPassesOverOneShape() {
    Scene s = WallScene();
    s.spheres = {{{0, 0, -10}, 1, 0}, {{0, 0, 0}, 1, 0}};
    s.triangles = {{{-1, -1, -10}, {1, -1, -10}, {0, 1, -10}, 0},
                   {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, 0}};
    Methods skip = kRobustMethods;
    skip.selfHit = SELF_HIT_SKIP;
    for (ShapeKind kind : {SHAPE_SPHERE, SHAPE_TRIANGLE}) {
        Scene one = s;
        if (kind == SHAPE_SPHERE)
            one.triangles.clear();
        else
            one.spheres.clear();
        RayHit from;
        from.shape = kind, from.index = 1;
        // the sphere's near side, the ray going in: its far side, at t = 2, is nearer than
        // sphere 0 at t = 10, and must not be taken
        from.point = kind == SHAPE_SPHERE ? vec3{0, 0, 1} : vec3{0, 0, 0};
        from.normal = {0, 0, 1}, from.pointError = {0, 0, 0};
        Ray ray;
        SelfHit start;
        LeaveSurface(&one, skip, &from, {0, 0, -1}, &ray, &start);
        RayHit hit;
        bool found = FindNearestHitFrom(&one, skip, &ray, &start, kInfinity, &hit);
        CHECK(found && hit.shape == kind && hit.index == 0 && hit.t > 7,
              std::string("--self-hit skip passes over the ") +
                  (kind == SHAPE_SPHERE ? "sphere" : "triangle") +
                  " it leaves and finds the one behind it, index 0");
    }
}

// The slides' GetRay: the ray starts at the pixel's point on the screen and has unit length, so
// t is the distance from the screen. The assignment's centre pixel meets the mirror sphere at
// z = -14 (t = 7 from the eye with the unnormalised vector to a screen 2 away, 12 from the screen).
static void TestSlidesGetRay() {
    Scene scene;
    BuildDefaultScene(&scene);
    RenderSettings settings = TestSettings(&scene);
    settings.methods = kHandoutMethods;
    PlanRender(&scene, &settings);
    Ray ray;
    GetCameraRay(&settings.camera, settings.width, settings.height, SamplePosition(256, 256, 0, 1),
                 &ray);
    RayHit hit;
    bool found = FindNearestHit(&scene, settings.methods, &ray, 0, kInfinity, &hit);
    CHECK(ray.origin.z == -2 && std::fabs(Length(ray.dir) - 1) <= 4 * kRelTol,
          "the slides' GetRay starts on the screen (z = -2) with a unit direction");
    CHECK(found, "the centre pixel's slides ray meets the sphere");
    if (found)
        CHECK_NEAR(hit.t, 12.000104907690215, 1e-4, "t = 12.0001, the distance from the screen");
}

// Schlick's approximation: R0 = ((1 - eta) / (1 + eta))^2 = 0.04 for glass of index 1.5 head-on,
// 1 at grazing incidence and under total internal reflection.
static void TestSchlick() {
    CHECK_NEAR(SchlickReflectance(1, 1 / real(1.5)), 0.04, 1e-6, "Schlick head-on: R0 = 0.04");
    CHECK_NEAR(SchlickReflectance(0, 1 / real(1.5)), 1, 1e-6, "Schlick at grazing incidence: 1");
    CHECK(SchlickReflectance(real(0.1), real(1.5)) == 1, "Schlick under total internal reflection");
}

void TestMethods() {
    TestHandoutHardCases();
    TestHandoutSetAtScaleOne();
    TestEpsilonAcneFarAway();
    TestEpsilonLosesSmallShadows();
    TestSkipCannotSeeGlassFromInside();
    TestSkipPassesOverOneShape();
    TestSlidesGetRay();
    TestSchlick();
}
