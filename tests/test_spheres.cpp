// tests/test_spheres.cpp -- the committed sphere blocks answer exactly what the plain loop answers.
//
// The kernel's sphere half (fast/kernel_spheres.h) runs the first step of the stable sphere test on
// kLanes spheres at once and sends the spheres that pass it to IntersectSphere, in scene order
// from one list of blocks, or leaf by leaf from the spheres' BVH (fast/commit_spheres.cpp, walked
// by kernel_walk.h). Both promise the plain loop's very bits: the same nearest sphere, t, point,
// normal and error bound, ties to the earlier sphere, the same any-hit answer and the same skip.
// Each check asks the same question of the scene as written and committed (as a list, and as a
// tree), and of the kernel's two copies directly (AVX2 vectors, where this processor has them,
// and lane by lane), and compares every field of the answers.
#include "../fast/fast.h"
#include "robust_scenes.h"
#include "test.h"

#include <cmath>
#include <cstdio>
#include <string>

static const bool kDouble = sizeof(real) == sizeof(double);

static vec3 RandomUnit(TestRng *rng) {
    for (;;) {
        vec3 v = {2 * Uniform(rng) - 1, 2 * Uniform(rng) - 1, 2 * Uniform(rng) - 1};
        if (Dot(v, v) > real(0.01) && Dot(v, v) <= 1)
            return Normalize(v);
    }
}

// The scene as written and committed, in one pair, with the committed one's layout.
struct SpherePair {
    Scene plain, committed;
    SceneLayout layout;
};

// The pair made from `scene`: the plain loop's, and committed as `choice` says.
static void MakePair(const Scene &scene, LayoutChoice choice, SpherePair *p) {
    p->plain = scene, p->committed = scene;
    p->plain.accelerator = nullptr;
    CommitScene(&p->committed, choice, 2, &p->layout);
}

// One question asked of the plain scene and the committed one (nearest and any hit), and, when
// the direction needs no rescaling (the search then passes the ray on as it is), of each copy of
// the kernel directly. False at the first answer that differs.
static bool SameSphereAnswers(SpherePair *p, const Ray *ray, const SelfHit *start) {
    RayHit a, b;
    bool foundA = FindNearestHitFrom(&p->plain, kRobustMethods, ray, start, kInfinity, &a);
    bool foundB = FindNearestHitFrom(&p->committed, kRobustMethods, ray, start, kInfinity, &b);
    if (foundA != foundB || (foundA && !SameHit(a, b)))
        return false;
    if (AnyHitFrom(&p->plain, kRobustMethods, ray, start, kInfinity) !=
        AnyHitFrom(&p->committed, kRobustMethods, ray, start, kInfinity))
        return false;
    if (!WithinWindow(MaxComponent(ray->dir), kDirectionWindow))
        return true;
    int skip = start->shape == SHAPE_SPHERE ? start->index : -1;
    const Scene *scene = &p->committed;
    bool vectorsBefore = p->layout.vectors, same = true;
    for (int vectors = 0; vectors <= (int)KernelHasVectors(); vectors++) {
        p->layout.vectors = vectors;
        for (int anyHit = 0; anyHit < 2; anyHit++) {
            RayHit c;
            real tMax = kInfinity;
            bool found =
                HitCommittedSpheres(scene, &p->layout, skip, ray, start->tMin, &tMax, anyHit, &c);
            bool plainAny = AnyHitFrom(&p->plain, kRobustMethods, ray, start, kInfinity);
            same = same && found == (anyHit ? plainAny : foundA) &&
                   (!found || anyHit || (SameHit(a, c) && SameBits(tMax, a.t)));
        }
    }
    p->layout.vectors = vectorsBefore;
    return same;
}

// n spheres around the origin at `scale`: centres in [-scale, scale]^3, radii from a thousandth
// of the scale to the scale, some of them copies (ties) and one of radius 0.
static Scene SpheresAt(int n, real scale, TestRng *rng) {
    Scene scene = WallScene();
    for (int i = 0; i < n; i++) {
        vec3 c = scale * vec3{2 * Uniform(rng) - 1, 2 * Uniform(rng) - 1, 2 * Uniform(rng) - 1};
        real r = scale * real(std::pow(10.0, -3 * (double)Uniform(rng)));
        scene.spheres.push_back({c, r, 0});
        if (i >= 2 && Uniform(rng) < real(0.15))
            scene.spheres.back() = scene.spheres[i / 2]; // a copy of an earlier sphere: a tie
    }
    if (n >= 5)
        scene.spheres[n - 2].radius = 0;
    return scene;
}

