// tests/test_packet.cpp -- a packet of rays from the eye answers what each ray alone answers.
//
// A pixel's samples are searched for together (FindEyeRayHits, where the accelerator takes them
// as packets, fast/kernel.cpp): up to kLanes rays in the lanes of the kernel, one shape at a time
// (fast/kernel_packet.h). Each ray must get the very bits the plain loop gives it alone: the same
// t, point, normal, error bound and shape, ties included. The checks ask each packet three ways
// (the packet kernel itself, FindEyeRayHits, and each ray alone in the scene as written) and
// count the packets the kernel took, so that a packet path that quietly fell back to one ray at a
// time would show; and they ask the shadow rays of the packet's hits of the committed scene, one
// by one, against the scene as written.
#include "../fast/fast.h"
#include "robust_scenes.h"
#include "test.h"

#include <cstdio>

static const bool kDouble = sizeof(real) == sizeof(double);

// What a set of packets found: rays whose answers differed, and packets the kernel took.
struct PacketCount {
    int differ, taken, packets;
    int shadows, blocked; // shadow rays asked (each twice), and how many of those were blocked
};

// The shadow rays of a packet's hits toward a point (ShadowRay: from the hit's own side, passing
// over the triangle it leaves where it goes plainly away), and from the same points with a
// tMin of 1/4 and leaving the shape hit (the second handout's skip): AnyHitFrom in the committed
// scene against the scene as written.
static void AskShadows(const Scene *committed, const Scene *plain, const RayHit *hits,
                       const bool *found, int count, PacketCount *c) {
    Ray rays[kLanes], skipping[kLanes];
    SelfHit starts[kLanes], skips[kLanes];
    int n = 0;
    for (int r = 0; r < count; r++) {
        vec3 light = hits[r].point + SafeLength(hits[r].point) * vec3{1, 2, 3} + vec3{1, 2, 3};
        if (found[r] &&
            ShadowRay(committed, kRobustMethods, &hits[r], light, &rays[n], &starts[n])) {
            skipping[n] = {hits[r].point, rays[n].dir};
            skips[n] = {real(0.25), hits[r].shape, hits[r].index};
            n++;
        }
    }
    bool blocked[kLanes], skipBlocked[kLanes];
    for (int k = 0; k < n; k++) {
        blocked[k] = AnyHitFrom(committed, kRobustMethods, &rays[k], &starts[k], 1);
        skipBlocked[k] = AnyHitFrom(committed, kRobustMethods, &skipping[k], &skips[k], 1);
    }
    for (int k = 0; k < n; k++) {
        c->differ += blocked[k] != AnyHitFrom(plain, kRobustMethods, &rays[k], &starts[k], 1);
        c->differ +=
            skipBlocked[k] != AnyHitFrom(plain, kRobustMethods, &skipping[k], &skips[k], 1);
        c->shadows++, c->blocked += blocked[k] + skipBlocked[k];
    }
}

// One packet, asked three ways against the committed scene and the scene as written, and its
// hits' shadow rays two ways.
static void AskPacket(const Scene *committed, const SceneLayout *layout, const Scene *plain,
                      const Ray *rays, int count, PacketCount *c) {
    RayHit kernel[kLanes], hits[kLanes], accelerated[kLanes];
    bool kernelFound[kLanes], found[kLanes], acceleratedFound[kLanes];
    bool answered[kEyeRaysTogether] = {};
    bool oneAxis = true; // HitCommittedPacket's condition: every ray sheared about one axis
    for (int r = 0; r < count; r++)
        oneAxis = oneAxis && DominantAxis(rays[r].dir) == DominantAxis(rays[0].dir);
    RayPacket packet = {rays, count, DominantAxis(rays[0].dir)};
    bool taken = oneAxis && HitCommittedPacket(committed, layout, &packet, kernel, kernelFound);
    SearchEyeRays(&layout->accelerator, committed, kRobustMethods, rays, count, accelerated,
                  acceleratedFound, answered);
    FindEyeRayHits(committed, kRobustMethods, rays, count, hits, found);
    c->differ += answered[0] && !taken; // a packet only where the kernel can take one
    for (int r = 0; r < count; r++)
        c->differ += answered[r] != answered[0] ||
                     (answered[r] && (acceleratedFound[r] != found[r] ||
                                      (found[r] && !SameHit(accelerated[r], hits[r]))));
    c->taken += taken, c->packets++;
    for (int r = 0; r < count; r++) {
        RayHit alone;
        bool one =
            FindNearestHitFrom(plain, kRobustMethods, &rays[r], &kNoSelfHit, kInfinity, &alone);
        bool same = found[r] == one && (!one || SameHit(hits[r], alone));
        if (taken)
            same = same && kernelFound[r] == one && (!one || SameHit(kernel[r], alone));
        c->differ += !same;
    }
    AskShadows(committed, plain, hits, found, count, c);
}

