// tests/grade/tiny.cpp -- a tiny tracer as a student writes it after the handouts, and the same
// tracer with one classic bug, for the tests of `make grade`: each grading scene must catch its
// bug. Not part of rt: no robust step, no speed, one file.
//
//   tiny [--bug NAME] SCENE -o OUT.png
//
// It reads the part of rt's scene format the grading scenes use (size, camera perspective,
// ambient, background, depth, light, material with diffuse and mirror, sphere, triangle) and
// draws with the handouts' methods as `ray --methods handout` does: the slide's eye ray, the
// textbook quadratic, Cramer's rule, shadow and mirror rays that start 1e-4 along, normals turned
// toward the viewer, at most `depth` rays in a chain. --bug NAME breaks one step (kBugs).
#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

struct V {
    double x, y, z;
};
static V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
static V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
static V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
static V Mul(V a, V b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
static double Dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static V Cross(V a, V b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static V Unit(V a) { return (1 / std::sqrt(Dot(a, a))) * a; }

struct Material {
    V diffuse = {1, 1, 1};
    double mirror = 0;
};
struct Shape {
    bool sphere;
    V a, b, c; // a sphere: its centre a and radius b.x
    int material;
};
struct Light {
    V position, intensity;
};
// The bugs, one at a time.
enum Bug { NONE, NORMALS, ACNE, BEYOND, REFLECT, FAR_ROOT, NO_LIMIT, UPSIDE_DOWN, MIRRORED, EDGES };
static const char *kBugs[] = {"none",     "normals",  "acne",        "beyond",   "reflect",
                              "far-root", "no-limit", "upside-down", "mirrored", "edges"};
struct Scene {
    int width = 512, height = 512, depth = 10;
    V eye = {0, 0, 0};
    double distance = 2, screenWidth = 2, ambient = 0.2;
    V background = {0, 0, 0};
    std::vector<Light> lights;
    std::vector<Material> materials;
    std::vector<Shape> shapes;
    Bug bug = NONE;
};

const double kEpsilon = 1e-4;

struct Hit {
    double t;
    V point, normal;
    int material;
};

static bool HitSphere(const Shape *s, Bug bug, V o, V d, double tMin, double tMax, Hit *hit) {
    V oc = o - s->a;
    double A = Dot(d, d), B = 2 * Dot(d, oc), C = Dot(oc, oc) - s->b.x * s->b.x;
    double disc = B * B - 4 * A * C;
    if (disc < 0)
        return false;
    double near = (-B - std::sqrt(disc)) / (2 * A), far = (-B + std::sqrt(disc)) / (2 * A);
    double t = bug == FAR_ROOT ? far : (near > tMin ? near : far);
    if (!(t > tMin && t < tMax))
        return false;
    hit->t = t, hit->point = o + t * d, hit->normal = (1 / s->b.x) * (hit->point - s->a);
    return true;
}

static bool HitTriangle(const Shape *s, Bug bug, V o, V d, double tMin, double tMax, Hit *hit) {
    double A = s->a.x - s->b.x, B = s->a.y - s->b.y, C = s->a.z - s->b.z;
    double D = s->a.x - s->c.x, E = s->a.y - s->c.y, F = s->a.z - s->c.z;
    double G = d.x, H = d.y, I = d.z, J = s->a.x - o.x, K = s->a.y - o.y, L = s->a.z - o.z;
    double M = A * (E * I - H * F) + B * (G * F - D * I) + C * (D * H - E * G);
    if (M == 0)
        return false;
    double t = -(F * (A * K - J * B) + E * (J * C - A * L) + D * (B * L - K * C)) / M;
    double gamma = (I * (A * K - J * B) + H * (J * C - A * L) + G * (B * L - K * C)) / M;
    double beta = (J * (E * I - H * F) + K * (G * F - D * I) + L * (D * H - E * G)) / M;
    bool inside = bug == EDGES ? gamma > 0 && beta > 0 && beta + gamma < 1
                               : gamma >= 0 && beta >= 0 && beta <= 1 - gamma;
    if (!(t > tMin && t < tMax) || !inside)
        return false;
    hit->t = t, hit->point = o + t * d, hit->normal = Unit(Cross(s->b - s->a, s->c - s->a));
    return true;
}

static bool Nearest(const Scene *scene, V o, V d, double tMin, double tMax, Hit *hit) {
    bool found = false;
    for (const Shape &s : scene->shapes)
        if (s.sphere ? HitSphere(&s, scene->bug, o, d, tMin, tMax, hit)
                     : HitTriangle(&s, scene->bug, o, d, tMin, tMax, hit)) {
            found = true, tMax = hit->t, hit->material = s.material;
        }
    if (found && scene->bug != NORMALS && Dot(hit->normal, d) > 0)
        hit->normal = -1 * hit->normal; // toward the viewer
    return found;
}

// Where a ray that leaves a surface may first hit: epsilon along it. (The acne bug: a shadow ray
// that starts at 0.)
static double Start(V d) { return kEpsilon / std::sqrt(Dot(d, d)); }

static V Trace(const Scene *scene, V o, V d, double tMin, int chain) {
    Hit hit;
    if (!Nearest(scene, o, d, tMin, INFINITY, &hit))
        return scene->background;
    const Material *m = &scene->materials[hit.material];
    V sum = {0, 0, 0}, result = {0, 0, 0};
    for (const Light &light : scene->lights) {
        V toLight = light.position - hit.point;
        double nDotL = Dot(hit.normal, toLight);
        Hit blocker;
        if (!(nDotL > 0) ||
            Nearest(scene, hit.point, toLight, scene->bug == ACNE ? 0 : Start(toLight),
                    scene->bug == BEYOND ? INFINITY : 1, &blocker))
            continue;
        sum = sum + (nDotL / std::sqrt(Dot(toLight, toLight))) * light.intensity;
    }
    double a = scene->ambient;
    if (m->mirror < 1)
        result = (1 - m->mirror) *
                 Mul(m->diffuse, {std::fmax(a, sum.x), std::fmax(a, sum.y), std::fmax(a, sum.z)});
    bool more = scene->bug == NO_LIMIT ? chain < 1000 : chain < scene->depth;
    if (m->mirror > 0 && more) {
        double s = scene->bug == REFLECT ? 2 : -2;
        V r = d + (s * Dot(d, hit.normal)) * hit.normal;
        result = result + m->mirror * Trace(scene, hit.point, r, Start(r), chain + 1);
    }
    return result;
}

static bool Read(const char *path, Scene *scene) {
    FILE *f = fopen(path, "r");
    if (!f)
        return false;
    std::map<std::string, int> names;
    char line[1024];
    while (fgets(line, sizeof line, f)) {
        if (char *hash = strchr(line, '#'))
            *hash = 0;
        char word[64] = "", name[64] = "", more[4][64] = {};
        double n[12] = {};
        if (sscanf(line, "%63s", word) != 1)
            continue;
        std::string w = word;
        if (w == "size")
            scene->height = sscanf(line, "size %d %d", &scene->width, &scene->height) == 2
                                ? scene->height
                                : scene->width;
        else if (w == "camera")
            sscanf(line, "camera perspective %lf %lf %lf %lf %lf", &scene->eye.x, &scene->eye.y,
                   &scene->eye.z, &scene->distance, &scene->screenWidth);
        else if (w == "ambient")
            sscanf(line, "ambient %lf", &scene->ambient);
        else if (w == "depth")
            sscanf(line, "depth %d", &scene->depth);
        else if (w == "background")
            sscanf(line, "background %lf %lf %lf", &scene->background.x, &scene->background.y,
                   &scene->background.z);
        else if (w == "light") {
            Light l = {{0, 0, 0}, {1, 1, 1}};
            sscanf(line, "light %lf %lf %lf %lf %lf %lf", &l.position.x, &l.position.y,
                   &l.position.z, &l.intensity.x, &l.intensity.y, &l.intensity.z);
            scene->lights.push_back(l);
        } else if (w == "material") {
            Material m;
            int k = sscanf(line, "material %63s %63s %lf %lf %lf %63s %lf", name, more[0], &n[0],
                           &n[1], &n[2], more[1], &n[3]);
            if (k >= 3 && strcmp(more[0], "mirror") == 0)
                m.mirror = n[0];
            if (k >= 5 && strcmp(more[0], "diffuse") == 0)
                m.diffuse = {n[0], n[1], n[2]};
            if (k >= 7 && strcmp(more[1], "mirror") == 0)
                m.mirror = n[3];
            names[name] = (int)scene->materials.size();
            scene->materials.push_back(m);
        } else if (w == "sphere" && sscanf(line, "sphere %lf %lf %lf %lf %63s", &n[0], &n[1], &n[2],
                                           &n[3], name) == 5)
            scene->shapes.push_back({true, {n[0], n[1], n[2]}, {n[3], 0, 0}, {}, names[name]});
        else if (w == "triangle" &&
                 sscanf(line, "triangle %lf %lf %lf %lf %lf %lf %lf %lf %lf %63s", &n[0], &n[1],
                        &n[2], &n[3], &n[4], &n[5], &n[6], &n[7], &n[8], name) == 10)
            scene->shapes.push_back(
                {false, {n[0], n[1], n[2]}, {n[3], n[4], n[5]}, {n[6], n[7], n[8]}, names[name]});
    }
    fclose(f);
    return true;
}

static unsigned char Byte(double c) {
    return c <= 0 ? 0 : c >= 1 ? 255 : (unsigned char)(c * 255 + 0.5);
}

// The image, row by row from the top, 3 bytes a pixel.
static std::vector<unsigned char> Render(const Scene *scene) {
    std::vector<unsigned char> pixels(3 * scene->width * scene->height);
    double size = scene->screenWidth / scene->width;
    for (int j = 0; j < scene->height; j++)
        for (int i = 0; i < scene->width; i++) {
            double x = (i + 0.5 - 0.5 * scene->width) * size,
                   y = (0.5 * scene->height - (j + 0.5)) * size;
            if (scene->bug == MIRRORED)
                x = -x;
            if (scene->bug == UPSIDE_DOWN)
                y = -y;
            V toScreen = {x, y, -scene->distance}; // the slide: from the pixel, normalised
            V c = Trace(scene, scene->eye + toScreen, Unit(toScreen), 0, 1);
            unsigned char *p = &pixels[3 * (j * scene->width + i)];
            p[0] = Byte(c.x), p[1] = Byte(c.y), p[2] = Byte(c.z);
        }
    return pixels;
}

int main(int argc, char **argv) {
    const char *scenePath = nullptr, *out = "out.png";
    Bug bug = NONE;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (strcmp(argv[i], "--bug") == 0 && i + 1 < argc) {
            const char *name = argv[++i];
            for (int b = 0; b < (int)(sizeof kBugs / sizeof *kBugs); b++)
                if (strcmp(name, kBugs[b]) == 0)
                    bug = (Bug)b;
        } else
            scenePath = argv[i];
    }
    Scene scene;
    if (!scenePath || !Read(scenePath, &scene)) {
        fprintf(stderr, "tiny: cannot read the scene\n");
        return 2;
    }
    scene.bug = bug;
    std::vector<unsigned char> pixels = Render(&scene);
    png_image image;
    memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION, image.width = scene.width, image.height = scene.height;
    image.format = PNG_FORMAT_RGB;
    return png_image_write_to_file(&image, out, 0, pixels.data(), 0, nullptr) ? 0 : 1;
}
