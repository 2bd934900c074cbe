// tests/test_mesh.cpp -- `mesh PATH MATERIAL [transform words]`: OBJ files read as predicted.
//
// Each face's triangles in fan order, each index form, each error at its line, each transform
// word moving a vertex to the place worked out by hand, and each path found beside its scene
// file. (Rays at meshes and the program's refusals: test_mesh_rays.cpp.)
#include "../app/app.h"
#include "test.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sys/stat.h>

// Reads OBJ text as the file m.obj (at most maxTriangles triangles, material 0).
static bool ReadObjText(const std::string &text, const std::vector<MeshStep> &steps,
                        std::vector<Triangle> *triangles, std::string *error,
                        size_t maxTriangles = 1000) {
    static const char kNothing[] = "\n"; // fmemopen needs at least one byte
    FILE *file = text.empty() ? fmemopen((void *)kNothing, 1, "r")
                              : fmemopen((void *)text.data(), text.size(), "r");
    if (!file)
        return false;
    triangles->clear();
    bool read = ReadObj(file, "m.obj", 0, steps, maxTriangles, "m.scene:1", triangles, error);
    fclose(file);
    return read;
}

// Vertex k (from 1) of kFive is (k, 2k, -k): a triangle's corners tell which vertices made it.
static const char *kFive = "v 1 2 -1\nv 2 4 -2\nv 3 6 -3\nv 4 8 -4\nv 5 10 -5\n";

static bool IsVertex(vec3 p, int k) { return p.x == k && p.y == 2 * k && p.z == -k; }

// The triangles, as the vertex numbers of their corners: "1 2 3, 1 3 4".
static std::string Corners(const std::vector<Triangle> &triangles) {
    std::string s;
    for (const Triangle &t : triangles) {
        bool known =
            IsVertex(t.a, (int)t.a.x) && IsVertex(t.b, (int)t.b.x) && IsVertex(t.c, (int)t.c.x);
        s += (s.empty() ? "" : ", ") +
             (known ? std::to_string((int)t.a.x) + " " + std::to_string((int)t.b.x) + " " +
                          std::to_string((int)t.c.x)
                    : std::string("?"));
    }
    return s;
}

struct ObjCase {
    const char *name;
    std::string text;
    const char *corners; // the triangles predicted, as Corners writes them
};

static void TestObjFaces() {
    std::string five = kFive;
    const ObjCase cases[] = {
        {"a triangle", five + "f 1 2 3\n", "1 2 3"},
        {"a quad: fan from corner 1", five + "f 1 2 3 4\n", "1 2 3, 1 3 4"},
        {"a pentagon: three fan triangles", five + "f 2 3 4 5 1\n", "2 3 4, 2 4 5, 2 5 1"},
        {"negative indices count back from the last vertex", five + "f -5 -4 -3\nf -1 -3 -2\n",
         "1 2 3, 5 3 4"},
        {"negative indices: relative to the vertices read so far",
         "v 1 2 -1\nv 2 4 -2\nv 3 6 -3\nf -3 -2 -1\nv 4 8 -4\nf -3 -2 -1\n", "1 2 3, 2 3 4"},
        {"v/vt, v//vn and v/vt/vn",
         five + "f 1/1 2/2 3/3\nf 1//7 2//8 3//9\nf 3/1/1 4/2/2 5/-1/3\n", "1 2 3, 1 2 3, 3 4 5"},
        {"indices with leading zeros, and with a sign", five + "f 000000000001 +2 -000003\n",
         "1 2 3"},
        {"vt and vn indices are read past, whatever their size",
         five + "f 1/99999999999 2//-99999999999 3/+1/0\n", "1 2 3"},
        {"degenerate faces are kept", five + "f 1 1 2\nf 1 2 3 3\n", "1 1 2, 1 2 3, 1 3 3"},
        {"no newline after the last face", five + "f 1 2 3", "1 2 3"},
        {"comments, blank lines and tabs",
         "# made by hand\n\n" + five + "# f 1 2 3 is not a face\n\tf 3 4 5 # a face\n", "3 4 5"},
        {"CRLF line endings", "v 1 2 -1\r\nv 2 4 -2\r\nv 3 6 -3\r\nf 1 2 3\r\n", "1 2 3"},
        {"CR line endings (classic Mac OS)", "v 1 2 -1\rv 2 4 -2\rv 3 6 -3\rf 1 2 3\r", "1 2 3"},
        {"vt vn g o s usemtl mtllib l p and others are skipped",
         "mtllib a.mtl\no thing\ng part\n" + five +
             "vt 0.5 0.5\nvn 0 0 1\ns 1\nusemtl red\nl 1 2\np 3\ncurv 0 1 2\nf 1 2 3\n",
         "1 2 3"},
        {"v with w, and v with vertex colours",
         "v 1 2 -1 1\nv 2 4 -2 0.5 0.5 0.5\nv 3 6 -3\nf 1 2 3\n", "1 2 3"},
    };
    for (const ObjCase &c : cases) {
        std::vector<Triangle> triangles;
        std::string error;
        bool read = ReadObjText(c.text, {}, &triangles, &error);
        CHECK(read && Corners(triangles) == c.corners,
              std::string(c.name) + ": triangles " + c.corners + " (got " + Corners(triangles) +
                  (read ? "" : "; error " + error) + ")");
    }
}