// Packets of `count` rays from `eye` (each origin moved by up to `wobble` times the eye's
// distance to `centre`, as the screen camera's rays start on the screen), aimed at random points
// of a cube of side `spread` around centre, or where `aim` is set at its triangles' corners and
// edge midpoints (a tie between the triangles that share them). Unit directions, so that rays at
// every scale are searched for as they are, where the packet can take them.
struct PacketRays {
    vec3 eye, centre;
    real spread, wobble;
    const std::vector<Triangle> *aim;
};
static PacketCount CountPacketDifferences(const Scene &scene, const PacketRays *p, int packets,
                                          int count, uint64_t seed) {
    Scene committed = scene, plain = scene;
    plain.accelerator = nullptr; // the plain loop
    SceneLayout layout;
    CommitScene(&committed, LAYOUT_LIST, 2, &layout);
    TestRng rng = {seed};
    PacketCount c = {0, 0, 0, 0, 0};
    real reach = SafeLength(p->centre - p->eye);
    for (int k = 0; k < packets; k++) {
        Ray rays[kLanes];
        for (int r = 0; r < count; r++) {
            vec3 target =
                p->centre + p->spread * vec3{Uniform(&rng) - real(0.5), Uniform(&rng) - real(0.5),
                                             Uniform(&rng) - real(0.5)};
            if (p->aim) {
                const Triangle &t = (*p->aim)[(k * kLanes + r) % p->aim->size()];
                target = r % 2 ? t.a : real(0.5) * (t.b + t.c);
            }
            vec3 o = p->eye + p->wobble * reach *
                                  vec3{Uniform(&rng) - real(0.5), Uniform(&rng) - real(0.5), 0};
            rays[r] = {o, SafeNormalize(target - o)}; // unit: ScaleRay leaves it as it is
        }
        AskPacket(&committed, &layout, &plain, rays, count, &c);
    }
    return c;
}

static void Report(const PacketCount &c, const char *what, bool mustTake) {
    char line[240];
    snprintf(line, sizeof line,
             "%s: of %d packets (%d taken by the kernel) and %d shadow rays asked twice (%d "
             "blocked), %d rays differ",
             what, c.packets, c.taken, c.shadows, c.blocked, c.differ);
    bool took = !mustTake || !KernelHasVectors() || c.taken > c.packets / 2;
    CHECK(c.differ == 0 && took, line);
}

// The test scene's spheres and 139 triangles, seen from its camera: clusters of rays as a pixel's
// samples are, then rays spread over the whole view, of every packet size.
static void TestPacketsInTheTestScene() {
    Scene test;
    BuildTestScene(&test);
    vec3 eye = test.camera.perspective.eye;
    for (int count = 1; count <= kLanes; count++) {
        PacketRays near = {eye, {0, 0, -8}, real(0.05), 0, nullptr};
        Report(CountPacketDifferences(test, &near, 150, count, 40 + count),
               "the test scene, clustered rays", true);
        PacketRays wide = {eye, {0, 0, -8}, 12, 0, nullptr};
        Report(CountPacketDifferences(test, &wide, 150, count, 60 + count),
               "the test scene, rays across the view", false);
    }
}

// A closed sphere mesh at the scales the robustness tables claim, rays aimed at its corners and
// edge midpoints from one eye, and from origins spread as the screen camera's are.
static void TestPacketsAtEveryScale() {
    const double scales[] = {1e-300, 1e-30, 1e-6, 1, 1e6, 1e30, 1e300};
    const double floatScales[] = {1e-30, 1e-8, 1e-3, 1, 1e3, 1e8, 1e30};
    for (int k = 0; k < 7; k++) {
        real s = real(kDouble ? scales[k] : floatScales[k]);
        Scene ball = WallScene();
        AddOctasphere(&ball, {s, -2 * s, 3 * s}, s, 3); // 512 triangles
        ball.spheres.push_back({{s, -2 * s, 3 * s}, real(0.5) * s, 0});
        ball.spheres.push_back({{2 * s, -2 * s, 3 * s}, real(0.25) * s, 0});
        vec3 eye = {s, -2 * s, 9 * s};
        PacketRays corners = {eye, {s, -2 * s, 3 * s}, s, 0, &ball.triangles};
        PacketRays spread = {eye, {s, -2 * s, 3 * s}, 2 * s, real(0.01), &ball.triangles};
        PacketRays inside = {{s, -2 * s, real(3.9) * s}, {s, -2 * s, 3 * s}, s, 0, nullptr};
        char what[120];
        snprintf(what, sizeof what, "a 512-triangle sphere mesh of radius %g, at its corners",
                 (double)s);
        Report(CountPacketDifferences(ball, &corners, 200, kLanes, 80 + k), what, true);
        snprintf(what, sizeof what, "radius %g, from origins 1/100 of the way apart", (double)s);
        Report(CountPacketDifferences(ball, &spread, 200, kLanes, 90 + k), what, true);
        snprintf(what, sizeof what, "radius %g, from inside the mesh", (double)s);
        Report(CountPacketDifferences(ball, &inside, 200, kLanes, 100 + k), what, false);
    }
}

