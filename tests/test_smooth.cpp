// tests/test_smooth.cpp -- smooth meshes: corner normals read, turned and interpolated as worked
// out by hand, and the shadow terminator measured against the true sphere.
//
// A mesh's `vn` (or `smooth`'s averages) give each triangle's corners a normal; SurfaceNormal
// interpolates them with the hit's barycentric weights, and lighting uses that normal while every
// intersection keeps the flat triangle's. The checks: weights and normals at chosen points, the
// transform words turning normals square to the turned surface, a flipped winding flipping them,
// `flat`, `smooth` and `fit`; then whole images: a low-polygon sphere at grazing light against
// the true sphere (the terminator), and a lamp inside a closed smooth box seen from outside
// (nothing may leak through), at every scale.
#include "../app/app.h"
#include "robust_scenes.h"
#include "test.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

static bool Near(vec3 a, vec3 b, double tolerance) {
    return std::fabs(a.x - b.x) <= tolerance && std::fabs(a.y - b.y) <= tolerance &&
           std::fabs(a.z - b.z) <= tolerance;
}

static std::string Show(vec3 v) {
    char text[96];
    snprintf(text, sizeof text, "(%.6g %.6g %.6g)", (double)v.x, (double)v.y, (double)v.z);
    return text;
}

// A scene file and its OBJ written into dir, read back; false with *error if it does not load.
static bool LoadScene(const std::string &dir, const std::string &obj, const std::string &scene,
                      Scene *out, std::string *error) {
    std::ofstream(dir + "/m.obj") << obj;
    std::ofstream(dir + "/s.scene") << scene;
    return ReadSceneFile((dir + "/s.scene").c_str(), out, error);
}

// The triangle (0,0,0) (1,0,0) (0,1,0), outward +z, with normals at its corners leaning out as a
// sphere's would: a = (-1,-1,2), b = (1,0,1), c = (0,1,1), normalised.
static const char *kLeaning = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                              "vn -1 -1 2\nvn 1 0 1\nvn 0 1 1\n"
                              "f 1//1 2//2 3//3\n";

// Barycentric weights at the corners, the middle of an edge and the centroid; the normal there is
// the weights' mix of the corner normals, normalised (worked out by hand).
static void TestInterpolation(const std::string &dir) {
    Scene scene;
    std::string error;
    bool read = LoadScene(dir, kLeaning, "material m\nmesh m.obj m\n", &scene, &error);
    CHECK(read && scene.cornerNormals.size() == 1, "a triangle with vn at its corners: " + error);
    if (!read || scene.cornerNormals.size() != 1)
        return;
    const Triangle *t = &scene.triangles[0];
    real w[3];
    Barycentric(t, {real(0.5), 0, 0}, w);
    CHECK(w[0] == real(0.5) && w[1] == real(0.5) && w[2] == 0,
          "the middle of edge ab: weights (1/2, 1/2, 0)");
    Barycentric(t, {real(0.25), real(0.5), 0}, w);
    CHECK(w[0] == real(0.25) && w[1] == real(0.25) && w[2] == real(0.5),
          "the point (1/4, 1/2): weights (1/4, 1/4, 1/2)");
    vec3 na = Normalize({-1, -1, 2}), nb = Normalize({1, 0, 1}), nc = Normalize({0, 1, 1});
    RayHit hit = {};
    hit.shape = SHAPE_TRIANGLE, hit.index = 0, hit.frontFace = true, hit.normal = {0, 0, 1};
    hit.point = {real(1) / 3, real(1) / 3, 0};
    vec3 expected = Normalize(na + nb + nc);
    vec3 got = SurfaceNormal(&scene, &hit);
    CHECK(Near(got, expected, 1e-5),
          "at the centroid: (na + nb + nc) normalised = " + Show(expected) + ", got " + Show(got));
    hit.point = {0, 0, 0};
    CHECK(Near(SurfaceNormal(&scene, &hit), na, 1e-5), "at corner a: na itself");
    hit.frontFace = false, hit.normal = {0, 0, -1};
    CHECK(Near(SurfaceNormal(&scene, &hit), -na, 1e-5),
          "seen from behind: the other side, -na (as the geometric normal turns)");
    Scene flat;
    read = LoadScene(dir, kLeaning, "material m\nmesh m.obj m flat\n", &flat, &error);
    CHECK(read && flat.cornerNormals.empty(), "`flat`: the file's vn are not used");
    // A file whose normals are broken still loads, every triangle of it: the faces that name a
    // normal that is not there, or not three numbers, are flat, and the reader warns once each
    Scene broken;
    read = LoadScene(dir,
                     "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0\nvn 0 0 1\n"
                     "f 1//1 2//1 3//1\nf 2//2 4//2 3//9\nf 1//2 2//2 3//2\n",
                     "material m\nmesh m.obj m\n", &broken, &error);
    bool flatOnes =
        read && broken.cornerNormals.size() == 3 && MaxComponent(broken.cornerNormals[0].a) == 0 &&
        MaxComponent(broken.cornerNormals[1].a) == 0 && MaxComponent(broken.cornerNormals[2].a) > 0;
    CHECK(read && broken.triangles.size() == 3 && flatOnes && broken.warnings.size() == 2,
          "a vn of two numbers and a normal index out of range: all 3 triangles, the two faces "
          "flat, the third smooth, two warnings: " +
              error + (broken.warnings.empty() ? "" : broken.warnings[0]));
}

