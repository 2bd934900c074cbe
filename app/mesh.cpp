// app/mesh.cpp -- the scene file's `mesh PATH MATERIAL [words]`: Wavefront OBJ meshes.
//
// The OBJ file is read a line at a time (ReadTextLine, as scene files are), never whole: only
// the vertex positions and normals are kept, because faces name them by number, and each face
// goes straight into the scene's triangles as a fan from its first corner. `v`, `vn` and `f` are
// the statements read; every other statement (texture coordinates, groups, materials, lines,
// points) is skipped. A smooth mesh's corner normals are made once the file is read
// (mesh_normals.cpp: the `vn` a face names, or for `smooth` the faces' normals averaged at each
// vertex). The words after the
// material are mesh_words.cpp's; `fit` needs the mesh's size before any vertex is placed, so a
// first pass reads the positions alone. Errors are values, "MESH:LINE: message", as for scene
// files.
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

// ---- the OBJ statements ----------------------------------------------------------------------

// What a mesh file gives as it is read: the positions (moved by the transform words) and normals
// (turned by them) named so far, and for each triangle made, its corners' places in both lists
// (-1: no normal), kept where the mesh's corner normals are to be made once it is read.
struct MeshReading {
    std::vector<vec3> vertices, normals;
    std::vector<int> cornerVertex, cornerNormal; // 3 a triangle
    bool keepCorners;
    bool fileNormals; // the file's `vn` are read (else skipped, as are the corners' vn indices)
    bool mirrored;    // the transform words mirror the mesh: each face's winding is turned back
    int line;         // the line being read
    int badNormal;    // the first line with a normal index out of range (its face is flat); 0
    std::string badIndex;
    int badVn; // the first `vn` line that is not three numbers, or not a direction (its normal is
               // 0); 0
    std::string badVnWhy;
};

// The three numbers of `v x y z [w]` or `vn x y z`. Further numbers (w, or the vertex colour
// r g b that some exporters add) are checked as numbers and not used.
static bool ReadThree(const std::vector<std::string> &tokens, real v[3], std::string *error) {
    for (size_t k = 1; k < tokens.size(); k++) { // (each word first: `v 0,0,0` is one bad number)
        real value;
        if (!ParseReal(tokens[k], &value, error)) {
            *error = tokens[0] + ": " + *error;
            return false;
        }
        if (k <= 3)
            v[k - 1] = value;
    }
    if (tokens.size() < 4) {
        *error =
            tokens[0] + ": expected 3 numbers x y z, found " + std::to_string(tokens.size() - 1);
        return false;
    }
    return true;
}

