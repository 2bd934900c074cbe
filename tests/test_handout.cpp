// tests/test_handout.cpp -- the handouts' steps checked as their debugging advice puts it: a
// scene, a ray, the answer worked out by hand, and, when the answer differs, what was found and
// the most likely cause. rt runs them (group `handout`, in the handouts' methods); a starter kit
// runs the groups of the functions its students write (tools/starter/stubs.list).
#include "test.h"

#include <cstdio>

// One check: `should` is the prediction, `got` what came out, `cause` the likely mistake.
#define ADVISE(ok, should, got, cause) Advise((ok), __FILE__, __LINE__, (should), (got), (cause))
static void Advise(bool ok, const char *file, int line, const std::string &should,
                   const std::string &got, const std::string &cause) {
    TestCheck(ok, file, line, should + "; " + got + (cause.empty() ? "" : ": " + cause), "handout");
}

static std::string Num(double x) {
    char text[32];
    snprintf(text, sizeof text, "%.6g", x);
    return text;
}
static std::string Vec(vec3 v) { return "(" + Num(v.x) + ", " + Num(v.y) + ", " + Num(v.z) + ")"; }
static bool Near(double a, double b) { return std::fabs(a - b) <= 1e-5 * (1 + std::fabs(b)); }
static bool Near(vec3 a, vec3 b) { return Near(a.x, b.x) && Near(a.y, b.y) && Near(a.z, b.z); }
static std::string Found(bool hit, real t) {
    return hit ? "you report t = " + Num(t) : "you report no hit";
}

// ---- GetRay ----------------------------------------------------------------------------------

static vec3 Direction(Perspective p, vec2 at) {
    Ray ray = {{9, 9, 9}, {0, 0, 0}};
    GetRay(p, at, &ray);
    return SafeNormalize(ray.dir);
}

static void TestGetRay() {
    Perspective p = {{0, 0, 0}, 2, 2, 512, 512}; // the assignment's: a 2-wide screen 2 ahead
    Ray ray = {{9, 9, 9}, {0, 0, 0}};
    GetRay(p, {256, 256}, &ray);
    vec3 d = SafeNormalize(ray.dir);
    ADVISE(Near(ray.origin, p.eye), "the ray starts at the eye (0, 0, 0)",
           "yours starts at " + Vec(ray.origin), "ray->origin = p.eye");
    ADVISE(Near(d, {0, 0, -1}), "the screen's centre, (256, 256), is straight ahead: (0, 0, -1)",
           "your ray goes " + Vec(d),
           d.z > 0 ? "the camera looks down -z: the screen is at z = -distance" : "");
    vec3 corner = Direction(p, {0.5, 0.5}),
         want = SafeNormalize({-1 + 1.0 / 512, 1 - 1.0 / 512, -2});
    std::string cause = corner.y < 0   ? "upside down: the screen's y grows up, pixel rows go down "
                                         "(y = (H/2 - sy) size)"
                        : corner.x > 0 ? "mirrored: x = (sx - W/2) size"
                        : Near(corner, SafeNormalize({-1 + 2.0 / 512, 1 - 2.0 / 512, -2}))
                            ? "screenCoord is already the pixel's centre: add no half pixel"
                            : "x = (sx - W/2) size, y = (H/2 - sy) size, size = width / W";
    ADVISE(Near(corner, want),
           "the top-left pixel's centre, (0.5, 0.5), is seen along " + Vec(want),
           "your ray goes " + Vec(corner), cause);
    Perspective wide = {{0, 0, 0}, 2, 2, 512, 256};
    vec3 top = Direction(wide, {0.5, 0.5}),
         wantTop = SafeNormalize({-1 + 1.0 / 512, 0.5 - 1.0 / 512, -2});
    ADVISE(Near(top, wantTop),
           "in a 512 x 256 image the pixels stay square: (0.5, 0.5) along " + Vec(wantTop),
           "your ray goes " + Vec(top), "one size for both axes, width / widthPixels");
}

// ---- the sphere --------------------------------------------------------------------------------

