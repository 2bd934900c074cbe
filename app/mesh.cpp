// app/mesh.cpp -- the scene file's `mesh PATH MATERIAL [transform words]`: Wavefront OBJ meshes.
//
// The OBJ file is read a line at a time (ReadTextLine, as scene files are), never whole: only
// the vertex positions are kept, because faces name them by number, and each face goes straight
// into the scene's triangles as a fan from its first corner. `v` and `f` are the statements that
// make geometry; every other statement (texture coordinates, normals, groups, materials, lines,
// points) is skipped. Errors are values, "MESH:LINE: message", as for scene files.
#include "app.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <sys/stat.h>

// The most vertices one mesh may hold while it is read: a vertex is 3 reals (24 bytes in
// double), so this is at most 96 MB (twice that while the vector grows), freed when the file is
// read. A closed mesh has about half as many vertices as triangles, so a file the scene's shape
// limit accepts is not refused here.
static const size_t kMaxMeshVertices = 4000000;

static bool MeshFail(const char *meshName, int line, const std::string &message,
                     std::string *error) {
    *error = std::string(meshName) + ":" + std::to_string(line) + ": " + message;
    return false;
}

// ---- transform words -------------------------------------------------------------------------

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
            *error = "scale must be > 0";
        return v[0] > 0;
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

// One word and its values, tokens[*k..]; moves *k past them.
static bool ParseMeshStep(const std::vector<std::string> &tokens, size_t *k, MeshStep *step,
                          std::string *error) {
    const std::string &word = tokens[*k];
    size_t count = word == "scale" ? 1 : word == "rotate" ? 2 : word == "translate" ? 3 : 0;
    if (count == 0) {
        *error = "unknown transform word " + Shown(word) +
                 " (expected scale, rotate or translate; if the file name has a space, that is "
                 "why: file names may not contain spaces)";
        return false;
    }
    if (*k + count >= tokens.size()) {
        *error = word + ": expected " +
                 (count == 1   ? "a factor (scale 2 doubles the mesh)"
                  : count == 2 ? "an axis and an angle in degrees (rotate y 30)"
                               : "three numbers X Y Z (translate 0 -1 -5)");
        return false;
    }
    real v[3];
    size_t firstNumber = word == "rotate" ? 2 : 1; // rotate's first value is its axis
    for (size_t j = firstNumber; j <= count; j++) {
        if (!ParseReal(tokens[*k + j], &v[j - firstNumber], error)) {
            *error = word + ": " + *error;
            return false;
        }
    }
    if (!MakeMeshStep(word, tokens[*k + 1], v, step, error))
        return false;
    *k += 1 + count;
    return true;
}

bool ParseMeshTransform(const std::vector<std::string> &tokens, size_t first,
                        std::vector<MeshStep> *steps, std::string *error) {
    steps->clear();
    real size = 1; // what the scale words make of a length of 1, step by step as a vertex's
    for (size_t k = first; k < tokens.size();) {
        MeshStep step;
        if (!ParseMeshStep(tokens, &k, &step, error))
            return false;
        steps->push_back(step);
        size = step.kind == MESH_SCALE ? step.factor * size : size;
    }
    // Scale words that together shrink a mesh below the normal numbers would round its
    // vertices toward 0 and make it vanish without a word (a mesh grown beyond the range of
    // numbers is refused at its first vertex)
    if (!(size >= std::numeric_limits<real>::min())) {
        *error = "scale: the mesh would shrink below the range of numbers";
        return false;
    }
    return true;
}

// Each step is applied as written, not folded into one matrix first: the arithmetic on a vertex
// is exactly what the words say (one rounding per operation), so a rotation by 90 degrees only
// swaps and negates coordinates, and `scale 2` only doubles them, both without rounding.
vec3 TransformVertex(const std::vector<MeshStep> &steps, vec3 p) {
    for (const MeshStep &step : steps) {
        if (step.kind == MESH_SCALE) {
            p = step.factor * p;
        } else if (step.kind == MESH_TRANSLATE) {
            p = p + step.offset;
        } else {
            // Counter-clockwise seen from the positive axis: the axes u, w after it (y, z for
            // x; z, x for y; x, y for z) turn as u' = cos u - sin w, w' = sin u + cos w
            real c[3] = {p.x, p.y, p.z};
            int u = (step.axis + 1) % 3, w = (step.axis + 2) % 3;
            real cu = c[u], cw = c[w];
            c[u] = step.cosine * cu - step.sine * cw;
            c[w] = step.sine * cu + step.cosine * cw;
            p = {c[0], c[1], c[2]};
        }
    }
    return p;
}

// ---- the OBJ statements ----------------------------------------------------------------------

