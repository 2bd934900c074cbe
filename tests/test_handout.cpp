// tests/test_handout.cpp -- the handouts' steps checked as their debugging advice puts it: a
// scene, a ray, the answer worked out by hand, and, when the answer differs, what was found and
// the most likely cause. This file: the rays and the shapes (GetRay, the normal, the sphere, the
// triangle by Cramer's rule or the plane test, the nearest hit); test_handout_light.cpp: the
// light (shadows, shading, mirrors, the depth, Phong, refraction, colours), and the groups. rt
// runs them all (group `handout`, in the handouts' methods); a starter kit runs the groups of the
// steps its students write (tools/starter/stubs.list).
#include "test_handout.h"

#include <cstdio>

std::string Num(double x) {
    char text[32];
    snprintf(text, sizeof text, "%.6g", x);
    return text;
}
std::string Vec(vec3 v) { return "(" + Num(v.x) + ", " + Num(v.y) + ", " + Num(v.z) + ")"; }
bool Near(double a, double b) { return std::fabs(a - b) <= 1e-5 * (1 + std::fabs(b)); }
bool Near(vec3 a, vec3 b) { return Near(a.x, b.x) && Near(a.y, b.y) && Near(a.z, b.z); }
std::string Found(bool hit, real t) { return hit ? "you report t = " + Num(t) : "you report no hit"; }

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
           "your ray goes " + Vec(top),
           "one size for both axes, width / widthPixels (a pixel's height is not width / H)");
}

// ---- the normal, turned toward the viewer ------------------------------------------------------

static void TestNormals() {
    Ray ray = {{0, 0, 0}, {0, 0, -1}};
    RayHit hit = {};
    SetFaceNormal(&ray, {0, 0, 1}, &hit);
    ADVISE(Near(hit.normal, {0, 0, 1}) && hit.frontFace,
           "a surface whose outward normal (0, 0, 1) faces the ray keeps it, seen from the front",
           "you give " + Vec(hit.normal) + (hit.frontFace ? ", front" : ", back"),
           "N stays as it is when N.D < 0");
    SetFaceNormal(&ray, {0, 0, -1}, &hit);
    ADVISE(Near(hit.normal, {0, 0, 1}) && !hit.frontFace,
           "seen from behind (outward normal (0, 0, -1), along the ray), the normal turns toward "
           "the viewer: (0, 0, 1), and frontFace is false",
           "you give " + Vec(hit.normal) + (hit.frontFace ? ", front" : ", back"),
           "if N.D > 0, N = -N: a light behind a surface must not light its front");
}

// ---- the sphere --------------------------------------------------------------------------------

static bool HitSphereAt(vec3 origin, vec3 dir, vec3 centre, real radius, real tMin, real tMax,
                        RayHit *hit) {
    Sphere s = {centre, radius, 0};
    Ray ray = {origin, dir};
    return IntersectSphereTextbook(&s, &ray, tMin, tMax, hit);
}

