// app/mesh_words.cpp -- the words of the scene file's `mesh PATH MATERIAL [words]`: the transform
// words (scale, rotate, translate), which move every vertex in the order written, and `flat`,
// `smooth` and `fit S` (docs/scene-format.md). The OBJ file itself is read by mesh.cpp.
#include "app.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

// cos and sin of an angle in degrees. A multiple of 90 degrees gets exact values (0, +-1), so
// `rotate y 90` moves a vertex to exactly the place a student predicts by hand; pi/2 in radians
// is not a floating-point number, and cos(pi/2) would be 6e-17 instead of 0. The angle is first
// reduced to (-360, 360) by fmod, which is exact, so `rotate z 3645` is as accurate as 45; other
// angles go through radians in double and are rounded once to real.
static void CosSinDegrees(double degrees, real *cosine, real *sine) {
    static const real kCos[4] = {1, 0, -1, 0}, kSin[4] = {0, 1, 0, -1}; // 0, 90, 180, 270
    double reduced = std::fmod(degrees, 360.0);
    if (std::fmod(reduced, 90.0) == 0) {
        int quarter = ((int)(reduced / 90) + 4) % 4; // reduced / 90 is a whole number in -3..3
        *cosine = kCos[quarter];
        *sine = kSin[quarter];
        return;
    }
    double radians = reduced * (3.14159265358979323846 / 180);
    *cosine = (real)std::cos(radians);
    *sine = (real)std::sin(radians);
}

// The step a word makes from its values: v, already read as numbers, and for rotate its axis.
static bool MakeMeshStep(const std::string &word, const std::string &axis, const real *v,
                         MeshStep *step, std::string *error) {
    *step = MeshStep();
    if (word == "scale") {
        step->kind = MESH_SCALE;
        step->factor = v[0];
        if (!(v[0] > 0)) // 0 would flatten the mesh, < 0 would turn it inside out
            *error = "scale must be > 0 (scale -1 1 1 mirrors in x)";
        return v[0] > 0;
    }
    if (word == "scale3") {
        step->kind = MESH_SCALE_AXES;
        step->factors = {v[0], v[1], v[2]};
        bool some = v[0] != 0 && v[1] != 0 && v[2] != 0; // (0 would flatten the mesh)
        if (!some)
            *error = "scale X Y Z: no factor may be 0";
        return some;
    }
    if (word == "translate") {
        step->kind = MESH_TRANSLATE;
        step->offset = {v[0], v[1], v[2]};
        return true;
    }
    step->kind = MESH_ROTATE;
    step->axis = axis == "x" ? 0 : axis == "y" ? 1 : axis == "z" ? 2 : -1;
    CosSinDegrees(v[0], &step->cosine, &step->sine);
    if (step->axis < 0)
        *error = "rotate: expected an axis x, y or z, not " + Shown(axis);
    return step->axis >= 0;
}

// Whether a token is one of the mesh statement's words.
static bool IsMeshWord(const std::string &t) {
    return t == "scale" || t == "rotate" || t == "translate" || t == "fit" || t == "flat" ||
           t == "smooth";
}

// Whether a token was meant as a number, good or bad: it starts as a decimal number does, or
// spells NaN or infinity (which rt refuses as numbers, but which are no words of the statement).
static bool MeantAsNumber(const std::string &t) {
    std::string lower;
    for (char c : t.substr(t[0] == '+' || t[0] == '-' ? 1 : 0, 3))
        lower += (char)std::tolower((unsigned char)c);
    return std::isdigit((unsigned char)t[0]) || t[0] == '+' || t[0] == '-' || t[0] == '.' ||
           lower == "nan" || lower == "inf";
}

