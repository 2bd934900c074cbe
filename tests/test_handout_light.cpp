// tests/test_handout_light.cpp -- the handouts' steps that light what the rays meet: the shadow,
// the floor shading, the mirror's reflection and the depth of a chain, the second handout's
// Phong, the journal's refraction, and colours to bytes. As in test_handout.cpp: a scene, a ray,
// the answer worked out by hand, what came out, and the likely cause.
#include "test_handout.h"

#include "../render.h"

// ---- the shadow --------------------------------------------------------------------------------

// A floor at y = 0, facing up, wide enough for every check below; its material 0.
static const Triangle kFloor = {{-10, 0, 10}, {10, 0, 10}, {0, 0, -10}, 0};

// A floor at y = 0 and a ball of radius 0.5 at (0, 2, 0); the point (0, 0, 0) on the floor.
static void ShadowScene(Scene *scene, RayHit *floorPoint) {
    InitScene(scene);
    scene->materials = {Plain({1, 1, 1})};
    scene->triangles = {kFloor};
    scene->spheres = {{{0, 2, 0}, 0.5, 0}};
    *floorPoint = {1, {0, 0, 0}, {0, 1, 0}, true, 0, SHAPE_TRIANGLE, 0, {0, 0, 0}, 0};
}

void TestShadow() {
    Scene scene;
    RayHit floor;
    ShadowScene(&scene, &floor);
    Methods m = kHandoutMethods;
    bool visible = LightVisible(&scene, m, &floor, {0, 4, 0});
    ADVISE(!visible,
           "the ball at (0, 2, 0) hides the light at (0, 4, 0) from the floor at (0, 0, 0)",
           "you say the light is visible",
           "the shadow ray toward the light must find the ball: a ray from the point toward the "
           "light, blocked by a hit at 0 < t < 1");
    visible = LightVisible(&scene, m, &floor, {0, 1, 0});
    ADVISE(visible, "with the light at (0, 1, 0), below the ball, the floor is lit",
           "you say the light is hidden", "a shape beyond the light (t > 1) casts no shadow");
    visible = LightVisible(&scene, m, &floor, {3, 4, 0});
    ADVISE(visible, "the light at (3, 4, 0) is not hidden: the ball is off the way",
           "you say the light is hidden",
           "does the floor hide itself? the shadow ray starts on it: start it past the surface");
    // A hit point is rounded, so it may lie a hair inside its surface: a shadow ray that starts
    // there and counts any hit at t > 0 finds that surface again (shadow acne).
    RayHit top = {1, {0, 2.5 - 1e-9, 0}, {0, 1, 0}, true, 0, SHAPE_SPHERE, 0, {0, 0, 0}, 0};
    visible = LightVisible(&scene, m, &top, {0, 4, 0});
    ADVISE(visible,
           "the top of the ball, a hair inside it at (0, 2.5 - 1e-9, 0) as a rounded hit point may "
           "be, sees the light at (0, 4, 0)",
           "you say the light is hidden",
           "shadow acne: the ray hits the ball it starts on (start it past the surface: tMin)");
    RayHit below = {1, {1, -1e-9, 1}, {0, 1, 0}, true, 0, SHAPE_TRIANGLE, 0, {0, 0, 0}, 0};
    visible = LightVisible(&scene, m, &below, {1, 4, 1});
    ADVISE(visible, "the floor's point (1, -1e-9, 1), a hair below it, sees the light at (1, 4, 1)",
           "you say the light is hidden",
           "shadow acne: the ray hits the floor it starts on (start it past the surface: tMin)");
}

// The colour one ray brings back from `scene`, traced as a render in the handouts' methods traces
// it (*stats: the rays it took, if asked).
static color TraceOne(const Scene *scene, Ray ray, RayStats *stats) {
    RenderSettings settings = {};
    settings.width = settings.height = 8, settings.samplesPerPixel = 1;
    settings.depth = scene->depth, settings.threads = 1, settings.methods = kHandoutMethods;
    PlanRender(scene, &settings);
    TraceLog log = {{}, nullptr, -1, 0};
    color c = TraceRay(scene, &settings, RAY_PRIMARY, &ray, &kNoSelfHit, RayChain{1, 1}, &log);
    if (stats)
        *stats = log.stats;
    return c;
}

// ---- the floor shading --------------------------------------------------------------------------

// The colour seen straight down at the floor's point (0, 0, 0), lit by `lights`.
static color FloorSeen(std::vector<Light> lights) {
    Scene scene;
    InitScene(&scene); // ambient 0.2
    scene.materials = {Plain({1, 0.5, 0.25})};
    scene.triangles = {kFloor};
    scene.lights = lights;
    Ray ray = {{0, 1, 0}, {0, -1, 0}};
    return TraceOne(&scene, ray, nullptr);
}

