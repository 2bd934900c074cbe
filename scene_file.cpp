// scene_file.cpp -- reads scene files (docs/scene-format.md) into a Scene.
//
// One statement a line, `#` comments, tokens between spaces or tabs. Every statement is checked
// as it is read, and the first problem ends the read with "FILE:LINE: message", the way a
// compiler reports it. Nothing here prints; the caller decides what to do with the message.
#include "io.h"
#include "ray.h"
#include "robust.h"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sys/stat.h>

// A limit that keeps a hostile or mistaken file from exhausting memory, high enough for the
// scanned and exported models a mesh statement brings (a scanned statue of a million
// triangles). A triangle costs about 390 bytes while a render is prepared (measured: the
// Triangle, its block, its box and the BVH build's record), so 4 million shapes take about
// 1.6 GB at the peak: what a machine of 4 GB can still hold. (The files themselves are read a
// line at a time, and a line is at most kMaxLineLength long.)
static const size_t kMaxObjects = 4000000; // shapes, lights and materials together

// One statement being read, for its handler and for error messages.
struct Statement {
    const char *file;
    int line;
    std::vector<std::string> tokens;
};

// What has been declared once already (a second one is an error), and material properties that
// only one shading uses, by line, for a warning once the shading is known.
struct Declared {
    bool size, camera, ambient, shading, background, depth;
    std::vector<std::pair<int, std::string>> shadingOnly; // line, "NAME: KEY"
};

void InitScene(Scene *scene) {
    *scene = Scene();
    scene->width = scene->height = 512;
    scene->camera = Camera();
    scene->camera.kind = CAMERA_PERSPECTIVE;
    scene->camera.perspective = {{0, 0, 0}, 2, 2, 512, 512};
    scene->shading = SHADING_FLOOR;
    scene->ambient = real(0.2);
    scene->background = {0, 0, 0};
    scene->depth = 10;
}

static bool Fail(const Statement *st, const std::string &message, std::string *error) {
    *error = std::string(st->file) + ":" + std::to_string(st->line) + ": " + message;
    return false;
}

// Reads `count` numbers from tokens[first...]; the statement must hold exactly `total` tokens.
static bool Numbers(const Statement *st, size_t first, int count, size_t total, real *out,
                    std::string *error) {
    const std::string &keyword = st->tokens[0];
    if (st->tokens.size() < total)
        return Fail(st,
                    keyword + ": missing number(s): expected " + std::to_string(total - 1) +
                        " values after " + keyword,
                    error);
    if (st->tokens.size() > total)
        return Fail(st, keyword + ": extra value " + Shown(st->tokens[total]), error);
    for (int k = 0; k < count; k++) {
        std::string why;
        if (!ParseReal(st->tokens[first + k], &out[k], &why))
            return Fail(st, keyword + ": " + why, error);
    }
    return true;
}

static bool WholeNumber(const Statement *st, size_t index, int lo, int hi, int *out,
                        std::string *error) {
    std::string why;
    return ParseWholeNumber(st->tokens[index], lo, hi, out, &why) ||
           Fail(st, st->tokens[0] + ": " + why, error);
}

// A colour (diffuse, ambient, background): each component in [0, 1]; the message shows the
// numbers as read.
static bool CheckColor(const Statement *st, const std::string &what, color c, std::string *error) {
    if (c.x >= 0 && c.x <= 1 && c.y >= 0 && c.y <= 1 && c.z >= 0 && c.z <= 1)
        return true;
    char numbers[96];
    snprintf(numbers, sizeof numbers, "%g %g %g", (double)c.x, (double)c.y, (double)c.z);
    return Fail(st, what + " " + numbers + ": each component must be in [0, 1]", error);
}

// Light (a light's intensity, a material's emitted radiance): any finite amount >= 0, since a
// light may be brighter than the white a pixel can show.
static bool CheckLight(const Statement *st, const char *what, color c, std::string *error) {
    bool ok = c.x >= 0 && c.y >= 0 && c.z >= 0 && IsFinite(c);
    return ok || Fail(st, std::string(what) + ": each value must be a finite number >= 0", error);
}

// A statement that may appear once: marks it, or reports the second one.
static bool Once(const Statement *st, bool *seen, std::string *error) {
    if (*seen)
        return Fail(st, "second '" + st->tokens[0] + "' statement (only one is allowed)", error);
    *seen = true;
    return true;
}