// How many values the transform word tokens[k] takes (0: it is no transform word), and *word:
// the word, or "scale3" for `scale X Y Z`. `scale` takes three where the token after its first
// is meant as a number (`scale 1 nan 1` is a scale of three, one of them bad, not a scale of 1
// and an unknown word 'nan').
static size_t WordValues(const std::vector<std::string> &tokens, size_t k, std::string *word) {
    *word = tokens[k];
    if (*word == "scale" && k + 2 < tokens.size() && !IsMeshWord(tokens[k + 2]) &&
        MeantAsNumber(tokens[k + 2]))
        *word = "scale3"; // `scale X Y Z`: three numbers follow
    if (*word == "scale")
        return 1;
    if (*word == "rotate")
        return 2;
    return *word == "translate" || *word == "scale3" ? 3 : 0;
}

// Why a token where a word was expected, and which is none, is refused.
static std::string NotAWord(const std::string &word) {
    if (MeantAsNumber(word))
        return "a number, " + Shown(word) +
               ", where a word was expected (scale takes 1 or 3 numbers, rotate an axis and an "
               "angle, translate 3, fit 1)";
    return "unknown word " + Shown(word) +
           " (expected scale, rotate, translate, fit, flat or smooth; if the file name has a "
           "space, that is why: file names may not contain spaces)";
}

// One word and its values, tokens[*k..]; moves *k past them.
static bool ParseMeshStep(const std::vector<std::string> &tokens, size_t *k, MeshStep *step,
                          std::string *error) {
    std::string word;
    size_t count = WordValues(tokens, *k, &word);
    if (count == 0) {
        *error = NotAWord(word);
        return false;
    }
    const char *kScaleNumbers = "scale needs 1 or 3 finite numbers (scale 2, or scale 1 -1 1 to "
                                "mirror in y)";
    if (*k + count >= tokens.size()) {
        *error = word == "scale3" ? kScaleNumbers + std::string(", found ") +
                                        std::to_string(tokens.size() - *k - 1)
                 : count == 1 ? "scale: expected a factor (scale 2 doubles the mesh)"
                 : count == 2 ? "rotate: expected an axis and an angle in degrees (rotate y 30)"
                              : "translate: expected three numbers X Y Z (translate 0 -1 -5)";
        return false;
    }
    real v[3];
    size_t firstNumber = word == "rotate" ? 2 : 1; // rotate's first value is its axis
    for (size_t j = firstNumber; j <= count; j++) {
        if (!ParseReal(tokens[*k + j], &v[j - firstNumber], error)) {
            *error = (word == "scale3" ? std::string(kScaleNumbers) : tokens[*k]) + ": " + *error;
            return false;
        }
    }
    if (!MakeMeshStep(word, tokens[*k + 1], v, step, error))
        return false;
    *k += 1 + count;
    return true;
}