static bool HitSphereAt(vec3 origin, vec3 dir, vec3 centre, real radius, real tMax, RayHit *hit) {
    Sphere s = {centre, radius, 0};
    Ray ray = {origin, dir};
    return IntersectSphereTextbook(&s, &ray, 0, tMax, hit);
}

static void TestSphere() {
    RayHit hit = {};
    bool found = HitSphereAt({0, 0, 0}, {0, 0, -1}, {0, 0, -5}, 1, kInfinity, &hit);
    std::string cause = !found ? "check B = 2 d.(o - c), and that B^2 - 4AC >= 0 is a hit"
                        : Near(hit.t, 6)
                            ? "you returned the far root: take the least root above tMin"
                        : hit.t < 0 ? "t is negative: the roots are (-B -+ sqrt(B^2 - 4AC)) / 2A"
                        : Near(hit.t, 8) || Near(hit.t, 2) ? "divide by 2A, not A or 4A"
                                                           : "check A, B and C";
    ADVISE(found && Near(hit.t, 4),
           "the ray (0,0,0) -> (0,0,-1) meets the sphere of radius 1 at (0,0,-5) at t = 4",
           Found(found, hit.t), cause);
    if (found) // (only a hit has a normal)
        ADVISE(Near(hit.normal, {0, 0, 1}), "there its normal is (0, 0, 1), back toward the eye",
               "yours is " + Vec(hit.normal), "SetHandoutSphereHit(s, ray, t, hit) writes it");
    found = HitSphereAt({0, 0, -5}, {0, 0, -1}, {0, 0, -5}, 1, kInfinity, &hit);
    ADVISE(found && Near(hit.t, 1),
           "from the sphere's centre, the ray (0,0,-5) -> (0,0,-1) meets it at t = 1",
           Found(found, hit.t),
           found && Near(hit.t, -1)
               ? "the near root is behind the ray: take the least root above tMin"
               : "from inside, the near root is negative: the far one is the hit");
    found = HitSphereAt({0, 0, 0}, {0, 0, 1}, {0, 0, -5}, 1, kInfinity, &hit);
    ADVISE(!found, "the sphere behind the ray (0,0,0) -> (0,0,1) is not hit", Found(found, hit.t),
           "both roots are negative: no root above tMin, no hit");
    found = HitSphereAt({0, 2, 0}, {0, 0, -1}, {0, 0, -5}, 1, kInfinity, &hit);
    ADVISE(!found,
           "the ray (0,2,0) -> (0,0,-1) passes 2 from the centre of a sphere of radius 1: a miss",
           Found(found, hit.t), "B^2 - 4AC < 0 means no hit");
    found = HitSphereAt({0, 0, 0}, {0, 0, -1}, {0, 0, -5}, 1, 3, &hit);
    ADVISE(!found, "with tMax = 3 the sphere at t = 4 is not hit (a shadow ray stops at its light)",
           Found(found, hit.t), "a root counts only if tMin < t < tMax");
    found = HitSphereAt({0, 0, 0}, {0, 0, -2}, {0, 0, -5}, 1, kInfinity, &hit);
    ADVISE(found && Near(hit.t, 2), "along d = (0, 0, -2), twice as long, the sphere is at t = 2",
           Found(found, hit.t),
           found && Near(hit.t, 3) ? "the far root again: take the least root above tMin"
                                   : "t counts lengths of d: A = d.d, and d is not normalised "
                                     "inside the test");
}

// ---- triangles ---------------------------------------------------------------------------------

typedef bool (*TriangleTest)(const Triangle *, const Ray *, real, real, RayHit *);