static void TestSphere() {
    RayHit hit = {};
    // The handout's numbers: o = (0,0,0), d = (0,0,-1), c = (0,0,-5), r = 1 give A = 1,
    // B = 2 d.(o - c) = -10, C = |o - c|^2 - r^2 = 24: B^2 - 4AC = 4, roots (10 -+ 2) / 2 = 4, 6.
    bool found = HitSphereAt({0, 0, 0}, {0, 0, -1}, {0, 0, -5}, 1, 0, kInfinity, &hit);
    std::string cause = !found ? "check B = 2 d.(o - c) = -10, C = 24, and that B^2 - 4AC >= 0 "
                                 "is a hit"
                        : Near(hit.t, 6)
                            ? "you returned the far root: take the least root above tMin"
                        : hit.t < 0 ? "t is negative: the roots are (-B -+ sqrt(B^2 - 4AC)) / 2A"
                        : Near(hit.t, 8) || Near(hit.t, 2) ? "divide by 2A, not A or 4A"
                                                           : "check A = 1, B = -10, C = 24";
    ADVISE(found && Near(hit.t, 4),
           "the ray (0,0,0) -> (0,0,-1) meets the sphere of radius 1 at (0,0,-5) at t = 4 "
           "(A = 1, B = -10, C = 24: roots 4 and 6)",
           Found(found, hit.t), cause);
    if (found) // (only a hit has a normal)
        ADVISE(Near(hit.normal, {0, 0, 1}), "there its normal is (0, 0, 1), back toward the eye",
               "yours is " + Vec(hit.normal), "SetHandoutSphereHit(s, ray, t, hit) writes it");
    found = HitSphereAt({0, 0, -5}, {0, 0, -1}, {0, 0, -5}, 1, 0, kInfinity, &hit);
    ADVISE(found && Near(hit.t, 1),
           "from the sphere's centre, the ray (0,0,-5) -> (0,0,-1) meets it at t = 1",
           Found(found, hit.t),
           found && Near(hit.t, -1)
               ? "the near root is behind the ray: take the least root above tMin"
               : "from inside, the near root is negative: the far one is the hit");
    found = HitSphereAt({0, 0, -4 + 1e-6}, {0, 0, -1}, {0, 0, -5}, 1, 1e-4, kInfinity, &hit);
    ADVISE(found && Near(hit.t, 2 + 1e-6),
           "a ray that starts on the sphere, 1e-6 before it, with tMin = 1e-4 (as a shadow or "
           "mirror ray leaving it does), passes the root at 1e-6 and meets the far side at t = 2",
           Found(found, hit.t),
           found && hit.t < 1e-4 ? "a root at or below tMin counts: accept only tMin < t < tMax "
                                   "(else every ray that leaves a sphere finds it again: acne)"
                                 : "the least root above tMin: here the far one");
    found = HitSphereAt({0, 0, 0}, {0, 0, 1}, {0, 0, -5}, 1, 0, kInfinity, &hit);
    ADVISE(!found, "the sphere behind the ray (0,0,0) -> (0,0,1) is not hit", Found(found, hit.t),
           "both roots are negative: no root above tMin, no hit");
    found = HitSphereAt({0, 2, 0}, {0, 0, -1}, {0, 0, -5}, 1, 0, kInfinity, &hit);
    ADVISE(!found,
           "the ray (0,2,0) -> (0,0,-1) passes 2 from the centre of a sphere of radius 1: a miss",
           Found(found, hit.t), "B^2 - 4AC < 0 means no hit");
    found = HitSphereAt({0, 0, 0}, {0, 0, -1}, {0, 0, -5}, 1, 0, 3, &hit);
    ADVISE(!found, "with tMax = 3 the sphere at t = 4 is not hit (a shadow ray stops at its light)",
           Found(found, hit.t), "a root counts only if tMin < t < tMax");
    found = HitSphereAt({0, 0, 0}, {0, 0, -2}, {0, 0, -5}, 1, 0, kInfinity, &hit);
    ADVISE(found && Near(hit.t, 2), "along d = (0, 0, -2), twice as long, the sphere is at t = 2",
           Found(found, hit.t),
           found && Near(hit.t, 3) ? "the far root again: take the least root above tMin"
                                   : "t counts lengths of d: A = d.d, and d is not normalised "
                                     "inside the test");
}

// ---- triangles ---------------------------------------------------------------------------------

typedef bool (*TriangleTest)(const Triangle *, const Ray *, real, real, RayHit *);

// What to say of a triangle test's mistakes, in the method's own terms.
struct TriangleAdvice {
    const char *name, *terms, *tSign, *parallel, *inside, *edge;
};
static const TriangleAdvice kCramer = {
    "Cramer's rule",
    "check the variables (J = a.x - e.x: the corner minus the eye) and each product of M, t, "
    "beta and gamma: a tilted triangle uses every term, so a sign in one shows here",
    "t's sign: t = -(F (AK - JB) + E (JC - AL) + D (BL - KC)) / M",
    "parallel means M = 0: no hit",
    "inside when beta >= 0, gamma >= 0 and beta + gamma <= 1 (beta <= 1 - gamma: not beta <= 1, "
    "nor gamma against 1 - gamma)",
    "an edge belongs to the triangle (beta >= 0, gamma >= 0, beta + gamma <= 1): with > the rays "
    "through an edge two triangles share slip through"};