struct BadObj {
    std::string text;
    int line;            // the line the error must name
    const char *message; // a piece of the message
};

static void TestObjErrors() {
    std::string three = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const BadObj cases[] = {
        {three + "f 1 2 4\n", 4, "vertex index 4 is out of range (3 vertices read so far"},
        {three + "f 0 1 2\n", 4, "vertex index 0"},
        {three + "f -4 1 2\n", 4, "vertex index -4 is out of range"},
        {three + "f 1 2 99999999999\n", 4, "vertex index 99999999999 is out of range (3 vertices"},
        {three + "f -99999999999/1 1 2\n", 4, "vertex index -99999999999 is out of range"},
        {three + "f 1 2 +-3\n", 4, "bad corner '+-3'"},
        {"f 1 2 3\n" + three, 1, "vertex index 1 is out of range (0 vertices"},
        {"# a cube\r\n\r\n" + three + "vn 0 0 1\r\nf 1 2 3\r\nf 1 2 9\r\n", 8, "index 9"},
        {three + "f 1 2\n", 4, "at least 3 corners, this one has 2"},
        {three + "f\n", 4, "at least 3 corners"},
        {"v 1 2\n", 1, "v: expected 3 numbers"},
        {"v 0,0,0\n", 1, "v: not a decimal number: '0,0,0'"}, // (not "found 1")
        {"v 1 2 nan\n", 1, "not a decimal number: 'nan'"},
        {"v 1 2 0x10\n", 1, "not a decimal number"},
        {"v 1 2 3e999\n", 1, "out of range"},
        {"v 1 2 3 w\n", 1, "not a decimal number: 'w'"},
        {three + "f 1 2 x\n", 4, "bad corner 'x'"},
        {three + "f 1 2/a 3\n", 4, "bad corner '2/a'"},
        {three + "f 1 2/1/1/1 3\n", 4, "bad corner '2/1/1/1'"},
        {three + "f 1.5 2 3\n", 4, "bad corner '1.5'"},
        {"", 1, "no faces"},
        // OBJ skips what it does not know, capitals too, and the message says so
        {"V 0 0 0\nV 1 0 0\nV 0 1 0\nF 1 2 3\n", 4,
         "no faces in this file ('f' statements): nothing to draw (lines that begin 'V' or 'F' "
         "were skipped: OBJ is lower case)"},
        {"v 0 0 0\nv 1 0 0\nV 0 1 0\nf 1 2 3\n", 4,
         "vertex index 3 is out of range (2 vertices read so far; the first is 1) (lines that "
         "begin 'V' or 'F' were skipped"},
        {three, 3, "no faces"},
        {three + std::string("v 1 1\0 0\n", 9), 4, "NUL byte"},
        // what old Windows exporters write for NaN and infinity: a number refused as one, with
        // why, not a comment cutting the line short ("found 1 number")
        {"v 1.#QNAN 1 0\n", 1, "v: not a decimal number: '1.#QNAN' (old Windows programs"},
        {"v 1 -1.#IND 0\n", 1, "'-1.#IND' (old Windows"},
        {"v 1 1 1.#INF\n", 1, "'1.#INF' (old Windows"},
        // a line continued with a backslash: said so, not "bad corner '\'"
        {three + "f 1 2 \\\n 3\n", 4,
         "a line that ends in '\\' goes on in the next one in some "
         "OBJ files; rt does not join lines"},
        {std::string("\xFF\xFEv\0 \0", 6), 1,
         "UTF-16 text (the file begins with its byte-order "
         "mark): rt reads ASCII or UTF-8"},
        {std::string("v\0 \0", 4), 1, "NUL byte: this is not a text file (or it is UTF-16"},
    };
    for (const BadObj &bad : cases) {
        std::vector<Triangle> triangles;
        std::string error, expected = "m.obj:" + std::to_string(bad.line) + ": ";
        bool read = ReadObjText(bad.text, {}, &triangles, &error);
        CHECK(!read && error.compare(0, expected.size(), expected) == 0 &&
                  error.find(bad.message) != std::string::npos,
              "OBJ `" + bad.text.substr(0, 40) + "`: error at line " + std::to_string(bad.line) +
                  " mentioning \"" + bad.message + "\" (got: " + error + ")");
    }
    // The hint about capitals goes only with the errors it explains, not with a bad corner
    std::vector<Triangle> none;
    std::string why;
    ReadObjText("F 1 2 3\n" + three + "f 1 2 x\n", {}, &none, &why);
    CHECK(why == "m.obj:5: f: bad corner 'x' (expected v, v/vt, v//vn or v/vt/vn)",
          "a bad corner after an 'F' line: no word of capitals (got: " + why + ")");
    // The shape limit is kept inside a mesh: 2 triangles allowed, a quad and a triangle given
    std::vector<Triangle> triangles;
    std::string error;
    bool read = ReadObjText(three + "v 1 1 0\nf 1 2 3 4\nf 1 2 3\n", {}, &triangles, &error, 2);
    CHECK(!read && error == "m.obj:6: too many triangles: with the mesh statement at m.scene:1, "
                            "rt's limit of shapes in a scene is reached",
          "a third triangle beyond a limit of 2: refused at line 6, the mesh statement named "
          "(got: " +
              error + ")");
    // The limit counts this mesh's triangles, not those already in the scene: after 3 triangles
    // of an earlier mesh, 2 more are allowed (a quad), and a third is refused
    for (bool third : {false, true}) {
        std::string text = three + "v 1 1 0\nf 1 2 3 4\n" + (third ? "f 1 2 3\n" : "");
        FILE *file = fmemopen((void *)text.data(), text.size(), "r");
        if (!file)
            continue;
        std::vector<Triangle> scene(3, Triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0});
        read = ReadObj(file, "m.obj", 0, {}, 2, "m.scene:1", &scene, &error);
        fclose(file);
        CHECK(third ? !read && error.rfind("m.obj:6: too many triangles", 0) == 0
                    : read && scene.size() == 5,
              std::string(third ? "a third triangle of a second mesh: refused at line 6"
                                : "a quad after another mesh's 3 triangles: read, 5 in all") +
                  " (got: " + (read ? "read, " + std::to_string(scene.size()) : error) + ")");
    }
}

