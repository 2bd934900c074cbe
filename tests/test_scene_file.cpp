// tests/test_scene_file.cpp -- scene files: every error names its line, valid variations read
// the same, the three cameras make the rays worked out by hand, and the built-in scenes' files
// draw the built-in scenes' bytes.
#include "../app/app.h"
#include "../fast/fast.h"
#include "../render.h"
#include "test.h"

#include <cstdio>
#include <dirent.h>
#include <fstream>
#include <sstream>

struct BadScene {
    const char *text;
    int line;            // the line the error must name
    const char *message; // a piece of the message
};

static const BadScene kBadScenes[] = {
    {"bogus 1 2", 1, "unknown keyword 'bogus'"},
    {"Sphere 0 0 0 1 m", 1, "unknown keyword"}, // keywords are lower case
    {"\n\n  size", 3, "missing number"},
    {"size 512 512 3", 1, "extra value '3'"},
    {"size 0 512", 1, "between 1 and 16384"},
    {"size 16385 2", 1, "between 1 and 16384"},
    {"size 1.5 2", 1, "not a whole number"},
    {"ambient nan", 1, "not a decimal number"},
    {"ambient inf", 1, "not a decimal number"},
    {"ambient 0x10", 1, "not a decimal number"},
    {"ambient 0.5x", 1, "not a decimal number"},
    {"ambient 1e999", 1, "out of range"},
    {"ambient 1e-999", 1, "too small, it would be 0"}, // (0e-999 and 0.000 are 0, as written)
    {"material m\nsphere 0 0 -5 1e-400 m", 2, "too small, it would be 0): '1e-400'"},
    {"ambient 1.5", 1, "[0, 1]"},
    {"ambient 0.1\nambient 0.2", 2, "second 'ambient'"},
    {"size 1 1\n# fine\nsize 2 2", 3, "second 'size'"},
    {"shading phong\nshading floor", 2, "second 'shading'"},
    {"background 0 0 0\nbackground 0 0 0", 2, "second 'background'"},
    {"depth 3\ndepth 4", 2, "second 'depth'"},
    {"camera perspective 0 0 0 2 2\ncamera perspective 0 0 0 2 2", 2, "second 'camera'"},
    {"depth 0", 1, "between 1 and 1000"},
    {"depth 1001", 1, "between 1 and 1000"},
    {"shading gouraud", 1, "'floor', 'phong' or 'path'"},
    {"shading Phong", 1, "expected 'floor', 'phong' or 'path' (lower case: 'phong')"},
    {"shading phong phong", 1, "shading: extra value 'phong'"},
    {"ambient", 1, "ambient: missing number(s): expected 1 value after ambient"},
    {"background 0 0 2", 1, "[0, 1]"},
    {"background 0 0", 1, "missing number"},
    {"camera fisheye 1", 1, "unknown kind"},
    {"camera perspective 0 0 0 0 2", 1, "must be > 0"},
    {"camera perspective 0 0 0 2", 1, "missing number"},
    {"camera lookat 0 0 0  0 0 0  0 1 0  60", 1, "from and to are the same point"},
    {"camera lookat 0 0 0  0 0 -1  0 0 -1  60", 1, "up is zero or along the view"},
    {"camera lookat 0 0 0  0 0 -1  0 0 0  60", 1, "up is zero or along the view"},
    {"camera screen 0 0 0  -1 -1 0  2 0 0  0 2 0", 1, "the eye lies on the screen's plane"},
    {"camera screen 1e20 0 0  1e20 -1 -1  0 0 2  0 2 0", 1, "the eye lies on the screen's plane"},
    {"camera screen 0 0 0  -1 -1 -1  2 0 0  4 0 0", 1, "not parallel"},
    {"camera screen 0 0 0  -1 -1 -1  2 0 0  2 1e-30 0", 1, "not parallel"}, // to rounding
    {"camera lookat 0 0 0  0 0 -1  0 1 0  180", 1, "more than 0 and less than 180"},
    {"camera screen 0 0 0  -1 -1 -1  2 0 0  4 0 0", 1, "not parallel"},
    {"sphere 0 0 0 1 m", 1, "material 'm' is not defined"},
    {"sphere 0 0 0 1 m\nmaterial m", 1, "not defined"}, // used before it is defined
    {"material m\nsphere 0 0 0 0 m", 2, "radius must be > 0"},
    {"material m\nsphere 0 0 0 -1 m", 2, "radius must be > 0"},
    {"material m\nsphere 0 0 0 m", 2,
     "expected 4 numbers and a material name, found 3 numbers and then 'm'"},
    {"material m\nsphere 0 0 -5 1 1 m", 2, "found 5 numbers and then 'm'"}, // not "extra value 'm'"
    {"material m\nsphere 0 0 -5 1 1e999 m", 2, "found 5 numbers and then 'm'"}, // (any size)
    {"material m\nsphere 0,0,-6 1 m", 2, "sphere: not a decimal number: '0,0,-6'"},
    {"material m\nsphere 0 0 -5 1 2", 2,
     "material '2' is not defined (define it above; or, if it is a number, the name is left out)"},
    {"material 2\nsphere 0 0 -5 1 1 2", 2, "found 5 numbers and then '2'"}, // (a name, though
                                                                            // written as a number)
    {"material m\nsphere 0 0 -5 1", 2, "found 4 numbers and no material name"},
    {"material m\ntriangle 0 0 0 1 0 0 0 1 0 0 m", 2,
     "expected 9 numbers and a material name, found 10"},
    {"material m\nsphere 0 0 0 1 m extra", 2, "extra value 'extra'"},
    {"material m\ntriangle 0 0 0 1 0 0 0 1 m", 2, "expected 9 numbers"},
    {"material m\ntriangle 0 0 0 1 0 0 0 1 z m", 2, "not a decimal number: 'z'"},
    {"material m\nmaterial m", 2, "defined twice"},
    {"material", 1, "missing name"},
    {"material m diffuse 1.5 0 0", 1,
     "material: diffuse 1.5 0 0: each component must be in [0, 1]"},
    {"material m diffuse -0.1 0 0", 1, "[0, 1]"},
    {"material m diffuse 1 1", 1, "needs 3 number"},
    {"material m ambient 1 1 7", 1, "[0, 1]"},
    {"material m specular 0.5", 1, "'specular' needs 2 numbers: KS N"},
    {"material m glass", 1, "'glass' needs 1 number: IOR"},
    {"material m specular -1 10", 1, ">= 0"},
    {"material m mirror 2", 1, "mirror fraction must be in [0, 1]"},
    {"material m mirror 0.5 mirror 0.2", 1, "given twice"},
    {"material m glass 0", 1, "index of refraction must be > 0"},
    {"material m glass -1.5", 1, "index of refraction must be > 0"},
    {"material m shiny 3", 1, "unknown property 'shiny'"},
    {"light 0 0 0 1 1", 1, "expected 3 numbers (X Y Z) or 6 (X Y Z R G B), got 5"},
    {"light 0 0 0 2", 1, "expected 3 numbers (X Y Z) or 6 (X Y Z R G B), got 4"},
    {"light 0 0 0 1 1 -2", 1, "finite number >= 0"},
    {"material m emit 1 -1 1", 1, "finite number >= 0"},
    {"material m emit 1 1", 1, "'emit' needs 3 numbers: R G B"},
    {"ambient 2", 1, "ambient 2: must be in [0, 1]"},
    {"background 0 2 0.5", 1, "background 0 2 0.5: each component must be in [0, 1]"},
    {"light 0 0 0 1 1 1 1", 1, "extra value"},
    {"\x01\x02\xff\xfe garbage", 1, "unknown keyword '?\?\?\?'"},
    {"# ok\r\nsize 64 64\r\nbogus\r\n", 3, "unknown keyword 'bogus'"}, // CRLF counts lines too
    {"# ok\rsize 64 64\rbogus\r", 3, "unknown keyword 'bogus'"}, // and CR alone (classic Mac OS)
    {"material m\r\r\nsphere 0 0 -5 1 n\r\n", 3, "material 'n' is not defined"}, // CR, CR LF
    // an unknown keyword says what the mistake may be
    {"Sphere 0 0 -5 1 m", 1,
     "unknown keyword 'Sphere' (keywords are written in lower case: 'sphere')"},
    {"tirangle 0 0 0 1 0 0 0 1 0 m", 1, "unknown keyword 'tirangle' (did you mean 'triangle'?)"},
    {"backgroud 0 0 0", 1, "unknown keyword 'backgroud' (did you mean 'background'?)"},
    {"ligth 1 1 1", 1, "unknown keyword 'ligth' (did you mean 'light'?)"},
    {"# a model\nv 0 0 0\nf 1 1 1\n", 2, "unknown keyword 'v' (this looks like a Wavefront OBJ"},
    {"o Cube\nv 0 0 0\n", 1, "unknown keyword 'o' (this looks like a Wavefront OBJ"},
    {"\x89PNG\r\n", 1, "unknown keyword '?PNG' (it holds bytes that are not UTF-8 text"},
    {"material m diffuse 1.0000001 0 0", 1, "diffuse 1.0000001 0 0: each component"},
};

