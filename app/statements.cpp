// app/statements.cpp -- the statements of a scene file (docs/scene-format.md), one reader each: the
// shapes, lights, materials, the camera and meshes, each checked as it is read. The file's loop,
// the settings that come once (size, shading, ...) and the messages' hints are scene_file.cpp's.
#include "statements.h"
#include "../robust/robust.h" // robust/: SetUpTriangle, for Unhittable
#include "app.h"

#include <cmath>
#include <cstring>

bool Fail(const Statement *st, const std::string &message, std::string *error) {
    *error = std::string(st->file) + ":" + std::to_string(st->line) + ": " + message;
    return false;
}

// Reads `count` numbers from tokens[first...]; the statement must hold exactly `total` tokens.
bool Numbers(const Statement *st, size_t first, int count, size_t total, real *out,
             std::string *error) {
    const std::string &keyword = st->tokens[0];
    if (st->tokens.size() < total)
        return Fail(st,
                    keyword + ": missing number(s): expected " + std::to_string(total - 1) +
                        (total == 2 ? " value after " : " values after ") + keyword,
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

bool WholeNumber(const Statement *st, size_t index, int lo, int hi, int *out, std::string *error) {
    std::string why;
    return ParseWholeNumber(st->tokens[index], lo, hi, out, &why) ||
           Fail(st, st->tokens[0] + ": " + why, error);
}

// A colour (diffuse, ambient, background), read from tokens[first...]: each component in [0, 1];
// the message shows the numbers as written.
bool CheckColor(const Statement *st, const std::string &what, size_t first, color c,
                std::string *error) {
    if (c.x >= 0 && c.x <= 1 && c.y >= 0 && c.y <= 1 && c.z >= 0 && c.z <= 1)
        return true;
    const std::vector<std::string> &t = st->tokens;
    return Fail(st,
                what + " " + t[first] + " " + t[first + 1] + " " + t[first + 2] +
                    ": each component must be in [0, 1]",
                error);
}

// Light (a light's intensity, a material's emitted radiance): any finite amount >= 0, since a
// light may be brighter than the white a pixel can show.
static bool CheckLight(const Statement *st, const char *what, color c, std::string *error) {
    bool ok = c.x >= 0 && c.y >= 0 && c.z >= 0 && IsFinite(c);
    return ok || Fail(st, std::string(what) + ": each value must be a finite number >= 0", error);
}

// The place of the material called `name` in scene->materials, or -1.
static int MaterialNamed(const Scene *scene, const std::string &name) {
    for (size_t k = 0; k < scene->materials.size(); k++)
        if (scene->materials[k].name == name)
            return (int)k;
    return -1;
}

static bool FindMaterial(const Statement *st, const Scene *scene, size_t index, int *material,
                         std::string *error) {
    const std::string &name = st->tokens[index];
    if ((*material = MaterialNamed(scene, name)) >= 0)
        return true;
    return Fail(st,
                st->tokens[0] + ": material " + Shown(name) + " is not defined (define it above" +
                    (LooksDecimal(name) ? "; or, if it is a number, the name is left out)" : ")"),
                error);
}

// A shape statement holds `numbers` numbers and then the name of its material. Where it holds
// another count, the message counts what it found: with one number too many, the word after the
// numbers is still the material's name, and calling that name the extra value would blame the
// wrong word. (Numbers are counted as written, in range or not: Numbers judges their range.)
static bool ShapeArity(const Statement *st, const Scene *scene, size_t numbers,
                       std::string *error) {
    const std::vector<std::string> &t = st->tokens;
    size_t given = t.size() - 1, found = 0; // found: the numbers before the first other word
    while (found < given && LooksDecimal(t[found + 1]))
        found++;
    // (the last word names a material, even one named like a number: `2`)
    bool named = given > 0 && MaterialNamed(scene, t[given]) >= 0;
    found = named && found == given ? given - 1 : found;
    if (given == numbers + 1) // the count is right: Numbers and FindMaterial judge the words
        return true;
    if (found == numbers && given > numbers + 1)
        return Fail(st, t[0] + ": extra value " + Shown(t[numbers + 2]), error);
    if (found + 1 < given) // a word that is no number where a number goes: that is the mistake
        return Fail(st, t[0] + ": not a decimal number: " + Shown(t[found + 1]), error);
    std::string count = std::to_string(found) + (found == 1 ? " number" : " numbers");
    std::string got = given == 0       ? "nothing"
                      : found == given ? count + " and no material name"
                                       : count + " and then " + Shown(t[given]);
    return Fail(st,
                t[0] + ": expected " + std::to_string(numbers) +
                    " numbers and a material name, found " + got,
                error);
}

bool ReadSphere(const Statement *st, Scene *scene, std::string *error) {
    real v[4];
    Sphere s;
    if (!ShapeArity(st, scene, 4, error) || !Numbers(st, 1, 4, 6, v, error) ||
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
    return EdgesFinite(t) ? "has no area (its corners are on one line)"
                          : "has edges beyond the range of numbers";
}

bool ReadTriangle(const Statement *st, Scene *scene, std::string *error) {
    real v[9];
    Triangle t;
    if (!ShapeArity(st, scene, 9, error) || !Numbers(st, 1, 9, 11, v, error) ||
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

bool ReadLight(const Statement *st, Scene *scene, std::string *error) {
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

// `material NAME [diffuse R G B] [ambient R G B] [specular KS N] [mirror K [fuzz F] [tint R G B]]
// [glass IOR] [emit R G B]`
// One property of a material statement, tokens[at], with its numbers v (already read): checked
// and set.
static bool SetMaterialProperty(const Statement *st, size_t at, const real *v, Material *m,
                                std::string *error) {
    const std::string &key = st->tokens[at];
    if (key == "diffuse" || key == "ambient") {
        color c = {v[0], v[1], v[2]};
        if (!CheckColor(st, "material: " + key, at + 1, c, error))
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
    } else if (key == "fuzz") { // (the book's metal takes fuzz up to 1, the fuzz sphere's radius
        if (!(v[0] >= 0 && v[0] <= 1)) // as long as the mirror direction)
            return Fail(st, "material: fuzz must be in [0, 1]", error);
        m->fuzz = v[0];
    } else if (key == "tint") {
        m->tint = {v[0], v[1], v[2]};
        return CheckColor(st, "material: tint", at + 1, m->tint, error);
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
                                                   {"glass", 1, "IOR"},     {"emit", 3, "R G B"},
                                                   {"fuzz", 1, "F"},        {"tint", 3, "R G B"}};
    for (const MaterialProperty &p : kProperties)
        if (key == p.key)
            return &p;
    return nullptr;
}

bool ReadMaterial(const Statement *st, Scene *scene, std::string *error) {
    if (st->tokens.size() < 2)
        return Fail(st, "material: missing name", error);
    Material m = {st->tokens[1], {1, 1, 1}, {1, 1, 1}, 0, 1, 0, 0, {0, 0, 0}};
    if (MaterialNamed(scene, m.name) >= 0)
        return Fail(st, "material " + Shown(m.name) + " is defined twice", error);
    std::string keysSeen;
    for (size_t k = 2; k < st->tokens.size();) {
        const std::string &key = st->tokens[k];
        const MaterialProperty *p = FindProperty(key);
        if (!p)
            return Fail(st,
                        "material: unknown property " + Shown(key) +
                            " (expected diffuse, ambient, specular, mirror, fuzz, tint, "
                            "glass or emit)",
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
        if (!SetMaterialProperty(st, k, v, &m, error))
            return false;
        k += 1 + count;
    }
    if (keysSeen.find(" ambient ") == std::string::npos) // ka defaults to kd
        m.ambient = m.diffuse;
    bool metal = keysSeen.find(" fuzz ") != std::string::npos ||
                 keysSeen.find(" tint ") != std::string::npos;
    if (metal && keysSeen.find(" mirror ") == std::string::npos)
        return Fail(st, "material: fuzz and tint are a mirror's: give mirror K too", error);
    scene->materials.push_back(m);
    return true;
}

// One lens word of a lookat camera, tokens[k] and its number: checked, and *value set. A value
// of -1 stands for a word not given yet.
static bool LensWord(const Statement *st, size_t k, real *value, std::string *error) {
    const std::string &word = st->tokens[k];
    std::string why;
    if (*value >= 0)
        return Fail(st, "camera lookat: '" + word + "' given twice", error);
    if (k + 1 >= st->tokens.size())
        return Fail(st, "camera lookat: '" + word + "' needs a number", error);
    if (!ParseReal(st->tokens[k + 1], value, &why))
        return Fail(st, "camera lookat: " + word + ": " + why, error);
    if (word == "defocus" && !(*value >= 0 && *value < 180))
        return Fail(st, "camera lookat: defocus must be at least 0 and less than 180 degrees",
                    error);
    if (word == "aperture" && !(*value >= 0))
        return Fail(st, "camera lookat: aperture must be >= 0", error);
    if (word == "focus" && !(*value > 0))
        return Fail(st, "camera lookat: focus must be > 0", error);
    return true;
}

// The thin lens of a lookat camera, the words after its field of view: `defocus ANGLE` (Ray
// Tracing in One Weekend's defocus_angle, in degrees: the cone of the rays that meet at one point
// of the plane in focus) or `aperture D` (the lens's diameter, in world units), and `focus DIST`
// (the book's focus_dist; without it, the distance from `from` to `to`: what the camera looks at
// is sharp). The lens's radius is focus tan(ANGLE / 2), or D / 2.
static bool ReadLens(const Statement *st, Camera *c, std::string *error) {
    real angle = -1, aperture = -1, focus = -1;
    for (size_t k = 12; k < st->tokens.size(); k += 2) {
        const std::string &word = st->tokens[k];
        real *value = word == "defocus"    ? &angle
                      : word == "aperture" ? &aperture
                      : word == "focus"    ? &focus
                                           : nullptr;
        if (!value)
            return Fail(st,
                        "camera lookat: unknown word " + Shown(word) +
                            " after the field of view (expected defocus, aperture or focus)",
                        error);
        if (!LensWord(st, k, value, error))
            return false;
    }
    if (angle >= 0 && aperture >= 0)
        return Fail(st, "camera lookat: give the lens as defocus or as aperture, not both", error);
    c->focusDistance = focus > 0 ? focus : SafeLength(c->lookAt - c->lookFrom);
    c->lensRadius = aperture >= 0 ? aperture / 2
                    : angle > 0   ? c->focusDistance * std::tan(angle * real(M_PI / 360))
                                  : 0;
    if (!std::isfinite(c->lensRadius) || !std::isfinite(c->focusDistance))
        return Fail(st, "camera lookat: the lens is beyond the range of numbers", error);
    return true;
}

bool ReadCamera(const Statement *st, Scene *scene, std::string *error) {
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
    } else if (kind == "lookat") { // (its lens words follow the numbers: ReadLens)
        bool lens = st->tokens.size() > 12 && !LooksDecimal(st->tokens[12]);
        if (!Numbers(st, 2, 10, lens ? st->tokens.size() : 12, v, error))
            return false;
        c.kind = CAMERA_LOOKAT;
        c.lookFrom = {v[0], v[1], v[2]};
        c.lookAt = {v[3], v[4], v[5]};
        c.vup = {v[6], v[7], v[8]};
        c.fovDegrees = v[9];
        Camera check;
        std::string why;
        if (!LookAtToScreen(&c, 1, 1, &check, &why))
            return Fail(st, "camera lookat: " + why, error);
        if (lens && !ReadLens(st, &c, error))
            return false;
    } else {
        return Fail(
            st, "camera: unknown kind " + Shown(kind) + " (expected perspective, screen or lookat)",
            error);
    }
    scene->camera = c;
    return true;
}

size_t ObjectCount(const Scene *scene) {
    return scene->spheres.size() + scene->triangles.size() + scene->lights.size() +
           scene->materials.size();
}

// `mesh PATH MATERIAL [transform words]` (mesh.cpp), with what is left of the object limit.
bool ReadMesh(const Statement *st, Scene *scene, std::string *error) {
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