// The vertex (1, 2, 3) moved by the transform words `words`.
static vec3 Moved(const std::string &words, bool *ok) {
    std::vector<std::string> tokens;
    std::vector<MeshStep> steps;
    std::string error;
    Tokenize(words, &tokens);
    *ok = ParseMeshTransform(tokens, 0, &steps, &error);
    return TransformVertex(steps, {1, 2, 3});
}

struct TransformCase {
    const char *words;
    vec3 expected; // (1, 2, 3) moved by hand
};

static void TestTransformWords() {
    // Rotations turn counter-clockwise seen from the axis's positive end: about x, y -> z; about
    // y, z -> x; about z, x -> y. Multiples of 90 degrees are exact: no rounding, tolerance 0
    const TransformCase exact[] = {
        {"", {1, 2, 3}},
        {"scale 2", {2, 4, 6}},
        {"scale 0.5", {0.5, 1, 1.5}},
        {"translate 1 -2 0.5", {2, 0, 3.5}},
        {"rotate x 90", {1, -3, 2}},
        {"rotate y 90", {3, 2, -1}},
        {"rotate z 90", {-2, 1, 3}},
        {"rotate z -90", {2, -1, 3}},
        {"rotate z 450", {-2, 1, 3}},
        {"rotate y 180", {-1, 2, -3}},
        {"rotate x 270", {1, 3, -2}},
        {"rotate x -1080", {1, 2, 3}},
        {"scale 2 translate 1 0 0", {3, 4, 6}}, // in the order written
        {"translate 1 0 0 scale 2", {4, 4, 6}},
        {"rotate z 90 rotate z 90", {-1, -2, 3}},
    };
    for (const TransformCase &c : exact) {
        bool ok;
        vec3 p = Moved(c.words, &ok);
        CHECK(ok && p.x == c.expected.x && p.y == c.expected.y && p.z == c.expected.z,
              std::string("`") + c.words + "` moves (1, 2, 3) to (" + std::to_string(c.expected.x) +
                  ", " + std::to_string(c.expected.y) + ", " + std::to_string(c.expected.z) +
                  ") exactly (got " + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " +
                  std::to_string(p.z) + ")");
    }
    // 45 degrees about z: (1, 2) turns to ((1 - 2) / sqrt 2, (1 + 2) / sqrt 2)
    bool ok;
    vec3 p = Moved("rotate z 45", &ok);
    CHECK(ok, "rotate z 45 reads");
    CHECK_NEAR(p.x, -1 / std::sqrt(2.0), 4 * kRelTol, "rotate z 45: x = -1/sqrt(2)");
    CHECK_NEAR(p.y, 3 / std::sqrt(2.0), 4 * kRelTol, "rotate z 45: y = 3/sqrt(2)");
    CHECK(p.z == 3, "rotate z 45 keeps z");

    const char *bad[] = {"scale 0",  "scale -1",  "scale nan",     "scale",  "rotate q 90",
                         "rotate x", "rotate 90", "translate 1 2", "spin 3", "scale 2 x"};
    for (const char *words : bad) {
        Moved(words, &ok);
        CHECK(!ok, std::string("`") + words + "` is refused");
    }
    std::vector<MeshStep> steps;
    std::string error;
    CHECK(!ParseMeshTransform({"rotate", "x"}, 0, &steps, &error) &&
              error == "rotate: expected an axis and an angle in degrees (rotate y 30)",
          "`rotate x` says what rotate expects: " + error);
}