// Closed boxes, long and turned, seen from inside (the robustness tables' hardest rows): many of
// their hits are left unsure by tier 1 and decided in double-double, lane by lane.
static void TestPacketsInLongBoxes() {
    for (int k = 0; k < 3; k++)
        for (int turn = 0; turn < 2; turn++) {
            double length = ClaimedBoxLength(k);
            Scene box = BoxScene(length, turn);
            vec3 eye = Turn({real(0.3), real(-0.2), real(0.25 * length)}, turn);
            vec3 far = Turn({0, 0, real(-0.4 * length)}, turn);
            PacketRays down = {eye, far, real(3), 0, nullptr};
            PacketRays across = {eye, eye, real(5), real(1e-3), nullptr};
            char what[120];
            snprintf(what, sizeof what, "a %s box of length %g, down its length",
                     turn ? "turned" : "straight", length);
            Report(CountPacketDifferences(box, &down, 150, kLanes, 120 + k), what, true);
            snprintf(what, sizeof what, "a %s box of length %g, across it",
                     turn ? "turned" : "straight", length);
            Report(CountPacketDifferences(box, &across, 150, kLanes, 130 + k), what, false);
        }
}

// Ties: two copies of each triangle and of each sphere, and spheres that touch. The plain loop
// keeps the earlier shape at equal t; so must every lane.
static void TestPacketTies() {
    Scene scene = WallScene();
    AddOctasphere(&scene, {0, 0, -6}, 2, 2);
    size_t n = scene.triangles.size();
    for (size_t i = 0; i < n; i++)
        scene.triangles.push_back(scene.triangles[i]);
    for (int i = 0; i < 12; i++) { // 24 spheres, more than one sphere block in either build
        Sphere s = {{real(i % 4) - real(1.5), real(i / 4) - 1, -3}, real(0.5), 0};
        scene.spheres.push_back(s), scene.spheres.push_back(s);
    }
    PacketRays rays = {{0, 0, 4}, {0, 0, -4}, 5, 0, nullptr};
    Report(CountPacketDifferences(scene, &rays, 400, kLanes, 7),
           "every triangle and every sphere twice, touching spheres", true);
    PacketRays corners = {{0, 0, 4}, {0, 0, -6}, 2, 0, &scene.triangles};
    Report(CountPacketDifferences(scene, &corners, 400, kLanes, 8),
           "the same, rays at the corners and edge midpoints", true);
}

// Rays in one packet whose shears would rename the axes differently (DominantAxis) are not taken
// as a packet; each is then searched for alone, with the same answers.
static void TestMixedAxesFallBack() {
    Scene scene = WallScene();
    AddOctasphere(&scene, {0, 0, 0}, 1, 2);
    Scene committed = scene;
    SceneLayout layout;
    CommitScene(&committed, LAYOUT_LIST, 2, &layout);
    Ray rays[2] = {{{0, 0, 5}, {0, 0, -1}}, {{5, 0, 0}, {-1, 0, 0}}};
    RayHit hits[2];
    bool found[2], answered[kEyeRaysTogether] = {};
    SearchEyeRays(&layout.accelerator, &committed, kRobustMethods, rays, 2, hits, found, answered);
    CHECK(!answered[0] && !answered[1], "a ray along z and a ray along x: not one packet");
    FindEyeRayHits(&committed, kRobustMethods, rays, 2, hits, found);
    RayHit alone[2];
    bool same = true;
    for (int r = 0; r < 2; r++)
        same = same && FindNearestHit(&scene, kRobustMethods, &rays[r], 0, kInfinity, &alone[r]) &&
               found[r] && SameHit(hits[r], alone[r]);
    CHECK(same, "each is answered as it is alone");
    CHECK_NEAR(hits[0].t, 4, 4 * kRelTol, "the ray along z meets the mesh's corner 4 away");
    CHECK_NEAR(hits[1].t, 4, 4 * kRelTol, "and so does the ray along x");
}