static void TestSceneErrors() {
    for (const BadScene &bad : kBadScenes) {
        Scene scene;
        std::string error;
        bool ok = ParseSceneText(bad.text, "s.scene", &scene, &error);
        std::string expected = "s.scene:" + std::to_string(bad.line) + ": ";
        CHECK(!ok && error.compare(0, expected.size(), expected) == 0 &&
                  error.find(bad.message) != std::string::npos,
              "scene `" + std::string(bad.text).substr(0, 40) + "`: error at line " +
                  std::to_string(bad.line) + " mentioning \"" + bad.message + "\" (got: " + error +
                  ")");
    }
    Scene scene;
    std::string error;
    // Where no hint fits, the message alone: a mistyped `sphere` is not taken for OBJ's `s`, nor
    // a stray `f` for a face; a Latin-1 line is text, but not UTF-8, and is told so
    const struct {
        const char *text, *message;
    } unknown[] = {
        {"bogus 1\n", "s.scene:1: unknown keyword 'bogus'"},
        {"s 0 0 -5 1 m\n", "s.scene:1: unknown keyword 's'"},
        {"f 1 2 3\n", "s.scene:1: unknown keyword 'f'"},
        {"sph\xe8re 0 0 -5 1 m\n", "s.scene:1: unknown keyword 'sph?re' (it holds bytes that are "
                                   "not UTF-8 text: a scene file is text, not an image)"},
        // UTF-8 is shown as written, 40 characters at most (not bytes: no character is cut)
        {"sph\xc3\xa8re 0 0 -5 1 m\n",
         "s.scene:1: unknown keyword 'sph\xc3\xa8re' (did you mean 'sphere'?)"},
        {"spear 0 0 -5 1 m\n", "s.scene:1: unknown keyword 'spear'"}, // (three slips from sphere)
        {"mast 1\n", "s.scene:1: unknown keyword 'mast'"}, // (two slips from mesh: a word of four
                                                           // letters may be one away)
        {"spher\x01 0 0 -5 1 m\n", "s.scene:1: unknown keyword 'spher?' (it holds a control "
                                   "character, shown as '?': an invisible character typed or "
                                   "pasted into the file)"},
        {"sphere\xe2\x80\xae 0 0 -5 1 m\n", "s.scene:1: unknown keyword 'sphere?\?\?' (it holds a "
                                            "control character, shown as '?': an invisible "
                                            "character typed or pasted into the file)"},
        {"\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83"
         "\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83"
         "\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83"
         "\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83"
         "\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83"
         "\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83\xe7\x90\x83"
         "\xe7\x90\x83\n", // 43 of the character U+7403
         nullptr},
    };
    std::string forty; // the 43-character keyword's message: its first 40, then "..."
    for (int k = 0; k < 40; k++)
        forty += "\xe7\x90\x83";
    std::string cut = "s.scene:1: unknown keyword '" + forty + "...'";
    for (const auto &u : unknown) {
        std::string message = u.message ? u.message : cut;
        CHECK(!ParseSceneText(u.text, "s.scene", &scene, &error) && error == message,
              "`" + PrintableLine(u.text) + "`: " + message + " (got: " + error + ")");
    }
}