// The transform words turn normals as the surface turns: a normal stays square to the edges of
// its triangle, which is here the triangle's face normal given at all three corners, after
// rotations, a uniform scale, a stretch and a mirror. And a flipped winding (the file's faces
// wound the other way) flips the corner normals with the triangle's outward side.
static void TestTransformedNormals(const std::string &dir) {
    const char *faceNormal = "v 0 0 0\nv 2 0 1\nv 0 3 -1\nvn -3 2 6\nf 1//1 2//1 3//1\n";
    Scene scene;
    std::string error;
    bool read =
        LoadScene(dir, faceNormal,
                  "material m\nmesh m.obj m rotate x 30 rotate y -70 scale 3 translate 1 2 3\n",
                  &scene, &error);
    CHECK(read && scene.cornerNormals.size() == 1, "a turned triangle with vn: " + error);
    if (!read || scene.cornerNormals.size() != 1)
        return;
    const Triangle *t = &scene.triangles[0];
    vec3 n = scene.cornerNormals[0].a;
    vec3 e1 = Normalize(t->b - t->a), e2 = Normalize(t->c - t->a);
    CHECK(std::fabs(Dot(n, e1)) < 1e-5 && std::fabs(Dot(n, e2)) < 1e-5 &&
              std::fabs(Length(n) - 1) < 1e-5,
          "rotate, rotate, scale, translate: the turned normal is a unit vector square to the "
          "turned edges (n.e1 = " +
              std::to_string((double)Dot(n, e1)) +
              ", n.e2 = " + std::to_string((double)Dot(n, e2)) + ")");
    CHECK(Dot(n, Cross(t->b - t->a, t->c - t->a)) > 0, "and on the triangle's outward side");
    Scene stretched;
    read = LoadScene(dir, faceNormal, "material m\nmesh m.obj m scale 1 -2 3 rotate z 20\n",
                     &stretched, &error);
    const Triangle *s = read && stretched.cornerNormals.size() == 1 ? &stretched.triangles[0] : t;
    vec3 m = read && stretched.cornerNormals.size() == 1 ? stretched.cornerNormals[0].a : n;
    vec3 outward = Cross(s->b - s->a, s->c - s->a);
    CHECK(read && stretched.cornerNormals.size() == 1 &&
              std::fabs(Dot(m, Normalize(s->b - s->a))) < 1e-5 &&
              std::fabs(Dot(m, Normalize(s->c - s->a))) < 1e-5 && Dot(m, outward) > 0,
          "scale 1 -2 3 (stretched and mirrored in y), rotate z 20: the normal, by the inverse "
          "transpose, square to the edges; the mirror turns the winding back, so it stays on the "
          "outward side (" +
              Show(m) + ")" + error);
    Scene flipped;
    read = LoadScene(dir, "v 0 0 0\nv 2 0 1\nv 0 3 -1\nvn -3 2 6\nf 1//1 3//1 2//1\n",
                     "material m\nmesh m.obj m\n", &flipped, &error);
    CHECK(read && flipped.cornerNormals.size() == 1 &&
              Near(flipped.cornerNormals[0].a, -Normalize({-3, 2, 6}), 1e-6),
          "the same triangle wound the other way: its corner normals flip with its outward side");
}

