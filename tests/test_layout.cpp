// tests/test_layout.cpp -- the committed scene answers exactly what the plain loop answers.
//
// The fast layout (fast/: commit.cpp, kernel.cpp) promises the very bits of the plain loop (the
// same t, point, normal, error bound and shape), with or without the BVH, in double and in float.
// Each check here asks the same question four ways: the scene as written (the plain loop of
// geometry.cpp, no accelerator), committed as one list of blocks, committed with a BVH, and with
// the BVH through the kernel's other copy, and compares every field of the answers.
#include "../fast/fast.h"
#include "../robust/robust.h"
#include "hard_cases.h"
#include "robust_scenes.h"
#include "test.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

static const bool kDouble = sizeof(real) == sizeof(double);

// The ways to ask: as written, one list of blocks, a BVH, and the BVH again with the kernel's
// other copy (lane by lane where this processor has AVX2, else the same again).
const int kWays = 4;
struct Layouts {
    Scene plain, list, tree, other;
    SceneLayout listLayout, treeLayout, otherLayout;
};
static void MakeLayouts(const Scene &scene, Layouts *l) {
    l->plain = scene, l->list = scene, l->tree = scene, l->other = scene;
    l->plain.accelerator = nullptr; // the plain loop
    CommitScene(&l->list, LAYOUT_LIST, 2, &l->listLayout);
    CommitScene(&l->tree, LAYOUT_BVH, 2, &l->treeLayout);
    CommitScene(&l->other, LAYOUT_BVH, 2, &l->otherLayout);
    l->otherLayout.vectors = false;
}

// One ray asked all four ways, nearest hit and any hit, from the eye and leaving the shape it
// hit (the second handout's skip): false at the first answer that differs.
static bool SameAnswers(const Layouts *l, const Ray *ray, real tMin, real tMax) {
    const Scene *scenes[kWays] = {&l->plain, &l->list, &l->tree, &l->other};
    RayHit hits[kWays];
    bool found[kWays], any[kWays];
    for (int k = 0; k < kWays; k++) {
        found[k] = FindNearestHit(scenes[k], kRobustMethods, ray, tMin, tMax, &hits[k]);
        any[k] = AnyHit(scenes[k], kRobustMethods, ray, tMin, tMax);
    }
    for (int k = 1; k < kWays; k++)
        if (found[k] != found[0] || any[k] != any[0] || (found[0] && !SameHit(hits[k], hits[0])))
            return false;
    if (!found[0] || hits[0].shape != SHAPE_TRIANGLE)
        return true;
    Methods skip = kRobustMethods;
    skip.selfHit = SELF_HIT_SKIP;
    Ray next;
    SelfHit start;
    LeaveSurface(scenes[0], skip, &hits[0], Reflect(ray->dir, hits[0].normal), &next, &start);
    RayHit again[kWays];
    bool foundAgain[kWays];
    for (int k = 0; k < kWays; k++)
        foundAgain[k] = FindNearestHitFrom(scenes[k], skip, &next, &start, kInfinity, &again[k]);
    for (int k = 1; k < kWays; k++)
        if (foundAgain[k] != foundAgain[0] || (foundAgain[0] && !SameHit(again[k], again[0])))
            return false;
    // The bound method, which passes over the triangle the ray leaves where it goes plainly away
    // from it (PassesOver): the same in every layout
    LeaveSurface(scenes[0], kRobustMethods, &hits[0], Reflect(ray->dir, hits[0].normal), &next,
                 &start);
    for (int k = 0; k < kWays; k++)
        foundAgain[k] =
            FindNearestHitFrom(scenes[k], kRobustMethods, &next, &start, kInfinity, &again[k]);
    for (int k = 1; k < kWays; k++)
        if (foundAgain[k] != foundAgain[0] || (foundAgain[0] && !SameHit(again[k], again[0])))
            return false;
    return true;
}

// A ray from a random point of the cube of side `spread` around centre, in a random direction.
static Ray RandomRay(TestRng *rng, vec3 centre, real spread) {
    vec3 o = centre + spread * vec3{Uniform(rng) - real(0.5), Uniform(rng) - real(0.5),
                                    Uniform(rng) - real(0.5)};
    return {o, UnitDirection(Uniform(rng), Uniform(rng))};
}