// The triangle (-1,-1,-3), (1,-1,-3), (0,1,-3), 3 ahead of the eye, by `test`.
static void TestTriangle(TriangleTest test, const char *name) {
    Triangle tri = {{-1, -1, -3}, {1, -1, -3}, {0, 1, -3}, 0};
    RayHit hit = {};
    Ray ray = {{0, 0, 0}, {0, 0, -1}};
    bool found = test(&tri, &ray, 0, kInfinity, &hit);
    ADVISE(
        found && Near(hit.t, 3),
        std::string(name) + ": the ray (0,0,0) -> (0,0,-1) meets the triangle at z = -3 at t = 3",
        Found(found, hit.t),
        found && Near(hit.t, -3) ? "t's sign: t = -(F (AK - JB) + E (JC - AL) + D (BL - KC)) / M"
                                 : "check the variables (J = a.x - e.x: the corner minus the eye)");
    ray.dir = {0.3, 0.3, -1};
    found = test(&tri, &ray, 0, kInfinity, &hit);
    ADVISE(!found,
           std::string(name) + ": the ray toward (0.9, 0.9, -3) passes outside the triangle",
           Found(found, hit.t), "outside when beta < 0, gamma < 0 or beta + gamma > 1");
    ray.dir = {0, 0, 1};
    found = test(&tri, &ray, 0, kInfinity, &hit);
    ADVISE(!found, std::string(name) + ": the triangle is behind the ray (0,0,0) -> (0,0,1)",
           Found(found, hit.t), "a hit needs tMin < t");
    ray.dir = {1, 0, 0};
    found = test(&tri, &ray, 0, kInfinity, &hit);
    ADVISE(!found, std::string(name) + ": the ray (0,0,0) -> (1,0,0) runs parallel to the triangle",
           Found(found, hit.t), "parallel means a zero determinant (M = 0, or n.d = 0): no hit");
    ray.dir = {0, -1, -3};
    found = test(&tri, &ray, 0, kInfinity, &hit);
    ADVISE(found && Near(hit.t, 1),
           std::string(name) +
               ": the ray toward (0, -1, -3), on the edge from a to b, hits it at t = 1",
           Found(found, hit.t),
           "an edge belongs to the triangle (beta >= 0, gamma >= 0, beta + gamma <= 1): with > the "
           "rays through an edge two triangles share slip through");
}

static void TestCramer() { TestTriangle(IntersectTriangleCramer, "Cramer's rule"); }
static void TestPlane() { TestTriangle(IntersectTrianglePlane, "the plane test"); }

// ---- the nearest hit ---------------------------------------------------------------------------

static Material Plain(color kd) { return {"plain", kd, kd, 0, 1, 0, 0, {0, 0, 0}}; }

static void TestNearestHit() {
    Scene scene;
    InitScene(&scene);
    scene.materials = {Plain({1, 1, 1})};
    scene.spheres = {{{0, 0, -10}, 1, 0}, {{0, 0, -5}, 1, 0}}; // the far one first
    Ray ray = {{0, 0, 0}, {0, 0, -1}};
    RayHit hit = {};
    bool found = FindNearestHit(&scene, kHandoutMethods, &ray, 0, kInfinity, &hit);
    ADVISE(
        found && Near(hit.t, 4) && hit.index == 1,
        "of two spheres on the ray, listed far one first, the near one (index 1) at t = 4 is hit",
        found ? "you report index " + std::to_string(hit.index) + " at t = " + Num(hit.t)
              : "you report no hit",
        found && Near(hit.t, 9) ? "you kept the first hit of the list: shrink tMax to each hit's t"
                                : "test every sphere (HitSphere), keeping the nearest hit");
    scene.triangles = {{{-2, -2, -3}, {2, -2, -3}, {0, 2, -3}, 0}};
    found = FindNearestHit(&scene, kHandoutMethods, &ray, 0, kInfinity, &hit);
    ADVISE(found && hit.shape == SHAPE_TRIANGLE && Near(hit.t, 3),
           "with a triangle at z = -3 before both spheres, the triangle is hit at t = 3",
           Found(found, hit.t),
           "test the triangles too (HitTriangle), after the spheres, with tMax shrunk");
    SelfHit leaving = {0, SHAPE_TRIANGLE, 0};
    found = FindNearestHitFrom(&scene, kHandoutMethods, &ray, &leaving, kInfinity, &hit);
    ADVISE(found && Near(hit.t, 4),
           "a ray that leaves the triangle passes over it (from names it): the near sphere, t = 4",
           Found(found, hit.t), "pass over the shape `from` names (from->shape, from->index)");
    ray.dir = {0, 0, 1};
    found = FindNearestHit(&scene, kHandoutMethods, &ray, 0, kInfinity, &hit);
    ADVISE(!found, "looking away, (0,0,0) -> (0,0,1), nothing is hit", Found(found, hit.t),
           "only hits with tMin < t < tMax count");
}

