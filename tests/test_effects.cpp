// tests/test_effects.cpp -- every effect where the scene calls for it, and only there.
//
// Ray counts predicted exactly (counted independently of the shading code), the effects each
// scene plans, Snell's law, total internal reflection and Fresnel worked by hand for a glass
// sphere, and Phong highlights, including the cases that must give no highlight and no NaN.
#include "../app/app.h"
#include "../render.h"
#include "test.h"

static Scene AssignmentWithoutMirrors() {
    Scene scene;
    BuildDefaultScene(&scene);
    scene.materials[0] = Matte("grey", {0.5, 0.5, 0.5}); // the mirror spheres become matte
    return scene;
}

// Counted independently of shade.cpp: for every sample's primary hit, the lights in front of the
// surface (N.L > 0), and how many primary rays hit sphere `mirrorSphere`.
static void CountByHand(const Scene *scene, const RenderSettings *s, int mirrorSphere,
                        uint64_t *litSides, uint64_t *mirrorHits) {
    *litSides = *mirrorHits = 0;
    for (int j = 0; j < s->height; j++)
        for (int i = 0; i < s->width; i++)
            for (int k = 0; k < s->samplesPerPixel; k++) {
                Ray ray;
                GetCameraRay(&s->camera, s->width, s->height,
                             SamplePosition(i, j, k, s->samplesPerPixel), &ray);
                RayHit hit;
                if (!FindNearestHit(scene, s->methods, &ray, 0, kInfinity, &hit))
                    continue;
                if (hit.shape == SHAPE_SPHERE && hit.index == mirrorSphere) {
                    (*mirrorHits)++;
                    continue;
                }
                for (const Light &l : scene->lights)
                    *litSides += Dot(hit.normal, l.position - hit.point) > 0;
            }
}

static RayStats RenderCounting(const Scene *scene, RenderSettings *settings) {
    PlanRender(scene, settings);
    Image image;
    RayStats stats = {};
    Render(scene, settings, &image, &stats);
    return stats;
}

static void TestRayCounts() {
    Scene scene = AssignmentWithoutMirrors();
    RenderSettings s = TestSettings(&scene);
    s.width = s.height = 96;
    s.samplesPerPixel = 2;
    uint64_t litSides, mirrorHits;
    PlanRender(&scene, &s);
    CountByHand(&scene, &s, -1, &litSides, &mirrorHits);
    RayStats stats = RenderCounting(&scene, &s);
    CHECK(stats.primary == 96 * 96 * 2, "diffuse only: exactly W x H x spp = 18432 primary rays");
    CHECK(stats.reflection == 0 && stats.refraction == 0 && stats.specularTerms == 0,
          "diffuse only: no reflection or refraction rays, no specular terms");
    CHECK(stats.shadow == litSides, "diffuse only: one shadow ray per lit-side hit point (" +
                                        std::to_string(stats.shadow) + " cast, " +
                                        std::to_string(litSides) + " counted by hand)");

    // One perfect mirror (sphere 0): one reflection ray for each primary ray that hits it
    scene.materials.push_back(Mirror("mirror", 1));
    scene.spheres[0].material = (int)scene.materials.size() - 1;
    CountByHand(&scene, &s, 0, &litSides, &mirrorHits);
    stats = RenderCounting(&scene, &s);
    CHECK(mirrorHits > 100 && stats.reflection == mirrorHits,
          "one mirror sphere: one reflection ray per primary hit on it (" +
              std::to_string(stats.reflection) + " cast, " + std::to_string(mirrorHits) +
              " counted)");

    // No light: no shadow rays at all
    scene.lights.clear();
    stats = RenderCounting(&scene, &s);
    CHECK(stats.shadow == 0, "a scene with no light casts no shadow rays");
}

static std::string EffectWords(const Scene *scene, RenderSettings s) {
    PlanRender(scene, &s);
    const Effects &e = s.effects;
    std::string w = std::string(e.shadows ? "shadows " : "") + (e.reflection ? "reflection " : "") +
                    (e.refraction ? "refraction " : "") + (e.specular ? "specular " : "") +
                    (e.antialiasing ? "antialiasing " : "");
    return w.empty() ? "none" : w.substr(0, w.size() - 1);
}

