// tests/test_path.cpp -- `shading path`: predictions worked out by hand, and Monte Carlo error.
//
// Both estimators: rt's (next-event estimation, MIS, roulette) and the journal's, as Ray Tracing
// in One Weekend writes it. Three scenes have exact answers: a diffuse sphere in a white furnace
// (every path returns rho), a diffuse wall under one point light (rho / pi I cos / r^2, nothing
// else), and the inside of a closed emitting sphere (Le / (1 - rho) in expectation, exactly a
// geometric sum under a fixed bounce cap). The rest are statistical: the tests derive their
// tolerance from the sample count.
#include "../render.h"
#include "test.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

static const double kPiDouble = 3.14159265358979323846; // (kPi is rounded to real)

// A path-traced scene of size n x n, the camera at the origin looking down -z.
static Scene PathScene(int n) {
    Scene scene;
    InitScene(&scene);
    scene.width = scene.height = n;
    scene.shading = SHADING_PATH;
    scene.depth = 1000;
    return scene;
}

static RenderSettings PathSettings(const Scene *scene, int spp, PathMethods path) {
    RenderSettings s = TestSettings(scene);
    s.samplesPerPixel = spp;
    s.path = path;
    PlanRender(scene, &s);
    return s;
}

// The pixel's linear light (before the sRGB curve), with its rays counted.
static color Pixel(const Scene *scene, const RenderSettings *s, int i, int j, RayStats *stats) {
    return RenderPixel(scene, s, i, j, stats);
}

// White furnace: a diffuse sphere of reflectance rho under a background of 1. A path meets the
// sphere, scatters (with cosine sampling its throughput becomes rho, exactly: the cosine and the
// density cancel) and escapes (a sphere is convex), bringing back 1: every sample is rho.
static void TestWhiteFurnace() {
    Scene scene = PathScene(9);
    scene.background = {1, 1, 1};
    color rho = {real(0.3), real(0.5), real(0.8)};
    scene.materials.push_back(Matte("grey", rho));
    scene.spheres.push_back({{0, 0, -4}, real(1.5), 0});
    for (int roulette = 0; roulette < 2; roulette++) {
        RenderSettings s = PathSettings(
            &scene, 1,
            {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_MIS, roulette == 1, 0, SPHERES_CONE});
        RayStats stats = {};
        bool exact = true;
        for (int j = 2; j <= 6; j++)
            for (int i = 2; i <= 6; i++) {
                color c = Pixel(&scene, &s, i, j, &stats);
                exact = exact && c.x == rho.x && c.y == rho.y && c.z == rho.z;
            }
        CHECK(exact, "white furnace: every path on the sphere brings back exactly rho");
        CHECK(stats.diffuse == stats.primary,
              "and every path scatters once and escapes: one diffuse ray a primary ray");
        s = PathSettings(
            &scene, 8,
            {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_MIS, roulette == 1, 0, SPHERES_CONE});
        s.sampling = SAMPLES_JITTER;
        color c = Pixel(&scene, &s, 4, 4, &stats);
        CHECK_NEAR(c.z, rho.z, 8 * kRelTol, "8 jittered samples average to rho (but rounding)");
    }
    RenderSettings s = PathSettings(&scene, 1, {});
    RayStats stats = {};
    color corner = Pixel(&scene, &s, 0, 0, &stats);
    CHECK(corner.x == 1 && corner.y == 1 && corner.z == 1, "the background itself is 1");
}

