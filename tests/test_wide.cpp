// tests/test_wide.cpp -- the wide tree's own parts (fast/kernel_wide.h, kernel_setup.h), each
// held to what it stands in for.
//
// The search through the tree is held to the plain loop's bits by test_layout.cpp. Here: the
// set-up the search makes for a triangle as it needs it is SetUpTriangle's, to the bit, for
// triangles of every size the docs claim and for the ones the plain set-up treats apart
// (degenerate, scaled, not finite); and the rays the walk treats apart (kernel_wide.h) find what
// the plain loop finds: from so far away that every box is entered, along an axis (1/d
// infinite), and with a component too small for float (that axis not tested).
#include "../fast/fast.h"
#include "robust_scenes.h"
#include "test.h"

#include <cstring>
#include <vector>

static const bool kDouble = sizeof(real) == sizeof(double);

static bool SameBox(const Box &a, const Box &b) {
    return SameBits({a.lo[0], a.lo[1], a.lo[2]}, {b.lo[0], b.lo[1], b.lo[2]}) &&
           SameBits({a.hi[0], a.hi[1], a.hi[2]}, {b.hi[0], b.hi[1], b.hi[2]}) &&
           SameBits(a.size, b.size);
}
static bool SameDoubles(dvec3 a, dvec3 b) {
    return memcmp(&a.x, &b.x, sizeof(double)) == 0 && memcmp(&a.y, &b.y, sizeof(double)) == 0 &&
           memcmp(&a.z, &b.z, sizeof(double)) == 0;
}

// Every field of two set-ups, bit for bit; a triangle without area has no normal to compare.
static bool SameSetUp(const TriangleSetUp &a, const TriangleSetUp &b) {
    bool same = SameBox(a.box, b.box) && a.scale == b.scale && a.normalKnown == b.normalKnown &&
                a.flat == b.flat && a.hasArea == b.hasArea && SameDoubles(a.n, b.n) &&
                SameDoubles(a.nError, b.nError) && SameBits(a.awayShare, b.awayShare);
    return same && (!a.hasArea || SameBits(a.normal, b.normal));
}

// Triangles of sizes 10^-k .. 10^k (random corners around a random centre), and the odd ones.
static std::vector<Triangle> SetUpCases(TestRng *rng) {
    std::vector<Triangle> cases;
    const double scales[] = {1e-300, 1e-30, 1e-6, 1, 1e6, 1e30, 1e300};
    const double floatScales[] = {1e-35, 1e-12, 1e-3, 1, 1e3, 1e12, 1e35};
    auto random = [rng](real s) {
        return vec3{s * (Uniform(rng) - real(0.5)), s * (Uniform(rng) - real(0.5)),
                    s * (Uniform(rng) - real(0.5))};
    };
    for (int k = 0; k < 7; k++) {
        real scale = real(kDouble ? scales[k] : floatScales[k]);
        for (int i = 0; i < 200; i++) {
            vec3 centre = random(i % 2 ? scale : 1000 * scale), size = random(scale);
            real across = i % 3 ? 1 : real(1e-5); // some slivers
            cases.push_back({centre + size, centre - size, centre + across * random(scale), 0});
        }
    }
    const real big = std::numeric_limits<real>::max() / 4, inf = kInfinity, nan = NAN;
    vec3 o = {0, 0, 0}, x = {1, 0, 0}, y = {0, 1, 0};
    cases.push_back({o, x, real(2) * x, 0});                     // corners in a line
    cases.push_back({x, x, x, 0});                               // one point
    cases.push_back({{-big, 0, 0}, {big, 0, 0}, {0, big, 0}, 0}); // edges beyond the range
    cases.push_back({o, {inf, 0, 0}, y, 0});                     // a corner at infinity
    cases.push_back({o, x, {0, nan, 0}, 0});                     // a NaN
    cases.push_back({o, {1e-30f, 0, 0}, {0, 1e-30f, 0}, 0});     // a normal to scale (float)
    return cases;
}