// Rays of every kind at one scene: random, grazing a sphere, from inside one, from a point
// rounded onto one's surface, leaving one (skip), with directions far outside the window. The
// number of questions whose answers differ.
static int SphereDifferences(const Scene &scene, LayoutChoice choice, real scale, int rays,
                             TestRng *rng) {
    SpherePair p;
    MakePair(scene, choice, &p);
    int differ = 0, n = (int)scene.spheres.size();
    for (int i = 0; i < rays; i++) {
        const Sphere &s = scene.spheres[i % n];
        vec3 u = RandomUnit(rng), w = RandomUnit(rng);
        vec3 side = SafeNormalize(Cross(u, w)); // perpendicular to u
        Ray ray;
        switch (i % 5) {
        case 0: // anywhere to anywhere
            ray = {2 * scale * RandomUnit(rng), RandomUnit(rng)};
            break;
        case 1: // grazing: along `side` through the point s.center + r u
            ray = {s.center + s.radius * u - 3 * scale * side, side};
            break;
        case 2: // from inside
            ray = {s.center + (s.radius / 2) * u, w};
            break;
        case 3: // from the surface, rounded
            ray = {s.center + s.radius * u, w};
            break;
        default: // toward the centre from afar
            ray = {s.center + 3 * scale * u, -u};
        }
        if (i % 7 == 0) // a direction that HitShapes rescales
            ray.dir =
                (i % 2 ? PowerOfTwo(2 * kDirectionWindow) : 1 / PowerOfTwo(2 * kDirectionWindow)) *
                ray.dir;
        SelfHit start = kNoSelfHit;
        differ += !SameSphereAnswers(&p, &ray, &start);
        start.shape = SHAPE_SPHERE, start.index = i % n; // leaving that sphere
        differ += !SameSphereAnswers(&p, &ray, &start);
        start = kNoSelfHit, start.tMin = s.radius / 4; // a later start
        differ += !SameSphereAnswers(&p, &ray, &start);
    }
    return differ;
}

// Scenes of 1 to 9 spheres (blocks partly filled), and of 70 and 150 (more than one chunk of
// blocks; a tree of a few levels), at scales from the smallest numbers to the largest, committed
// as a list and as a tree.
static void TestSameSphereHits() {
    // (1e-156 and 1e-20: many squares of radii fall below the normal numbers, where the first
    // step is not trusted)
    const double scales[] = {1e-300, 1e-156, 1e-20, 1, 1e20, 1e150, 1e300};
    const double floatScales[] = {1e-30, 1e-20, 1e-5, 1, 1e5, 1e15, 1e30};
    TestRng rng = {2024};
    for (LayoutChoice choice : {LAYOUT_LIST, LAYOUT_BVH}) {
        const char *as = choice == LAYOUT_LIST ? "a list" : "a tree";
        for (int k = 0; k < 7; k++) {
            real scale = real(kDouble ? scales[k] : floatScales[k]);
            int differ = 0;
            for (int n = 1; n <= 9; n++)
                differ += SphereDifferences(SpheresAt(n, scale, &rng), choice, scale, 100, &rng);
            char what[120];
            snprintf(what, sizeof what, "1 to 9 spheres at scale %g: the same bits as %s",
                     (double)scale, as);
            CHECK(differ == 0, what);
            differ = SphereDifferences(SpheresAt(70, scale, &rng), choice, scale, 200, &rng) +
                     SphereDifferences(SpheresAt(150, scale, &rng), choice, scale, 300, &rng);
            snprintf(what, sizeof what, "70 and 150 spheres at scale %g: the same bits as %s",
                     (double)scale, as);
            CHECK(differ == 0, what);
        }
    }
}

// What a tree must not trip over: 2,000 copies of one sphere (no split separates them: one leaf,
// and the first copy wins every tie), spheres no ray can hit (radius 0, infinite or NaN, a centre
// at infinity), walls of radius 1e5 around small spheres (smallpt's box), and spheres nested in
// one another. The same bits as the plain loop, and a tree that stays small.
static void TestTreeHardCases() {
    TestRng rng = {77};
    Scene copies = SpheresAt(40, 1, &rng);
    Sphere one = {{0, 0, -3}, real(0.5), 0};
    for (int k = 0; k < 2000; k++)
        copies.spheres.push_back(one);
    copies.spheres.push_back({{1, 1, 1}, kInfinity, 0});
    copies.spheres.push_back({{1, 1, 1}, real(std::nan("")), 0});
    copies.spheres.push_back({{kInfinity, 0, 0}, 1, 0});
    SpherePair p;
    MakePair(copies, LAYOUT_BVH, &p);
    CHECK(!p.layout.sphereNodes.empty() && p.layout.sphereNodes.size() < 40,
          "2,000 copies of a sphere among 40 others: a tree of " +
              std::to_string(p.layout.sphereNodes.size()) + " nodes (fewer than 40)");
    Ray ray = {{0, 0, 0}, {0, 0, -1}};
    RayHit hit;
    CHECK(FindNearestHit(&p.committed, kRobustMethods, &ray, 0, kInfinity, &hit) &&
              hit.index == 40 && hit.t == real(2.5),
          "of 2,000 copies of a sphere 2.5 ahead, the first (place 40) is hit");
    int differ = SphereDifferences(copies, LAYOUT_BVH, 1, 300, &rng);
    Scene box = SpheresAt(60, 20, &rng);
    const real walls[6][4] = {{100001, 40, 80, 1e5}, {-99901, 40, 80, 1e5}, {50, 40, 1e5, 1e5},
                              {50, 40, -99830, 1e5}, {50, 1e5, 80, 1e5},    {50, -99918, 80, 1e5}};
    for (const real *w : walls)
        box.spheres.push_back({{w[0], w[1], w[2]}, w[3], 0});
    for (int k = 1; k <= 20; k++)
        box.spheres.push_back({{3, 2, 1}, real(k) / 4, 0});
    differ += SphereDifferences(box, LAYOUT_BVH, 50, 600, &rng);
    CHECK(differ == 0, "copies, spheres no ray can hit, walls of radius 1e5 and nested spheres in "
                       "a tree: the same bits as the plain loop");
}