static bool FindMaterial(const Statement *st, const Scene *scene, size_t index, int *material,
                         std::string *error) {
    const std::string &name = st->tokens[index];
    for (size_t k = 0; k < scene->materials.size(); k++) {
        if (scene->materials[k].name == name) {
            *material = (int)k;
            return true;
        }
    }
    return Fail(st,
                st->tokens[0] + ": material " + Shown(name) + " is not defined (define it above)",
                error);
}

// A shape statement holds `numbers` numbers and then the name of its material.
static bool ShapeArity(const Statement *st, size_t numbers, std::string *error) {
    if (st->tokens.size() < numbers + 2)
        return Fail(st,
                    st->tokens[0] + ": expected " + std::to_string(numbers) +
                        " numbers and a material name",
                    error);
    if (st->tokens.size() > numbers + 2)
        return Fail(st, st->tokens[0] + ": extra value " + Shown(st->tokens[numbers + 2]), error);
    return true;
}

static bool ReadSphere(const Statement *st, Scene *scene, std::string *error) {
    real v[4];
    Sphere s;
    if (!ShapeArity(st, 4, error) || !Numbers(st, 1, 4, 6, v, error) ||
        !FindMaterial(st, scene, 5, &s.material, error))
        return false;
    if (!(v[3] > 0))
        return Fail(st, "sphere: radius must be > 0", error);
    s.center = {v[0], v[1], v[2]};
    s.radius = v[3];
    scene->spheres.push_back(s);
    return true;
}

// Why no ray can hit triangle t, or null if one can. The intersection's own judgement
// (SetUpTriangle, at any scale: corners of 1e-200 have an area there, though their plain cross
// product underflows to 0).
static const char *Unhittable(const Triangle *t) {
    TriangleSetUp setUp;
    SetUpTriangle(t, &setUp);
    if (setUp.hasArea)
        return nullptr;
    bool edgesFinite = true; // in double, as SetUpTriangle works
    for (vec3 c : {t->b, t->c})
        edgesFinite = edgesFinite && std::isfinite((double)c.x - t->a.x) &&
                      std::isfinite((double)c.y - t->a.y) && std::isfinite((double)c.z - t->a.z);
    return edgesFinite ? "has no area (its corners are on one line)"
                       : "has edges beyond the range of numbers";
}

static bool ReadTriangle(const Statement *st, Scene *scene, std::string *error) {
    real v[9];
    Triangle t;
    if (!ShapeArity(st, 9, error) || !Numbers(st, 1, 9, 11, v, error) ||
        !FindMaterial(st, scene, 10, &t.material, error))
        return false;
    t.a = {v[0], v[1], v[2]};
    t.b = {v[3], v[4], v[5]};
    t.c = {v[6], v[7], v[8]};
    if (const char *why = Unhittable(&t))
        scene->warnings.push_back(std::string(st->file) + ":" + std::to_string(st->line) +
                                  ": warning: this triangle " + why + ", so no ray ever hits it");
    scene->triangles.push_back(t);
    return true;
}