// The kernel's set-up against SetUpTriangle, in both of the kernel's copies.
static void TestSetUpOnDemand() {
    TestRng rng = {77};
    std::vector<Triangle> cases = SetUpCases(&rng);
    int differ = 0;
    for (const Triangle &t : cases)
        for (bool vectors : {false, KernelHasVectors()}) {
            TriangleSetUp plain, made;
            SetUpTriangle(&t, &plain);
            KernelSetUp(&t, vectors, &made);
            differ += !SameSetUp(plain, made);
        }
    CHECK(differ == 0, std::to_string(cases.size()) +
                           " triangles from 1e-300 to 1e300 across (float 1e-35 to 1e35), slivers, "
                           "lines, points, infinite and NaN corners: the search's set-up is "
                           "SetUpTriangle's, every field to the bit");
}

// The nearest hit and any hit of each ray, through the tree and by the plain loop, bit for bit.
static int TreeDifferences(const Scene &scene, const std::vector<Ray> &rays) {
    Scene plain = scene, tree = scene;
    plain.accelerator = nullptr;
    SceneLayout layout;
    CommitScene(&tree, LAYOUT_BVH, 1, &layout);
    int differ = 0;
    for (const Ray &ray : rays) {
        RayHit a, b;
        bool foundA = FindNearestHit(&plain, kRobustMethods, &ray, 0, kInfinity, &a);
        bool foundB = FindNearestHit(&tree, kRobustMethods, &ray, 0, kInfinity, &b);
        differ += foundA != foundB || (foundA && !SameHit(a, b)) ||
                  AnyHit(&plain, kRobustMethods, &ray, 0, kInfinity) !=
                      AnyHit(&tree, kRobustMethods, &ray, 0, kInfinity);
    }
    return differ;
}

// A closed sphere mesh of radius 1 at the origin, and rays at each corner of some of its
// triangles: from 1e13 of its size away (beyond the walk's 2^40: every box entered), along the
// axes from inside and outside (1/d infinite on two axes), and with one component 1e-20 of the
// others (below the walk's 2^-40: that axis not tested).
static void TestRaysTheWalkTreatsApart() {
    Scene ball = WallScene();
    AddOctasphere(&ball, {0, 0, 0}, 1, 3); // 512 triangles
    std::vector<Ray> far, axes, thin;
    real away = real(kDouble ? 1e13 : 1e12); // (float: still beyond 2^40 of the sphere's size)
    for (size_t i = 0; i < ball.triangles.size(); i += 7) {
        vec3 c = ball.triangles[i].a, from = {away, real(0.5) * away, real(0.25) * away};
        far.push_back({from, c - from});
        from = real(1e-4) * from; // (and from within 2^40: boxes widened by the far origin's pad)
        far.push_back({from, c - from});
        thin.push_back({{c.x, real(-3), c.z}, {real(1e-20), 1, real(1e-20) * c.z}});
    }
    for (real s : {real(-1), real(1)})
        for (vec3 d : {vec3{1, 0, 0}, vec3{0, 1, 0}, vec3{0, 0, 1}}) {
            axes.push_back({{0, 0, 0}, s * d});
            axes.push_back({real(-3) * s * d, s * d});
            axes.push_back({real(-3) * s * d + vec3{real(0.1), real(0.2), real(0.05)}, s * d});
        }
    CHECK(TreeDifferences(ball, far) == 0,
          "rays from 1e13 (float 1e12) of a sphere's size away, walked without boxes, and from "
          "1e9 (1e8): the plain loop's hits, bit for bit");
    CHECK(TreeDifferences(ball, axes) == 0,
          "rays along the axes (1/d infinite on two axes), from inside and outside: the plain "
          "loop's hits, bit for bit");
    CHECK(TreeDifferences(ball, thin) == 0,
          "rays with components 1e-20 of the largest (those axes not tested by the walk): the "
          "plain loop's hits, bit for bit");
}

void TestWide() {
    TestSetUpOnDemand();
    TestRaysTheWalkTreatsApart();
}