// Whole renders: scenes traced with packets (committed) and one ray at a time (as written) give
// the same bytes and the same ray counts. The test scene (mirrors, glass, two lights), the
// assignment scene with ten lights in Phong shading, and the test scene path traced.
static void SameRenderScenes(Scene scenes[3]) {
    BuildTestScene(&scenes[0]);
    BuildDefaultScene(&scenes[1]);
    scenes[1].shading = SHADING_PHONG;
    for (int i = 0; i < 10; i++)
        scenes[1].lights.push_back({{real(i) - 5, 6, real(-9 - i)}, {real(0.1), 0, real(0.1)}});
    BuildTestScene(&scenes[2]); // path traced, with an emitting material
    scenes[2].shading = SHADING_PATH;
    scenes[2].materials[0].emit = {2, 2, 2};
}

// A pixel's colour as one sample at a time gives it (the grid's positions, SamplePosition), each
// traced alone (TraceRay; FindNearestHit, then TracePath): RenderPixel, which traces them in
// packets and finds their cells row after row (NextCell), must give these very bits and count the
// same rays. One sample (the pixel's centre, which RenderPixel finds without the grid), sample
// counts whose grid rows differ in length (3: 1 + 2; 10: 3 + 3 + 4; 17: 4 + 4 + 4 + 5) and a
// square (9).
static int PixelsThatDiffer(const Scene *scene, RenderSettings settings, int samples) {
    int size = 8, differ = 0;
    settings.width = settings.height = size;
    settings.samplesPerPixel = samples;
    PlanRender(scene, &settings);
    for (int j = 0; j < size; j++)
        for (int i = 0; i < size; i++) {
            TraceLog log = {RayStats{}, nullptr, -1, 0};
            color sum = {0, 0, 0};
            for (int k = 0; k < samples; k++) {
                Ray ray;
                GetCameraRay(&settings.camera, size, size, SamplePosition(i, j, k, samples), &ray);
                RayHit hit;
                bool found = FindNearestHit(scene, settings.methods, &ray, 0, kInfinity, &hit);
                sum = sum + (scene->shading == SHADING_PATH
                                 ? TracePath(scene, &settings, &ray, found, &hit, i, j, k, &log)
                                 : TraceRay(scene, &settings, RAY_PRIMARY, &ray, &kNoSelfHit,
                                            RayChain{1, 1}, &log));
            }
            sum = (real(1) / samples) * sum;
            RayStats stats = {};
            color pixel = RenderPixel(scene, &settings, i, j, &stats);
            differ += !SameBits(pixel, sum) || stats.shadow != log.stats.shadow ||
                      stats.diffuse != log.stats.diffuse ||
                      stats.reflection != log.stats.reflection;
        }
    return differ;
}

static void TestPixelsAsOneByOne() {
    Scene scenes[3];
    SameRenderScenes(scenes);
    for (Scene &scene : scenes) {
        SceneLayout layout;
        CommitScene(&scene, LAYOUT_LIST, 2, &layout);
        for (int samples : {1, 3, 9, 10, 17}) {
            int differ = PixelsThatDiffer(&scene, TestSettings(&scene), samples);
            CHECK(differ == 0, "of 64 pixels of " + std::to_string(samples) +
                                   " samples, traced in packets and one by one, " +
                                   std::to_string(differ) + " differ in colour or in rays counted");
        }
    }
}

static void TestSameRenders() {
    Scene scenes[3];
    SameRenderScenes(scenes);
    for (Scene &scene : scenes) {
        scene.width = scene.height = 40;
        Scene committed = scene;
        SceneLayout layout;
        CommitScene(&committed, LAYOUT_LIST, 2, &layout);
        for (SampleMethod sampling : {SAMPLES_GRID, SAMPLES_JITTER}) {
            RenderSettings settings = TestSettings(&scene);
            settings.samplesPerPixel = 9; // two packets and a part in either build
            settings.sampling = sampling;
            Image plainImage, packetImage;
            RayStats plainStats = {}, packetStats = {};
            Render(&scene, &settings, &plainImage, &plainStats);
            Render(&committed, &settings, &packetImage, &packetStats);
            CHECK(packetImage.pixels == plainImage.pixels &&
                      packetStats.shadow == plainStats.shadow &&
                      packetStats.reflection == plainStats.reflection &&
                      packetStats.refraction == plainStats.refraction &&
                      packetStats.specularTerms == plainStats.specularTerms &&
                      packetStats.diffuse == plainStats.diffuse,
                  "packets of samples: the same image bytes and ray counts as one ray at a time");
        }
    }
}

void TestPacket() {
    TestPixelsAsOneByOne();
    TestSameRenders();
    TestPacketsInTheTestScene();
    TestPacketsAtEveryScale();
    TestPacketsInLongBoxes();
    TestPacketTies();
    TestMixedAxesFallBack();
}