// Passing over the triangle a ray leaves (PassesOver) changes no answer where the self-hit bound
// holds: a ray leaving a hit on a closed sphere mesh, reflected (back to the side it came from)
// or going on through (to the other side), finds the same nearest hit as a search from the same
// moved origin that tries that triangle too. Counts in *passed the rays that were passed over.
static int PassOverDifferences(const Scene &scene, vec3 centre, real spread, int rays,
                               uint64_t seed, int *passed) {
    TestRng rng = {seed};
    int differ = 0;
    for (int i = 0; i < rays; i++) {
        Ray ray = RandomRay(&rng, centre, spread);
        RayHit hit;
        if (!FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &hit))
            continue;
        for (vec3 dir : {Reflect(ray.dir, hit.normal), ray.dir}) {
            Ray next;
            SelfHit start;
            LeaveSurface(&scene, kRobustMethods, &hit, dir, &next, &start);
            if (start.index < 0)
                continue;
            ++*passed;
            RayHit over, tried;
            bool a = FindNearestHitFrom(&scene, kRobustMethods, &next, &start, kInfinity, &over);
            bool b = FindNearestHit(&scene, kRobustMethods, &next, 0, kInfinity, &tried);
            differ += a != b || (a && !SameHit(over, tried));
        }
    }
    return differ;
}

// Random rays, and rays at every corner and edge midpoint, from points inside and outside.
static int CountDifferences(const Scene &scene, vec3 centre, real spread, int rays, uint64_t seed) {
    Layouts l;
    MakeLayouts(scene, &l);
    TestRng rng = {seed};
    int differ = 0;
    for (int i = 0; i < rays; i++) {
        Ray ray = RandomRay(&rng, centre, spread);
        vec3 o = ray.origin;
        differ += !SameAnswers(&l, &ray, 0, kInfinity);
        const Triangle &t = scene.triangles[i % scene.triangles.size()];
        vec3 targets[2] = {t.a, real(0.5) * (t.b + t.c)}; // a corner and an edge's midpoint
        for (vec3 target : targets) {
            ray = {o, target - o};
            differ += !SameAnswers(&l, &ray, 0, kInfinity);
        }
    }
    return differ;
}

// The test scene and a closed sphere mesh, at scales the robustness tables claim.
static void TestSameHitsEveryLayout() {
    Scene test;
    BuildTestScene(&test);
    CHECK(CountDifferences(test, {0, 1, -4}, 12, 400, 11) == 0,
          "the test scene's 139 triangles: 1,200 rays give the same bits in every layout");
    const double scales[] = {1e-30, 1e-6, 1, 1e6, 1e30};
    const double floatScales[] = {1e-8, 1e-3, 1, 1e3, 1e8};
    for (int k = 0; k < 5; k++) {
        real scale = real(kDouble ? scales[k] : floatScales[k]);
        Scene ball = WallScene();
        AddOctasphere(&ball, {scale, -2 * scale, 3 * scale}, scale, 4); // 2,048 triangles
        int differ = CountDifferences(ball, {scale, -2 * scale, 3 * scale}, 3 * scale, 300, 5 + k);
        char what[120];
        snprintf(what, sizeof what, "a closed 2,048-triangle sphere of radius %g: same bits",
                 (double)scale);
        CHECK(differ == 0, what);
    }
}

// The pass-over on closed sphere meshes, from near the bottom of the normal numbers to near the
// top: exact, and used.
static void TestPassOverIsExact() {
    const double scales[] = {1e-305, 1e-30, 1e-6, 1, 1e6, 1e30, 1e300};
    const double floatScales[] = {1e-35, 1e-8, 1e-3, 1, 1e3, 1e8, 1e30};
    for (int k = 0; k < 7; k++) {
        real scale = real(kDouble ? scales[k] : floatScales[k]);
        Scene ball = WallScene();
        AddOctasphere(&ball, {scale, -2 * scale, 3 * scale}, scale, 4); // 2,048 triangles
        SceneLayout layout;
        CommitScene(&ball, LAYOUT_AUTO, 2, &layout);
        int passed = 0;
        int differ = PassOverDifferences(ball, {scale, -2 * scale, 3 * scale}, 3 * scale, 800,
                                         20 + k, &passed);
        char what[160];
        snprintf(what, sizeof what,
                 "radius %g: of %d rays that pass over the triangle they leave, %d find other than "
                 "a search that tries it finds",
                 (double)scale, passed, differ);
        CHECK(differ == 0 && passed >= 300, what);
    }
}