// `v x y z [w]`: the position, moved by the transform words. Further numbers (w, or the vertex
// colour r g b that some exporters add) are checked as numbers and not used.
static bool ReadVertex(const std::vector<std::string> &tokens, const std::vector<MeshStep> &steps,
                       const std::string &statement, std::vector<vec3> *vertices,
                       std::string *error) {
    real v[3];
    for (size_t k = 1; k < tokens.size(); k++) { // (each word first: `v 0,0,0` is one bad number)
        real value;
        if (!ParseReal(tokens[k], &value, error)) {
            *error = "v: " + *error;
            return false;
        }
        if (k <= 3)
            v[k - 1] = value;
    }
    if (tokens.size() < 4) {
        *error = "v: expected 3 numbers x y z, found " + std::to_string(tokens.size() - 1);
        return false;
    }
    if (vertices->size() >= kMaxMeshVertices) {
        *error = "too many vertices (rt's limit is " + std::to_string(kMaxMeshVertices) + ")";
        return false;
    }
    vec3 p = TransformVertex(steps, {v[0], v[1], v[2]});
    if (!IsFinite(p)) {
        *error = "v: the transform words of the mesh statement at " + statement +
                 " move this vertex beyond the range of numbers";
        return false;
    }
    vertices->push_back(p);
    return true;
}

// The value of an index written as a whole number (IsWholeNumber), leading zeros and all. Its size
// is kept up to 10^15, beyond any count of vertices: an index of more digits than that is out of
// range either way.
static long long IndexValue(const std::string &v) {
    size_t first = v[0] == '+' || v[0] == '-' ? 1 : 0;
    const long long kBeyond = 1000000000000000LL;
    long long value = 0;
    for (size_t k = first; k < v.size(); k++)
        value = std::min(kBeyond, value * 10 + (v[k] - '0'));
    return v[0] == '-' ? -value : value;
}

// One corner of a face, `v`, `v/vt`, `v//vn` or `v/vt/vn`: the vertex it names, counted from 1,
// or back from the last vertex read so far if negative (-1 is the last one). The texture and
// normal indices are not used, but must be whole numbers, of any size, where they are written.
// `hint` is added to the message of an index out of range (CapitalsHint).
static bool ReadCorner(const std::string &corner, size_t vertexCount, const std::string &hint,
                       size_t *vertex, std::string *error) {
    size_t slash = corner.find('/');
    std::string rest = slash == std::string::npos ? "" : corner.substr(slash + 1);
    size_t second = rest.find('/');
    std::string vt = rest.substr(0, second);
    std::string vn = second == std::string::npos ? "" : rest.substr(second + 1);
    std::string v = corner.substr(0, slash);
    if (!IsWholeNumber(v) || (!vt.empty() && !IsWholeNumber(vt)) || // (vt and vn are read
        (!vn.empty() && !IsWholeNumber(vn))) {                      // past, never used)
        *error = "f: bad corner " + Shown(corner) + " (expected v, v/vt, v//vn or v/vt/vn)";
        return false;
    }
    long long index = IndexValue(v);
    long long k = index > 0 ? index - 1 : (long long)vertexCount + index;
    if (index == 0 || k < 0 || k >= (long long)vertexCount) {
        *error = "f: vertex index " + v + " is out of range (" + std::to_string(vertexCount) +
                 " vertices read so far; the first is 1)" + hint;
        return false;
    }
    *vertex = (size_t)k;
    return true;
}

// `f c1 c2 ... cn`: n - 2 triangles (c1, c2, c3), (c1, c3, c4), ..., a fan from the first corner
// that keeps the face's winding, degenerate ones included (they are harmless: no ray hits them).
static bool ReadFace(const std::vector<std::string> &tokens, const std::vector<vec3> &vertices,
                     int material, size_t most, const std::string &hint,
                     const std::string &statement, std::vector<Triangle> *triangles,
                     std::string *error) {
    size_t corners = tokens.size() - 1;
    if (corners < 3) {
        *error = "f: a face needs at least 3 corners, this one has " + std::to_string(corners);
        return false;
    }
    if (triangles->size() + (corners - 2) > most) { // most: how many *triangles may hold
        *error = "too many triangles: with the mesh statement at " + statement +
                 ", rt's limit of shapes in a scene is reached";
        return false;
    }
    size_t first, previous, next;
    if (!ReadCorner(tokens[1], vertices.size(), hint, &first, error) ||
        !ReadCorner(tokens[2], vertices.size(), hint, &previous, error))
        return false;
    for (size_t k = 3; k <= corners; k++) {
        if (!ReadCorner(tokens[k], vertices.size(), hint, &next, error))
            return false;
        triangles->push_back({vertices[first], vertices[previous], vertices[next], material});
        previous = next;
    }
    return true;
}