// `smooth` on two squares that meet at a right angle along x = 0 (a floor and a wall): a vertex
// on the shared edge gets the mean of the two faces' normals, (0,1,0) + (1,0,0) normalised; a
// vertex of the floor alone gets (0,1,0). `fit 2`: a box 10 x 4 x 6 at (100, 0, 0) becomes 2 x
// 0.8 x 1.2, centred at the origin.
static void TestSmoothAndFit(const std::string &dir) {
    const char *fold = "v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\nv 0 1 0\nv 0 1 1\n"
                       "f 1 2 3 4\nf 1 5 6 2\n";
    Scene scene;
    std::string error;
    bool read = LoadScene(dir, fold, "material m\nmesh m.obj m smooth\n", &scene, &error);
    CHECK(read && scene.cornerNormals.size() == 4,
          "`smooth` on a fold of four triangles: " + error);
    if (!read || scene.cornerNormals.size() != 4)
        return;
    vec3 shared = Normalize({1, 1, 0}), floor = {0, 1, 0};
    const CornerNormals &c = scene.cornerNormals[0]; // triangle 1 2 3: vertices 1, 2 shared
    CHECK(Near(c.a, shared, 1e-6) && Near(c.b, shared, 1e-6) && Near(c.c, floor, 1e-6),
          "the shared edge's vertices: (1,1,0)/sqrt 2; the floor's own vertex: (0,1,0); got " +
              Show(c.a) + " " + Show(c.b) + " " + Show(c.c));
    Scene fitted;
    read = LoadScene(dir, "v 95 -2 -3\nv 105 2 3\nv 95 2 -3\nf 1 2 3\n",
                     "material m\nmesh m.obj m fit 2\n", &fitted, &error);
    CHECK(read && fitted.triangles.size() == 1 &&
              Near(fitted.triangles[0].a, {-1, -0.4, -0.6}, 1e-6) &&
              Near(fitted.triangles[0].b, {1, 0.4, 0.6}, 1e-6),
          "`fit 2`: the box 10 x 4 x 6 around (100, 0, 0) becomes 2 x 0.8 x 1.2 around the "
          "origin: " +
              error);
    read =
        LoadScene(dir, "v 1 1 1\nf 1 1 1\n", "material m\nmesh m.obj m fit 2\n", &fitted, &error);
    CHECK(!read && error.find("no size to fit") != std::string::npos,
          "`fit` of a mesh that is one point: an error (" + error + ")");
}