// Spheres at the end of the range of numbers: centres at the corners (+-M, +-M, +-M), M 1e308
// (float 2e38), radius 0.7 M, so that a centre's coordinates sum beyond the range although each
// is finite (the tree once left such spheres out, and a ray at one met nothing), among smaller
// spheres. A tree answers as the plain loop: the ray of the report, and rays of every kind.
static void TestSpheresAtTheEndOfTheRange() {
    real most = real(kDouble ? 1e308 : 2e38);
    TestRng rng = {308};
    Scene scene = SpheresAt(30, most / 10, &rng);
    for (Sphere &small : scene.spheres) // (kept off the ray of the report)
        small.center.x = std::fabs(small.center.x) + most / 5;
    for (int k = 0; k < 8; k++)
        scene.spheres.push_back({{k & 1 ? most : -most, k & 2 ? most : -most, k & 4 ? most : -most},
                                 real(0.7) * most,
                                 0});
    SpherePair p;
    MakePair(scene, LAYOUT_BVH, &p);
    Ray ray = {{0, -most / 10, 0},
               {real(-0.6642548229051699), real(-0.7567862020024458), real(0.8270619320275827)}};
    SelfHit start = kNoSelfHit;
    RayHit hit;
    bool found = FindNearestHitFrom(&p.committed, kRobustMethods, &ray, &start, kInfinity, &hit);
    char what[160];
    snprintf(what, sizeof what,
             "a ray toward the sphere at (-M, -M, M) of radius 0.7 M, M = %g: the tree meets it "
             "(found %d), as the plain loop does",
             (double)most, (int)found);
    CHECK(found && hit.index == 30 + 4 && SameSphereAnswers(&p, &ray, &start), what);
    int differ = SphereDifferences(scene, LAYOUT_BVH, most / 10, 400, &rng);
    CHECK(differ == 0, "spheres at (+-M, +-M, +-M) among smaller ones, in a tree: the same bits "
                       "as the plain loop (" +
                           std::to_string(differ) + " answers differ)");
}

// Ties: copies of one sphere at places 1, 4 and 6, behind it a larger one; the first copy wins,
// committed or not, and leaving it, the next copy.
static void TestSphereTies() {
    Scene scene = WallScene();
    Sphere s = {{0, 0, -5}, 1, 0}, big = {{0, 0, -9}, 3, 0};
    scene.spheres = {big, s, big, big, s, big, s};
    SpherePair p;
    MakePair(scene, LAYOUT_AUTO, &p);
    Ray ray = {{0, 0, 0}, {0, 0, -1}};
    SelfHit start = kNoSelfHit;
    RayHit hit;
    CHECK(FindNearestHitFrom(&p.committed, kRobustMethods, &ray, &start, kInfinity, &hit) &&
              hit.index == 1 && hit.t == 4,
          "three copies of a sphere, committed: the first, place 1, at t = 4");
    start.shape = SHAPE_SPHERE, start.index = 1;
    CHECK(FindNearestHitFrom(&p.committed, kRobustMethods, &ray, &start, kInfinity, &hit) &&
              hit.index == 4,
          "leaving place 1 (skip): the next copy, place 4");
    CHECK(SameSphereAnswers(&p, &ray, &start), "the same bits, committed or not");
}

// A scene given another sphere after its commit is answered as written: the committed blocks no
// longer hold its spheres, so the plain loop runs. (A sphere changed in place is not noticed:
// the scene must be committed again, as CommitScene says.) And the handout's textbook sphere
// keeps the plain loop.
static void TestEditedSpheresAreNotStale() {
    Scene scene = WallScene();
    scene.spheres.push_back({{0, 0, -9}, 1, 0});
    SceneLayout layout;
    CommitScene(&scene, LAYOUT_AUTO, 2, &layout);
    scene.spheres.push_back({{0, 0, -5}, 1, 0});
    Ray ray = {{0, 0, 0}, {0, 0, -1}};
    RayHit hit;
    CHECK(FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &hit) && hit.index == 1 &&
              hit.t == 4,
          "a sphere added after the commit, 4 in front of the eye, is hit at t = 4");
    CommitScene(&scene, LAYOUT_AUTO, 2, &layout);
    RayHit textbook;
    bool found = FindNearestHit(&scene, kHandoutMethods, &ray, 0, kInfinity, &textbook);
    CHECK(found && textbook.index == 1 && textbook.t == 4,
          "committed, the handout's textbook sphere gives its own answer: t = 4");
}

void TestSpheres() {
    TestSameSphereHits();
    TestSphereTies();
    TestTreeHardCases();
    TestSpheresAtTheEndOfTheRange();
    TestEditedSpheresAreNotStale();
}
