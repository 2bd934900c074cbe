// app/scene_file.cpp -- reads scene files (docs/scene-format.md) into a Scene.
//
// One statement a line, `#` comments, tokens between spaces or tabs. Every statement is checked
// as it is read, and the first problem ends the read with "FILE:LINE: message", the way a
// compiler reports it. Nothing here prints; the caller decides what to do with the message.
// Here: the file's loop, the settings that come once, and the hints of an unknown keyword; the
// statements that add shapes, lights, materials, the camera and meshes are statements.cpp's.
#include "app.h"
#include "statements.h"

#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sys/stat.h>

// What has been declared once already (a second one is an error), and material properties that
// only one shading uses, by line, for a warning once the shading is known.
struct Declared {
    bool size, camera, ambient, shading, background, depth;
    std::vector<std::pair<int, std::string>> shadingOnly; // line, "NAME: KEY"
};

// A statement that may appear once: marks it, or reports the second one.
static bool Once(const Statement *st, bool *seen, std::string *error) {
    if (*seen)
        return Fail(st, "second '" + st->tokens[0] + "' statement (only one is allowed)", error);
    *seen = true;
    return true;
}

// Whether a statement is one that only a Wavefront OBJ file holds, by its shape: a vertex, a
// material library or its use, or an object, group or smoothing name of one word. (Not `f`,
// nor `s` with numbers after it, which a scene file's mistyped `sphere` could be.)
static bool LooksLikeObj(const std::vector<std::string> &t) {
    const std::string &k = t[0];
    if (k == "v" || k == "vt" || k == "vn" || k == "mtllib" || k == "usemtl")
        return true;
    return (k == "o" || k == "g" || k == "s") && t.size() == 2;
}

// What an unknown keyword may say about the mistake: a keyword in capitals, a Wavefront OBJ file
// given where a scene file goes, a file that is not UTF-8 text (a PNG image), an invisible
// control character, or a slip of the keyboard (NearWord).
// A word with its ASCII capitals made small (every keyword and setting word is ASCII).
static std::string LowerCase(std::string word) {
    for (char &c : word)
        c = (char)std::tolower((unsigned char)c);
    return word;
}

static std::string KeywordHint(const std::vector<std::string> &tokens) {
    static const char *const kKeywords[] = {"size",       "camera", "shading",  "ambient",
                                            "background", "depth",  "material", "sphere",
                                            "triangle",   "mesh",   "light",    nullptr};
    std::string lower = LowerCase(tokens[0]);
    for (const char *const *keyword = kKeywords; *keyword; keyword++)
        if (lower == *keyword)
            return " (keywords are written in lower case: '" + lower + "')";
    if (LooksLikeObj(tokens))
        return " (this looks like a Wavefront OBJ mesh: a scene file draws one with `mesh FILE "
               "MATERIAL`)";
    if (!IsUtf8(tokens[0]))
        return " (it holds bytes that are not UTF-8 text: a scene file is text, not an image)";
    if (!IsPrintableText(tokens[0]))
        return " (it holds a control character, shown as '?': an invisible character typed or "
               "pasted into the file)";
    int near = NearWord(lower, kKeywords);
    return near < 0 ? "" : " (did you mean '" + std::string(kKeywords[near]) + "'?)";
}

// `shading floor|phong|path`: one word, lower case like every word of a scene file (a word in
// capitals is told so, as a keyword in capitals is).
static bool ReadShading(const Statement *st, Scene *scene, std::string *error) {
    if (st->tokens.size() > 2)
        return Fail(st, "shading: extra value " + Shown(st->tokens[2]), error);
    std::string word = st->tokens.size() == 2 ? st->tokens[1] : "", lower = LowerCase(word);
    if (lower != "floor" && lower != "phong" && lower != "path")
        return Fail(st, "shading: expected 'floor', 'phong' or 'path'", error);
    if (word != lower)
        return Fail(st,
                    "shading: expected 'floor', 'phong' or 'path' (lower case: '" + lower + "')",
                    error);
    scene->shading = word == "phong"  ? SHADING_PHONG
                     : word == "path" ? SHADING_PATH
                                      : SHADING_FLOOR;
    return true;
}

// The statements that set one thing for the whole scene, each at most once.
static bool ReadSetting(const Statement *st, Scene *scene, Declared *declared, std::string *error) {
    const std::string &k = st->tokens[0];
    real v[6];
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
        scene->ambientLight = v[0];
        return (v[0] >= 0 && v[0] <= 1) ||
               Fail(st, "ambient " + st->tokens[1] + ": must be in [0, 1]", error);
    }
    if (k == "background") { // `background R G B`, or the book's sky: `background R G B up R G B`
        bool sky = st->tokens.size() > 4 && st->tokens[4] == "up";
        size_t total = sky ? 8 : 4;
        if (!Once(st, &declared->background, error) || !Numbers(st, 1, 3, total, v, error) ||
            (sky && !Numbers(st, 5, 3, total, v + 3, error)))
            return false;
        scene->background = {v[0], v[1], v[2]};
        if (sky)
            scene->sky = true, scene->skyUp = {v[3], v[4], v[5]};
        return CheckColor(st, "background", 1, scene->background, error) &&
               (!sky || CheckColor(st, "background: up", 5, scene->skyUp, error));
    }
    if (k == "shading")
        return Once(st, &declared->shading, error) && ReadShading(st, scene, error);
    return Fail(st, "unknown keyword " + Shown(k) + KeywordHint(st->tokens), error);
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
        if (st.line == INT_MAX) // line numbers are ints; an endless file stops here
            return Fail(&st, "too many lines", error);
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

// The first sphere that holds point p strictly inside, glass ones too or not, or null.
// (SafeLength: a scene of 1e200 units has the same answer as at scale 1.)
static const Sphere *SphereAround(const Scene *scene, vec3 p, bool glass) {
    for (const Sphere &s : scene->spheres)
        if (SafeLength(p - s.center) < s.radius &&
            (glass || !(scene->materials[s.material].ior > 0)))
            return &s;
    return nullptr;
}

static std::string Where(const char *what, vec3 p) {
    char text[160];
    snprintf(text, sizeof text, "%s (%g %g %g)", what, (double)p.x, (double)p.y, (double)p.z);
    return text;
}
static std::string Described(const Sphere *s) {
    char radius[40];
    snprintf(radius, sizeof radius, " of radius %g", (double)s->radius);
    return Where("the sphere at", s->center) + radius;
}

std::vector<std::string> InsideWarnings(const Scene *scene, vec3 eyeRaysStart) {
    std::vector<std::string> warnings;
    for (const Light &light : scene->lights)
        if (const Sphere *s = SphereAround(scene, light.position, true))
            warnings.push_back(Where("the light at", light.position) + " is inside " +
                               Described(s) +
                               ": its shadow rays end on that sphere, so nothing outside it is lit "
                               "by that light");
    if (const Sphere *s = SphereAround(scene, eyeRaysStart, false))
        warnings.push_back(Where("the eye rays start at", eyeRaysStart) + ", inside " +
                           Described(s) + ": the image shows that sphere from inside");
    return warnings;
}