static real MinAbs(vec3 v) { return std::min({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

// `flat`, `smooth` or `fit S` at tokens[*k]; moves *k past it. False with *error where the word is
// given twice, flat and smooth both, or fit's size is not a positive number.
static bool ParseMeshWord(const std::vector<std::string> &tokens, size_t *k, MeshWords *words,
                          std::string *error) {
    const std::string &word = tokens[*k];
    if (word == "fit") {
        if (words->fit > 0) {
            *error = "fit: given twice";
            return false;
        }
        if (*k + 1 >= tokens.size() || !ParseReal(tokens[*k + 1], &words->fit, error) ||
            !(words->fit > 0)) {
            *error = "fit: expected the size of the box the mesh is fitted into, a number > 0 "
                     "(fit 2: its longest side becomes 2, centred at the origin)";
            return false;
        }
        *k += 2;
        return true;
    }
    MeshNormals normals = word == "flat" ? MESH_FLAT : MESH_SMOOTH;
    if (words->normals != MESH_NORMALS_FROM_FILE) {
        *error = word + ": flat and smooth may be given once, and not both";
        return false;
    }
    words->normals = normals;
    *k += 1;
    return true;
}

bool ParseMeshWords(const std::vector<std::string> &tokens, size_t first, MeshWords *words,
                    std::string *error) {
    *words = {{}, MESH_NORMALS_FROM_FILE, 0};
    real size = 1; // what the scale words make of a length of 1, step by step as a vertex's
    for (size_t k = first; k < tokens.size();) {
        const std::string &word = tokens[k];
        if (word == "flat" || word == "smooth" || word == "fit") {
            if (!ParseMeshWord(tokens, &k, words, error))
                return false;
            continue;
        }
        MeshStep step;
        if (!ParseMeshStep(tokens, &k, &step, error))
            return false;
        words->steps.push_back(step);
        size = step.kind == MESH_SCALE ? step.factor * size : size;
        if (step.kind == MESH_SCALE_AXES) // (its smallest factor shrinks the most)
            size = MinAbs(step.factors) * size;
    }
    // Scale words that together shrink a mesh below the normal numbers would round its
    // vertices toward 0 and make it vanish without a word (a mesh grown beyond the range of
    // numbers is refused at its first vertex); and `fit S` makes its longest side S before them
    if (!(size >= std::numeric_limits<real>::min())) {
        *error = "scale: the mesh would shrink below the range of numbers";
        return false;
    }
    if (words->fit > 0 && !(words->fit * size >= std::numeric_limits<real>::min())) {
        *error = std::string("fit") + (size < 1 ? " and scale" : "") +
                 ": the mesh would shrink below the range of numbers";
        return false;
    }
    return true;
}

bool ParseMeshTransform(const std::vector<std::string> &tokens, size_t first,
                        std::vector<MeshStep> *steps, std::string *error) {
    MeshWords words;
    if (!ParseMeshWords(tokens, first, &words, error))
        return false;
    if (words.normals != MESH_NORMALS_FROM_FILE || words.fit > 0) {
        *error = "flat, smooth and fit are words of the mesh statement, not transform words";
        return false;
    }
    *steps = words.steps;
    return true;
}

// A rotate step: counter-clockwise seen from the positive axis, the axes u, w after it (y, z for
// x; z, x for y; x, y for z) turn as u' = cos u - sin w, w' = sin u + cos w.
static vec3 Rotate(const MeshStep *step, vec3 p) {
    real c[3] = {p.x, p.y, p.z};
    int u = (step->axis + 1) % 3, w = (step->axis + 2) % 3;
    real cu = c[u], cw = c[w];
    c[u] = step->cosine * cu - step->sine * cw;
    c[w] = step->sine * cu + step->cosine * cw;
    return {c[0], c[1], c[2]};
}

// Each step is applied as written, not folded into one matrix first: the arithmetic on a vertex
// is exactly what the words say (one rounding per operation), so a rotation by 90 degrees only
// swaps and negates coordinates, and `scale 2` only doubles them, both without rounding.
vec3 TransformVertex(const std::vector<MeshStep> &steps, vec3 p) {
    for (const MeshStep &step : steps) {
        if (step.kind == MESH_SCALE) {
            p = step.factor * p;
        } else if (step.kind == MESH_SCALE_AXES) {
            p = {step.factors.x * p.x, step.factors.y * p.y, step.factors.z * p.z};
        } else if (step.kind == MESH_TRANSLATE) {
            p = p + step.offset;
        } else {
            p = Rotate(&step, p);
        }
    }
    return p;
}

vec3 TransformNormal(const std::vector<MeshStep> &steps, vec3 n) {
    for (const MeshStep &step : steps) {
        if (step.kind == MESH_SCALE_AXES) // the inverse transpose of diag(X, Y, Z)
            n = {n.x / step.factors.x, n.y / step.factors.y, n.z / step.factors.z};
        if (step.kind == MESH_ROTATE) // (a uniform scale or a move leaves a normal as it is)
            n = Rotate(&step, n);
    }
    return SafeNormalize(n);
}

bool MirrorsMesh(const std::vector<MeshStep> &steps) {
    bool mirrored = false;
    for (const MeshStep &step : steps)
        if (step.kind == MESH_SCALE_AXES)
            mirrored ^= (step.factors.x < 0) ^ (step.factors.y < 0) ^ (step.factors.z < 0);
    return mirrored;
}