static bool ReadLight(const Statement *st, Scene *scene, std::string *error) {
    real v[6] = {0, 0, 0, 1, 1, 1};
    size_t given = st->tokens.size() - 1, total = given <= 3 ? 4 : 7;
    if (given != 3 && given < 6) // (a light has a place, and may have a colour)
        return Fail(st,
                    "light: expected 3 numbers (X Y Z) or 6 (X Y Z R G B), got " +
                        std::to_string(given),
                    error);
    if (!Numbers(st, 1, (int)total - 1, total, v, error))
        return false;
    Light light = {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    if (!CheckLight(st, "light", light.intensity, error))
        return false;
    scene->lights.push_back(light);
    return true;
}

// `material NAME [diffuse R G B] [ambient R G B] [specular KS N] [mirror K] [glass IOR]
// [emit R G B]`
// One property of a material statement with its numbers v (already read): checked and set.
static bool SetMaterialProperty(const Statement *st, const std::string &key, const real *v,
                                Material *m, std::string *error) {
    if (key == "diffuse" || key == "ambient") {
        color c = {v[0], v[1], v[2]};
        if (!CheckColor(st, "material: " + key, c, error))
            return false;
        (key == "diffuse" ? m->diffuse : m->ambient) = c;
    } else if (key == "specular") {
        if (!(v[0] >= 0) || !(v[1] >= 0))
            return Fail(st, "material: specular KS and N must be >= 0", error);
        m->specular = v[0];
        m->shininess = v[1];
    } else if (key == "emit") {
        m->emit = {v[0], v[1], v[2]};
        return CheckLight(st, "material: emit", m->emit, error);
    } else if (key == "mirror") {
        if (!(v[0] >= 0 && v[0] <= 1))
            return Fail(st, "material: mirror fraction must be in [0, 1]", error);
        m->mirror = v[0];
    } else {
        if (!(v[0] > 0))
            return Fail(st, "material: index of refraction must be > 0", error);
        m->ior = v[0];
    }
    return true;
}

// A material's properties, how many numbers each takes, and their names for messages.
struct MaterialProperty {
    const char *key;
    int count;
    const char *names;
};
static const MaterialProperty *FindProperty(const std::string &key) {
    static const MaterialProperty kProperties[] = {{"diffuse", 3, "R G B"}, {"ambient", 3, "R G B"},
                                                   {"specular", 2, "KS N"}, {"mirror", 1, "K"},
                                                   {"glass", 1, "IOR"},     {"emit", 3, "R G B"}};
    for (const MaterialProperty &p : kProperties)
        if (key == p.key)
            return &p;
    return nullptr;
}

static bool ReadMaterial(const Statement *st, Scene *scene, std::string *error) {
    if (st->tokens.size() < 2)
        return Fail(st, "material: missing name", error);
    Material m = {st->tokens[1], {1, 1, 1}, {1, 1, 1}, 0, 1, 0, 0, {0, 0, 0}};
    for (const Material &other : scene->materials)
        if (other.name == m.name)
            return Fail(st, "material " + Shown(m.name) + " is defined twice", error);
    std::string keysSeen;
    for (size_t k = 2; k < st->tokens.size();) {
        const std::string &key = st->tokens[k];
        const MaterialProperty *p = FindProperty(key);
        if (!p)
            return Fail(st,
                        "material: unknown property " + Shown(key) +
                            " (expected diffuse, ambient, specular, mirror, glass or emit)",
                        error);
        if (keysSeen.find(" " + key + " ") != std::string::npos)
            return Fail(st, "material: '" + key + "' given twice", error);
        keysSeen += " " + key + " ";
        real v[3];
        int count = p->count;
        for (int j = 0; j < count; j++) {
            std::string why;
            if (k + 1 + j >= st->tokens.size())
                return Fail(st,
                            "material: '" + key + "' needs " + std::to_string(count) +
                                (count == 1 ? " number: " : " numbers: ") + p->names,
                            error);
            if (!ParseReal(st->tokens[k + 1 + j], &v[j], &why))
                return Fail(st, "material: " + key + ": " + why, error);
        }
        if (!SetMaterialProperty(st, key, v, &m, error))
            return false;
        k += 1 + count;
    }
    if (keysSeen.find(" ambient ") == std::string::npos) // ka defaults to kd
        m.ambient = m.diffuse;
    scene->materials.push_back(m);
    return true;
}

static bool ReadCamera(const Statement *st, Scene *scene, std::string *error) {
    if (st->tokens.size() < 2)
        return Fail(st, "camera: expected perspective, screen or lookat", error);
    const std::string &kind = st->tokens[1];
    real v[12];
    Camera c = Camera();
    if (kind == "perspective") {
        if (!Numbers(st, 2, 5, 7, v, error))
            return false;
        if (!(v[3] > 0) || !(v[4] > 0))
            return Fail(st, "camera perspective: distance and width must be > 0", error);
        c.kind = CAMERA_PERSPECTIVE;
        c.perspective = {{v[0], v[1], v[2]}, v[3], v[4], 0, 0};
    } else if (kind == "screen") {
        if (!Numbers(st, 2, 12, 14, v, error))
            return false;
        c.kind = CAMERA_SCREEN;
        c.eye = {v[0], v[1], v[2]};
        c.lowerLeft = {v[3], v[4], v[5]};
        c.horizontal = {v[6], v[7], v[8]};
        c.vertical = {v[9], v[10], v[11]};
        std::string why;
        if (!ScreenCameraIsValid(&c, &why))
            return Fail(st, "camera screen: " + why, error);
    } else if (kind == "lookat") {
        if (!Numbers(st, 2, 10, 12, v, error))
            return false;
        c.kind = CAMERA_LOOKAT;
        c.from = {v[0], v[1], v[2]};
        c.to = {v[3], v[4], v[5]};
        c.up = {v[6], v[7], v[8]};
        c.fovDegrees = v[9];
        Camera check;
        std::string why;
        if (!LookAtToScreen(&c, 1, 1, &check, &why))
            return Fail(st, "camera lookat: " + why, error);
    } else {
        return Fail(
            st, "camera: unknown kind " + Shown(kind) + " (expected perspective, screen or lookat)",
            error);
    }
    scene->camera = c;
    return true;
}

static size_t ObjectCount(const Scene *scene) {
    return scene->spheres.size() + scene->triangles.size() + scene->lights.size() +
           scene->materials.size();
}

// `mesh PATH MATERIAL [transform words]` (mesh.cpp), with what is left of the object limit.
static bool ReadMesh(const Statement *st, Scene *scene, std::string *error) {
    int material;
    if (st->tokens.size() < 3)
        return Fail(st, "mesh: expected a file name and a material name", error);
    if (!FindMaterial(st, scene, 2, &material, error)) {
        if (st->tokens.size() > 3) // perhaps a file name with a space, cut in two: "(... here)"
            error->insert(error->size() - 1, "; a mesh's file name may not contain spaces");
        return false;
    }
    return ReadMeshStatement(st->tokens, st->file, st->line, material,
                             kMaxObjects - ObjectCount(scene), scene, error);
}

// The statements that set one thing for the whole scene, each at most once.
// What an unknown keyword may say about the mistake: a keyword in capitals, a Wavefront OBJ file
// given where a scene file goes, or a file that is not text at all (a PNG image).
static std::string KeywordHint(const std::string &k) {
    static const char *const kKeywords[] = {"size",       "camera", "shading",  "ambient",
                                            "background", "depth",  "material", "sphere",
                                            "triangle",   "mesh",   "light"};
    static const char *const kObj[] = {"v", "vt", "vn", "f", "o", "g", "s", "usemtl", "mtllib"};
    std::string lower = k;
    for (char &c : lower)
        c = (char)std::tolower((unsigned char)c);
    for (const char *keyword : kKeywords)
        if (lower == keyword)
            return " (keywords are written in lower case: '" + lower + "')";
    for (const char *statement : kObj)
        if (k == statement)
            return " (this looks like an OBJ mesh: a scene file draws one with `mesh FILE "
                   "MATERIAL`)";
    if (!IsPrintableText(k))
        return " (this does not look like a text file: a scene file is text, a statement a line)";
    return "";
}

static bool ReadSetting(const Statement *st, Scene *scene, Declared *declared, std::string *error) {
    const std::string &k = st->tokens[0];
    real v[3];
    if (k == "size") { // `size W H`, or `size W` for a square image, as --size takes it
        size_t total = st->tokens.size() == 2 ? 2 : 3;
        if (!Once(st, &declared->size, error) || !Numbers(st, 1, 0, total, v, error) ||
            !WholeNumber(st, 1, 1, 16384, &scene->width, error))
            return false;
        scene->height = scene->width;
        return total == 2 || WholeNumber(st, 2, 1, 16384, &scene->height, error);
    }
    if (k == "depth")
        return Once(st, &declared->depth, error) && Numbers(st, 1, 0, 2, v, error) &&
               WholeNumber(st, 1, 1, 1000, &scene->depth, error);
    if (k == "ambient") {
        if (!Once(st, &declared->ambient, error) || !Numbers(st, 1, 1, 2, v, error))
            return false;
        scene->ambient = v[0];
        return (v[0] >= 0 && v[0] <= 1) ||
               Fail(st, "ambient " + st->tokens[1] + ": must be in [0, 1]", error);
    }
    if (k == "background") {
        if (!Once(st, &declared->background, error) || !Numbers(st, 1, 3, 4, v, error))
            return false;
        scene->background = {v[0], v[1], v[2]};
        return CheckColor(st, "background", scene->background, error);
    }
    if (k == "shading") {
        if (!Once(st, &declared->shading, error))
            return false;
        const std::string *word = st->tokens.size() == 2 ? &st->tokens[1] : nullptr;
        if (!word || (*word != "floor" && *word != "phong" && *word != "path"))
            return Fail(st, "shading: expected 'floor', 'phong' or 'path'", error);
        scene->shading = *word == "phong"  ? SHADING_PHONG
                         : *word == "path" ? SHADING_PATH
                                           : SHADING_FLOOR;
        return true;
    }
    return Fail(st, "unknown keyword " + Shown(k) + KeywordHint(k), error);
}

// One statement: checks it and adds what it says to the scene.
static bool ReadStatement(const Statement *st, Scene *scene, Declared *declared,
                          std::string *error) {
    const std::string &k = st->tokens[0];
    if (k == "sphere")
        return ReadSphere(st, scene, error);
    if (k == "triangle")
        return ReadTriangle(st, scene, error);
    if (k == "mesh")
        return ReadMesh(st, scene, error);
    if (k == "material") {
        for (const char *key : {"ambient", "specular", "emit"})
            for (size_t t = 2; t < st->tokens.size(); t++)
                if (st->tokens[t] == key)
                    declared->shadingOnly.push_back({st->line, st->tokens[1] + ": " + key});
        return ReadMaterial(st, scene, error);
    }
    if (k == "light")
        return ReadLight(st, scene, error);
    if (k == "camera")
        return Once(st, &declared->camera, error) && ReadCamera(st, scene, error);
    return ReadSetting(st, scene, declared, error);
}

// Reads statements a line at a time from `file` (never the whole file at once).
static bool ParseSceneLines(FILE *file, const char *fileName, Scene *scene, std::string *error) {
    InitScene(scene);
    Declared declared = {};
    Statement st = {fileName, 0, {}};
    std::string line, why;
    for (;;) {
        st.line++;
        LineStatus status = ReadTextLine(file, st.line, &line, &why);
        if (status == LINE_END)
            break;
        if (status != LINE_READ)
            return Fail(&st, why, error);
        Tokenize(line, &st.tokens);
        if (st.tokens.empty())
            continue;
        if (!ReadStatement(&st, scene, &declared, error))
            return false;
        if (ObjectCount(scene) > kMaxObjects)
            return Fail(&st, "too many objects (rt's limit is " + std::to_string(kMaxObjects) + ")",
                        error);
    }
    // Material properties the scene's shading does not use: legal, but probably not meant
    for (const auto &[line, what] : declared.shadingOnly) {
        bool emit = what.compare(what.size() - 4, 4, "emit") == 0;
        bool used = emit ? scene->shading == SHADING_PATH : scene->shading == SHADING_PHONG;
        if (!used)
            scene->warnings.push_back(std::string(fileName) + ":" + std::to_string(line) +
                                      ": warning: material " + what + " is used only by " +
                                      (emit ? "shading path" : "shading phong"));
    }
    // The perspective camera's pixel counts follow the image size
    scene->camera.perspective.widthPixels = scene->width;
    scene->camera.perspective.heightPixels = scene->height;
    return true;
}

bool ParseSceneText(const std::string &text, const char *fileName, Scene *scene,
                    std::string *error) {
    static const char kNothing[] = "\n"; // fmemopen needs at least one byte
    FILE *file = text.empty() ? fmemopen((void *)kNothing, 1, "r")
                              : fmemopen((void *)text.data(), text.size(), "r");
    if (!file) {
        *error = std::string(fileName) + ": " + strerror(errno);
        return false;
    }
    bool read = ParseSceneLines(file, fileName, scene, error);
    fclose(file);
    return read;
}

bool ReadSceneFile(const char *path, Scene *scene, std::string *error) {
    struct stat info;
    if (stat(path, &info) != 0) {
        *error = std::string(path) + ": " + strerror(errno);
        return false;
    }
    if (S_ISDIR(info.st_mode)) {
        *error = std::string(path) + ": is a directory, not a scene file";
        return false;
    }
    FILE *file = fopen(path, "rb");
    if (!file) {
        *error = std::string(path) + ": " + strerror(errno);
        return false;
    }
    bool read = ParseSceneLines(file, path, scene, error);
    fclose(file);
    return read;
}