// The corner normals rt will not interpolate, each with one warning a mesh naming the file: a
// triangle whose corner normal leans behind its face, or opposes the other two (drawn flat: a
// quarter of it would otherwise be shaded from behind); a zero `vn`; a `vn` the transform words
// take beyond the range of numbers; and under `smooth`, faces wound against their neighbours.
static void TestNormalWarnings(const std::string &dir) {
#ifdef RT_FLOAT // (a normal that a scale of 1e-10 in x takes beyond float's range, or double's)
    const char *kHugeNormal = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 1e30 0 1\nf 1//1 2//1 3//1\n";
#else
    const char *kHugeNormal = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 1e300 0 1\nf 1//1 2//1 3//1\n";
#endif
    struct {
        const char *obj, *words, *warning;
        size_t smooth, warnings; // how many triangles keep corner normals; how many warnings
    } cases[] = {
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 0 -1\n"
         "f 1//1 2//1 3//2\nf 2//1 4//1 3//1\n",
         "", "m.obj: warning: 1 triangle has a corner normal that leans behind its face", 1, 1},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -1\nvn 0 0 1\nf 1//1 2//1 3//2\n", "",
         "m.obj: warning: 1 triangle has a corner normal that leans behind its face", 0, 1},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nvn 0 0 1\nf 1//1 2//2 3//2\n", "",
         "m.obj:4: warning: vn: a normal of length 0 has no direction", 0, 1},
        {kHugeNormal, "scale 1e-10 1 1",
         "m.obj:4: warning: vn: the transform words take this normal beyond the range", 0, 1},
        {"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
         "f 1 2 5\nf 2 3 5\nf 3 5 4\nf 1 5 4\nf 1 4 3 2\n",
         // (and the face wound against the rest is flat: its averaged corners lean behind it)
         "smooth", "m.obj: warning: smooth: 3 edges join faces wound opposite ways", 5, 2},
    };
    for (const auto &c : cases) {
        Scene scene;
        std::string error;
        bool read = LoadScene(dir, c.obj, std::string("material m\nmesh m.obj m ") + c.words + "\n",
                              &scene, &error);
        size_t smooth = 0;
        for (const CornerNormals &n : scene.cornerNormals)
            smooth += MaxComponent(n.a) > 0;
        std::string all;
        for (const std::string &w : scene.warnings)
            all += "'" + w + "' ";
        bool warned =
            scene.warnings.size() == c.warnings && all.find(c.warning) != std::string::npos;
        CHECK(read && warned && smooth == c.smooth,
              std::to_string(c.warnings) + " warning(s), one '" + c.warning + "...', and " +
                  std::to_string(c.smooth) + " smooth triangle(s); got " + std::to_string(smooth) +
                  " and " + all + error);
    }
}

// ---- whole images ----------------------------------------------------------------------------

// The linear light of every pixel of an n x n image of the scene.
static std::vector<double> Pixels(const Scene *scene, Methods methods) {
    RenderSettings s = TestSettings(scene);
    s.methods = methods;
    std::vector<double> v;
    RayStats stats = {};
    for (int j = 0; j < scene->height; j++)
        for (int i = 0; i < scene->width; i++) {
            color c = RenderPixel(scene, &s, i, j, &stats);
            v.push_back((c.x + c.y + c.z) / 3);
        }
    return v;
}