// Comments, tabs, CRLF, signs and scientific notation read as the plain form does.
static void TestSceneVariations() {
    const char *text = "  # a comment line\r\n"
                       "size\t64   32\r\n"
                       "\r\n"
                       "ambient +2e-1   # the floor\r\n"
                       "material m diffuse .5 1. 0 specular 0.25 1E1 mirror 0.5\n"
                       "\tsphere 1e0 -2 +3 5e-1 m\n"
                       "light 1 2 3\n"
                       "shading phong\n";
    Scene scene;
    std::string error;
    bool ok = ParseSceneText(text, "v.scene", &scene, &error);
    CHECK(ok, "comments, tabs, CRLF and scientific notation are accepted (" + error + ")");
    if (!ok)
        return;
    CHECK(scene.width == 64 && scene.height == 32, "size 64 32 read through a tab");
    Scene crs;
    CHECK(ParseSceneText("material m\r\r\nsphere 0 0 -5 1 m\r\n", "c.scene", &crs, &error) &&
              crs.materials.size() == 1 && crs.materials[0].name == "m" && crs.spheres.size() == 1,
          "a doubled CR (an editor's slip) ends a line: material 'm', not 'm\\r' (" + error + ")");
    Scene warned;
    CHECK(ParseSceneText("material m specular 0.5 10 ambient 1 1 1 emit 1 1 1\n"
                         "triangle 0 0 0 1 1 1 2 2 2 m\ntriangle 0 0 0 1 0 0 0 1 0 m\n",
                         "w.scene", &warned, &error) &&
              warned.warnings.size() == 4 &&
              warned.warnings[0].find("w.scene:2: warning: this triangle has no area") == 0 &&
              warned.warnings[1] == "w.scene:1: warning: material m: ambient is used only by "
                                    "shading phong" &&
              warned.warnings[3].find("emit is used only by shading path") != std::string::npos &&
              warned.triangles.size() == 2,
          "a triangle without area and properties the floor shading does not use: warnings "
          "with their lines, and the scene read as written");
    // Area is judged at any scale, as the intersection judges it: corners of 1e-200 (float:
    // 1e-30), whose plain cross product underflows to 0, have an area; in double, edges of 2e308
    // do not
    const char *e = sizeof(real) == sizeof(double) ? "e-200" : "e-30";
    std::string corners = std::string("-1") + e + " -1" + e + " -5" + e + " 1" + e + " -1" + e +
                          " -5" + e + " 0 1" + e + " -5" + e;
    Scene tiny;
    CHECK(ParseSceneText("ambient 0e-999\nbackground 0.000 -0.0e-400 0\n", "z.scene", &tiny,
                         &error) &&
              tiny.ambientLight == 0,
          "zeros written with an exponent are 0, not numbers too small (" + error + ")");
    CHECK(ParseSceneText("material m\ntriangle " + corners + " m\n", "t.scene", &tiny, &error) &&
              tiny.warnings.empty(),
          "a triangle 1" + std::string(e) + " across: no warning (rays do hit it)");
    if (sizeof(real) == sizeof(double))
        CHECK(ParseSceneText("material m\ntriangle -1e308 0 0 1e308 0 0 0 1e308 0 m\n", "t.scene",
                             &tiny, &error) &&
                  tiny.warnings.size() == 1 &&
                  tiny.warnings[0].find("t.scene:2: warning: this triangle has edges beyond") == 0,
              "a triangle whose edges overflow: warned of, as such");
    // The same, whichever corner comes first: here b - a and c - a are finite and c - b is not
    if (sizeof(real) == sizeof(double))
        for (const char *t : {"-1.7e308 -1 -5  1.7e308 -1 -5  0 1.7e308 -5",
                              "0 1.7e308 -5  -1.7e308 -1 -5  1.7e308 -1 -5",
                              "1.7e308 -1 -5  0 1.7e308 -5  -1.7e308 -1 -5"}) {
            Scene huge;
            bool read = ParseSceneText("material m\ntriangle " + std::string(t) + " m\n", "t.scene",
                                       &huge, &error);
            SceneLayout layout;
            CommitScene(&huge, LAYOUT_AUTO, 2, &layout);
            RayHit hit;
            Ray ray = {{0, 0, 0}, {0, 0, -1}};
            CHECK(read && huge.warnings.size() == 1 &&
                      huge.warnings[0].find("edges beyond the range") != std::string::npos &&
                      !FindNearestHit(&huge, kRobustMethods, &ray, 0, kInfinity, &hit),
                  std::string("triangle ") + t +
                      ": edges beyond the range of numbers, whichever "
                      "corner comes first: warned of, and no ray hits it");
        }
    CHECK(
        ParseSceneText("shading phong\nmaterial m specular 0.5 10\n", "w.scene", &warned, &error) &&
            warned.warnings.empty(),
        "specular under shading phong: no warning");
    Scene square;
    CHECK(ParseSceneText("size 100\n", "s.scene", &square, &error) && square.width == 100 &&
              square.height == 100,
          "size 100: a square image of 100 x 100, as --size 100 makes one");
    CHECK_NEAR(scene.ambientLight, 0.2, kRelTol, "ambient +2e-1 is 0.2");
    const Material &m = scene.materials[0];
    CHECK(m.diffuse.x == real(0.5) && m.diffuse.y == 1 && m.diffuse.z == 0 &&
              m.specular == real(0.25) && m.shininess == 10 && m.mirror == real(0.5) &&
              m.ambient.x == real(0.5),
          "material: .5, 1., 1E1 read; ambient defaults to the diffuse colour");
    CHECK(scene.spheres.size() == 1 && scene.spheres[0].center.x == 1 &&
              scene.spheres[0].center.z == 3 && scene.spheres[0].radius == real(0.5),
          "sphere 1e0 -2 +3 5e-1 read as centre (1, -2, 3), radius 0.5");
    CHECK(scene.lights.size() == 1 && scene.lights[0].intensity.x == 1,
          "a light without a colour is white");
    CHECK(scene.shading == SHADING_PHONG, "shading phong");

    // An empty file is a valid scene: the defaults of the README's scene format
    ok = ParseSceneText("", "e.scene", &scene, &error);
    CHECK(ok && scene.width == 512 && scene.camera.kind == CAMERA_PERSPECTIVE &&
              scene.camera.perspective.distance == 2 && scene.camera.perspective.screenWidth == 2 &&
              scene.depth == 10 && scene.ambientLight == real(0.2) && scene.spheres.empty(),
          "an empty scene file: 512 x 512, camera perspective 0 0 0 2 2, depth 10");
}