// Closed boxes, long and turned (the robustness tables' hardest rows), in every layout.
static void TestSameHitsInLongBoxes() {
    for (int k = 0; k < 3; k++)
        for (int turn = 0; turn < 2; turn++) {
            double length = ClaimedBoxLength(k);
            Scene box = BoxScene(length, turn);
            char what[120];
            snprintf(what, sizeof what, "a 4 x 3 x %g box%s: same bits", length,
                     turn ? ", turned" : "");
            CHECK(CountDifferences(box, {0, 0, 0}, 2, 300, 40 + k + turn) == 0, what);
        }
}

// The reach test (OutOfReach, kernel_blocks.h) across the axis a wall faces, where a ray moves
// along that axis not at all (a direction component of 0, so 1/d is infinite), barely (the
// smallest subnormal, 1/d overflowing), or little (1e-30): rays along and across a closed box and
// two inner walls facing x and z, from inside it and from points on its faces and edges, with the
// search cut at each hit's own t (a tie: no hit), one number past it, and starting at it. The same
// bits in every layout (the plain loop never tries the test).
static void TestReachAcrossFlatAxes() {
    Scene box = BoxScene(8, false);
    auto wall = [&box](vec3 a, vec3 b, vec3 c, vec3 d) {
        box.triangles.push_back({a, b, c, 0});
        box.triangles.push_back({a, c, d, 0});
    };
    wall({-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}); // facing z
    wall({real(0.5), -1, -2}, {real(0.5), 1, -2}, {real(0.5), 1, 2}, {real(0.5), -1, 2}); // x
    Layouts l;
    MakeLayouts(box, &l);
    const vec3 origins[] = {{0, 0, 0},         {2, 0, 0},           {-2, real(1.5), 0},
                            {real(0.5), 0, 1}, {1, real(-1.5), -3}, {0, 0, 1}};
    const real small[] = {0, std::numeric_limits<real>::denorm_min(), real(1e-30)};
    int differ = 0, hits = 0, asked = 0;
    for (vec3 o : origins)
        for (real e : small)
            for (int axis = 0; axis < 3; axis++)
                for (real sign : {real(1), real(-1)}) {
                    vec3 d = axis == 0   ? vec3{sign, e, -e} // one axis of 1, the others 0
                             : axis == 1 ? vec3{e, sign, e}  // or tiny
                                         : vec3{-e, e, sign};
                    for (vec3 dir : {d, vec3{d.x + d.y, d.y + d.z, d.z + d.x}}) { // and diagonals
                        Ray ray = {o, dir};
                        RayHit hit;
                        differ += !SameAnswers(&l, &ray, 0, kInfinity), asked++;
                        if (!FindNearestHit(&l.plain, kRobustMethods, &ray, 0, kInfinity, &hit))
                            continue;
                        hits++;
                        differ += !SameAnswers(&l, &ray, 0, hit.t);
                        differ += !SameAnswers(&l, &ray, 0, NextAfter(hit.t, true));
                        differ += !SameAnswers(&l, &ray, hit.t, kInfinity);
                        asked += 3;
                    }
                }
    CHECK(hits > asked / 8, "the axis rays meet the walls");
    CHECK(differ == 0, "rays along the axes the walls face, with and without cut intervals: "
                       "the same bits in every layout");
}