// The terminator: a low-polygon sphere lit from nearly behind its silhouette, against the true
// sphere. Over the pixels both images show (neither is background): the pixels the true sphere
// lights (above the ambient floor) that the mesh leaves at the floor, shadowed by its own facets,
// and the share of the true sphere's light that the mesh's image lacks. The naive method (the
// handouts': the shadow ray from the flat triangle) leaves a band of facets dark; rt's (the
// origin moved out to the curved surface) none, and lacks a fraction of the naive share (what
// it lacks is the interpolated normals' own difference from the sphere's).
static void TestTerminator(const std::string &dir) {
    for (int level : {1, 2}) {
        const char *scene = "size 64 64\ncamera lookat 0 0 3.2  0 0 0  0 1 0  40\n"
                            "shading floor\nambient 0.01\nlight 10 3 -2.5\n"
                            "material m diffuse 1 1 1\n";
        Scene mesh, sphere;
        std::string error;
        bool read = LoadScene(dir, IcosphereObj(level), std::string(scene) + "mesh m.obj m\n",
                              &mesh, &error) &&
                    LoadScene(dir, "", std::string(scene) + "sphere 0 0 0 1 m\n", &sphere, &error);
        CHECK(read, "the icosphere and the true sphere load: " + error);
        if (!read)
            return;
        std::vector<double> truth = Pixels(&sphere, kRobustMethods);
        int dark[2] = {0, 0}, lit = 0;
        double lacks[2] = {0, 0}, total = 0;
        for (int way = 0; way < 2; way++) {
            std::vector<double> v = Pixels(&mesh, way == 0 ? kHandoutMethods : kRobustMethods);
            for (size_t p = 0; p < v.size(); p++) {
                if (!(v[p] > 0 && truth[p] > 0))
                    continue;
                bool lights = truth[p] > 0.02;
                lit += way == 0 && lights, total += way == 0 ? truth[p] : 0;
                dark[way] += lights && v[p] <= 0.011;
                lacks[way] += std::max(0.0, truth[p] - v[p]);
            }
        }
        char text[240];
        snprintf(text, sizeof text,
                 "icosphere of %d faces at grazing light: of %d pixels the true sphere lights, the "
                 "naive method leaves %d dark, rt's %d; their images lack %.1f%% and %.1f%% of its "
                 "light",
                 20 << (2 * level), lit, dark[0], dark[1], 100 * lacks[0] / total,
                 100 * lacks[1] / total);
        CHECK(dark[0] >= 10 && dark[1] * 10 <= dark[0] && lacks[1] * 2 <= lacks[0], text);
    }
}

// A lamp inside a closed smooth box, seen from outside with no ambient light: every pixel black,
// under floor, phong and path shading, at every scale (the smooth normals at the box's corners
// lean 55 degrees off its faces, so they face the lamp from outside near every edge).
static void TestNoLeak(const std::string &dir) {
    const char *cube = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\n"
                       "v 1 1 1\nv -1 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\n"
                       "f 1 5 8 4\nf 2 3 7 6\n";
#ifdef RT_FLOAT
    const double scales[] = {1e-15, 1, 1e15};
#else
    const double scales[] = {1e-150, 1, 1e150};
#endif
    for (double scale : scales)
        for (const char *shading : {"floor", "phong", "path"}) {
            char text[600];
            snprintf(text, sizeof text,
                     "size 24 24\ncamera lookat %g %g %g  0 0 0  0 1 0  40\nshading %s\n"
                     "ambient 0\nbackground 0 0 0\nmaterial m diffuse 0.8 0.8 0.8\n"
                     "material lamp diffuse 0 0 0 emit 5 5 5\nmesh m.obj m smooth scale %g\n"
                     "light %g %g %g 4 4 4\nsphere %g %g %g %g lamp\n",
                     3 * scale, 2.5 * scale, 4 * scale, shading, scale, 0.9 * scale, 0.9 * scale,
                     0.9 * scale, 0.5 * scale, 0.5 * scale, 0.5 * scale, 0.3 * scale);
            Scene scene;
            std::string error;
            bool read = LoadScene(dir, cube, text, &scene, &error);
            std::vector<double> v = read ? Pixels(&scene, kRobustMethods) : std::vector<double>();
            double most = 0;
            for (double x : v)
                most = std::max(most, x);
            snprintf(text, sizeof text,
                     "a lamp inside a closed smooth box, shading %s, scale %g: no light leaks out "
                     "(brightest pixel %g)",
                     shading, scale, most);
            CHECK(read && !v.empty() && most == 0, text + (read ? "" : ": " + error));
        }
}

void TestSmooth() {
    std::string dir = MakeTestDir("smooth");
    TestInterpolation(dir);
    TestTransformedNormals(dir);
    TestSmoothAndFit(dir);
    TestNormalWarnings(dir);
    TestTerminator(dir);
    TestNoLeak(dir);
    RemoveTestDir(dir);
}