void TestFloor() {
    color white = {1, 1, 1};
    color c = FloorSeen({{{0, 4, 0}, white}});
    ADVISE(Near(c, {1, 0.5, 0.25}),
           "lit from straight above, N.L = 1: the colour kd = (1, 0.5, 0.25)", "you give " + Vec(c),
           Near(c, {0.2, 0.1, 0.05}) ? "the light is missing: add I (N.L) for a visible light"
           : Near(c, {4, 2, 1}) ? "L is not of length 1: N.L with L = (light - P) / |light - P|"
                                : "kd max(ambient, N.L), with L of length 1");
    c = FloorSeen({{{4 * std::sqrt(real(3)), 4, 0}, white}}); // 60 degrees: N.L = 0.5
    ADVISE(Near(c, {0.5, 0.25, 0.125}), "lit at 60 degrees, N.L = 0.5: kd 0.5 = (0.5, 0.25, 0.125)",
           "you give " + Vec(c), "N.L with L normalised: (N.L) / |L|");
    c = FloorSeen({{{4, 0.4, 0}, white}}); // N.L = 0.0995, below the ambient 0.2
    ADVISE(Near(c, {0.2, 0.1, 0.05}),
           "lit at a grazing angle, N.L = 0.1: kd max(0.2, 0.1) = (0.2, 0.1, 0.05)",
           "you give " + Vec(c), "the ambient floor: max(ambient, N.L)");
    c = FloorSeen({{{0, -4, 0}, white}});
    ADVISE(Near(c, {0.2, 0.1, 0.05}),
           "lit from below the floor: only the ambient floor, (0.2, 0.1, 0.05)",
           "you give " + Vec(c), "a light behind the surface (N.L < 0) adds nothing");
    c = FloorSeen({{{0, 4, 0}, white}, {{0, -4, 0}, white}});
    ADVISE(
        Near(c, {1, 0.5, 0.25}),
        "lit from above and from below: the light below adds nothing, kd = (1, 0.5, 0.25)",
        "you give " + Vec(c),
        "a light behind the surface takes light away: skip it when N.L <= 0 (or clamp N.L at 0)");
}

// ---- mirrors -----------------------------------------------------------------------------------

void TestReflect() {
    vec3 r = Reflect({0.6, -0.8, 0}, {0, 1, 0});
    ADVISE(Near(r, {0.6, 0.8, 0}),
           "(0.6, -0.8, 0) off a floor with N = (0, 1, 0) goes (0.6, 0.8, 0)", "you give " + Vec(r),
           Near(r, {0.6, -2.4, 0})   ? "R = D - 2 (D.N) N: the second term's sign"
           : Near(r, {-0.6, 0.8, 0}) ? "that is -R: R = D - 2 (D.N) N, not 2 (D.N) N - D"
                                     : "R = D - 2 (D.N) N");
    r = Reflect({3, -4, 0}, {0, 1, 0});
    ADVISE(Near(r, {3, 4, 0}), "(3, -4, 0), not of length 1, comes back as (3, 4, 0)",
           "you give " + Vec(r), "reflect D as it is: only N needs length 1");
}

// Reflection rays in one chain between two facing mirrors, 2 apart, with `depth`.
static uint64_t MirrorChain(int depth) {
    Scene scene;
    InitScene(&scene);
    Material half = Plain({1, 1, 1});
    half.mirror = 0.5;
    scene.materials = {half};
    scene.triangles = {{{-10, -10, -1}, {10, -10, -1}, {0, 10, -1}, 0},
                       {{-10, -10, 1}, {0, 10, 1}, {10, -10, 1}, 0}};
    scene.depth = depth;
    Ray ray = {{0, 0, 0}, {0, 0, -1}};
    RayStats stats;
    TraceOne(&scene, ray, &stats);
    return stats.reflection;
}

void TestDepth() {
    uint64_t n = MirrorChain(10);
    std::string cause = n == 0    ? "no reflection at all: the depth check stops the eye's ray's "
                                    "reflection (the eye's ray is number 1)"
                        : n == 8  ? "one ray short: the eye's ray is the first of `depth`, so 9 "
                                    "reflections follow it (if next.number > depth, black)"
                        : n == 10 ? "one ray too many: the eye's ray counts as the first of `depth`"
                                  : "at most `depth` rays in a chain: if next.number > depth, "
                                    "return black";
    ADVISE(n == 9,
           "between two facing mirrors, depth 10: the eye's ray and 9 reflections, then black",
           "you trace " + std::to_string(n) + " reflections", cause);
    n = MirrorChain(1);
    ADVISE(n == 0, "with depth 1, only the eye's ray",
           "you trace " + std::to_string(n) + " reflections",
           "the eye's ray is number 1: with depth 1 nothing follows it");
}

// ---- Phong -------------------------------------------------------------------------------------