static void TestPlannedEffects() {
    Scene scene = AssignmentWithoutMirrors();
    RenderSettings s = TestSettings(&scene);
    CHECK(EffectWords(&scene, s) == "shadows", "diffuse scene with a light: shadows only");
    Scene assignment;
    BuildDefaultScene(&assignment);
    CHECK(EffectWords(&assignment, s) == "shadows reflection", "assignment: shadows reflection");
    s.depth = 1;
    CHECK(EffectWords(&assignment, s) == "shadows", "depth 1: no room for a reflection ray");
    s.depth = 10;
    s.samplesPerPixel = 4;
    CHECK(EffectWords(&assignment, s) == "shadows reflection antialiasing", "spp 4: antialiasing");
    s.samplesPerPixel = 1;

    scene.shading = SHADING_PHONG;
    CHECK(EffectWords(&scene, s) == "shadows", "phong without a shiny material: no specular");
    scene.materials[1].specular = real(0.5);
    CHECK(EffectWords(&scene, s) == "shadows specular", "phong with ks > 0: specular");
    scene.materials[2].ior = real(1.5);
    CHECK(EffectWords(&scene, s) == "shadows reflection refraction specular",
          "a glass material in use: reflection and refraction");
    scene.lights.clear();
    CHECK(EffectWords(&scene, s) == "reflection refraction", "no lights: no shadows, no specular");
    scene.materials.push_back(Mirror("unused", 1));
    scene.materials[2].ior = 0;
    CHECK(EffectWords(&scene, s) == "none", "a mirror material no shape uses plans no reflection");
}

// Shadow rays only where a light could change a pixel: a light of intensity 0, a black surface
// under `floor` or `phong`, an ambient floor no light can rise above. Each scene rendered: its
// shadow rays counted, and its image the same as with the lights taken out (or, for the scenes
// one step away, not).
static void TestLightsThatChangeNothing() {
    struct Case {
        const char *text, *why;
        bool shadows; // the prediction: shadow rays cast, and the image differs without lights
    };
    const char *shapes = "material w diffuse 1 1 1\nmaterial black diffuse 0 0 0\n"
                         "sphere 0 0 -5 1 %s\ntriangle -9 -1 -1 9 -1 -1 0 -1 -20 %s\n";
    const Case cases[] = {
        {"ambient 0\nlight 0 5 0 0 0 0\n", "a light of intensity 0", false},
        {"ambient 0.2\nlight 0 5 0 0 0 0\nlight 5 5 0 0 0 0\n", "two lights of intensity 0", false},
        {"ambient 1\nlight 0 5 0 1 1 1\n", "ambient 1 under floor, a light of 1", false},
        {"ambient 0.6\nlight 0 5 0 0.3 0.3 0.3\nlight 5 5 0 0.3 0.3 0.3\n",
         "ambient 0.6 under floor, two lights of 0.3", false},
        {"ambient 0.2\nlight 0 5 0 1 1 1\n#black\n", "black shapes under floor", false},
        {"shading phong\nlight 0 5 0 1 1 1\n#black\n", "black shapes under phong", false},
        {"ambient 0.2\nlight 0 5 0 1 1 1\n", "one step away: a light of 1, ambient 0.2", true},
        {"ambient 0.99\nlight 0 5 0 1 1 1\n", "one step away: ambient 0.99 under a light of 1",
         true},
        {"ambient 0\nlight 0 5 0 0 0 0.01\n", "one step away: a faint blue light, ambient 0", true},
    };
    for (const Case &c : cases) {
        std::string text = c.text;
        const char *material = text.find("#black") != std::string::npos ? "black" : "w";
        char body[200];
        snprintf(body, sizeof body, shapes, material, material);
        Scene scene, dark;
        std::string error;
        bool read = ParseSceneText("size 32 32\n" + text + body, "l.scene", &scene, &error);
        CHECK(read, std::string(c.why) + ": the scene reads (" + error + ")");
        if (!read)
            continue;
        dark = scene;
        dark.lights.clear();
        Image images[2];
        RayStats stats[2] = {};
        for (int k = 0; k < 2; k++) {
            RenderSettings s = TestSettings(k ? &dark : &scene);
            Render(k ? &dark : &scene, &s, &images[k], &stats[k]);
        }
        bool differs = images[0].pixels != images[1].pixels;
        CHECK((stats[0].shadow > 0) == c.shadows && differs == c.shadows,
              std::string(c.why) + ": " + std::to_string(stats[0].shadow) +
                  " shadow rays, and the image " + (differs ? "differs from" : "is") +
                  " the one without lights (predicted: " +
                  (c.shadows ? "rays, and a different image" : "none, and the same image") + ")");
    }
}