// A diffuse wall z = -4 under a point light of intensity I at (0, 0, -2): the centre pixel's
// ray (33 x 33, pixel 16) meets the wall at (0, 0, -4), 2 from the light, head on: radiance
// rho / pi * I / 4. The scattered ray escapes into a black background: nothing else adds.
static void TestWallUnderPointLight() {
    Scene scene = PathScene(33);
    real rho = real(0.5);
    scene.materials.push_back(Matte("wall", {rho, rho, rho}));
    scene.triangles.push_back({{-50, -50, -4}, {50, -50, -4}, {0, 50, -4}, 0});
    scene.lights.push_back({{0, 0, -2}, {4, 4, 4}});
    RenderSettings s = PathSettings(&scene, 4, {});
    s.sampling = SAMPLES_GRID;
    s.samplesPerPixel = 1;
    RayStats stats = {};
    color c = Pixel(&scene, &s, 16, 16, &stats);
    double expected = 0.5 / kPiDouble * 4 / 4;
    CHECK_NEAR(c.x, expected, 8 * kRelTol * expected, "rho / pi * I cos / r^2 = 0.5 / pi");
    // Another pixel: its ray from the camera, the hit predicted from the geometry
    Ray ray;
    GetCameraRay(&s.camera, 33, 33, {real(3.5), real(28.5)}, &ray);
    double t = 4 / -(double)ray.dir.z;
    double x = t * ray.dir.x, y = t * ray.dir.y, r2 = x * x + y * y + 4;
    double cosTheta = 2 / std::sqrt(r2);
    expected = 0.5 / kPiDouble * 4 * cosTheta / r2;
    c = Pixel(&scene, &s, 3, 28, &stats);
    CHECK_NEAR(c.y, expected, 64 * kRelTol * expected,
               "off-centre: rho / pi * I cos(theta) / r^2 at the hit the camera ray predicts");
    CHECK(stats.primary == 2 && stats.shadow == 2 && stats.diffuse == 2,
          "one shadow ray and one scattered ray a pixel, exactly");
}

// Inside a closed diffuse sphere of reflectance rho that emits Le: every ray meets the sphere,
// so the light is Le (1 + rho + rho^2 + ...) = Le / (1 - rho). Under a cap of k rays a path,
// scattered rays only and no roulette, it is exactly Le (1 + rho + ... + rho^(k-1)).
static Scene InsideGlowingSphere(real rho, real emit) {
    Scene scene = PathScene(8);
    Material m = Matte("glow", {rho, rho, rho});
    m.emit = {emit, emit, emit};
    scene.materials.push_back(m);
    scene.spheres.push_back({{0, 0, 0}, 10, 0});
    return scene;
}

static void TestInsideGlowingSphere() {
    Scene scene = InsideGlowingSphere(real(0.5), 1);
    for (int k : {1, 3, 8}) {
        scene.depth = k;
        RenderSettings s = PathSettings(
            &scene, 2, {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_NONE, true, 0, SPHERES_CONE});
        RayStats stats = {};
        color c = Pixel(&scene, &s, 3, 4, &stats);
        double expected = (1 - std::pow(0.5, k)) / 0.5;
        CHECK_NEAR(c.x, expected, 8 * kRelTol,
                   "cap of " + std::to_string(k) + " rays: Le (1 + rho + ... + rho^(k-1))");
        // With next-event estimation the k-th ray's hit also samples the lamp, the sphere itself:
        // rho/pi Le cos cos' / r^2 over the density 1 / (4 pi R^2), and on a sphere cos = cos' =
        // r / 2R, so exactly rho Le, weighted rho^(k-1): one term more
        for (LightMethod lights : {LIGHTS_NEE, LIGHTS_MIS}) {
            RenderSettings n = PathSettings(
                &scene, 2, {ESTIMATOR_FULL, SCATTER_COSINE, lights, true, 0, SPHERES_CONE});
            color d = Pixel(&scene, &n, 3, 4, &stats);
            CHECK_NEAR(d.x, (1 - std::pow(0.5, k + 1)) / 0.5, 8 * kRelTol,
                       "cap of " + std::to_string(k) +
                           " rays, next-event estimation: Le (1 + rho + ... + rho^k)");
        }
    }
    // Unbiased methods, no cap to speak of: the mean of 64 pixels within 4 standard errors
    for (LightMethod lights : {LIGHTS_MIS, LIGHTS_NEE, LIGHTS_NONE}) {
        scene.depth = 1000;
        RenderSettings s = PathSettings(
            &scene, 16, {ESTIMATOR_FULL, SCATTER_COSINE, lights, false, 0, SPHERES_CONE});
        double sum = 0, sum2 = 0;
        RayStats stats = {};
        for (int j = 0; j < 8; j++)
            for (int i = 0; i < 8; i++) {
                double v = Pixel(&scene, &s, i, j, &stats).x;
                sum += v, sum2 += v * v;
            }
        double mean = sum / 64, error = std::sqrt((sum2 / 64 - mean * mean) / 63);
        CHECK(std::fabs(mean - 2) <= 4 * error + 1e-6,
              "roulette: the mean light inside is Le / (1 - rho) = 2, within 4 standard errors (" +
                  std::to_string(mean) + " +- " + std::to_string(error) + ")");
        CHECK(error > 0, "and the estimate does vary: the paths are random");
    }
}