// ---- the shadow --------------------------------------------------------------------------------

// A floor at y = 0, facing up, wide enough for every check below; its material 0.
const Triangle kFloor = {{-10, 0, 10}, {10, 0, 10}, {0, 0, -10}, 0};

// A floor at y = 0 and a ball of radius 0.5 at (0, 2, 0); the point (0, 0, 0) on the floor.
static void ShadowScene(Scene *scene, RayHit *floorPoint) {
    InitScene(scene);
    scene->materials = {Plain({1, 1, 1})};
    scene->triangles = {kFloor};
    scene->spheres = {{{0, 2, 0}, 0.5, 0}};
    *floorPoint = {1, {0, 0, 0}, {0, 1, 0}, true, 0, SHAPE_TRIANGLE, 0, {0, 0, 0}, 0};
}

static void TestShadow() {
    Scene scene;
    RayHit floor;
    ShadowScene(&scene, &floor);
    const Methods *m = &kHandoutMethods;
    bool visible = LightVisible(&scene, m, &floor, {0, 4, 0});
    ADVISE(!visible,
           "the ball at (0, 2, 0) hides the light at (0, 4, 0) from the floor at (0, 0, 0)",
           "you say the light is visible",
           "the shadow ray toward the light must find the ball (this needs the sphere test and the "
           "nearest-hit loop)");
    visible = LightVisible(&scene, m, &floor, {0, 1, 0});
    ADVISE(visible, "with the light at (0, 1, 0), below the ball, the floor is lit",
           "you say the light is hidden", "a shape beyond the light (t > 1) casts no shadow");
    visible = LightVisible(&scene, m, &floor, {3, 4, 0});
    ADVISE(visible, "the light at (3, 4, 0) is not hidden: the ball is off the way",
           "you say the light is hidden",
           "does the floor hide itself? the shadow ray starts on it: use ShadowRay's `from`");
    RayHit top = {1, {0, 2.5, 0}, {0, 1, 0}, true, 0, SHAPE_SPHERE, 0, {0, 0, 0}, 0};
    visible = LightVisible(&scene, m, &top, {0, 4, 0});
    ADVISE(visible, "the top of the ball, (0, 2.5, 0), sees the light at (0, 4, 0)",
           "you say the light is hidden", "shadow acne: the ray hits the ball it starts on");
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

// The colour seen straight down at the floor's point (0, 0, 0), lit from `light`.
static color FloorSeen(vec3 light) {
    Scene scene;
    InitScene(&scene); // ambient 0.2
    scene.materials = {Plain({1, 0.5, 0.25})};
    scene.triangles = {kFloor};
    scene.lights = {{light, {1, 1, 1}}};
    Ray ray = {{0, 1, 0}, {0, -1, 0}};
    return TraceOne(&scene, ray, nullptr);
}

static void TestFloor() {
    const std::string needs = " (this needs Cramer's rule and the nearest-hit loop)";
    color c = FloorSeen({0, 4, 0});
    ADVISE(Near(c, {1, 0.5, 0.25}),
           "lit from straight above, N.L = 1: the colour kd = (1, 0.5, 0.25)", "you give " + Vec(c),
           Near(c, {0.2, 0.1, 0.05}) ? "the light is missing: N.L > 0 and visible, add it" + needs
                                     : "kd max(ambient, N.L), with L of length 1");
    c = FloorSeen({4 * std::sqrt(real(3)), 4, 0}); // 60 degrees from the normal: N.L = 0.5
    ADVISE(Near(c, {0.5, 0.25, 0.125}), "lit at 60 degrees, N.L = 0.5: kd 0.5 = (0.5, 0.25, 0.125)",
           "you give " + Vec(c), "N.L with L normalised: (N.L) / |L|");
    c = FloorSeen({4, 0.4, 0}); // N.L = 0.0995, below the ambient 0.2
    ADVISE(Near(c, {0.2, 0.1, 0.05}),
           "lit at a grazing angle, N.L = 0.1: kd max(0.2, 0.1) = (0.2, 0.1, 0.05)",
           "you give " + Vec(c), "the ambient floor: max(ambient, N.L)");
    c = FloorSeen({0, -4, 0});
    ADVISE(Near(c, {0.2, 0.1, 0.05}),
           "lit from below the floor: only the ambient floor, (0.2, 0.1, 0.05)",
           "you give " + Vec(c), "a light behind the surface (N.L < 0) adds nothing");
}

// ---- mirrors
// -------------------------------------------------------------------------------------

static void TestReflect() {
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

static void TestDepth() {
    uint64_t n = MirrorChain(10);
    ADVISE(
        n == 9, "between two facing mirrors, depth 10: the eye's ray and 9 reflections, then black",
        "you trace " + std::to_string(n) + " reflections",
        n == 0 ? "no reflection at all: the reflect step, Cramer's rule and the nearest-hit loop "
                 "come first"
               : "at most `depth` rays in a chain: if next.number > depth, return black");
    n = MirrorChain(1);
    ADVISE(n == 0, "with depth 1, only the eye's ray",
           "you trace " + std::to_string(n) + " reflections",
           "the eye's ray is number 1: with depth 1 nothing follows it");
}

// ---- Phong and refraction ------------------------------------------------------------------

static void TestPhong() {
    Scene scene;
    InitScene(&scene);
    scene.shading = SHADING_PHONG;
    scene.ambient = 0.1;
    Material m = Plain({0.5, 0.5, 0.5});
    m.ambient = {1, 1, 1}, m.specular = 0.5, m.shininess = 1;
    scene.materials = {m};
    scene.triangles = {kFloor};
    scene.lights = {{{0, 4, 0}, {1, 1, 1}}};
    Ray ray = {{0, 1, 0}, {0, -1, 0}};
    color c = TraceOne(&scene, ray, nullptr);
    // ka Ia + I (kd N.L + ks (R.V)^n) = 0.1 + (0.5 + 0.5) = 1.1 in every channel
    ADVISE(Near(c, {1.1, 1.1, 1.1}),
           "Phong, light and eye straight above: ka Ia + kd + ks = 0.1 + 0.5 + 0.5 = 1.1",
           "you give " + Vec(c), "ka Ia + I (kd (N.L) + ks max(0, R.V)^n), with R = 2 (N.L) N - L");
}

static void TestRefraction() {
    vec3 t = {0, 0, 0};
    real s = std::sqrt(real(0.5));
    bool refracts = Refract({s, -s, 0}, {0, 1, 0}, 1 / real(1.5), &t);
    real sinT = s / real(1.5); // Snell: sin t = eta sin i
    vec3 want = {sinT, -std::sqrt(1 - sinT * sinT), 0};
    ADVISE(refracts && Near(t, want),
           "into glass of index 1.5 at 45 degrees: sin t = sin 45 / 1.5, t = " + Vec(want),
           refracts ? "you give " + Vec(t) : "you say it does not refract",
           "eta d + (eta cos i - cos t) n");
    refracts = Refract({s, -s, 0}, {0, 1, 0}, real(1.5), &t);
    ADVISE(!refracts, "out of glass at 45 degrees: eta sin i = 1.06 > 1, total internal reflection",
           "you say it refracts", "no refraction when eta^2 (1 - cos^2 i) > 1");
}

// ---- the groups ------------------------------------------------------------------------------

const HandoutGroup kHandoutGroups[] = {
    {"get-ray", TestGetRay}, {"sphere", TestSphere},          {"cramer", TestCramer},
    {"plane", TestPlane},    {"nearest-hit", TestNearestHit}, {"shadow", TestShadow},
    {"floor", TestFloor},    {"reflect", TestReflect},        {"depth", TestDepth},
    {"phong", TestPhong},    {"refraction", TestRefraction},
};
const int kHandoutGroupCount = sizeof kHandoutGroups / sizeof kHandoutGroups[0];

void TestHandout() {
    for (const HandoutGroup &g : kHandoutGroups)
        g.run();
}