// Ties: a flat grid of 2,048 triangles in shuffled scene order, and rays through its corners
// and edge midpoints, each of which lies on two to six triangles at exactly the same t. The
// list keeps the earliest in the scene (a later one must be strictly nearer); the BVH meets them
// in its own order and must answer the same one. Two copies of one triangle tie everywhere.
static void TestTiesGoToTheEarlierTriangle() {
    Scene scene = WallScene();
    const int n = 32;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            vec3 p = {real(i), real(j), -5}, px = {real(i + 1), real(j), -5};
            vec3 py = {real(i), real(j + 1), -5}, pxy = {real(i + 1), real(j + 1), -5};
            scene.triangles.push_back({p, px, pxy, 0});
            scene.triangles.push_back({p, pxy, py, 0});
        }
    TestRng rng = {77};
    for (int i = (int)scene.triangles.size() - 1; i > 0; i--) // Fisher-Yates
        std::swap(scene.triangles[i], scene.triangles[(int)(Uniform(&rng) * (i + 1))]);
    scene.triangles[1000] = scene.triangles[7];
    Layouts l;
    MakeLayouts(scene, &l);
    int differ = 0, ties = 0;
    for (int i = 0; i <= 2 * n; i++)
        for (int j = 0; j <= 2 * n; j++) {
            Ray ray = {{real(0.3), real(0.7), 0},
                       {real(i) / 2 - real(0.3), real(j) / 2 - real(0.7), -5}};
            differ += !SameAnswers(&l, &ray, 0, kInfinity);
            RayHit hit;
            ties += (i % 2 == 0 || j % 2 == 0) &&
                    FindNearestHit(&l.plain, kRobustMethods, &ray, 0, kInfinity, &hit);
        }
    CHECK(ties > 3000, "the grid's corners and edge midpoints are hit");
    CHECK(differ == 0, "ties between triangles go to the same one in every layout");
    const Triangle &t = scene.triangles[7];
    Ray ray = {{0, 0, 0}, real(1.0 / 3) * (t.a + t.b + t.c)}; // through its centroid
    RayHit hit;
    bool found = FindNearestHit(&l.tree, kRobustMethods, &ray, 0, kInfinity, &hit);
    CHECK(found && hit.index == 7, "of two copies of a triangle, places 7 and 1000: place 7");
}

// The catalogue of hard cases (docs/robustness.md) with the triangle answered by a committed
// one-triangle scene: each row's answer must be what the reference function gives, to the bit.
static int sDifferences = 0; // counted by CommittedTriangle, for the check below
static bool CommittedTriangle(const Triangle *tri, const Ray *ray, real tMin, real tMax,
                              RayHit *hit) {
    Scene scene = WallScene();
    scene.triangles = {*tri};
    Layouts l;
    MakeLayouts(scene, &l);
    RayHit reference, list, tree, other;
    bool found = IntersectTriangle(tri, ray, tMin, tMax, &reference);
    bool inList = FindNearestHit(&l.list, kRobustMethods, ray, tMin, tMax, &list);
    bool inTree = FindNearestHit(&l.tree, kRobustMethods, ray, tMin, tMax, &tree);
    bool inOther = FindNearestHit(&l.other, kRobustMethods, ray, tMin, tMax, &other);
    reference.index = 0; // (the shape loop sets the index; IntersectTriangle does not)
    if (inList != found || inTree != found || inOther != found ||
        (found &&
         (!SameHit(list, reference) || !SameHit(tree, reference) || !SameHit(other, reference))))
        sDifferences++;
    *hit = tree;
    return inTree;
}

static void TestHardCasesCommitted() {
    std::vector<HardCaseResult> results;
    RunHardCases(IntersectSphere, CommittedTriangle, &results);
    int failed = 0;
    for (const HardCaseResult &r : results)
        failed += !r.passed;
    CHECK(failed == 0, "every hard case passes through the committed scene");
    CHECK(sDifferences == 0, "and each answer is the reference function's, bit for bit");
}

// Images: the test scene and a mesh scene rendered every way (MakeLayouts), with jittered
// samples and every effect: the same bytes.
static void TestSameImages() {
    Scene scenes[2];
    BuildTestScene(&scenes[0]);
    BuildDefaultScene(&scenes[1]);
    AddOctasphere(&scenes[1], {-1, 2, -12}, real(1.5), 3);
    scenes[1].triangles.back().material = 0; // and one mirror triangle among them
    for (Scene &scene : scenes) {
        scene.width = scene.height = 48;
        Layouts l;
        MakeLayouts(scene, &l);
        RenderSettings settings = TestSettings(&scene);
        settings.samplesPerPixel = 4;
        settings.sampling = SAMPLES_JITTER;
        Image images[kWays];
        RayStats stats;
        const Scene *ways[kWays] = {&l.plain, &l.list, &l.tree, &l.other};
        for (int k = 0; k < kWays; k++)
            Render(ways[k], &settings, &images[k], &stats);
        CHECK(images[1].pixels == images[0].pixels && images[2].pixels == images[0].pixels &&
                  images[3].pixels == images[0].pixels,
              "the same image bytes as written, as a list and with a BVH (both kernels)");
    }
}

