// tests/test_render.cpp -- the camera's rays and the assignment image, predicted by hand.
//
// The assignment camera: eye at the origin, screen 2 wide at distance 2, 512 pixels, so a pixel
// is 2/512 = 1/256 wide and pixel (i, j)'s centre ray is ((i + 0.5 - 256)/256,
// (256 - j - 0.5)/256, -2). Every number below is exact in binary.
#include "../render.h"
#include "../robust/robust.h"
#include "test.h"

static void CheckRay(const Perspective &p, real sx, real sy, vec3 expected, const char *what) {
    Ray ray;
    GetRay(p, {sx, sy}, &ray);
    CHECK(ray.origin.x == 0 && ray.origin.y == 0 && ray.origin.z == 0,
          std::string("GetRay ") + what + ": starts at the eye");
    CHECK(ray.dir.x == expected.x && ray.dir.y == expected.y && ray.dir.z == expected.z,
          std::string("GetRay ") + what + ": exact direction");
}

void TestCamera() {
    Scene scene;
    BuildDefaultScene(&scene);
    Perspective p = scene.camera.perspective;
    // Top-left pixel (0, 0): (0.5 - 256)/256 = -0.998046875 across, +0.998046875 up
    CheckRay(p, 0.5, 0.5, {-0.998046875, 0.998046875, -2}, "top-left pixel (0, 0)");
    // Bottom-right pixel (511, 511): the mirror image
    CheckRay(p, 511.5, 511.5, {0.998046875, -0.998046875, -2}, "bottom-right pixel (511, 511)");
    // Top-right pixel (511, 0)
    CheckRay(p, 511.5, 0.5, {0.998046875, 0.998046875, -2}, "top-right pixel (511, 0)");
    // The screen's centre falls between four pixels; pixel (256, 256) is half a pixel right/down
    CheckRay(p, 256.5, 256.5, {0.001953125, -0.001953125, -2}, "centre pixel (256, 256)");
    CheckRay(p, 256, 256, {0, 0, -2}, "screen centre (256, 256) itself");
    // A non-square image keeps square pixels: 512 x 256 spans y in [-0.5, 0.5]
    p.heightPixels = 256;
    CheckRay(p, 0, 0, {-1, 0.5, -2}, "top-left corner of a 512 x 256 screen");
}

struct PixelPrediction {
    int i, j;
    uint8_t rgb[3];
    const char *why;
};

// Worked out from the scene table with kd * max(0.2, N.L), light (3, 5, -15); checked against
// an independent render. N.L values to 4 places.
static const PixelPrediction kAssignmentPixels[] = {
    {110, 330, {51, 51, 51}, "floor at (-3.91, -2, -13.74), in the red sphere's shadow: 0.2 * 255"},
    {256, 100, {0, 0, 215}, "back wall at (0.02, 6.07, -20), lit: N.L = 0.8447, 0.8447 * 255"},
    {256, 330, {231, 231, 231}, "floor at (0.01, -2, -13.74), lit: N.L = 0.9075"},
    {400, 340, {235, 235, 235}, "floor at (3.42, -2, -12.12), lit: N.L = 0.9233"},
    {490, 150, {222, 0, 0}, "red wall at (8, 3.60, -17.47), lit: N.L = 0.8698"},
    {150, 280, {66, 0, 0}, "red sphere, lit side: N.L = 0.2591, just above the 0.2 floor"},
    {146, 292, {51, 0, 0}, "red sphere's centre pixel: the surface there faces away (N.L < 0)"},
    {256, 256, {0, 0, 0}, "big mirror sphere, head on: reflects back past the eye into nothing"},
    {300, 300, {244, 244, 244}, "big mirror sphere reflecting the lit floor"},
    {256, 500, {0, 0, 0}, "below the floor's front edge: the ray misses everything, black"},
    {0, 0, {0, 0, 0}, "top-left corner: passes left of the back wall, black"},
};

// A channel's byte: clamp(c, 0, 1) * 255 rounded half away from zero, as std::lround rounds it.
// The values next to every half step (k + 0.5, one ulp either side) and those just below
// 0.5 / 255, among them one whose product is the largest float below 0.5, where the shortcut
// (int)(v + 0.5) would round up, give lround's answer; 0, 1, NaN and the values outside [0, 1]
// give 0 and 255.
static void CheckToByte() {
    int wrong = 0;
    for (int k = 0; k < 255; k++) {
        real half = (real(k) + real(0.5)) / 255;
        for (real c : {NextAfter(half, false), half, NextAfter(half, true)})
            wrong += ToByte(c) != (uint8_t)std::lround(c * 255);
    }
    // 16 steps down from 0.5 / 255: in float, one step down, c * 255 is the largest float below 0.5
    real below = real(0.5) / 255;
    for (int step = 0; step < 16; step++, below = NextAfter(below, false))
        wrong += ToByte(below) != (uint8_t)std::lround(below * 255);
    CHECK(wrong == 0, "ToByte rounds as std::lround at all 255 half steps and just around them (" +
                          std::to_string(wrong) + " differ)");
    CHECK(ToByte(0) == 0 && ToByte(-1) == 0 && ToByte(std::nan("")) == 0 && ToByte(1) == 255 &&
              ToByte(2) == 255 && ToByte(real(0.5)) == 128,
          "ToByte: 0, -1 and NaN give 0; 1 and 2 give 255; 0.5 gives 127.5 rounded up, 128");
}

