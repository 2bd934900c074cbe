// tests/test_lens.cpp -- the thin lens of `camera lookat ... defocus|aperture ... focus ...`
// (Ray Tracing in One Weekend's defocus blur), predicted by hand: every ray through a pixel meets
// at one point of the plane in focus, so an edge on that plane stays sharp, and an edge off it is
// spread over the circle of confusion of the thin-lens formula, with the profile a disk gives. A
// camera without a lens draws the same bytes as before, and does none of the lens's work.
#include "../app/app.h"
#include "../render.h"
#include "test.h"

#include <cmath>
#include <string>

static const double kPiDouble = 3.14159265358979323846;

static Scene ReadScene(const std::string &text) {
    Scene scene;
    std::string error;
    CHECK(ParseSceneText(text, "lens.scene", &scene, &error), "the scene reads: " + error);
    return scene;
}

// The lens words, read: the radius is focus tan(angle / 2) for `defocus`, D / 2 for `aperture`,
// and the focus distance defaults to |to - from|.
static void TestLensWords() {
    const char *look = "camera lookat 0 0 0  0 0 -8  0 1 0  40";
    Scene s = ReadScene(std::string(look) + " defocus 2 focus 10");
    CHECK_NEAR(s.camera.lensRadius, 10 * std::tan(kPiDouble / 180), 4 * kRelTol,
               "defocus 2 focus 10: radius 10 tan(1 degree), the book's defocus_radius");
    CHECK(s.camera.focusDistance == 10, "focus 10");
    s = ReadScene(std::string(look) + " aperture 0.5");
    CHECK(s.camera.lensRadius == real(0.25) && s.camera.focusDistance == 8,
          "aperture 0.5: radius 0.25; no focus word: in focus at `to`, 8 away");
    s = ReadScene(std::string(look) + " focus 3");
    CHECK(s.camera.lensRadius == 0, "focus alone: no lens (a pinhole is sharp at every distance)");
    const char *bad[][2] = {
        {" defocus 180", "defocus must be at least 0 and less than 180 degrees"},
        {" defocus -1", "defocus must be at least 0"},
        {" aperture -1", "aperture must be >= 0"},
        {" aperture 1 focus 0", "focus must be > 0"},
        {" defocus 1 aperture 1", "defocus or as aperture, not both"},
        {" focus 1 focus 2", "'focus' given twice"},
        {" defocus", "'defocus' needs a number"},
        {" blur 2", "unknown word 'blur'"},
        {" 7", "extra value '7'"},
        {" aperture 1e30 focus 1e30", ""}, // (a finite radius: it reads)
        {sizeof(real) == sizeof(double) ? " defocus 179.9999 focus 1e307"
                                        : " defocus 179.9999 focus 1e37",
         "beyond the range of numbers"}, // (tan of 89.99995 degrees is about 1e6)
    };
    for (const auto &b : bad) {
        Scene scene;
        std::string error;
        bool ok = ParseSceneText(std::string(look) + b[0], "l.scene", &scene, &error);
        CHECK(b[1][0] == 0 ? ok : !ok && error.find(b[1]) != std::string::npos,
              std::string("lookat") + b[0] + ": " + (b[1][0] ? b[1] : "reads") + " (" + error +
                  ")");
    }
}