// A scene edited after its commit, or a copy of it edited, is not answered from the layout,
// which no longer holds what the scene does.
static void TestEditedSceneIsNotStale() {
    Scene scene = WallScene();
    AddOctasphere(&scene, {0, 0, -5}, 1, 2);
    SceneLayout layout;
    CommitScene(&scene, LAYOUT_BVH, 2, &layout);
    Scene copy = scene;
    scene.triangles.push_back({{-9, -9, -2}, {9, -9, -2}, {0, 9, -2}, 0});
    Ray ray = {{0, 0, 0}, {0, 0, -1}};
    RayHit hit;
    CHECK(FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &hit) && hit.t == 2,
          "a triangle added after the commit, 2 in front of the eye, is hit at t = 2");
    copy.spheres.push_back({{0, 0, -3}, real(0.5), 0});
    CHECK(FindNearestHit(&copy, kRobustMethods, &ray, 0, kInfinity, &hit) && hit.t == real(2.5),
          "a sphere added to a copy of the committed scene, 2.5 in front of the eye, is hit");
    copy.spheres.pop_back();
    copy.triangles[0].a.z = 100;         // a copy edited in place: as many shapes, another triangle
    Ray wall = {{0, 0, 95}, {0, 0, -1}}; // meets the edited triangle's corner, z = 100
    RayHit a, b;
    bool foundA = SearchLayout(&layout.accelerator, &copy, kRobustMethods, &wall, &kNoSelfHit,
                               kInfinity, false, &a);
    bool foundB = SearchList(&copy, kRobustMethods, &wall, &kNoSelfHit, kInfinity, false, &b);
    CHECK(foundA == foundB && (!foundA || SameHit(a, b)),
          "a copy of the committed scene, edited in place: the plain loop's answer");
}

// Triangles of every shape at once: corners drawn from a small shared pool (so slivers, nearly
// collinear corners, shared edges and repeated corners are common) with sizes spread over 16
// orders of magnitude, at the ends of the range; rays aimed at corners and edge midpoints. This
// is where a triangle's answer depending on tMax (a bound that does not hold for a nearly
// degenerate triangle or a grazing ray) would show as a list and a BVH that disagree.
static int MixedSizeDifferences(real scale, uint64_t seed) {
    TestRng rng = {seed};
    auto coordinate = [&]() {
        real size = real(std::pow(10.0, 16 * (double)Uniform(&rng) - 8)) * scale;
        return (Uniform(&rng) - real(0.5)) * size;
    };
    std::vector<vec3> pool;
    for (int k = 0; k < 40; k++)
        pool.push_back({coordinate(), coordinate(), coordinate()});
    Scene scene = WallScene();
    for (int k = 0; k < 120; k++) {
        auto pick = [&]() { return pool[(size_t)(Uniform(&rng) * pool.size())]; };
        scene.triangles.push_back({pick(), pick(), pick(), 0});
    }
    Layouts l;
    MakeLayouts(scene, &l);
    int differ = 0;
    for (int k = 0; k < 600; k++) {
        vec3 o = {coordinate(), coordinate(), coordinate()};
        const Triangle &t = scene.triangles[k % scene.triangles.size()];
        vec3 target = k % 2 ? t.a : real(0.5) * (t.a + t.c);
        Ray ray = {o, target - o};
        if (MaxComponent(ray.dir) > 0)
            differ += !SameAnswers(&l, &ray, 0, kInfinity);
    }
    return differ;
}

