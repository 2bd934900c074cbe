// tests/robust_scenes.cpp -- the scenes of rt's robustness claims (robust_scenes.h).
#include "robust_scenes.h"
#include "../app/app.h"
#include "../render.h"
#include "../robust/robust.h"

#include <cstdio>

vec3 Turn(vec3 p, bool turn) {
    if (!turn)
        return p;
    long double n = sqrtl(14.0L), ax = 1 / n, ay = 2 / n, az = 3 / n;
    long double c = cosl(0.7L), s = sinl(0.7L), k = 1 - c, x = p.x, y = p.y, z = p.z;
    return {
        (real)((k * ax * ax + c) * x + (k * ax * ay - s * az) * y + (k * ax * az + s * ay) * z),
        (real)((k * ax * ay + s * az) * x + (k * ay * ay + c) * y + (k * ay * az - s * ax) * z),
        (real)((k * ax * az - s * ay) * x + (k * ay * az + s * ax) * y + (k * az * az + c) * z)};
}

Scene WallScene() {
    Scene s;
    InitScene(&s);
    Material wall = {"wall", {1, 1, 1}, {1, 1, 1}, 0, 1, 0, 0, {0, 0, 0}};
    s.materials.push_back(wall);
    return s;
}

Scene BoxScene(double length, bool turn) {
    Scene s = WallScene();
    const real X[2] = {-2, 2}, Y[2] = {real(-1.5), real(1.5)};
    const real Z[2] = {(real)(-length / 2), (real)(length / 2)};
    const int faces[6][4][3] = {
        {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
        {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
        {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
    for (const auto &f : faces) {
        vec3 v[4];
        for (int k = 0; k < 4; k++)
            v[k] = Turn({X[f[k][0]], Y[f[k][1]], Z[f[k][2]]}, turn);
        s.triangles.push_back({v[0], v[1], v[2], 0});
        s.triangles.push_back({v[0], v[2], v[3], 0});
    }
    return s;
}

Scene FloorScene(real half, bool turn, vec3 corners[4]) {
    Scene s = WallScene();
    vec3 a = Turn({-half, 0, -half}, turn), b = Turn({half, 0, -half}, turn);
    vec3 c = Turn({half, 0, half}, turn), d = Turn({-half, 0, half}, turn);
    s.triangles = {{a, c, b, 0}, {a, d, c, 0}};
    corners[0] = a, corners[1] = b, corners[2] = c, corners[3] = d;
    return s;
}

vec3 UnitDirection(real u1, real u2) {
    real z = 2 * u1 - 1, phi = real(6.283185307179586) * u2;
    real r = std::sqrt(std::max(real(0), 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

std::string AssignmentText(double scale, double shift, const char *camera, bool glass) {
    auto p = [&](double x, double y, double z) {
        char t[96];
        snprintf(t, sizeof t, "%.17g %.17g %.17g", x * scale + shift, y * scale - shift,
                 z * scale + shift);
        return std::string(t);
    };
    char number[64];
    std::string s = "size 64 64\nmaterial mirror mirror 1\nmaterial red diffuse 1 0 0\n"
                    "material blue diffuse 0 0 1\nmaterial white diffuse 1 1 1\n"
                    "material glass glass 1.5\n";
    if (std::string(camera) == "lookat") {
        snprintf(number, sizeof number, "%.17g", 2 * std::atan(0.5) * 180 / 3.14159265358979323846);
        s += "camera lookat " + p(0, 0, 0) + " " + p(0, 0, -1) + " 0 1 0 " + number + "\n";
    } else if (std::string(camera) == "screen") {
        snprintf(number, sizeof number, "%.17g 0 0 0 %.17g 0", 2 * scale, 2 * scale);
        s += "camera screen " + p(0, 0, 0) + " " + p(-1, -1, -2) + " " + number + "\n";
    } else {
        snprintf(number, sizeof number, "%.17g %.17g", 2 * scale, 2 * scale);
        s += "camera perspective " + p(0, 0, 0) + " " + number + "\n";
    }
    auto radius = [&](double r) {
        snprintf(number, sizeof number, "%.17g", r * scale);
        return std::string(number);
    };
    s += "light " + p(3, 5, -15) + "\n";
    s += "sphere " + p(0, 0, -16) + " " + radius(2) + (glass ? " glass\n" : " mirror\n");
    s += "sphere " + p(3, -1, -14) + " " + radius(1) + " mirror\n";
    s += "sphere " + p(-3, -1, -14) + " " + radius(1) + " red\n";
    s += "triangle " + p(-8, -2, -20) + " " + p(8, -2, -20) + " " + p(8, 10, -20) + " blue\n";
    s += "triangle " + p(-8, -2, -20) + " " + p(8, 10, -20) + " " + p(-8, 10, -20) + " blue\n";
    s += "triangle " + p(-8, -2, -20) + " " + p(8, -2, -10) + " " + p(8, -2, -20) + " white\n";
    s += "triangle " + p(-8, -2, -20) + " " + p(-8, -2, -10) + " " + p(8, -2, -10) + " white\n";
    s += "triangle " + p(8, -2, -20) + " " + p(8, -2, -10) + " " + p(8, 10, -20) + " red\n";
    return s;
}

BoxLeaks CountBoxLeaks(double length, bool turn, int rays, uint64_t seed) {
    uint64_t state = seed;
    auto uniform = [&state]() { // a 64-bit LCG's top 53 bits, in [0, 1)
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return (double)(state >> 11) * (1.0 / 9007199254740992.0);
    };
    Scene box = BoxScene(length, turn);
    BoxLeaks leaks = {0, 0, 0};
    for (int i = 0; i < rays; i++) {
        vec3 o = {(real)(-2 + 4 * uniform()), (real)(-1.5 + 3 * uniform()),
                  (real)((uniform() - 0.5) * length)};
        real u1 = (real)uniform(), u2 = (real)uniform();
        Ray ray = {Turn(o, turn), Turn(UnitDirection(u1, u2), turn)};
        RayHit hit, next;
        if (!FindNearestHit(&box, kRobustMethods, &ray, 0, kInfinity, &hit)) {
            leaks.escapes++;
            continue;
        }
        vec3 r = ray.dir - (2 * Dot(ray.dir, hit.normal)) * hit.normal;
        Ray mirror = {LeavingPoint(&box, &hit, r), r};
        if (!FindNearestHit(&box, kRobustMethods, &mirror, 0, kInfinity, &next))
            leaks.mirrorEscapes++;
        else if (next.index / 2 == hit.index / 2)
            leaks.reHits++;
    }
    return leaks;
}

Scene TransformedScene(const Scene &original, real scale, vec3 shift) {
    Scene s = original;
    auto move = [&](vec3 p) { return scale * p + shift; };
    for (Sphere &sp : s.spheres) {
        sp.center = move(sp.center);
        sp.radius *= scale;
    }
    for (Triangle &t : s.triangles)
        t = {move(t.a), move(t.b), move(t.c), t.material};
    for (Light &l : s.lights)
        l.position = move(l.position);
    s.camera.perspective.eye = move(s.camera.perspective.eye);
    s.camera.perspective.distance *= scale;
    s.camera.perspective.screenWidth *= scale;
    return s;
}

// A closed, watertight sphere of 8 * 4^level triangles (a subdivided octahedron, corners
// pushed out to radius r) around c: rays aimed at its corners and edge midpoints meet shared
// edges and corners, where ties between triangles are decided by their order in the scene.
void AddOctasphere(Scene *scene, vec3 c, real r, int level) {
    std::vector<Triangle> faces;
    vec3 p[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    int f[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (auto &t : f)
        faces.push_back({p[t[0]], p[t[1]], p[t[2]], 0});
    for (int k = 0; k < level; k++) {
        std::vector<Triangle> finer;
        for (const Triangle &t : faces) {
            vec3 ab = SafeNormalize(t.a + t.b), bc = SafeNormalize(t.b + t.c);
            vec3 ca = SafeNormalize(t.c + t.a);
            finer.push_back({t.a, ab, ca, 0}), finer.push_back({ab, t.b, bc, 0});
            finer.push_back({ca, bc, t.c, 0}), finer.push_back({ab, bc, ca, 0});
        }
        faces = finer;
    }
    for (Triangle t : faces)
        scene->triangles.push_back({c + r * t.a, c + r * t.b, c + r * t.c, 0});
}

double ClaimedBoxLength(int k) {
    const double lengths[] = {1e2, 1e8, 1e12}, floatLengths[] = {1e2, 1e3, 1e4};
    return sizeof(real) == sizeof(double) ? lengths[k] : floatLengths[k];
}

// ---- closed meshes seen from inside: the leak detector ----------------------------------------

Scene LeakScene(bool mirrorWalls, vec3 eye, vec3 view, int size) {
    Scene scene;
    InitScene(&scene);
    scene.width = scene.height = size;
    scene.shading = mirrorWalls ? SHADING_FLOOR : SHADING_PATH;
    scene.ambientLight = 0;
    scene.background = {0, 1, 0};
    scene.depth = 100;
    Material wall = {"wall", {1, 1, 1}, {1, 1, 1}, 0, 1, mirrorWalls ? real(1) : real(0),
                     0,      {0, 0, 0}};
    Material glass = {"glass", {1, 1, 1}, {1, 1, 1}, 0, 1, 0, real(1.5), {0, 0, 0}};
    scene.materials = {wall, glass};
    scene.camera.kind = CAMERA_LOOKAT;
    scene.camera.lookFrom = eye, scene.camera.lookAt = eye + view, scene.camera.vup = {0, 1, 0};
    scene.camera.fovDegrees = 100;
    return scene;
}

std::string TurnWords(double x, double y, double z) {
    char words[160];
    snprintf(words, sizeof words, "rotate x %.17g rotate y %.17g rotate z %.17g", x, y, z);
    return words;
}

// The corners moved by the words, as the `mesh` statement moves an OBJ file's vertices.
static bool MoveCorners(const std::string &words, vec3 *corners, int count) {
    std::vector<std::string> tokens;
    Tokenize(words, &tokens);
    std::vector<MeshStep> steps;
    std::string error;
    if (!ParseMeshTransform(tokens, 0, &steps, &error))
        return false;
    for (int k = 0; k < count; k++)
        corners[k] = TransformVertex(steps, corners[k]);
    return true;
}

// Quads as `mesh` turns them into triangles: (p0, p1, p2) and (p0, p2, p3).
static void AddQuads(Scene *scene, const vec3 *v, const int (*quads)[4], int count) {
    for (int q = 0; q < count; q++) {
        const int *f = quads[q];
        scene->triangles.push_back({v[f[0]], v[f[1]], v[f[2]], 0});
        scene->triangles.push_back({v[f[0]], v[f[2]], v[f[3]], 0});
    }
}

bool AddMeshBox(Scene *scene, double w, double h, double l, const std::string &words) {
    vec3 v[8];
    for (int k = 0; k < 8; k++)
        v[k] = {(real)((k & 4 ? 0.5 : -0.5) * w), (real)((k & 2 ? 0.5 : -0.5) * h),
                (real)((k & 1 ? 0.5 : -0.5) * l)};
    if (!MoveCorners(words, v, 8))
        return false;
    const int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                             {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    AddQuads(scene, v, quads, 6);
    return true;
}

bool AddPrism(Scene *scene, double degrees, double l, const std::string &words) {
    double half = degrees / 2 * 3.14159265358979323846 / 180;
    double x = 10 * std::cos(half), y = 10 * std::sin(half), cx = 2 * x / 3; // centroid at cx
    vec3 v[6];
    for (int k = 0; k < 6; k++) {
        double px[3] = {-cx, x - cx, x - cx}, py[3] = {0, y, -y};
        v[k] = {(real)px[k % 3], (real)py[k % 3], (real)(k < 3 ? -l / 2 : l / 2)};
    }
    if (!MoveCorners(words, v, 6))
        return false;
    scene->triangles.push_back({v[0], v[2], v[1], 0});
    scene->triangles.push_back({v[3], v[4], v[5], 0});
    const int quads[3][4] = {{0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
    AddQuads(scene, v, quads, 3);
    return true;
}

int PixelsThatSeeOut(const Scene *scene, int seed) {
    RenderSettings settings = {scene->width,
                               scene->height,
                               1,
                               SAMPLES_GRID,
                               scene->depth,
                               1,
                               kRobustMethods,
                               nullptr,
                               {},
                               {},
                               {}};
    settings.path.seed = seed;
    Image image;
    RayStats stats = {};
    Render(scene, &settings, &image, &stats);
    int green = 0;
    for (size_t p = 0; p < image.pixels.size(); p += 3)
        green += image.pixels[p + 1] > 0;
    return green;
}

// ---- smooth meshes ---------------------------------------------------------------------------

std::string IcosphereObj(int level) {
    real t = real((1 + std::sqrt(5.0)) / 2);
    std::vector<vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                           {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                           {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<int> f = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                          4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                          6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    for (vec3 &p : v)
        p = Normalize(p);
    for (int l = 0; l < level; l++) {
        std::vector<int> finer;
        for (size_t k = 0; k < f.size(); k += 3) {
            int m[3];
            for (int e = 0; e < 3; e++) { // (edges split twice: closed enough for a test)
                v.push_back(Normalize(v[f[k + e]] + v[f[k + (e + 1) % 3]]));
                m[e] = (int)v.size() - 1;
            }
            finer.insert(finer.end(), {f[k], m[0], m[2], m[0], f[k + 1], m[1], m[2], m[1], f[k + 2],
                                       m[0], m[1], m[2]});
        }
        f.swap(finer);
    }
    std::string text;
    char line[256];
    for (vec3 p : v) {
        snprintf(line, sizeof line, "v %.17g %.17g %.17g\nvn %.17g %.17g %.17g\n", (double)p.x,
                 (double)p.y, (double)p.z, (double)p.x, (double)p.y, (double)p.z);
        text += line;
    }
    for (size_t k = 0; k < f.size(); k += 3) {
        snprintf(line, sizeof line, "f %d//%d %d//%d %d//%d\n", f[k] + 1, f[k] + 1, f[k + 1] + 1,
                 f[k + 1] + 1, f[k + 2] + 1, f[k + 2] + 1);
        text += line;
    }
    return text;
}

bool AddMeshText(Scene *scene, const std::string &dir, const std::string &obj,
                 const std::string &words, std::string *error) {
    FILE *file = fopen((dir + "/mesh.obj").c_str(), "wb");
    if (!file || fwrite(obj.data(), 1, obj.size(), file) != obj.size()) {
        *error = dir + "/mesh.obj: cannot write";
        if (file)
            fclose(file);
        return false;
    }
    fclose(file);
    std::vector<std::string> tokens;
    Tokenize("mesh mesh.obj wall " + words, &tokens);
    return ReadMeshStatement(tokens, (dir + "/leak.scene").c_str(), 1, 0, 1000000, scene, error);
}