// A tilted camera, so that no coordinate is special: with the lens at any point of its disk, the
// ray through a screen position reaches, at t = 1, the very point the pinhole's ray through it
// reaches at the focus distance, eye + focus d (to a few roundings of that point's size).
static void TestFocusPlaneIsSharp() {
    Scene scene = ReadScene("size 40 30\ncamera lookat 1 2 3  -2 0.5 -4  0 1 0  50 "
                            "aperture 0.8 focus 6.5\n");
    RenderSettings s = TestSettings(&scene);
    CHECK(s.effects.defocus, "a lens: the render draws lens points");
    int farthest = 0, offRim = 0;
    for (vec2 position : {vec2{3.25, 7.5}, vec2{20, 15}, vec2{39.75, 0.25}}) {
        Ray pinhole, ray; // (the pinhole: the screen camera's own ray, from the lens's centre)
        GetScreenRay(&s.camera, 40, 30, position, &pinhole);
        vec3 sharp = pinhole.origin + real(6.5) * pinhole.dir;
        for (int k = 0; k < 64; k++) { // points across the disk, and on its rim
            real r = k < 32 ? real(k % 8) / 7 : 1, angle = real(2 * kPiDouble * k / 13);
            GetLensRay(&s.camera, 40, 30, position, {r * std::cos(angle), r * std::sin(angle)},
                       &ray);
            vec3 meet = ray.origin + ray.dir, gap = meet - sharp;
            double ulps = MaxComponent(gap) / (kUnitRoundoff * (MaxComponent(sharp) + 3));
            farthest = std::max(farthest, (int)std::ceil(ulps));
            offRim += k >= 32 &&
                      !(std::fabs(Length(ray.origin - pinhole.origin) - real(0.4)) <= 16 * kRelTol);
        }
    }
    CHECK(offRim == 0, "a rim point of the lens is the radius, 0.4, from the eye");
    CHECK(farthest <= 16, "every lens ray meets the pinhole's at the focus plane, to 16 "
                          "roundings: " +
                              std::to_string(farthest));
}

// The fraction of a unit disk on the side x < a of a vertical line: (a sqrt(1 - a^2) + asin a) / pi
// + 1/2 (the area of a circular segment), 0 below -1 and 1 above 1.
static double DiskBelow(double a) {
    if (a <= -1)
        return 0;
    if (a >= 1)
        return 1;
    return (a * std::sqrt(1 - a * a) + std::asin(a)) / kPiDouble + 0.5;
}

// An edge seen through the lens: a white half-plane x > 0 at depth z (ambient 1, no light: white
// wherever a ray meets it) on black, camera at the origin looking down -z, 64 x 64 pixels, a
// screen 1 high at distance 1 (fov 2 atan(1/2)), so a pixel is 1/64. The ray from lens point L
// through screen point s meets the focus plane at f s and depth z at s z + L (1 - z / f), so it
// meets the half-plane where L.x (1 - z / f) > -z s.x. With the lens of radius R = 1, focus f = 4
// and z = 8, that is L.x < 8 s.x: the thin lens's circle of confusion, R |z - f| / (z f) = 1/8 of
// the screen, 8 pixels, and the pixel at s shows the share of the disk below 8 s.x, averaged over
// the pixel. On the focus plane (z = 4) every lens point agrees: the edge stays in one column.
static void TestCircleOfConfusion() {
    for (int depth : {4, 8}) {
        Scene scene = ReadScene("size 64 64\ncamera lookat 0 0 0  0 0 -1  0 1 0  "
                                "53.130102354155978703 aperture 2 focus 4\nambient 1\n"
                                "material white diffuse 1 1 1\n"
                                "triangle 0 -1000 -" +
                                std::to_string(depth) + "  1000 0 -" + std::to_string(depth) +
                                "  0 1000 -" + std::to_string(depth) + " white\n");
        RenderSettings s = TestSettings(&scene);
        s.samplesPerPixel = 1024;
        int partial = 0, wrong = 0, first = -1, last = -1;
        uint64_t eyeRays = 0;
        for (int i = 0; i < 64; i++) {
            RayStats stats = {};
            double value = RenderPixel(&scene, &s, i, 32, &stats).x, expected = 0;
            eyeRays += stats.primary;
            for (int k = 0; k < 64; k++) // the pixel's average, by the midpoint rule
                expected += DiskBelow(depth == 8 ? (i + (k + 0.5) / 64 - 32) / 8
                                                 : (i + (k + 0.5) / 64 - 32) * 1e9) /
                            64;
            bool isPartial = value > 0 && value < 1;
            partial += isPartial, first = first < 0 && isPartial ? i : first;
            last = isPartial ? i : last;
            // Each sample hits or not: the average of 1024 has deviation sqrt(p (1 - p) / 1024)
            // about the expected share; 5 deviations, and 1/1024 for the midpoint rule
            double tolerance = 5 * std::sqrt(expected * (1 - expected) / 1024) + 1.0 / 1024;
            wrong += std::fabs(value - expected) > tolerance;
        }
        CHECK(s.effects.defocus && eyeRays == 64 * 1024, "1,024 eye rays a pixel, on the lens");
        if (depth == 4) {
            CHECK(partial == 0, "on the focus plane the edge is sharp: no column between black "
                                "and white (the edge falls between columns 31 and 32)");
        } else {
            CHECK(first == 24 && last == 39,
                  "off it, 8 pixels either side of the edge are grey (columns 24..39): " +
                      std::to_string(first) + ".." + std::to_string(last));
        }
        CHECK(wrong == 0, "each column is the share of the lens disk that sees the half-plane, "
                          "within 5 deviations: " +
                              std::to_string(wrong) + " columns off");
    }
}