// A glass sphere (ior 1.5, radius 1, at the origin) and nothing else; traces one ray and returns
// its ray tree.
static std::vector<RayNode> GlassTree(vec3 origin, vec3 dir) {
    Scene scene;
    InitScene(&scene);
    Material glass = Matte("glass", {1, 1, 1});
    glass.ior = real(1.5);
    scene.materials = {glass};
    scene.spheres = {{{0, 0, 0}, 1, 0}};
    RenderSettings s = TestSettings(&scene);
    std::vector<RayNode> tree;
    TraceLog log = {RayStats{}, &tree, -1, 0};
    Ray ray = {origin, dir};
    TraceRay(&scene, &s, RAY_PRIMARY, &ray, &kNoSelfHit, RayChain{1, 1}, &log);
    return tree;
}

static bool Near(vec3 a, vec3 b, double tolerance) {
    return std::fabs(a.x - b.x) <= tolerance && std::fabs(a.y - b.y) <= tolerance &&
           std::fabs(a.z - b.z) <= tolerance;
}

static void TestGlass() {
    // hard case REF-1: O = (-5, 0.5, 0), d = (1, 0, 0) enters at (-0.866, 0.5, 0) with
    // sin(i) = 0.5, so sin(t) = 1/3: T = (0.98316324759439270, -0.18272938619621880, 0)
    vec3 n = {-std::sqrt(real(0.75)), real(0.5), 0}, t;
    CHECK(Refract({1, 0, 0}, n, 1 / real(1.5), &t) &&
              Near(t, {0.9831632475943927, -0.1827293861962188, 0}, 16 * kRelTol),
          "hard case REF-1: Snell's law entering glass: sin 30 deg / 1.5 = sin 19.47 deg");
    // The tree: primary -> refraction (inside) -> refraction (out), exit direction
    // (0.93321994284070624, -0.35930563352720894, 0): deviated 21.0576 deg in total
    std::vector<RayNode> tree = GlassTree({-5, 0.5, 0}, {1, 0, 0});
    int inside = -1, out = -1;
    for (int k = 0; k < (int)tree.size(); k++) {
        if (tree[k].kind == RAY_REFRACTION && tree[k].parent == 0)
            inside = k;
        if (tree[k].kind == RAY_REFRACTION && inside >= 0 && tree[k].parent == inside)
            out = k;
    }
    CHECK(inside > 0 && out > 0, "a ray through a glass sphere refracts in and out again");
    if (out > 0)
        CHECK(Near(Normalize(tree[out].ray.dir), {0.93321994284070624, -0.35930563352720894, 0},
                   64 * kRelTol),
              "hard case REF-1: exit direction after two refractions, within 1e-14 in double");

    // hard case REF-2: from inside at (0, 0.9, 0) along +x, the wall is met at t = 0.43589 with
    // sin(i) = 0.9 > 1/1.5: total internal reflection, R = 1, no refracted ray; the reflected
    // direction is (0.62, -0.78460180983732118, 0)
    CHECK(!Refract({1, 0, 0}, {-real(0.43588989435406731), -real(0.9), 0}, real(1.5), &t),
          "hard case REF-2: Snell's law: sin(t) = 1.5 * 0.9 > 1 is total internal reflection");
    tree = GlassTree({0, 0.9, 0}, {1, 0, 0});
    CHECK(tree.size() > 1 && tree[1].kind == RAY_REFLECTION && tree[1].parent == 0,
          "inside the glass at 64 deg: a reflection ray");
    bool refracted = false;
    for (const RayNode &node : tree)
        refracted = refracted || (node.parent == 0 && node.kind == RAY_REFRACTION);
    CHECK(!refracted, "hard case REF-2: total internal reflection casts no refraction ray");
    if (tree.size() > 1) {
        CHECK_NEAR(tree[0].record.t, 0.43588989435406731, 4 * kRelTol, "TIR: wall met at t");
        CHECK(Near(Normalize(tree[1].ray.dir), {0.62, -0.78460180983732118, 0}, 16 * kRelTol),
              "hard case REF-2: reflected direction (0.62, -0.7846, 0)");
    }

    // hard case REF-3: exact Fresnel leaving glass (eta = 1.5) for sin(i) 0, 0.3, 0.6, 0.65, 0.66
    const double sines[] = {0, 0.3, 0.6, 0.65, 0.66};
    const double reflectance[] = {0.04, 0.04091892868995756, 0.1141411002213538, 0.3031021167517616,
                                  0.4593127663784946};
    for (int k = 0; k < 5; k++)
        CHECK_NEAR(FresnelReflectance(real(std::sqrt(1 - sines[k] * sines[k])), real(1.5)),
                   reflectance[k], 1e-12 + 64 * kRelTol,
                   "hard case REF-3: Fresnel leaving glass at sin(i) = " +
                       std::to_string(sines[k]));
    CHECK(FresnelReflectance(real(0.6), real(1.5)) == 1, "Fresnel past the critical angle is 1");
    CHECK_NEAR(FresnelReflectance(real(std::sqrt(1 - 0.99 * 0.99)), 1 / real(1.5)),
               0.4593127663784964, 1e-12 + 64 * kRelTol, "Fresnel entering glass at sin(i) 0.99");

    // hard case REF-4: head-on with a normalised normal whose dot with -n rounds past 1
    vec3 n4 = Normalize({-0.9433050469559874, 0.6715302078397394, -0.13446586418989326});
    vec3 uv = -n4;
    CHECK(Refract(uv, n4, 1 / real(1.5), &t) && IsFinite(t) && Near(t, uv, 4 * kRelTol),
          "hard case REF-4: head-on refraction: no NaN, the ray goes straight through");
    CHECK(std::isfinite(FresnelReflectance(-Dot(uv, n4), 1 / real(1.5))),
          "hard case REF-4: head-on Fresnel: no NaN");
}