// The colour of the floor's point (0, 0, 0) under Phong (Ia = 0.1, ka = 1, kd = 0.5, ks = 0.5,
// n = 1), lit from `light`, seen from `eye`; `blocker` puts a ball between point and light.
static color PhongSeen(vec3 light, vec3 eye, bool blocker) {
    Scene scene;
    InitScene(&scene);
    scene.shading = SHADING_PHONG;
    scene.ambientLight = 0.1;
    Material m = Plain({0.5, 0.5, 0.5});
    m.ambient = {1, 1, 1}, m.specular = 0.5, m.shininess = 1;
    scene.materials = {m};
    scene.triangles = {kFloor};
    if (blocker)
        scene.spheres = {{real(0.5) * light, 0.25, 0}};
    scene.lights = {{light, {1, 1, 1}}};
    Ray ray = {eye, -eye};
    return TraceOne(&scene, ray, nullptr);
}

void TestPhong() {
    color c = PhongSeen({0, 4, 0}, {0, 1, 0}, false);
    ADVISE(Near(c, {1.1, 1.1, 1.1}),
           "Phong, light and eye straight above: ka Ia + kd + ks = 0.1 + 0.5 + 0.5 = 1.1",
           "you give " + Vec(c),
           Near(c, {0.85, 0.85, 0.85})
               ? "the highlight is white: ks (R.V)^n adds to each channel, "
                 "not times kd"
               : "ka Ia + I (kd (N.L) + ks max(0, R.V)^n), R = 2 (N.L) N - L");
    real s = std::sqrt(real(0.5)); // light 45 degrees to the left, eye 45 degrees to the right
    c = PhongSeen({-4, 4, 0}, {4, 4, 0}, false);
    real want = real(0.1) + real(0.5) * s + real(0.5); // R = V: (R.V)^n = 1
    ADVISE(Near(c, {want, want, want}),
           "light at 45 degrees on one side, eye at 45 on the other: R = V, the full highlight, "
           "0.1 + 0.5 (0.707) + 0.5 = " +
               Num(want),
           "you give " + Vec(c),
           Near(c.x, real(0.1) + real(0.5) * s) ? "no highlight: V goes from the point toward the "
                                                  "eye, V = -normalize(D)"
                                                : "R = 2 (N.L) N - L, V = -normalize(D)");
    c = PhongSeen({0, 4, 0}, {0, 1, 0}, true);
    ADVISE(Near(c, {0.1, 0.1, 0.1}),
           "with a ball hiding the light, only ka Ia = 0.1: no diffuse, no highlight",
           "you give " + Vec(c),
           Near(c, {0.6, 0.6, 0.6}) ? "the highlight shows where the light is hidden: a hidden "
                                      "light adds neither term"
                                    : "a light counts only if it is visible (ShadowTest)");
}

// ---- refraction ---------------------------------------------------------------------------------

void TestRefraction() {
    vec3 t = {0, 0, 0};
    real s = std::sqrt(real(0.5));
    bool refracts = Refract({s, -s, 0}, {0, 1, 0}, 1 / real(1.5), &t);
    real sinT = s / real(1.5); // Snell: sin t = eta sin i
    vec3 want = {sinT, -std::sqrt(1 - sinT * sinT), 0};
    ADVISE(refracts && Near(t, want),
           "into glass of index 1.5 at 45 degrees: sin t = sin 45 / 1.5, t = " + Vec(want),
           refracts ? "you give " + Vec(t) : "you say it does not refract",
           "Snell: eta d + (eta cos i - cos t) n, with cos i = -d.n and eta = n1 / n2");
    refracts = Refract({0, -1, 0}, {0, 1, 0}, 1 / real(1.5), &t);
    ADVISE(refracts && Near(t, {0, -1, 0}), "straight down into glass: on, unbent, (0, -1, 0)",
           refracts ? "you give " + Vec(t) : "you say it does not refract",
           "at normal incidence cos i = cos t = 1: t = d");
    refracts = Refract({s, -s, 0}, {0, 1, 0}, real(1.5), &t);
    ADVISE(!refracts, "out of glass at 45 degrees: eta sin i = 1.06 > 1, total internal reflection",
           "you say it refracts", "no refraction when eta^2 (1 - cos^2 i) > 1");
}

// ---- colours to bytes ---------------------------------------------------------------------------

void TestClamp() {
    const struct {
        real c;
        int byte;
        const char *cause;
    } kCases[] = {{0.5, 128, "round(c 255): 127.5 rounds up"},
                  {1.5, 255, "above 1 stays 255: clamp to [0, 1] before the byte (else it wraps)"},
                  {2.2, 255, "above 1 stays 255: clamp to [0, 1] before the byte (else it wraps)"},
                  {-0.3, 0, "below 0 is 0: clamp to [0, 1] first"}};
    for (const auto &k : kCases) {
        int b = ToByte(k.c);
        ADVISE(b == k.byte,
               "the colour " + Num(k.c) + " becomes the byte " + std::to_string(k.byte),
               "you give " + std::to_string(b), k.cause);
    }
}
