// tests/test_shade.cpp -- the handout's lighting rule, shadows, mirrors and the chain limit.
//
// The stage: a white floor triangle in the plane y = 0 (outward side up), seen from above by a
// ray from (0, 5, 0) straight down, which hits the origin. The light and what stands between
// them change from test to test; each colour is worked out from kd * max(ambient, N.L).
#include "../render.h"
#include "test.h"

#include <cmath>

// A matte material of grey level kd, or a mirror reflecting the fraction k.
Material Matte(const char *name, color kd) { return {name, kd, kd, 0, 1, 0, 0, {0, 0, 0}}; }
Material Mirror(const char *name, real k) {
    return {name, {1, 1, 1}, {1, 1, 1}, 0, 1, k, 0, {0, 0, 0}};
}

static Scene FloorScene(vec3 lightPosition, real diffuse) {
    Scene scene;
    InitScene(&scene); // ambient 0.2, floor shading, black background, depth 10
    scene.materials = {Matte("floor", {diffuse, diffuse, diffuse}), Mirror("mirror", 1)};
    scene.triangles = {{{-100, 0, 100}, {100, 0, 100}, {0, 0, -100}, 0}};
    scene.lights = {{lightPosition, {1, 1, 1}}};
    return scene;
}

// Traces one primary ray, with the effects planned for the scene as a render would.
static color Shade(const Scene *scene, vec3 origin, vec3 dir, RayStats *stats) {
    RenderSettings settings = TestSettings(scene);
    Ray ray = {origin, dir};
    TraceLog log = {RayStats{}, nullptr, -1, 0};
    color c = TraceRay(scene, &settings, RAY_PRIMARY, &ray, &kNoSelfHit, RayChain{1, 1}, &log);
    *stats = log.stats;
    return c;
}

static void TestLit() {
    // Light straight above: N.L = 1, colour = kd = 0.5
    Scene scene = FloorScene({0, 10, 0}, 0.5f);
    RayStats stats;
    color c = Shade(&scene, {0, 5, 0}, {0, -1, 0}, &stats);
    CHECK_NEAR(c.x, 0.5, kRelTol, "lit from straight above: kd * N.L = 0.5 * 1");
    CHECK(stats.shadow == 1, "one light in front of the surface: one shadow ray");

    // Light at 45 degrees, (10, 10, 0): N.L = cos 45 = 0.70710678
    scene = FloorScene({10, 10, 0}, 1);
    c = Shade(&scene, {0, 5, 0}, {0, -1, 0}, &stats);
    CHECK_NEAR(c.x, std::sqrt(0.5), 4 * kRelTol, "lit at 45 degrees: N.L = sqrt(1/2)");

    // Light nearly at the horizon, (10, 1, 0): N.L = 1 / sqrt(101) = 0.0995 < ambient 0.2
    scene = FloorScene({10, 1, 0}, 1);
    c = Shade(&scene, {0, 5, 0}, {0, -1, 0}, &stats);
    CHECK_NEAR(c.x, 0.2, kRelTol, "grazing light: the ambient floor 0.2 wins over N.L = 0.0995");
}

static void TestShadow() {
    // A sphere of radius 1 at height 5 between the origin and the light at height 10
    Scene scene = FloorScene({0, 10, 0}, 0.5f);
    scene.spheres = {{{0, 5, 0}, 1, 0}};
    RayStats stats;
    color c = Shade(&scene, {0, 3, 0}, {0, -1, 0}, &stats);
    CHECK_NEAR(c.x, 0.1, kRelTol, "in the sphere's shadow: kd * ambient = 0.5 * 0.2");
    CHECK(stats.shadow == 1, "in shadow: exactly one shadow ray was cast");

    // The blocker beyond the light does not cast a shadow: sphere at height 15, light at 10
    scene.spheres = {{{0, 15, 0}, 1, 0}};
    c = Shade(&scene, {0, 3, 0}, {0, -1, 0}, &stats);
    CHECK_NEAR(c.x, 0.5, kRelTol, "a sphere beyond the light casts no shadow: lit, 0.5");
}