// The floor of test_shade.cpp, lit by Phong: kd = 0.5 (so ka = 0.5), ks = 0.25, n as given,
// Ia = 0.2. The eye ray comes down from `eye` to the origin.
static color PhongAt(vec3 eye, vec3 lightPosition, real shininess, RayStats *stats) {
    Scene scene;
    InitScene(&scene);
    scene.shading = SHADING_PHONG;
    Material m = Matte("plastic", {0.5, 0.5, 0.5});
    m.specular = real(0.25);
    m.shininess = shininess;
    scene.materials = {m};
    scene.triangles = {{{-100, 0, 100}, {100, 0, 100}, {0, 0, -100}, 0}};
    scene.lights = {{lightPosition, {1, 1, 1}}};
    RenderSettings s = TestSettings(&scene);
    TraceLog log = {RayStats{}, nullptr, -1, 0};
    Ray ray = {eye, vec3{0, 0, 0} - eye};
    color c = TraceRay(&scene, &s, RAY_PRIMARY, &ray, &kNoSelfHit, RayChain{1, 1}, &log);
    *stats = log.stats;
    return c;
}

static void TestPhong() {
    RayStats stats;
    // Light and eye straight above: N.L = 1, R = V, so 0.5 * 0.2 + 0.5 * 1 + 0.25 * 1^n = 0.85
    color c = PhongAt({0, 5, 0}, {0, 10, 0}, 10, &stats);
    CHECK_NEAR(c.x, 0.85, 4 * kRelTol, "Phong highlight at its peak: 0.1 + 0.5 + 0.25 = 0.85");
    CHECK(stats.specularTerms == 1, "one light, one specular term");
    // Light at 45 deg: N.L = R.V = sqrt(1/2), n = 2: 0.1 + 0.5 sqrt(1/2) + 0.25 / 2 = 0.578553
    c = PhongAt({0, 5, 0}, {10, 10, 0}, 2, &stats);
    CHECK_NEAR(c.x, 0.1 + 0.5 * std::sqrt(0.5) + 0.125, 8 * kRelTol,
               "Phong at 45 deg, n = 2: 0.1 + 0.35355 + 0.125");
    // hard case PH-1: light below the surface: no diffuse, no highlight, ambient 0.1 only
    c = PhongAt({0, 5, 0}, {0, -10, 1}, 10, &stats);
    CHECK_NEAR(c.x, 0.1, kRelTol,
               "hard case PH-1: light below the horizon: ambient only, no highlight");
    CHECK(stats.specularTerms == 0 && stats.shadow == 0, "no specular term, no shadow ray");
    // hard case PH-2: R.V < 0 with n = 2.5: pow(max(0, R.V), n) = 0, never NaN. The light is
    // near the horizon at +x (N.L = 0.0995) and the eye is also on the +x side
    c = PhongAt({5, 5, 0}, {10, 1, 0}, real(2.5), &stats);
    CHECK(IsFinite(c), "hard case PH-2: R.V < 0 with a fractional exponent: no NaN");
    CHECK_NEAR(c.x, 0.1 + 0.5 / std::sqrt(101.0), 8 * kRelTol,
               "R.V < 0: ambient + diffuse only, 0.1 + 0.5 * 0.0995");
}