static void TestMixedSizes() {
    const double scales[] = {1e-300, 1e-10, 1, 1e10, 1e290};
    const double floatScales[] = {1e-30, 1e-5, 1, 1e5, 1e28};
    for (int k = 0; k < 5; k++) {
        real scale = real(kDouble ? scales[k] : floatScales[k]);
        char what[120];
        snprintf(what, sizeof what, "slivers and mixed sizes at scale %g: the same bits every way",
                 (double)scale);
        CHECK(MixedSizeDifferences(scale, 100 + k) == 0, what);
    }
    // Two triangles, the second a sliver whose plain t is off by far more than its first-order
    // bound: both orders give the sliver, the nearer (double: float rounds the corners to
    // another pair of triangles)
    Scene scene = WallScene();
    Triangle a = {
        {real(-0.058541184133933499), real(0.0053882262489025421), real(0.05784944771382295)},
        {real(-61.008546702020269), real(57.620696045508524), real(36.852868349216862)},
        {real(289080.77327381348), real(-249071.57387850736), real(-237605.06619748232)},
        0};
    Triangle b = {
        {real(-1.1338058849555787e-05), real(1.7801241128182465e-05), real(2.4170658167533157e-06)},
        {real(-59.747569807499495), real(56.429742296509708), real(36.091161611625438)},
        {real(-66.875450309011498), real(63.161805383928524), real(40.396834956109394)},
        0};
    Ray ray = {{real(-73.694706823406563), real(69.602484473112128), real(44.516151654046155)},
               {real(61.008080141975611), real(-57.620738004334555), real(-36.852932450658692)}};
    RayHit ab, ba;
    scene.triangles = {a, b};
    bool foundAb = FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &ab);
    scene.triangles = {b, a};
    bool foundBa = FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &ba);
    CHECK(!kDouble || (foundAb && foundBa && ab.index == 1 && ba.index == 0 && ab.t == ba.t),
          "an answer does not depend on the nearest hit so far: the sliver in both orders");
}

// A BVH over a mesh a thousand times smaller than the smallest normal double's square root:
// the bins' scale would be infinite; the build splits at the median instead (no crash).
static void TestTinyMeshBuild() {
    real scale = real(kDouble ? 1e-306 : 1e-36);
    Scene ball = WallScene();
    AddOctasphere(&ball, {0, 0, -5 * scale}, scale, 3);
    CHECK(CountDifferences(ball, {0, 0, -5 * scale}, 3 * scale, 100, 9) == 0,
          "a 512-triangle sphere of radius 1e-306 (float 1e-36): built, and the same bits");
}

// The same tree, node for node and block for block, whether one thread builds it or two: a
// sphere of 8,192 triangles twice over (each centre twice: ties in every bin), shuffled, well
// above the size from which the build takes a second thread (kThreadMin, 4,096).
static bool SameTree(const SceneLayout &a, const SceneLayout &b) {
    if (a.wideNodes.size() != b.wideNodes.size() || a.wideBlocks.size() != b.wideBlocks.size() ||
        a.wideExponent != b.wideExponent)
        return false;
    return memcmp(a.wideNodes.data(), b.wideNodes.data(), a.wideNodes.size() * sizeof(WideNode)) ==
               0 &&
           memcmp(a.wideBlocks.data(), b.wideBlocks.data(),
                  a.wideBlocks.size() * sizeof(WideBlock)) == 0;
}
static void TestSameTreeAnyThreads() {
    Scene one = WallScene();
    AddOctasphere(&one, {0, 0, -5}, 1, 5);
    AddOctasphere(&one, {0, 0, -5}, 1, 5);
    uint64_t state = 12345;
    for (size_t i = one.triangles.size() - 1; i > 0; i--) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        std::swap(one.triangles[i], one.triangles[(state >> 33) % (i + 1)]);
    }
    Scene two = one;
    SceneLayout oneLayout, twoLayout;
    CommitScene(&one, LAYOUT_BVH, 1, &oneLayout);
    CommitScene(&two, LAYOUT_BVH, 2, &twoLayout);
    CHECK(!oneLayout.wideNodes.empty() && SameTree(oneLayout, twoLayout),
          "16,384 shuffled triangles: the same nodes and blocks built by one thread and by two");
}

void TestLayout() {
    TestSameHitsEveryLayout();
    TestPassOverIsExact();
    TestSameHitsInLongBoxes();
    TestReachAcrossFlatAxes();
    TestTiesGoToTheEarlierTriangle();
    TestHardCasesCommitted();
    TestSameImages();
    TestEditedSceneIsNotStale();
    TestMixedSizes();
    TestTinyMeshBuild();
    TestSameTreeAnyThreads();
}