// No lens, no work: a lens of radius 0 (or no lens words) draws the bytes of the pinhole camera,
// and draws no lens point. The slides' ray (`--camera-ray slides`) through a lens starts on the
// screen, one unit in front of the lens point, with unit length, toward the same point in focus.
static void TestNoLensNoWork() {
    const char *rest = "size 24 16\nmaterial red diffuse 1 0 0\nlight 2 3 4\n"
                       "sphere 0 0 -5 1 red\nsphere 1 -0.5 -9 1 red\n";
    Image images[3];
    const char *lenses[3] = {"", " defocus 0 focus 3", " aperture 0"};
    for (int k = 0; k < 3; k++) {
        Scene scene = ReadScene(std::string("camera lookat 0 0 0  0 0 -5  0 1 0  40") + lenses[k] +
                                "\n" + rest);
        RenderSettings s = TestSettings(&scene);
        s.samplesPerPixel = 4;
        RayStats stats = {};
        Render(&scene, &s, &images[k], &stats);
        CHECK(!s.effects.defocus && s.camera.lensRadius == 0,
              "no lens: GetCameraRay takes the pinhole's way, and draws no lens point");
    }
    CHECK(images[0].pixels == images[1].pixels && images[0].pixels == images[2].pixels,
          "defocus 0 and aperture 0 draw the pinhole camera's bytes");
    Scene scene = ReadScene(std::string("camera lookat 0 0 0  0 0 -5  0 1 0  40 aperture 1 "
                                        "focus 5\n") +
                            rest);
    RenderSettings s = TestSettings(&scene);
    s.methods.cameraRay = CAMERA_RAY_SLIDES;
    PlanRender(&scene, &s);
    Ray ray;
    GetLensRay(&s.camera, 24, 16, {3, 5}, {real(0.6), real(-0.8)}, &ray);
    vec3 lens = real(0.5) * vec3{real(0.6), real(-0.8), 0};
    CHECK_NEAR(ray.origin.z, -1, 4 * kRelTol, "the slides' lens ray starts on the screen, z = -1");
    CHECK_NEAR(Length(ray.dir), 1, 4 * kRelTol, "with a unit direction");
    Ray pinhole;
    GetScreenRay(&s.camera, 24, 16, {3, 5}, &pinhole);
    vec3 sharp = real(5) * pinhole.dir, toward = sharp - ray.origin;
    CHECK(Length(Cross(toward, ray.dir)) <= 64 * kRelTol * Length(toward) &&
              Dot(ray.origin - lens, pinhole.dir) > 0,
          "from the lens point, toward the pinhole's point in focus");
}

void TestLens() {
    TestLensWords();
    TestFocusPlaneIsSharp();
    TestCircleOfConfusion();
    TestNoLensNoWork();
}