// Next-event estimation at every scale the robustness summary claims: an emitter's density is
// a ratio of lengths (EmitterPdf), never an area over a squared distance, which leave the range
// of numbers in a scene 1e160 wide (1e20 in float) or that small. Inside the glowing sphere of
// radius 10 s, one ray and its lamp sample give exactly Le (1 + rho) at every scale s; inside a
// glowing octahedron of radius s (triangles: a sampled point is not a sphere's, so its estimate
// varies), the mean of 64 pixels is Le (1 + rho), within 4 standard errors.
static void TestEmittersAtEveryScale() {
#ifdef RT_FLOAT
    const real scales[] = {real(1e-37), real(1e-22), 1, real(1e19), real(1e36)};
#else
    const real scales[] = {real(1e-300), real(1e-170), 1, real(1e154), real(1e300)};
#endif
    for (real scale : scales) {
        char text[32];
        snprintf(text, sizeof text, " (scale %g)", (double)scale);
        std::string at = text;
        Scene sphere = InsideGlowingSphere(real(0.5), 1);
        sphere.spheres[0].radius = 10 * scale, sphere.depth = 1;
        RenderSettings s = PathSettings(
            &sphere, 2, {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_NEE, true, 0, SPHERES_CONE});
        RayStats stats = {};
        CHECK_NEAR(Pixel(&sphere, &s, 3, 4, &stats).x, 1.5, 8 * kRelTol,
                   "inside a glowing sphere, one ray and its lamp sample: Le (1 + rho)" + at);
        Scene octahedron = PathScene(8);
        octahedron.materials = sphere.materials, octahedron.depth = 1;
        vec3 p[6] = {{scale, 0, 0},  {-scale, 0, 0}, {0, scale, 0},
                     {0, -scale, 0}, {0, 0, scale},  {0, 0, -scale}};
        int f[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                       {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
        for (auto &t : f)
            octahedron.triangles.push_back({p[t[0]], p[t[1]], p[t[2]], 0});
        for (LightMethod lights : {LIGHTS_NEE, LIGHTS_MIS}) {
            RenderSettings o = PathSettings(
                &octahedron, 16, {ESTIMATOR_FULL, SCATTER_COSINE, lights, true, 0, SPHERES_CONE});
            double sum = 0, sum2 = 0;
            for (int j = 0; j < 8; j++)
                for (int i = 0; i < 8; i++) {
                    double v = Pixel(&octahedron, &o, i, j, &stats).x;
                    sum += v, sum2 += v * v;
                }
            double mean = sum / 64, error = std::sqrt((sum2 / 64 - mean * mean) / 63);
            CHECK(std::fabs(mean - 1.5) <= 4 * error && error > 0,
                  std::string(lights == LIGHTS_NEE ? "next-event estimation" : "MIS") +
                      " inside a glowing octahedron: Le (1 + rho) = 1.5 within 4 standard "
                      "errors (" +
                      std::to_string(mean) + " +- " + std::to_string(error) + ")" + at);
        }
    }
}

// A small Cornell-like box: white, red and green walls, a lamp patch under the ceiling, a white
// sphere, one point light; n x n pixels.
static Scene SmallBox(int n) {
    Scene scene = PathScene(n);
    scene.depth = 10;
    Material lamp = Matte("lamp", {0, 0, 0});
    lamp.emit = {12, 12, 12};
    scene.materials = {Matte("white", {real(0.7), real(0.7), real(0.7)}),
                       Matte("red", {real(0.6), real(0.05), real(0.05)}),
                       Matte("green", {real(0.1), real(0.45), real(0.15)}), lamp};
    auto quad = [&](vec3 a, vec3 b, vec3 c, vec3 d, int m) {
        scene.triangles.push_back({a, b, c, m});
        scene.triangles.push_back({a, c, d, m});
    };
    quad({-1, -1, -2}, {1, -1, -2}, {1, -1, -4}, {-1, -1, -4}, 0); // floor
    quad({-1, 1, -2}, {-1, 1, -4}, {1, 1, -4}, {1, 1, -2}, 0);     // ceiling
    quad({-1, -1, -4}, {1, -1, -4}, {1, 1, -4}, {-1, 1, -4}, 0);   // back
    quad({-1, -1, -2}, {-1, -1, -4}, {-1, 1, -4}, {-1, 1, -2}, 1); // left
    quad({1, -1, -2}, {1, 1, -2}, {1, 1, -4}, {1, -1, -4}, 2);     // right
    real y = real(0.99);
    quad({real(-0.3), y, real(-2.7)}, {real(0.3), y, real(-2.7)}, {real(0.3), y, real(-3.3)},
         {real(-0.3), y, real(-3.3)}, 3);
    scene.spheres.push_back({{real(-0.3), real(-0.6), real(-3.2)}, real(0.4), 0});
    scene.lights.push_back({{real(0.5), real(0.5), real(-2.5)}, {real(0.3), real(0.3), real(0.3)}});
    return scene;
}

// The linear light of every pixel, averaged over the channels.
static std::vector<double> Light(const Scene *scene, int spp, PathMethods path,
                                 SampleMethod sampling = SAMPLES_JITTER) {
    RenderSettings s = PathSettings(scene, spp, path);
    s.sampling = sampling;
    std::vector<double> v;
    RayStats stats = {};
    for (int j = 0; j < scene->height; j++)
        for (int i = 0; i < scene->width; i++) {
            color c = Pixel(scene, &s, i, j, &stats);
            v.push_back((c.x + c.y + c.z) / 3);
        }
    return v;
}

static double Rmse(const std::vector<double> &a, const std::vector<double> &b) {
    double sum = 0;
    for (size_t k = 0; k < a.size(); k++)
        sum += (a[k] - b[k]) * (a[k] - b[k]);
    return std::sqrt(sum / a.size());
}

// Monte Carlo error falls as 1 / sqrt(N): each fourfold of samples halves the RMSE. Inside the
// glowing sphere every pixel's exact answer is 2 and no edge is in view, so all the error is
// the paths' noise.
static void TestConvergence() {
    Scene scene = InsideGlowingSphere(real(0.5), 1);
    scene.width = scene.height = 16;
    std::vector<double> exact(256, 2.0);
    double e16 = Rmse(Light(&scene, 16, {}), exact);
    double e64 = Rmse(Light(&scene, 64, {}), exact);
    double e256 = Rmse(Light(&scene, 256, {}), exact);
    CHECK(e16 / e64 > 1.6 && e16 / e64 < 2.5,
          "RMSE 16 -> 64 samples falls by about 2 (" + std::to_string(e16 / e64) + ")");
    CHECK(e64 / e256 > 1.6 && e64 / e256 < 2.5,
          "RMSE 64 -> 256 samples falls by about 2 (" + std::to_string(e64 / e256) + ")");
}

// Two estimates of the same light agree: the per-pixel differences average to 0 within 4
// standard errors of their mean.
static void CheckAgree(const std::vector<double> &base, const std::vector<double> &other,
                       const std::string &name) {
    double sum = 0, sum2 = 0, n = (double)base.size();
    for (size_t p = 0; p < base.size(); p++) {
        double d = other[p] - base[p];
        sum += d, sum2 += d * d;
    }
    double mean = sum / n, error = std::sqrt((sum2 / n - mean * mean) / (n - 1));
    CHECK(std::fabs(mean) <= 4 * error, name + " agrees with the reference estimate: mean " +
                                            "difference " + std::to_string(mean) + " within 4 x " +
                                            std::to_string(error));
}

// Every method estimates the same light: for each pair, the per-pixel differences average to 0
// within 4 standard errors of their mean.
static void TestMethodsAgree() {
    Scene scene = SmallBox(10);
    std::vector<double> base =
        Light(&scene, 256, {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_MIS, false, 1, SPHERES_CONE});
    const PathMethods others[] = {
        {ESTIMATOR_FULL, SCATTER_UNIFORM, LIGHTS_MIS, false, 2, SPHERES_CONE},
        {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_NEE, false, 3, SPHERES_CONE},
        {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_NONE, false, 4, SPHERES_CONE},
        {ESTIMATOR_FULL, SCATTER_UNIFORM, LIGHTS_NONE, true, 5, SPHERES_CONE}};
    const char *names[] = {"uniform sampling", "NEE without MIS", "no NEE",
                           "uniform, no NEE, no roulette", "adaptive sampling (no NEE)"};
    for (int k = 0; k < 5; k++) {
        if (k == 4) // adaptive, where the lamp is the only light and found only by chance: a
            scene.lights.clear(); // count chosen from the averaged samples would darken it
        std::vector<double> other =
            k < 4 ? Light(&scene, 256, others[k])
                  : Light(&scene, 256,
                          {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_NONE, false, 6, SPHERES_CONE},
                          SAMPLES_ADAPTIVE);
        if (k == 4)
            base = Light(&scene, 256,
                         {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_NONE, false, 1, SPHERES_CONE});
        CheckAgree(base, other, names[k]);
    }
}

// An emitting sphere, found by next-event estimation (points drawn on it by Marsaglia's method)
// and by the scattered rays that hit it: with either alone, or both under MIS, the same light.
static void TestSphereLampAgrees() {
    Scene scene = SmallBox(10);
    scene.lights.clear();
    scene.spheres[0].material = 3; // the lamp's material: the sphere glows
    std::vector<double> hits =
        Light(&scene, 256, {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_NONE, false, 1, SPHERES_CONE});
    CheckAgree(
        hits,
        Light(&scene, 256, {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_NEE, false, 2, SPHERES_CONE}),
        "a glowing sphere found by next-event estimation alone");
    CheckAgree(
        hits,
        Light(&scene, 256, {ESTIMATOR_FULL, SCATTER_UNIFORM, LIGHTS_MIS, false, 3, SPHERES_CONE}),
        "a glowing sphere under MIS, uniform sampling");
    CheckAgree(
        hits,
        Light(&scene, 256, {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_MIS, false, 4, SPHERES_AREA}),
        "a glowing sphere under MIS, its points drawn over its area");
}

// Light from a glowing sphere seen from outside, by hand: a surface point at distance D from the
// centre of a sphere of radius R and radiance Le, the centre at angle beta from its normal and
// the whole sphere above its horizon, receives irradiance pi Le (R / D)^2 cos beta (the sphere
// looks like a disk of that solid angle), and a matte surface sends rho / pi of it back. Here the
// eye ray meets the floor z = -s at (0, 0, -s), the lamp's centre is at (s, 0, s), R = s / 2: D =
// s sqrt(5), cos beta = 2 / sqrt(5). With one ray (depth 1) only next-event estimation lights the
// point; with two, a scattered ray can find the lamp too, weighted by MIS. The mean of 256
// samples (one a seed) is the hand answer within 4 standard errors at every scale, under either
// way of drawing the lamp's points, and drawn in the cone the lamp is seen in, a sample varies
// less than when drawn over its whole area, half of which faces away.
static double LampSample(real scale, int depth, PathMethods methods, int seed) {
    Scene scene = PathScene(1);
    scene.depth = depth;
    Material lamp = Matte("lamp", {0, 0, 0});
    lamp.emit = {4, 4, 4};
    scene.materials = {Matte("floor", {real(0.5), real(0.5), real(0.5)}), lamp};
    scene.triangles.push_back({{-8 * scale, -8 * scale, -scale},
                               {8 * scale, -8 * scale, -scale},
                               {0, 8 * scale, -scale},
                               0});
    scene.spheres.push_back({{scale, 0, scale}, scale / 2, 1});
    methods.seed = seed;
    RenderSettings s = PathSettings(&scene, 1, methods);
    s.sampling = SAMPLES_GRID;
    RayStats stats = {};
    return Pixel(&scene, &s, 0, 0, &stats).x;
}

static void TestSphereLampFromOutside() {
    double exact = 0.5 * 4 * (0.25 / 5) * (2 / std::sqrt(5.0)); // rho Le (R/D)^2 cos beta
#ifdef RT_FLOAT
    const real scales[] = {real(1e-30), 1, real(1e30)};
#else
    const real scales[] = {real(1e-300), 1, real(1e300)};
#endif
    for (real scale : scales)
        for (int depth : {1, 2}) {
            double spread[2];
            for (SphereSampling how : {SPHERES_CONE, SPHERES_AREA}) {
                double sum = 0, sum2 = 0;
                for (int seed = 0; seed < 256; seed++) {
                    double v = LampSample(scale, depth,
                                          {ESTIMATOR_FULL, SCATTER_COSINE,
                                           depth == 1 ? LIGHTS_NEE : LIGHTS_MIS, false, 0, how},
                                          seed);
                    sum += v, sum2 += v * v;
                }
                double mean = sum / 256, sd = std::sqrt(std::max(0.0, sum2 / 256 - mean * mean));
                spread[how] = sd;
                char text[160];
                snprintf(text, sizeof text,
                         "a lamp sphere seen from outside, %s, %s, scale %g: rho Le (R/D)^2 cos "
                         "beta = %.5f, mean %.5f +- %.5f",
                         how == SPHERES_CONE ? "its cone" : "its area",
                         depth == 1 ? "next-event estimation" : "MIS", (double)scale, exact, mean,
                         sd / 16);
                CHECK(sd > 0 && std::fabs(mean - exact) <= 4 * sd / 16, text);
            }
            CHECK(spread[SPHERES_CONE] < 0.5 * spread[SPHERES_AREA],
                  "drawn in its cone, a sample varies less than half as much as over its area (" +
                      std::to_string(spread[SPHERES_CONE]) + " against " +
                      std::to_string(spread[SPHERES_AREA]) + ")");
        }
}

// The same bytes on 1 and 2 threads; exact ray counts where they are predictable.
static void TestThreadsAndCounts() {
    Scene scene = SmallBox(16);
    RenderSettings s = PathSettings(&scene, 8, {});
    Image one, two;
    RayStats a = {}, b = {};
    s.threads = 1;
    Render(&scene, &s, &one, &a);
    s.threads = 2;
    Render(&scene, &s, &two, &b);
    CHECK(one.pixels == two.pixels && a.diffuse == b.diffuse && a.shadow == b.shadow,
          "path tracing: the same image bytes and ray counts on 1 and 2 threads");
    // A cap of 2 rays: every primary ray meets a wall (the box is closed but for the front,
    // which the camera looks through), adds 1 shadow ray for the point light and 1 for an
    // emitter, and scatters once; the scattered ray's vertex adds its shadow rays and ends
    scene.depth = 2;
    RayStats c = {};
    RenderSettings capped = PathSettings(
        &scene, 1, {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_MIS, true, 0, SPHERES_CONE});
    Render(&scene, &capped, &one, &c);
    uint64_t diffuseHits = 0; // pixels whose centre sees a diffuse wall, not the lamp
    for (int j = 0; j < 16; j++)
        for (int i = 0; i < 16; i++) {
            Ray ray;
            RayHit hit;
            GetCameraRay(&capped.camera, 16, 16, {i + real(0.5), j + real(0.5)}, &ray);
            diffuseHits += FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &hit) &&
                           hit.material != 3;
        }
    CHECK(c.diffuse == diffuseHits && diffuseHits > 200,
          "a cap of 2 rays: one scattered ray for each pixel that sees a diffuse surface");
    CHECK(c.shadow <= 4 * 256 && c.shadow >= 256,
          "at most 2 shadow rays at each of the 2 vertices (the last one still sees the lights)");
    // No diffuse surface: a mirror box casts no scattered rays
    Scene mirrors = SmallBox(8);
    for (Material &m : mirrors.materials)
        m.mirror = 1;
    RayStats d = {};
    RenderSettings ms = PathSettings(&mirrors, 1, {});
    Render(&mirrors, &ms, &one, &d);
    CHECK(d.diffuse == 0 && d.shadow == 0 && d.reflection > 0,
          "mirrors only: no scattered rays, no shadow rays, only reflections");
    CHECK(ms.effects.indirect == false, "and the plan says no indirect light");
}

// An emitting triangle without area can be neither hit nor sampled: it is not an emitter, and
// no density is divided by its area of 0 (which made NaN pixels).
static void TestEmitterWithoutArea() {
    Scene scene = SmallBox(6);
    Material flat = Matte("flat", {0, 0, 0});
    flat.emit = {5, 5, 5};
    scene.materials.push_back(flat);
    scene.triangles.push_back({{-1, real(0.5), -3}, {0, real(0.5), -3}, {1, real(0.5), -3}, 4});
    RenderSettings s = PathSettings(&scene, 8, {});
    RayStats stats = {};
    bool finite = true;
    for (int j = 0; j < 6; j++)
        for (int i = 0; i < 6; i++)
            finite = finite && IsFinite(Pixel(&scene, &s, i, j, &stats));
    CHECK(finite && s.effects.emitters.size() == 2,
          "a lamp without area is left out of the emitters (2 remain), and no pixel is NaN");
}

// The journal's estimator (--estimator journal): colour = emitted + reflectance x what the
// scattered ray brings back. Exact where every path is the same sum: in the white furnace every
// sample is rho (the scattered ray escapes to a background of 1), inside a closed glowing
// sphere Le (1 + rho + ... + rho^(k-1)) under a cap of k rays. A point light, which no ray can
// hit, lights nothing. And where a scene has no point light, it estimates the same light as
// rt's estimator, within 4 standard errors.
static void TestJournalEstimator() {
    PathMethods journal = {ESTIMATOR_JOURNAL, SCATTER_COSINE, LIGHTS_MIS, false, 0, SPHERES_CONE};
    Scene furnace = PathScene(9);
    furnace.background = {1, 1, 1};
    furnace.materials.push_back(Matte("grey", {real(0.3), real(0.5), real(0.8)}));
    furnace.spheres.push_back({{0, 0, -4}, real(1.5), 0});
    RenderSettings s = PathSettings(&furnace, 1, journal);
    RayStats stats = {};
    color c = Pixel(&furnace, &s, 4, 4, &stats);
    CHECK(c.x == real(0.3) && c.y == real(0.5) && c.z == real(0.8) && stats.diffuse == 1,
          "the journal's estimator in the white furnace: rho exactly, one diffuse ray");
    Scene inside = InsideGlowingSphere(real(0.5), 1);
    for (int k : {1, 3, 8}) {
        inside.depth = k;
        s = PathSettings(&inside, 2, journal);
        CHECK_NEAR(Pixel(&inside, &s, 3, 4, &stats).x, (1 - std::pow(0.5, k)) / 0.5, 8 * kRelTol,
                   "the journal's estimator inside a glowing sphere, cap of " + std::to_string(k) +
                       " rays: Le (1 + rho + ... + rho^(k-1))");
    }
    Scene wall = PathScene(33);
    wall.materials.push_back(Matte("wall", {real(0.5), real(0.5), real(0.5)}));
    wall.triangles.push_back({{-50, -50, -4}, {50, -50, -4}, {0, 50, -4}, 0});
    wall.lights.push_back({{0, 0, -2}, {4, 4, 4}});
    s = PathSettings(&wall, 1, journal);
    c = Pixel(&wall, &s, 16, 16, &stats);
    CHECK(c.x == 0 && c.y == 0 && c.z == 0,
          "the journal's estimator: a wall under a point light only is black (no ray hits it)");
    Scene box = SmallBox(10);
    box.lights.clear();
    CheckAgree(
        Light(&box, 256, {ESTIMATOR_FULL, SCATTER_COSINE, LIGHTS_MIS, false, 1, SPHERES_CONE}),
        Light(&box, 256, {ESTIMATOR_JOURNAL, SCATTER_COSINE, LIGHTS_MIS, false, 2, SPHERES_CONE}),
        "the journal's estimator against rt's, a box lit by a lamp");
}

// The program: the path options, --stats and --pixel.
static void TestPathProgram() {
    std::string dir = MakeTestDir("path");
    if (dir.empty())
        return;
    std::string scene = "size 8 8\nshading path\nlight 0 0.5 -2 2 2 2\nmaterial lamp emit 3 3 3\n"
                        "material white diffuse 0.7 0.7 0.7\n"
                        "triangle -9 -1 -9 9 -1 -9 0 -1 9 white\nsphere 0 1.5 -4 0.5 lamp\n";
    FILE *f = fopen((std::string(dir) + "/p.scene").c_str(), "w");
    fputs(scene.c_str(), f);
    fclose(f);
    std::string err;
    int status = RunRay(dir,
                        "p.scene --spp 4 --scatter uniform --lights nee --roulette off "
                        "--seed 3 --threads 1 --stats -o p.png",
                        &err);
    CHECK(status == 0 && err.find(" diffuse=") != std::string::npos &&
              err.find("indirect") != std::string::npos,
          "--scatter, --lights, --roulette, --seed: a render whose --stats counts diffuse rays "
          "and names the indirect effect");
    status = RunRay(dir, "p.scene --pixel 4 6", &err);
    std::string tree = ReadFile(std::string(dir) + "/out.txt");
    CHECK(status == 0 && tree.find("\"kind\":\"diffuse\"") != std::string::npos &&
              tree.find("\"kind\":\"shadow\"") != std::string::npos,
          "--pixel shows the path: a diffuse ray and shadow rays in the tree");
    CHECK(RunRay(dir, "p.scene --lights some", &err) == 2, "--lights some: exit 2");
    status = RunRay(dir, "p.scene --estimator journal --pixel 4 6", &err);
    tree = ReadFile(std::string(dir) + "/out.txt");
    CHECK(status == 0 && tree.find("\"kind\":\"diffuse\"") != std::string::npos &&
              tree.find("\"kind\":\"shadow\"") == std::string::npos,
          "--estimator journal --pixel: a diffuse ray in the tree, and no shadow ray");
    CHECK(RunRay(dir, "p.scene --estimator journal --spp 2 --stats -o j.png", &err) == 0 &&
              err.find(" shadow=0 ") != std::string::npos,
          "--estimator journal: a render that casts no shadow ray");
    CHECK(RunRay(dir, "p.scene --estimator book", &err) == 2, "--estimator book: exit 2");
    RemoveTestDir(dir);
}

void TestPath() {
    TestWhiteFurnace();
    TestWallUnderPointLight();
    TestInsideGlowingSphere();
    TestEmittersAtEveryScale();
    TestConvergence();
    TestMethodsAgree();
    TestSphereLampAgrees();
    TestSphereLampFromOutside();
    TestThreadsAndCounts();
    TestEmitterWithoutArea();
    TestJournalEstimator();
    TestPathProgram();
}