// A vertex the transform words move beyond the range of numbers is refused: half the largest
// number, scaled by 4, is infinite (in double and in float).
static void TestTransformOverflow() {
    char text[80];
    snprintf(text, sizeof text, "v %.9g 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n",
             (double)std::numeric_limits<real>::max() / 2);
    std::vector<std::string> tokens = {"scale", "4"};
    std::vector<MeshStep> steps;
    std::vector<Triangle> triangles;
    std::string error;
    bool parsed = ParseMeshTransform(tokens, 0, &steps, &error);
    CHECK(parsed && !ReadObjText(text, steps, &triangles, &error) &&
              error.rfind("m.obj:1: v: the transform words of the mesh statement at m.scene:1 move "
                          "this vertex beyond",
                          0) == 0,
          "a vertex scaled beyond the largest number: refused at its line (" + error + ")");
    steps[0].factor = 1;
    CHECK(ReadObjText(text, steps, &triangles, &error), "the same vertex unscaled reads");
}

// A scene file in dir holding `text`, read; *error on failure.
static bool ReadScene(const std::string &path, const std::string &text, Scene *scene,
                      std::string *error) {
    std::ofstream(path, std::ios::binary) << text;
    return ReadSceneFile(path.c_str(), scene, error);
}

static const bool kDouble = sizeof(real) == sizeof(double);

// The unit square z = 0 as a quad; its outward side, (b - a) x (c - a), faces +z. The fan makes
// triangle 0 below the diagonal y = x and triangle 1 above it.
static const char *kQuad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";

// PATH is found beside the scene file, and its triangles come in scene order.
static void TestMeshPaths(const std::string &dir) {
    CHECK(MeshPath("scenes/a.scene", "m.obj") == "scenes/m.obj" &&
              MeshPath("a.scene", "m.obj") == "m.obj" &&
              MeshPath("x/y/a.scene", "../m.obj") == "x/y/../m.obj" &&
              MeshPath("x/a.scene", "/abs/m.obj") == "/abs/m.obj",
          "a mesh's path is relative to its scene file's folder; absolute paths as given");
    mkdir((dir + "/sub").c_str(), 0700);
    std::ofstream(dir + "/sub/quad.obj") << kQuad;
    Scene scene;
    std::string error, text =
                           "material m\nsphere 0 0 -9 1 m\ntriangle 0 0 -9  1 0 -9  0 1 -9 m\n"
                           "mesh quad.obj m translate 0 0 -5\ntriangle 0 0 -9  1 0 -9  0 1 -9 m\n";
    bool read = ReadScene(dir + "/sub/s.scene", text, &scene, &error);
    CHECK(read && scene.triangles.size() == 4 && scene.triangles[1].a.z == -5 &&
              scene.triangles[2].c.x == -1 && scene.triangles[3].a.z == -9 &&
              scene.meshFiles == std::vector<std::string>{dir + "/sub/quad.obj"},
          "sub/s.scene's `mesh quad.obj` reads sub/quad.obj: triangles 1 and 2 (" + error + ")");
}