static const TriangleAdvice kPlane = {
    "the plane test",
    "check n = (b - a) x (c - a), t = n.(a - o) / n.d and p = o + t d",
    "t's sign: t = n.(a - o) / n.d, the corner minus the ray's origin",
    "parallel means n.d = 0: no hit",
    "inside when (b - a) x (p - a), (c - b) x (p - b) and (a - c) x (p - c) each point the way n "
    "does, compared on n's largest coordinate (drop that one, not always z)",
    "an edge belongs to the triangle: a cross product of 0 there is not against n (< 0 is "
    "outside, not <= 0)"};

// The triangle (-1,-1,-3), (1,-1,-3), (0,1,-3), 3 ahead of the eye, and the ray toward the point
// a + beta (b - a) + gamma (c - a) of its plane, which meets it at t = 1 if it is inside.
static const Triangle kTriangle = {{-1, -1, -3}, {1, -1, -3}, {0, 1, -3}, 0};
static const struct {
    real beta, gamma;
    bool inside;
    const char *where;
} kRegions[] = {
    {0.1, 0.1, true, "inside, near a"},        {0.8, 0.1, true, "inside, near b"},
    {0.1, 0.8, true, "inside, near c"},        {0.5, -0.2, false, "beyond the edge a-b"},
    {0.6, 0.6, false, "beyond the edge b-c"},  {-0.2, 0.5, false, "beyond the edge c-a"},
    {-0.2, -0.2, false, "beyond the corner a"}, {1.2, -0.1, false, "beyond the corner b"},
    {-0.1, 1.2, false, "beyond the corner c"},
};

static void TestRegions(TriangleTest test, const TriangleAdvice *a) {
    const Triangle *tri = &kTriangle;
    for (const auto &r : kRegions) {
        vec3 p = tri->a + r.beta * (tri->b - tri->a) + r.gamma * (tri->c - tri->a);
        Ray ray = {{0, 0, 0}, p};
        RayHit hit = {};
        bool found = test(tri, &ray, 0, kInfinity, &hit);
        ADVISE(found == r.inside && (!found || Near(hit.t, 1)),
               std::string(a->name) + ": the ray toward " + Vec(p) + " (beta " + Num(r.beta) +
                   ", gamma " + Num(r.gamma) + ": " + r.where + ") " +
                   (r.inside ? "hits it at t = 1" : "misses it"),
               Found(found, hit.t), a->inside);
    }
}

static void TestTriangle(TriangleTest test, const TriangleAdvice *a) {
    const Triangle *tri = &kTriangle;
    RayHit hit = {};
    Ray ray = {{0, 0, 0}, {0, 0, -1}};
    bool found = test(tri, &ray, 0, kInfinity, &hit);
    ADVISE(found && Near(hit.t, 3),
           std::string(a->name) + ": the ray (0,0,0) -> (0,0,-1) meets the triangle at z = -3 at t = 3",
           Found(found, hit.t), found && Near(hit.t, -3) ? a->tSign : a->terms);
    Triangle tilted = {{1, 0, -4}, {0, 2, -5}, {-1, -1, -3}, 0};
    ray.dir = {0, real(1) / 3, -4}; // toward its centroid
    found = test(&tilted, &ray, 0, kInfinity, &hit);
    ADVISE(found && Near(hit.t, 1),
           std::string(a->name) + ": the tilted triangle (1,0,-4), (0,2,-5), (-1,-1,-3) is met at "
                                  "its centroid (0, 1/3, -4) at t = 1",
           Found(found, hit.t), found && Near(hit.t, -1) ? a->tSign : a->terms);
    ray.dir = {0, 0, -1};
    ray.origin = {0, 0, -3 + 1e-6};
    found = test(tri, &ray, 1e-4, kInfinity, &hit);
    ADVISE(!found,
           std::string(a->name) + ": a ray that starts 1e-6 before the triangle, with tMin = 1e-4 "
                                  "(a shadow or mirror ray leaving it), does not hit it",
           Found(found, hit.t),
           "a hit needs tMin < t < tMax (else every ray that leaves a triangle finds it again)");
    ray.origin = {0, 0, 0};
    ray.dir = {0, 0, 1};
    found = test(tri, &ray, 0, kInfinity, &hit);
    ADVISE(!found, std::string(a->name) + ": the triangle is behind the ray (0,0,0) -> (0,0,1)",
           Found(found, hit.t), found ? a->tSign : "a hit needs tMin < t");
    ray.dir = {1, 0, 0};
    found = test(tri, &ray, 0, kInfinity, &hit);
    ADVISE(!found, std::string(a->name) + ": the ray (0,0,0) -> (1,0,0) runs parallel to the triangle",
           Found(found, hit.t), a->parallel);
    ray.dir = {0, -1, -3};
    found = test(tri, &ray, 0, kInfinity, &hit);
    ADVISE(found && Near(hit.t, 1),
           std::string(a->name) +
               ": the ray toward (0, -1, -3), on the edge from a to b, hits it at t = 1",
           Found(found, hit.t), a->edge);
    TestRegions(test, a);
    Triangle floor = {{-2, -1, -2}, {2, -1, -2}, {0, -1, -6}, 0}; // (facing up: n along y)
    ray.dir = {0, -1, -3};
    found = test(&floor, &ray, 0, kInfinity, &hit);
    ADVISE(found && Near(hit.t, 1),
           std::string(a->name) + ": the floor triangle (-2,-1,-2), (2,-1,-2), (0,-1,-6) is met "
                                  "at (0, -1, -3) at t = 1",
           Found(found, hit.t), a->inside);
    ray.dir = {1.9, -1, -5};
    found = test(&floor, &ray, 0, kInfinity, &hit);
    ADVISE(!found, std::string(a->name) + ": the ray toward (1.9, -1, -5) passes beside that floor",
           Found(found, hit.t), a->inside);
}