// The scenes whose lit image can only be one colour, each for its reason, and scenes one step
// away from them, which are not: each rendered, to check the prediction against the image.
static void TestOneColour() {
    struct Case {
        const char *text, *warning; // the scene; a piece of the warning, or "" for none
        int rgb[3];                 // the one colour of every pixel, 8 bits a channel; -1: several
    };
    const Case cases[] = {
        {"size 8 8\nbackground 0.2 0.4 0.6\n", "no shapes", {51, 102, 153}},
        {"size 8 8\nambient 0\nmaterial m\nsphere 0 0 -5 1 m\n", "every pixel is black", {0, 0, 0}},
        {"size 8 8\nambient 0\nlight 0 5 0 0 0 0\nmaterial m\nsphere 0 0 -5 1 m\n",
         "every pixel is black",
         {0, 0, 0}},
        {"size 8 8\nambient 0\nmaterial m mirror 1\nsphere 0 0 -5 1 m\n",
         "every pixel is black",
         {0, 0, 0}},
        {"size 8 8\nshading path\nmaterial m\nsphere 0 0 -5 1 m\n",
         "nothing gives off light",
         {0, 0, 0}},
        {"size 8 8\nambient 0.2\nmaterial m\nsphere 0 0 -5 1 m\n", "", {-1}},
        {"size 8 8\nambient 0\nlight 0 5 0\nmaterial m\nsphere 0 0 -5 1 m\n", "", {-1}},
        {"size 8 8\nambient 0\nbackground 0 0 1\nmaterial m\nsphere 0 0 -5 1 m\n", "", {-1}},
        {"size 8 8\nshading path\nmaterial m emit 1 1 1\nsphere 0 0 -5 1 m\n", "", {-1}},
    };
    for (const Case &c : cases) {
        Scene scene;
        std::string error;
        bool read = ParseSceneText(c.text, "one.scene", &scene, &error);
        std::string warning = read ? OneColourWarning(&scene) : "(not read: " + error + ")";
        bool expected =
            c.warning[0] == 0 ? warning.empty() : warning.find(c.warning) != std::string::npos;
        Image image = {0, 0, {}};
        if (read) {
            RenderSettings s = TestSettings(&scene);
            RayStats stats = {};
            Render(&scene, &s, &image, &stats);
        }
        bool flat = !image.pixels.empty(), agrees = true; // (flat: every pixel as the first)
        for (size_t k = 0; k < image.pixels.size(); k++) {
            flat = flat && image.pixels[k] == image.pixels[k % 3];
            agrees = agrees && (c.rgb[0] < 0 || image.pixels[k] == c.rgb[k % 3]);
        }
        CHECK(read && expected && agrees && flat == (c.rgb[0] >= 0),
              std::string("one colour? `") + c.text + "`: warning '" + warning +
                  "', as predicted, and the image " +
                  (c.rgb[0] >= 0 ? "all of the predicted colour" : "of more than one colour"));
    }
}

void TestEffects() {
    TestOneColour();
    TestRayCounts();
    TestPlannedEffects();
    TestLightsThatChangeNothing();
    TestGlass();
    TestPhong();
}