static Ray CameraRay(const char *text, int i, int j) {
    Scene scene;
    std::string error;
    bool ok = ParseSceneText(text, "c.scene", &scene, &error);
    CHECK(ok, std::string("camera scene reads: ") + error);
    RenderSettings settings = TestSettings(&scene);
    Ray ray;
    GetCameraRay(&settings.camera, settings.width, settings.height, SamplePosition(i, j, 0, 1),
                 &ray);
    return ray;
}

static void CheckDir(const Ray &ray, vec3 expected, real tolerance, const std::string &what) {
    vec3 d = ray.dir;
    CHECK(std::fabs(d.x - expected.x) <= tolerance && std::fabs(d.y - expected.y) <= tolerance &&
              std::fabs(d.z - expected.z) <= tolerance,
          what + ": direction (" + std::to_string(d.x) + ", " + std::to_string(d.y) + ", " +
              std::to_string(d.z) + ")");
}

static void TestCameras() {
    // The second handout's screen with l = (-1, -1, -2), h = (2, 0, 0), v = (0, 2, 0) is the
    // assignment camera: pixel (0, 0) of 512 goes through l + (0.5/512) h + (511.5/512) v =
    // (-0.998046875, 0.998046875, -2), exactly as GetRay's
    const char *screen = "camera screen 0 0 0  -1 -1 -2  2 0 0  0 2 0";
    CheckDir(CameraRay(screen, 0, 0), {-0.998046875, 0.998046875, -2}, 0,
             "screen camera, top-left pixel");
    CheckDir(CameraRay(screen, 511, 511), {0.998046875, -0.998046875, -2}, 0,
             "screen camera, bottom-right pixel");
    // The same screen for a 4 x 2 image: pixel (3, 1) is right and bottom: across 3.5/4,
    // up (2 - 1.5)/2 = 0.25: (-1 + 1.75, -1 + 0.5, -2)
    std::string wide = std::string("size 4 2\n") + screen;
    CheckDir(CameraRay(wide.c_str(), 3, 1), {0.75, -0.5, -2}, 0, "screen camera, 4 x 2 image");

    // lookat from the origin toward -z, fov 90 (screen 1 away, tan 45 = 1 high above centre),
    // 2 x 2 image: pixel (0, 0)'s centre is a quarter across and three quarters up:
    // (-1 + 0.5, -1 + 1.5, -1) = (-0.5, 0.5, -1)
    const char *look = "size 2 2\ncamera lookat 0 0 0  0 0 -1  0 1 0  90";
    CheckDir(CameraRay(look, 0, 0), {-0.5, 0.5, -1}, 4 * kRelTol, "lookat, fov 90, pixel (0, 0)");
    // A 4 x 2 image widens the screen to 4 units: pixel (0, 0) at (-2 + 0.5, 0.5, -1)
    const char *lookWide = "size 4 2\ncamera lookat 0 0 0  0 0 -1  0 1 0  90";
    CheckDir(CameraRay(lookWide, 0, 0), {-1.5, 0.5, -1}, 4 * kRelTol,
             "lookat 4 x 2 keeps square pixels");
    // From (5, 0, 0) toward the origin, a 1 x 1 image: the only ray goes straight at the target
    Ray centre = CameraRay("size 1 1\ncamera lookat 5 0 0  0 0 0  0 1 0  30", 0, 0);
    CHECK(centre.origin.x == 5, "lookat: rays start at `from`");
    CheckDir(centre, {-1, 0, 0}, 4 * kRelTol, "lookat from +x: the centre ray points at `to`");

    // The handout's perspective camera with its eye moved: pixel (0, 0) of 512, eye (1, 2, 3)
    CheckDir(CameraRay("camera perspective 1 2 3 2 2", 0, 0), {-0.998046875, 0.998046875, -2}, 0,
             "perspective camera, eye moved: same direction");
}