static void TestFacingAway() {
    // Light below the floor, seen from above: N.L < 0, ambient only, no shadow ray
    Scene scene = FloorScene({0, -10, 0}, 0.5f);
    RayStats stats;
    color c = Shade(&scene, {0, 5, 0}, {0, -1, 0}, &stats);
    CHECK_NEAR(c.x, 0.1, kRelTol, "light behind the surface: kd * ambient = 0.1");
    CHECK(stats.shadow == 0, "light behind the surface: no shadow ray is cast");

    // Seen from below with the light above: the normal turns to the viewer (down), N.L < 0
    scene = FloorScene({0, 10, 0}, 0.5f);
    c = Shade(&scene, {0, -5, 0}, {0, 1, 0}, &stats);
    CHECK_NEAR(c.x, 0.1, kRelTol, "underside of a lit floor: normal faces the viewer, ambient");
}

static void TestMirror() {
    // A perfect mirror floor reflects the ray going down-right at 45 degrees up into a red
    // wall (plane x = 10, facing -x) lit head-on by a light at (5, 5, 0): N.L = 1 at (10, 5, 0)
    Scene scene = FloorScene({5, 5, 0}, 1);
    scene.materials.push_back(Matte("red", {1, 0, 0}));
    scene.triangles[0].material = 1; // the floor is now the mirror
    scene.triangles.push_back({{10, -100, -100}, {10, 100, 0}, {10, -100, 100}, 2});
    RayStats stats;
    color c = Shade(&scene, {0, 5, 0}, {1, -1, 0}, &stats);
    CHECK_NEAR(c.x, 1, kRelTol, "mirror floor shows the red wall, lit head-on: red 1");
    CHECK(c.y == 0 && c.z == 0, "mirror floor: only red comes back");
    CHECK(stats.reflection == 1 && stats.shadow == 1,
          "mirror: one reflection ray; the shadow ray is cast at the wall, not the mirror");

    // A miss after the mirror returns the background
    scene.background = {0, 0, real(0.25)};
    c = Shade(&scene, {0, 5, 0}, {-1, -1, 0}, &stats);
    CHECK(c.x == 0 && c.z == real(0.25), "mirror reflecting the empty sky gives the background");
}

static void TestDepthCutsFacingMirrors() {
    // Two parallel mirrors y = 0 (facing up) and y = 10 (facing down); a vertical ray bounces
    // between them forever. With depth 10 the chain is 1 primary + 9 reflection rays, then black.
    Scene scene = FloorScene({0, 5, 0}, 1);
    scene.triangles[0].material = 1;
    scene.triangles.push_back({{-100, 10, 100}, {0, 10, -100}, {100, 10, 100}, 1});
    scene.background = {1, 1, 1};
    for (int depth : {1, 2, 10}) {
        scene.depth = depth;
        RayStats stats;
        color c = Shade(&scene, {0, 5, 0}, {0, -1, 0}, &stats);
        CHECK(stats.reflection == (uint64_t)(depth - 1) && stats.shadow == 0,
              "facing mirrors, depth " + std::to_string(depth) + ": " + std::to_string(depth - 1) +
                  " reflection rays, then the chain stops");
        CHECK(c.x == 0 && c.y == 0 && c.z == 0,
              "facing mirrors cut off at depth " + std::to_string(depth) + ": black");
    }
}

// The floor's max(ambient, S) is taken channel by channel: a light of intensity (1, 0.1, 0)
// straight above a white floor lights red fully, and green and blue not above the ambient 0.2,
// so the colour is (1, 0.2, 0.2).
static void TestFloorMaxPerChannel() {
    Scene scene = FloorScene({0, 10, 0}, 1);
    scene.lights[0].intensity = {1, real(0.1), 0};
    RayStats stats;
    color c = Shade(&scene, {0, 5, 0}, {0, -1, 0}, &stats);
    CHECK(c.x == 1 && c.y == real(0.2) && c.z == real(0.2),
          "light (1, 0.1, 0) from straight above: max(0.2, S) per channel is (1, 0.2, 0.2)");
}

void TestShading() {
    TestFloorMaxPerChannel();
    TestLit();
    TestShadow();
    TestFacingAway();
    TestMirror();
    TestDepthCutsFacingMirrors();
}