// Mistakes in the statement, or a file that cannot be read, are reported at the statement's
// line; a mistake inside the file, at the file's own line.
static void TestMeshStatementErrors(const std::string &dir) {
    Scene scene;
    std::string error;
    bool read;
    const BadObj bad[] = {
        {"material m\nmesh quad.obj\n", 2, "expected a file name and a material name"},
        {"mesh quad.obj m\n", 1, "material 'm' is not defined"},
        {"material m\nmesh quad.obj m scale 0\n", 2, "mesh: scale must be > 0"},
        // Each factor a number, together below the normal numbers: the mesh would round to 0
        {"material m\nmesh quad.obj m scale 1e-30 scale 1e-30 rotate x 90 scale 1e-30 scale 1e-30 "
         "scale 1e-30 scale 1e-30 scale 1e-30 scale 1e-30 scale 1e-30 scale 1e-30 scale 1e-30\n",
         2, "mesh: scale: the mesh would shrink below the range of numbers"},
        {"material m\nmesh . m\n", 2, "not a regular file"},
        // `fit` refuses what `scale` refuses: a mesh whose longest side would be subnormal
        {std::string("material m\nmesh quad.obj m fit ") + (kDouble ? "1e-320" : "1e-40") + "\n", 2,
         "mesh: fit: the mesh would shrink below the range of numbers"},
        {std::string("material m\nmesh quad.obj m fit ") +
             (kDouble ? "1e-200 scale 1e-200" : "1e-20 scale 1e-20") + "\n",
         2, "mesh: fit and scale: the mesh would shrink below the range of numbers"},
        // A bad value names itself, and what the word wanted
        {"material m\nmesh quad.obj m scale 1 nan 1\n", 2,
         "mesh: scale needs 1 or 3 finite numbers (scale 2, or scale 1 -1 1 to mirror in y): not "
         "a decimal number: 'nan'"},
        {"material m\nmesh quad.obj m scale 2 3\n", 2,
         "mesh: scale needs 1 or 3 finite numbers (scale 2, or scale 1 -1 1 to mirror in y), "
         "found 2"},
        {"material m\nmesh quad.obj m translate 1 2 3 4\n", 2,
         "mesh: a number, '4', where a word was expected"},
        // A file name with a space is two tokens: the message says what may have happened
        {"material m\nmesh my quad.obj m\n", 2,
         "material 'quad.obj' is not defined (define it above; a mesh's file name may not "
         "contain spaces)"},
        {"material m\nmaterial quad.obj\nmesh my quad.obj m\n", 3,
         "unknown word 'm' (expected scale, rotate, translate, fit, flat or smooth; if the file "
         "name has a space, that is why: file names may not contain spaces)"},
    };
    for (const BadObj &b : bad) {
        std::string expected = dir + "/sub/s.scene:" + std::to_string(b.line) + ": ";
        read = ReadScene(dir + "/sub/s.scene", b.text, &scene, &error);
        CHECK(!read && error.compare(0, expected.size(), expected) == 0 &&
                  error.find(b.message) != std::string::npos,
              "scene `" + b.text + "`: error at the mesh statement's line (got: " + error + ")");
    }
    read = ReadScene(dir + "/sub/s.scene", "material m\nmesh nowhere.obj m\n", &scene, &error);
    CHECK(error ==
              dir + "/sub/s.scene:2: mesh: " + dir + "/sub/nowhere.obj: No such file or directory",
          "a missing mesh: the scene's file and line, the path as opened, the reason (" + error +
              ")");
    std::ofstream(dir + "/sub/bad.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 0\n";
    read = ReadScene(dir + "/sub/s.scene", "material m\nmesh bad.obj m\n", &scene, &error);
    CHECK(!read && error.rfind(dir + "/sub/bad.obj:5: f: vertex index 0", 0) == 0,
          "an error inside the mesh names the mesh file as opened and its line (" + error + ")");
}

void TestMesh() {
    std::string dir = MakeTestDir("mesh");
    if (dir.empty())
        return;
    TestObjFaces();
    TestObjErrors();
    TestTransformWords();
    TestTransformOverflow();
    TestMeshPaths(dir);
    TestMeshStatementErrors(dir);
    RemoveTestDir(dir);
}