// The handout's numbers for TestTriangle's first check: a = (-1,-1,-3), b = (1,-1,-3),
// c = (0,1,-3), e = (0,0,0), d = (0,0,-1) give A = -2, B = 0, C = 0, D = -1, E = -2, F = 0,
// G = 0, H = 0, I = -1, J = -1, K = -1, L = -3; then EI - HF = 2, GF - DI = -1, DH - EG = 0,
// M = A (EI - HF) + B (GF - DI) + C (DH - EG) = -4; AK - JB = 2, JC - AL = -6, BL - KC = 0,
// t = -(F (AK - JB) + E (JC - AL) + D (BL - KC)) / M = -12 / -4 = 3,
// gamma = (I (AK - JB) + H (JC - AL) + G (BL - KC)) / M = -2 / -4 = 1/2,
// beta = (J (EI - HF) + K (GF - DI) + L (DH - EG)) / M = -1 / -4 = 1/4: the point a + beta (b - a)
// + gamma (c - a) = (0, 0, -3), inside (beta, gamma >= 0, beta + gamma <= 1).
static void TestCramer() { TestTriangle(IntersectTriangleCramer, &kCramer); }
static void TestPlane() { TestTriangle(IntersectTrianglePlane, &kPlane); }

// ---- the nearest hit ---------------------------------------------------------------------------

Material Plain(color kd) { return {"plain", kd, kd, 0, 1, 0, 0, {0, 0, 0}}; }

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

// The groups, a step each, in the handouts' order; each names the steps its checks go through
// first (a check of the shadow traces rays that the sphere and the nearest hit must find), so
// that a failure there is blamed on the earliest step that fails.
const HandoutGroup kHandoutGroups[] = {
    {"get-ray", TestGetRay, ""},
    {"normals", TestNormals, ""},
    {"sphere", TestSphere, "normals"},
    {"cramer", TestCramer, "normals"},
    {"plane", TestPlane, "normals"},
    {"nearest-hit", TestNearestHit, "sphere cramer"},
    {"shadow", TestShadow, "sphere cramer nearest-hit"},
    {"floor", TestFloor, "normals cramer nearest-hit shadow"},
    {"reflect", TestReflect, ""},
    {"depth", TestDepth, "normals cramer nearest-hit reflect"},
    {"phong", TestPhong, "normals sphere cramer nearest-hit shadow"},
    {"refraction", TestRefraction, ""},
    {"clamp", TestClamp, ""},
};
const int kHandoutGroupCount = sizeof kHandoutGroups / sizeof kHandoutGroups[0];

void TestHandout() {
    for (const HandoutGroup &g : kHandoutGroups)
        g.run();
}