// What an error adds when the file has `V` or `F` lines, which OBJ skips as statements it does not
// know: its keywords are lower case.
static std::string CapitalsHint(int capitals) {
    return capitals == 0 ? "" : " (lines that begin 'V' or 'F' were skipped: OBJ is lower case)";
}

bool ReadObj(FILE *file, const char *meshName, int material, const std::vector<MeshStep> &steps,
             size_t maxTriangles, const std::string &statement, std::vector<Triangle> *triangles,
             std::string *error) {
    std::vector<vec3> vertices;
    std::vector<std::string> tokens;
    std::string line, why;
    size_t faces = 0, most = triangles->size() + maxTriangles; // (maxTriangles more, at most)
    int capitals = 0;
    int lineNumber = 1;
    for (;; lineNumber++) {
        LineStatus status = ReadTextLine(file, lineNumber, &line, &why);
        if (status == LINE_END)
            break;
        if (status != LINE_READ)
            return MeshFail(meshName, lineNumber, why, error);
        if (lineNumber == INT_MAX) // line numbers are ints; a real mesh is far shorter
            return MeshFail(meshName, lineNumber, "too many lines", error);
        Tokenize(line, &tokens);
        if (!tokens.empty() && tokens.back().back() == '\\') // (the OBJ specification's)
            return MeshFail(meshName, lineNumber,
                            "a line that ends in '\\' goes on in the next one in some OBJ files; "
                            "rt does not join lines: put the statement on one line",
                            error);
        // (A statement OBJ does not know is skipped, as the format says; 'V' and 'F' are
        // counted, to say why a face finds too few vertices, or none is found.)
        capitals += !tokens.empty() && (tokens[0] == "V" || tokens[0] == "F");
        bool read = true;
        if (!tokens.empty() && tokens[0] == "v")
            read = ReadVertex(tokens, steps, statement, &vertices, &why);
        if (!tokens.empty() && tokens[0] == "f") {
            read = ReadFace(tokens, vertices, material, most, CapitalsHint(capitals), statement,
                            triangles, &why);
            faces++;
        }
        if (!read)
            return MeshFail(meshName, lineNumber, why, error);
    }
    if (faces == 0) // named at the end of the file, where the faces were looked for last
        return MeshFail(meshName, lineNumber > 1 ? lineNumber - 1 : 1,
                        "no faces in this file ('f' statements): nothing to draw" +
                            CapitalsHint(capitals),
                        error);
    return true;
}

// ---- the mesh statement ----------------------------------------------------------------------

std::string MeshPath(const char *sceneFile, const std::string &path) {
    std::string scene = sceneFile;
    size_t slash = scene.find_last_of('/');
    if (path[0] == '/' || slash == std::string::npos)
        return path;
    return scene.substr(0, slash + 1) + path;
}

// Opens a mesh file: a regular file only (a directory cannot be read, and a device or a FIFO
// might never end). nullptr with *error otherwise.
static FILE *OpenMesh(const std::string &path, std::string *error) {
    struct stat info;
    if (stat(path.c_str(), &info) != 0) {
        *error = path + ": " + strerror(errno);
        return nullptr;
    }
    if (!S_ISREG(info.st_mode)) {
        *error = path + ": not a regular file (a mesh is read from a file: not a directory, a "
                        "device, a pipe or standard input)";
        return nullptr;
    }
    FILE *file = fopen(path.c_str(), "rb");
    if (!file)
        *error = path + ": " + strerror(errno);
    return file;
}

bool ReadMeshStatement(const std::vector<std::string> &tokens, const char *sceneFile, int line,
                       int material, size_t maxTriangles, Scene *scene, std::string *error) {
    std::string where = std::string(sceneFile) + ":" + std::to_string(line) + ": mesh: ", why;
    std::vector<MeshStep> steps;
    if (!ParseMeshTransform(tokens, 3, &steps, &why)) {
        *error = where + why;
        return false;
    }
    std::string path = MeshPath(sceneFile, tokens[1]);
    FILE *file = OpenMesh(path, &why);
    if (!file) {
        *error = where + why;
        return false;
    }
    bool read =
        ReadObj(file, path.c_str(), material, steps, maxTriangles,
                std::string(sceneFile) + ":" + std::to_string(line), &scene->triangles, error);
    fclose(file);
    if (read &&
        std::find(scene->meshFiles.begin(), scene->meshFiles.end(), path) == scene->meshFiles.end())
        scene->meshFiles.push_back(path);
    return read;
}