// `v x y z [w]`: the position, moved by the transform words; `vn x y z`: a normal, turned by
// them (a zero normal, or one turned beyond the range of numbers, is 0, and the faces that name
// it are flat).
static bool ReadVertex(const std::vector<std::string> &tokens, const std::vector<MeshStep> &steps,
                       const std::string &statement, MeshReading *r, std::string *error) {
    real v[3];
    if (!ReadThree(tokens, v, error)) {
        if (tokens[0] == "v")
            return false;
        // (A bad normal is no reason to refuse a mesh that draws without it: the faces that
        // name it are flat, and the reader warns once)
        if (r->badVn == 0)
            r->badVn = r->line, r->badVnWhy = *error;
        r->normals.push_back({0, 0, 0});
        return true;
    }
    std::vector<vec3> *list = tokens[0] == "v" ? &r->vertices : &r->normals;
    if (list->size() >= kMaxMeshVertices) {
        *error = "too many vertices (rt's limit is " + std::to_string(kMaxMeshVertices) + ")";
        return false;
    }
    if (tokens[0] == "vn") {
        vec3 n = TransformNormal(steps, {v[0], v[1], v[2]});
        if (!IsFinite(n) || MaxComponent(n) == 0) { // (warned about once, as a bad vn line is)
            if (r->badVn == 0)
                r->badVn = r->line,
                r->badVnWhy = MaxComponent({v[0], v[1], v[2]}) == 0
                                  ? "vn: a normal of length 0 has no direction"
                                  : "vn: the transform words take this normal beyond the range "
                                    "of numbers";
            n = {0, 0, 0};
        }
        r->normals.push_back(n);
        return true;
    }
    vec3 p = TransformVertex(steps, {v[0], v[1], v[2]});
    if (!IsFinite(p)) {
        *error = "v: the transform words of the mesh statement at " + statement +
                 " move this vertex beyond the range of numbers";
        return false;
    }
    r->vertices.push_back(p);
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

// The place an index names in a list of `count` items: counted from 1, or back from the last one
// read so far if negative (-1 is the last one); -1 if out of range.
static long long IndexPlace(const std::string &index, size_t count) {
    long long value = IndexValue(index);
    long long k = value > 0 ? value - 1 : (long long)count + value;
    return value == 0 || k < 0 || k >= (long long)count ? -1 : k;
}

// One corner of a face, `v`, `v/vt`, `v//vn` or `v/vt/vn`: the vertex it names, and the normal
// (-1 where it names none). The texture index is not used, but must be a whole number, of any
// size, where it is written. `hint` is added to the message of an index out of range
// (CapitalsHint).
static bool ReadCorner(const std::string &corner, MeshReading *r, const std::string &hint,
                       size_t *vertex, int *normal, std::string *error) {
    size_t slash = corner.find('/');
    std::string rest = slash == std::string::npos ? "" : corner.substr(slash + 1);
    size_t second = rest.find('/');
    std::string vt = rest.substr(0, second);
    std::string vn = second == std::string::npos ? "" : rest.substr(second + 1);
    std::string v = corner.substr(0, slash);
    if (!IsWholeNumber(v) || (!vt.empty() && !IsWholeNumber(vt)) || // (vt is read past,
        (!vn.empty() && !IsWholeNumber(vn))) {                      // never used)
        *error = "f: bad corner " + Shown(corner) + " (expected v, v/vt, v//vn or v/vt/vn)";
        return false;
    }
    long long k = IndexPlace(v, r->vertices.size());
    if (k < 0) {
        *error = "f: vertex index " + v + " is out of range (" +
                 std::to_string(r->vertices.size()) + " vertices read so far; the first is 1)" +
                 hint;
        return false;
    }
    // (A normal index out of range is no reason to refuse the mesh, which draws without it: the
    // face is flat, and the reader warns once)
    long long n = vn.empty() || !r->fileNormals ? -1 : IndexPlace(vn, r->normals.size());
    if (!vn.empty() && r->fileNormals && n < 0 && r->badNormal == 0)
        r->badNormal = r->line, r->badIndex = vn;
    *vertex = (size_t)k, *normal = (int)n;
    return true;
}

// `f c1 c2 ... cn`: n - 2 triangles (c1, c2, c3), (c1, c3, c4), ..., a fan from the first corner
// that keeps the face's winding, degenerate ones included (they are harmless: no ray hits them).
static bool ReadFace(const std::vector<std::string> &tokens, MeshReading *r, int material,
                     size_t most, const std::string &hint, const std::string &statement,
                     std::vector<Triangle> *triangles, std::string *error) {
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
    int firstN, previousN, nextN;
    if (!ReadCorner(tokens[1], r, hint, &first, &firstN, error) ||
        !ReadCorner(tokens[2], r, hint, &previous, &previousN, error))
        return false;
    for (size_t k = 3; k <= corners; k++) {
        if (!ReadCorner(tokens[k], r, hint, &next, &nextN, error))
            return false;
        const std::vector<vec3> &v = r->vertices;
        size_t b = r->mirrored ? next : previous, c = r->mirrored ? previous : next;
        int bN = r->mirrored ? nextN : previousN, cN = r->mirrored ? previousN : nextN;
        triangles->push_back({v[first], v[b], v[c], material});
        if (r->keepCorners) {
            r->cornerVertex.insert(r->cornerVertex.end(), {(int)first, (int)b, (int)c});
            r->cornerNormal.insert(r->cornerNormal.end(), {firstN, bN, cN});
        }
        previous = next, previousN = nextN;
    }
    return true;
}

// What an error adds when the file has `V` or `F` lines, which OBJ skips as statements it does not
// know: its keywords are lower case.
static std::string CapitalsHint(int capitals) {
    return capitals == 0 ? "" : " (lines that begin 'V' or 'F' were skipped: OBJ is lower case)";
}

// The file's lines into *r and *triangles (ReadObj, ReadObjInto): `v`, `f`, and `vn` where
// `normals` asks for the file's.
static bool ReadLines(FILE *file, const char *meshName, int material,
                      const std::vector<MeshStep> &steps, bool normals, size_t maxTriangles,
                      const std::string &statement, MeshReading *r,
                      std::vector<Triangle> *triangles, std::string *error) {
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
        r->line = lineNumber;
        if (!tokens.empty() && (tokens[0] == "v" || (normals && tokens[0] == "vn")))
            read = ReadVertex(tokens, steps, statement, r, &why);
        if (!tokens.empty() && tokens[0] == "f") {
            read = ReadFace(tokens, r, material, most, CapitalsHint(capitals), statement, triangles,
                            &why);
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

bool ReadObj(FILE *file, const char *meshName, int material, const std::vector<MeshStep> &steps,
             size_t maxTriangles, const std::string &statement, std::vector<Triangle> *triangles,
             std::string *error) {
    MeshReading r;
    r.keepCorners = r.fileNormals = false, r.badNormal = r.badVn = 0;
    r.mirrored = MirrorsMesh(steps);
    return ReadLines(file, meshName, material, steps, false, maxTriangles, statement, &r, triangles,
                     error);
}

// ---- a mesh statement's file, into the scene --------------------------------------------------

bool ReadObjInto(FILE *file, const char *meshName, int material, const MeshWords *words,
                 size_t maxTriangles, const std::string &statement, Scene *scene,
                 std::string *error) {
    MeshReading r;
    r.keepCorners = words->normals != MESH_FLAT;
    r.fileNormals = words->normals == MESH_NORMALS_FROM_FILE, r.badNormal = r.badVn = 0;
    r.mirrored = MirrorsMesh(words->steps);
    size_t first = scene->triangles.size();
    if (!ReadLines(file, meshName, material, words->steps, r.fileNormals, maxTriangles, statement,
                   &r, &scene->triangles, error))
        return false;
    if (r.keepCorners) {
        MeshCorners corners = {r.cornerVertex.data(), r.cornerNormal.data(), r.vertices.size(),
                               r.normals.data()};
        AddCornerNormals(&corners, words->normals, first, meshName, scene);
    }
    if (r.badNormal > 0)
        scene->warnings.push_back(std::string(meshName) + ":" + std::to_string(r.badNormal) +
                                  ": warning: normal index " + r.badIndex + " is out of range (" +
                                  std::to_string(r.normals.size()) +
                                  " normals, vn, in the file); faces that name a normal that is "
                                  "not there are drawn flat");
    if (r.badVn > 0)
        scene->warnings.push_back(std::string(meshName) + ":" + std::to_string(r.badVn) +
                                  ": warning: " + r.badVnWhy +
                                  "; the faces that name this normal are drawn flat");
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

// For `fit S`: the box of the file's positions as written (a first pass over its `v` lines), and
// the steps that put its centre at the origin and make its longest side S, to go before the other
// words. False with *error where the file cannot be read or its positions have no extent.
static bool FitSteps(FILE *file, const char *meshName, real size, std::vector<MeshStep> *steps,
                     std::string *error) {
    vec3 lo = {kInfinity, kInfinity, kInfinity}, hi = -lo;
    std::vector<std::string> tokens;
    std::string line, why;
    for (int lineNumber = 1;; lineNumber++) {
        LineStatus status = ReadTextLine(file, lineNumber, &line, &why);
        if (status == LINE_END)
            break;
        if (status != LINE_READ)
            return MeshFail(meshName, lineNumber, why, error);
        Tokenize(line, &tokens);
        real v[3];
        if (tokens.empty() || tokens[0] != "v")
            continue;
        if (!ReadThree(tokens, v, &why))
            return MeshFail(meshName, lineNumber, why, error);
        lo = {std::min(lo.x, v[0]), std::min(lo.y, v[1]), std::min(lo.z, v[2])};
        hi = {std::max(hi.x, v[0]), std::max(hi.y, v[1]), std::max(hi.z, v[2])};
    }
    rewind(file);
    // (halves first: lo + hi could overflow; the sides' differences may, for a mesh that spans
    // the range of numbers, which then has no size to fit)
    vec3 centre = real(0.5) * lo + real(0.5) * hi, side = hi - lo;
    real longest = std::max({side.x, side.y, side.z});
    if (!(longest > 0) || !std::isfinite(longest)) {
        *error = std::string(meshName) + ": fit: the mesh's vertices have no size to fit (" +
                 (longest > 0 ? "its box spans more than the range of numbers)"
                              : "they are all one point, or there are none)");
        return false;
    }
    MeshStep move = MeshStep(), scale = MeshStep();
    move.kind = MESH_TRANSLATE, move.offset = -centre;
    scale.kind = MESH_SCALE, scale.factor = size / longest;
    steps->insert(steps->begin(), {move, scale});
    return true;
}

bool ReadMeshStatement(const std::vector<std::string> &tokens, const char *sceneFile, int line,
                       int material, size_t maxTriangles, Scene *scene, std::string *error) {
    std::string where = std::string(sceneFile) + ":" + std::to_string(line) + ": mesh: ", why;
    MeshWords words;
    if (!ParseMeshWords(tokens, 3, &words, &why)) {
        *error = where + why;
        return false;
    }
    std::string path = MeshPath(sceneFile, tokens[1]);
    FILE *file = OpenMesh(path, &why);
    if (!file) {
        *error = where + why;
        return false;
    }
    size_t first = scene->triangles.size();
    bool read = (words.fit == 0 || FitSteps(file, path.c_str(), words.fit, &words.steps, error)) &&
                ReadObjInto(file, path.c_str(), material, &words, maxTriangles,
                            std::string(sceneFile) + ":" + std::to_string(line), scene, error);
    fclose(file);
    if (!read)
        return false;
    if (std::find(scene->meshFiles.begin(), scene->meshFiles.end(), path) == scene->meshFiles.end())
        scene->meshFiles.push_back(path);
    scene->meshes.push_back({path, first, scene->triangles.size() - first});
    return true;
}