static bool SameScene(const Scene &a, const Scene &b) {
    bool same = a.width == b.width && a.height == b.height && a.depth == b.depth &&
                a.ambientLight == b.ambientLight && a.shading == b.shading &&
                a.materials.size() == b.materials.size() && a.spheres.size() == b.spheres.size() &&
                a.triangles.size() == b.triangles.size() && a.lights.size() == b.lights.size();
    for (size_t k = 0; same && k < a.triangles.size(); k++) {
        const Triangle &s = a.triangles[k], &t = b.triangles[k];
        same = s.a.x == t.a.x && s.a.y == t.a.y && s.a.z == t.a.z && s.b.x == t.b.x &&
               s.b.y == t.b.y && s.b.z == t.b.z && s.c.x == t.c.x && s.c.y == t.c.y &&
               s.c.z == t.c.z && s.material == t.material;
    }
    return same;
}

// scenes/reference.scene and scenes/test.scene hold the built-in scenes: the same data, and the
// same bytes when rendered.
static void TestBuiltInSceneFiles() {
    const char *files[] = {"scenes/reference.scene", "scenes/test.scene"};
    for (int k = 0; k < 2; k++) {
        Scene builtIn, fromFile;
        k == 0 ? BuildDefaultScene(&builtIn) : BuildTestScene(&builtIn);
        std::string error;
        bool ok = ReadSceneFile(files[k], &fromFile, &error);
        CHECK(ok && SameScene(builtIn, fromFile),
              std::string(files[k]) + " holds the built-in scene (" + error + ")");
        if (!ok)
            continue;
        RenderSettings a = TestSettings(&builtIn), b = TestSettings(&fromFile);
        a.threads = b.threads = 2;
        if (k == 1) { // the test scene at a quarter of the size keeps the tests quick
            a.width = a.height = b.width = b.height = 128;
            PlanRender(&builtIn, &a);
            PlanRender(&fromFile, &b);
        }
        Image imageA, imageB;
        RayStats stats = {};
        Render(&builtIn, &a, &imageA, &stats);
        Render(&fromFile, &b, &imageB, &stats);
        CHECK(imageA.pixels == imageB.pixels,
              std::string(files[k]) + " renders the built-in scene's bytes");
    }
}

// Every scene in scenes/ reads without error (they are the students' starting points).
static void TestGalleryScenesRead() {
    DIR *dir = opendir("scenes");
    CHECK(dir != nullptr, "the scenes/ directory exists");
    if (!dir)
        return;
    int count = 0;
    while (dirent *entry = readdir(dir)) {
        std::string name = entry->d_name;
        if (name.size() < 7 || name.compare(name.size() - 6, 6, ".scene") != 0)
            continue;
        Scene scene;
        std::string error;
        CHECK(ReadSceneFile(("scenes/" + name).c_str(), &scene, &error),
              "scenes/" + name + " reads (" + error + ")");
        count++;
    }
    closedir(dir);
    CHECK(count >= 4, "scenes/ holds the built-in scenes and starting points");
}

void TestSceneFiles() {
    TestSceneErrors();
    TestSceneVariations();
    TestCameras();
    TestBuiltInSceneFiles();
    TestGalleryScenesRead();
}