void TestAssignmentImage() {
    CheckToByte();
    Scene scene;
    BuildDefaultScene(&scene);
    RenderSettings settings = TestSettings(&scene);
    CHECK(settings.width == 512 && settings.height == 512 && scene.depth == 10 &&
              scene.spheres.size() == 3 && scene.triangles.size() == 5 && scene.lights.size() == 1,
          "assignment scene: 512 x 512, depth 10, 3 spheres, 5 triangles, 1 light");
    for (const PixelPrediction &p : kAssignmentPixels) {
        RayStats stats = {};
        color c = RenderPixel(&scene, &settings, p.i, p.j, &stats);
        uint8_t got[3] = {ToByte(c.x), ToByte(c.y), ToByte(c.z)};
        CHECK(got[0] == p.rgb[0] && got[1] == p.rgb[1] && got[2] == p.rgb[2],
              "pixel (" + std::to_string(p.i) + ", " + std::to_string(p.j) + "): " + p.why +
                  " -> got " + std::to_string(got[0]) + " " + std::to_string(got[1]) + " " +
                  std::to_string(got[2]));
    }

    // The whole image: the same bytes for 1 and 2 threads, and the rays the scene needs
    Image one, two;
    RayStats stats1 = {}, stats2 = {};
    Render(&scene, &settings, &one, &stats1);
    settings.threads = 2;
    Render(&scene, &settings, &two, &stats2);
    CHECK(one.pixels == two.pixels, "assignment image: identical bytes on 1 and 2 threads");
    CHECK(stats1.primary == 512 * 512 && stats2.primary == 512 * 512,
          "one primary ray per pixel: 262144");
    CHECK(stats1.reflection == stats2.reflection && stats1.shadow == stats2.shadow,
          "ray counts do not depend on the thread count");
    CHECK(stats1.refraction == 0, "no glass in the assignment scene: no refraction rays");

    // Jittered and adaptive samples are seeded by the pixel: the same bytes on 1 and 2 threads
    settings.width = settings.height = 64;
    settings.samplesPerPixel = 16;
    for (SampleMethod method : {SAMPLES_JITTER, SAMPLES_ADAPTIVE}) {
        settings.sampling = method;
        settings.threads = 1;
        RayStats a = {}, b = {};
        Render(&scene, &settings, &one, &a);
        settings.threads = 2;
        Render(&scene, &settings, &two, &b);
        const char *name = method == SAMPLES_JITTER ? "jitter" : "adaptive";
        CHECK(one.pixels == two.pixels && a.primary == b.primary,
              std::string("--aa ") + name + " 16 spp: identical bytes on 1 and 2 threads");
        if (method == SAMPLES_ADAPTIVE)
            CHECK(a.primary > 64 * 64 * 5 && a.primary < 64 * 64 * 16,
                  "--aa adaptive 16 spp: 5 rays where flat, 20 where refined, fewer than the "
                  "grid's 16 on average (" +
                      std::to_string(a.primary) + " for 4096 pixels)");
    }
    // Where nothing varies (an empty scene), adaptive sampling stops at its first 5 samples
    Scene empty;
    InitScene(&empty);
    RayStats e = {};
    Render(&empty, &settings, &one, &e);
    CHECK(e.primary == 64 * 64 * 5, "--aa adaptive on an empty scene: exactly 5 rays per pixel");
    // Two triangles of one flat colour (no light: ambient only) filling the view: the colour never
    // varies, but the pixels their shared diagonal crosses see two shapes, and are refined (each
    // such pixel costs 20 rays: 5 that decide, 15 more)
    Scene flat;
    InitScene(&flat);
    flat.materials.push_back(Matte("grey", {real(0.5), real(0.5), real(0.5)}));
    flat.triangles = {{{-5, -5, -2}, {5, -5, -2}, {5, 5, -2}, 0},
                      {{-5, -5, -2}, {5, 5, -2}, {-5, 5, -2}, 0}};
    RayStats f = {};
    Render(&flat, &settings, &one, &f);
    CHECK(f.primary > 64 * 64 * 5 && (f.primary - 64 * 64 * 5) % 15 == 0 &&
              f.primary < 64 * 64 * 5 + 15 * 64 * 3,
          "--aa adaptive refines where the shapes differ though the colour does not: the pixels "
          "along the diagonal (" +
              std::to_string(f.primary) + " rays)");
    settings.sampling = SAMPLES_GRID;
    settings.threads = 1;
    // 4 samples per pixel: exactly 4 primary rays per pixel
    settings.samplesPerPixel = 4;
    settings.width = settings.height = 64;
    PlanRender(&scene, &settings);
    RayStats stats4 = {};
    Render(&scene, &settings, &one, &stats4);
    CHECK(stats4.primary == 64 * 64 * 4, "--spp 4 on 64 x 64: exactly 16384 primary rays");
}
